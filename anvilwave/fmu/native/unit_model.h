/*
 * unit_model.h -- what a generic native unit (Ram, PileSoil) gives the FMI 2.0 layer
 * unit_fmu.c. One binary per kind serves every build: the model data, the GUID and the
 * parameters' start values come from resources/anvilwave_unit.txt (fmu_common.h).
 *
 * Variables are Reals or Booleans (parameters only), all held in double slots (the index
 * into the variable table; a Boolean is 0.0 or 1.0). A unit provides its variable table (value
 * references as in the pythonfmu unit of the same kind) and five functions:
 *   load:    the model from the resource (NULL with the reason on bad data);
 *   start:   a state from the model and the parameter slots, at the experiment's start time
 *            (NULL with the reason on a bad parameter value);
 *   outputs: the output slots from the state (and, for a feedthrough, the input slots);
 *   step:    advance the state over h [s] with the input slots held (0 with the reason);
 *   free_model / free_state.
 */
#ifndef UNIT_MODEL_H
#define UNIT_MODEL_H

#include <stddef.h>

#include "fmi2TypesPlatform.h"
#include "fmu_common.h"

typedef enum { UNIT_PARAMETER, UNIT_INPUT, UNIT_OUTPUT } UnitCausality;

typedef enum { UNIT_REAL, UNIT_BOOLEAN } UnitType;

typedef struct {
    fmi2ValueReference vr;
    UnitCausality causality;
    const char *name;
    double start; /* parameters: the default when the resource has none; inputs: the start */
    UnitType type;
} UnitVariable;

typedef struct {
    const char *kind; /* the model identifier, e.g. "Ram" */
    const UnitVariable *variables;
    size_t n_variables;
    void *(*load)(const FmuResource *res, char *reason, size_t reason_size);
    void (*free_model)(void *model);
    void *(*start)(const void *model, const double *slots, double start_time, char *reason,
                   size_t reason_size);
    void (*free_state)(void *state);
    void (*outputs)(const void *state, double *slots);
    int (*step)(void *state, const double *slots, double h, char *reason, size_t reason_size);
} UnitModel;

/* The unit of this binary (ram_model.c or pile_soil_model.c). */
extern const UnitModel UNIT_MODEL;

#endif /* UNIT_MODEL_H */
