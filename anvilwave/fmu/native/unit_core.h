/*
 * unit_core.h -- the instance of every native unit, whatever the FMI version: its life cycle
 * (state machine), its variables, its errors and its logging. The FMI 2.0 layer (unit_fmu.c)
 * and the FMI 3.0 layer (unit_fmi3.c) are thin wrappers over these functions; the model is
 * that of unit_model.h.
 *
 * The functions return the FMI status numbers both versions share (0 OK, 1 Warning, 3 Error)
 * and take the name of the FMI function they serve (for the messages). The rules:
 * - Instantiation reads resources/anvilwave_unit.txt from the resources folder, takes the
 *   model of its kind, refuses a GUID (instantiation token) that is not the resource's, loads
 *   the model and applies the start values (the resource's, else the table's).
 * - Setting a value refuses (Error, reason logged, state kept) a non-finite Real, a parameter
 *   after initialization, an output, an unknown value reference or one of another type; the
 *   value is not stored. A parameter of a new value drops the unit's state (rebuilt from the
 *   parameters when needed).
 * - Leaving initialization builds the state (a bad value: Error with the model's reason);
 *   a step refuses a non-finite, non-positive or too large step (FMU_MAX_STEP) and reports
 *   non-finite outputs as an Error. After an Error in initialization or stepping the instance
 *   refuses to step until reset; reset restores the build's start values.
 * - Calls out of sequence: Error, the reason logged, the state kept.
 * - Errors and warnings always go to the logger; category logCalls traces calls with debug
 *   logging on. Nothing here aborts or exits the host; no global mutable state.
 */
#ifndef UNIT_CORE_H
#define UNIT_CORE_H

#include <stddef.h>

#include "unit_model.h"

#define UNIT_STATUS_OK 0
#define UNIT_STATUS_WARNING 1
#define UNIT_STATUS_ERROR 3

typedef enum {
    ST_INSTANTIATED = 1,
    ST_INITIALIZATION = 2,
    ST_STEP_COMPLETE = 4,
    ST_TERMINATED = 8,
    ST_ERROR = 16
} UnitState;

typedef struct Unit Unit;

/* The FMI layer's logger: hands a finished message to the host's callback. */
typedef void (*UnitLogFunction)(const Unit *unit, int status, const char *category,
                                const char *message);

/* The host's logging: the layer's function, the host's callback (any function pointer type,
 * cast back by the layer) and its environment. */
typedef struct {
    UnitLogFunction log;
    void (*callback)(void);
    void *environment;
} UnitHost;

struct Unit {
    char *name;
    const UnitModel *m; /* the model of the resource's kind */
    UnitHost host;
    int logging_on; /* debug logging */
    int log_calls;  /* category logCalls */
    UnitState state;
    char *resources; /* the resources folder */
    FmuResource resource;
    void *model;
    void *run; /* the unit's state, NULL until built */
    double *slots;
    char **strings;
    int outputs_valid;
    double start_time, time;
    char reason[FMU_MESSAGE_SIZE];
};

/* Log "<kind> <name>: <message>" (the model's kind, or the binary's first before there is
 * one). */
void unit_log(const Unit *u, int status, const char *category, const char *format, ...);

/* The instance (NULL with the reason logged): function names the FMI function, token_name
 * what the host calls the GUID ("GUID", "instantiation token"), resources the folder. */
Unit *unit_instantiate(const char *function, const char *name, const char *token_name,
                       const char *token, const char *resources, const UnitHost *host,
                       int logging_on);
void unit_free(Unit *u);
int unit_set_debug_logging(Unit *u, const char *function, int on, size_t n,
                           const char *const categories[]);
int unit_setup(Unit *u, const char *function, double start_time);
int unit_enter_initialization(Unit *u, const char *function);
int unit_exit_initialization(Unit *u, const char *function);
int unit_terminate(Unit *u, const char *function);
int unit_reset(Unit *u, const char *function);

/* Values; with_time: value reference m->time_vr is the time (FMI 3.0). */
int unit_get_real(Unit *u, const char *function, const unsigned int vr[], size_t n,
                  double values[], int with_time);
int unit_set_real(Unit *u, const char *function, const unsigned int vr[], size_t n,
                  const double values[]);
int unit_get_boolean(Unit *u, const char *function, const unsigned int vr[], size_t n,
                     int values[]);
int unit_set_boolean(Unit *u, const char *function, const unsigned int vr[], size_t n,
                     const int values[]);
int unit_get_string(Unit *u, const char *function, const unsigned int vr[], size_t n,
                    const char *values[]);
int unit_set_string(Unit *u, const char *function, const unsigned int vr[], size_t n,
                    const char *const values[]);
/* A type the units have no variables of: OK for none, else Error. */
int unit_no_variables(Unit *u, const char *function, const char *type, size_t n);

int unit_do_step(Unit *u, const char *function, double t, double h);

/* Error: the function is not supported (the reason logged). */
int unit_unsupported(Unit *u, const char *function, const char *why);

#endif /* UNIT_CORE_H */
