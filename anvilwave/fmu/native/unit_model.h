/*
 * unit_model.h -- what a native unit (Ram, PileSoil, Anvil, AnvilLumped) gives the FMI layers.
 *
 * One binary per unit kind serves every build: the FMI 2.0 layer (unit_fmu.c) and the FMI 3.0
 * layer (unit_fmi3.c) share one instance, state machine and error handling (unit_core.c),
 * which reads resources/anvilwave_unit.txt (fmu_common.h): the model identifier of the FMU
 * (kind), the GUID and the parameters' start values, with the unit's arrays. A binary holds
 * one or more models (UNIT_MODELS); the resource's kind picks one.
 *
 * Variables are Reals, Booleans or Strings (parameters only for the last two), held in double
 * slots (the index into the variable table; a Boolean is 0.0 or 1.0) and, for Strings, in
 * string slots. A unit provides its variable table (value references as in the pythonfmu unit
 * of the same kind) and these functions:
 *   load:    the model from the resource and the resources folder (NULL with the reason on
 *            bad data);
 *   start:   a state from the model and the parameter slots, at the experiment's start time
 *            (NULL with the reason on a bad parameter value);
 *   outputs: the output slots from the state at time [s] (and, with feedthrough, the inputs);
 *   step:    advance the state over h [s] from time [s] with the input slots held (0 with the
 *            reason);
 *   inputs_set (optional): told before new input values are stored, at time [s];
 *   outputs_read (optional): told after the host read values (fmi2GetReal, fmi3GetFloat64);
 *   free_model / free_state.
 * With feedthrough the outputs depend on the inputs: the layer evaluates them when the host
 * reads them after new inputs; otherwise (states) after building and after each step.
 */
#ifndef UNIT_MODEL_H
#define UNIT_MODEL_H

#include <stddef.h>

#include "fmu_common.h"

typedef enum { UNIT_PARAMETER, UNIT_INPUT, UNIT_OUTPUT } UnitCausality;

typedef enum { UNIT_REAL, UNIT_BOOLEAN, UNIT_STRING } UnitType;

typedef struct {
    unsigned int vr;
    UnitCausality causality;
    const char *name;
    double start; /* parameters: the default when the resource has none; inputs: the start */
    UnitType type;
    const char *text; /* String parameters: the start value; NULL otherwise */
} UnitVariable;

typedef struct {
    const char *kind; /* the model identifier, e.g. "Ram" */
    const UnitVariable *variables;
    size_t n_variables;
    unsigned int time_vr; /* FMI 3.0 value reference of the independent variable time */
    int feedthrough;      /* outputs depend directly on the inputs */
    void *(*load)(const FmuResource *res, const char *resources, char *reason,
                  size_t reason_size);
    void (*free_model)(void *model);
    void *(*start)(void *model, const double *slots, char *const *strings, double start_time,
                   char *reason, size_t reason_size);
    void (*free_state)(void *state);
    void (*outputs)(void *state, double *slots, double time);
    int (*step)(void *state, const double *slots, double time, double h, char *reason,
                size_t reason_size);
    void (*inputs_set)(void *state, const double *slots, double time);
    void (*outputs_read)(void *state);
} UnitModel;

/* The models of this binary (ram_model.c, pile_soil_model.c or anvil_unit.c). */
extern const UnitModel *const UNIT_MODELS[];
extern const size_t N_UNIT_MODELS;

#endif /* UNIT_MODEL_H */
