/*
 * unit_fmu.c -- the FMI 2.0 co-simulation layer of the generic native units (Ram, PileSoil).
 *
 * One binary per unit kind (unit_model.h) serves every build: fmi2Instantiate reads
 * resources/anvilwave_unit.txt (fmu_common.h) from fmuResourceLocation, checks that it is of
 * this binary's kind and that its GUID is the host's (modelDescription.xml), loads the model
 * and takes the parameters' start values from it. So no per-build compilation: the FMU carries
 * prebuilt binaries for each platform and its data as a resource.
 *
 * Life cycle and errors (the anvil's behaviour, anvil_fmu.c):
 * - fmi2SetReal refuses (fmi2Error, reason logged) a non-finite value, a parameter after
 *   initialization, an output or an unknown value reference; the value is not stored.
 * - fmi2ExitInitializationMode builds the unit's state from the parameters (a bad value:
 *   fmi2Error with the unit's reason); fmi2DoStep refuses a non-finite, non-positive or too
 *   large step (above FMU_MAX_STEP, or one the unit cannot sub-step) and reports non-finite
 *   outputs after a step as fmi2Error. After an fmi2Error in initialization or stepping the
 *   instance refuses to step until fmi2Reset; fmi2Reset restores the build's start values.
 * - Calls out of sequence: fmi2Error, the reason logged, the state kept.
 * - Errors and warnings always go to the logger; category logCalls traces calls with debug
 *   logging on. Nothing here aborts or exits the host; no global mutable state.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_common.h"
#include "unit_model.h"


typedef enum {
    ST_INSTANTIATED = 1,
    ST_INITIALIZATION = 2,
    ST_STEP_COMPLETE = 4,
    ST_TERMINATED = 8,
    ST_ERROR = 16
} State;

typedef struct {
    char *name;
    fmi2CallbackLogger logger;
    fmi2ComponentEnvironment environment;
    int logging_on;
    State state;
    char *resources;
    FmuResource resource;
    void *model;
    void *unit; /* the unit's state, NULL until built */
    double *slots;
    double start_time;
    double time;
    char reason[FMU_MESSAGE_SIZE];
} Instance;

#define N_VARIABLES (UNIT_MODEL.n_variables)
#define VARIABLES (UNIT_MODEL.variables)

static void log_message(Instance *inst, fmi2Status status, const char *category,
                        const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fmu_log_va(inst->logger, inst->environment, UNIT_MODEL.kind, inst->name, status, category,
               format, args);
    va_end(args);
}

static void log_raw(const fmi2CallbackFunctions *functions, const char *name,
                    const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fmu_log_va(functions->logger, functions->componentEnvironment, UNIT_MODEL.kind, name,
               fmi2Error, "logStatusError", format, args);
    va_end(args);
}

#define LOG_CALL(inst, ...)                                                                      \
    do {                                                                                         \
        if ((inst)->logging_on) log_message((inst), fmi2OK, "logCalls", __VA_ARGS__);            \
    } while (0)

static fmi2Status fail(Instance *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fmu_log_va(inst->logger, inst->environment, UNIT_MODEL.kind, inst->name, fmi2Error,
               "logStatusError", format, args);
    va_end(args);
    inst->state = ST_ERROR;
    return fmi2Error;
}

static fmi2Status refuse(Instance *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fmu_log_va(inst->logger, inst->environment, UNIT_MODEL.kind, inst->name, fmi2Error,
               "logStatusError", format, args);
    va_end(args);
    return fmi2Error;
}

static const char *state_name(State state)
{
    switch (state) {
    case ST_INSTANTIATED: return "instantiated";
    case ST_INITIALIZATION: return "initialization mode";
    case ST_STEP_COMPLETE: return "step complete";
    case ST_TERMINATED: return "terminated";
    default: return "error";
    }
}

#define REQUIRE_STATE(inst, function, mask)                                                      \
    do {                                                                                         \
        if (((inst)->state & (mask)) == 0)                                                       \
            return refuse((inst), "%s: not allowed in state %s", (function),                    \
                          state_name((inst)->state));                                            \
    } while (0)

#define REQUIRE_ARRAYS(inst, function, nvr, vr, value)                                           \
    do {                                                                                         \
        if ((nvr) > 0 && ((vr) == NULL || (value) == NULL))                                      \
            return refuse((inst), "%s: null value-reference or value array", (function));      \
    } while (0)

/* The slot of a variable of this type, -1 when there is none (FMI 2.0 value references are
 * per type). */
static long find_slot(fmi2ValueReference vr, UnitType type)
{
    size_t i;
    for (i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].vr == vr && VARIABLES[i].type == type) return (long)i;
    return -1;
}

static int has_type(UnitType type)
{
    size_t i;
    for (i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].type == type) return 1;
    return 0;
}

static void apply_start_values(Instance *inst)
{
    size_t i;
    for (i = 0; i < N_VARIABLES; i++) {
        double value = VARIABLES[i].start;
        if (VARIABLES[i].causality == UNIT_PARAMETER)
            fmu_resource_start(&inst->resource, VARIABLES[i].name, &value);
        inst->slots[i] = VARIABLES[i].causality == UNIT_OUTPUT ? 0.0 : value;
    }
}

static void drop_unit(Instance *inst)
{
    if (inst->unit != NULL) UNIT_MODEL.free_state(inst->unit);
    inst->unit = NULL;
}

/* The unit's state from the current parameters (once per parameter set); 0 with the reason. */
static int build(Instance *inst)
{
    if (inst->unit != NULL) return 1;
    inst->reason[0] = '\0';
    inst->unit = UNIT_MODEL.start(inst->model, inst->slots, inst->start_time, inst->reason,
                                  sizeof inst->reason);
    if (inst->unit == NULL) return 0;
    UNIT_MODEL.outputs(inst->unit, inst->slots);
    return 1;
}

/* The name of the first non-finite output, NULL when all are finite. */
static const char *non_finite_output(const Instance *inst)
{
    size_t i;
    for (i = 0; i < N_VARIABLES; i++)
        if (VARIABLES[i].causality == UNIT_OUTPUT && !isfinite(inst->slots[i]))
            return VARIABLES[i].name;
    return NULL;
}

static void free_instance(Instance *inst)
{
    if (inst == NULL) return;
    drop_unit(inst);
    if (inst->model != NULL) UNIT_MODEL.free_model(inst->model);
    fmu_resource_free(&inst->resource);
    free(inst->slots);
    free(inst->resources);
    free(inst->name);
    free(inst);
}

/* ------------------------------------------------------------------ inquiry */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (nCategories > 0 && categories == NULL)
        return refuse(inst, "fmi2SetDebugLogging: null categories");
    for (i = 0; i < nCategories; i++)
        if (categories[i] == NULL || (strcmp(categories[i], "logCalls") != 0 &&
                                      strcmp(categories[i], "logStatusError") != 0 &&
                                      strcmp(categories[i], "logStatusWarning") != 0))
            return refuse(inst, "fmi2SetDebugLogging: unknown log category %s",
                          categories[i] != NULL ? categories[i] : "(null)");
    inst->logging_on = loggingOn ? 1 : 0;
    return fmi2OK;
}

/* ------------------------------------------------------------------ life cycle */
fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    const char *name = instanceName != NULL ? instanceName : "";
    Instance *inst;
    char *path;
    (void)visible;
    if (functions == NULL) return NULL;
    if (name[0] == '\0') {
        log_raw(functions, name, "fmi2Instantiate: the instance name is missing");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        log_raw(functions, name, "fmi2Instantiate: this FMU supports co-simulation only "
                "(fmuType = %d)", (int)fmuType);
        return NULL;
    }
    inst = (Instance *)calloc(1, sizeof *inst);
    if (inst == NULL) return NULL;
    inst->name = fmu_copy_string(name);
    inst->resources = fmu_resource_folder(fmuResourceLocation);
    inst->slots = (double *)calloc(N_VARIABLES, sizeof(double));
    inst->logger = functions->logger;
    inst->environment = functions->componentEnvironment;
    inst->logging_on = loggingOn ? 1 : 0;
    if (inst->name == NULL || inst->resources == NULL || inst->slots == NULL) {
        log_raw(functions, name, "fmi2Instantiate: out of memory");
        free_instance(inst);
        return NULL;
    }
    if (inst->resources[0] == '\0') {
        log_raw(functions, name, "fmi2Instantiate: no resource location (got %s): this unit "
                "reads its model from resources/%s", fmuResourceLocation != NULL ?
                fmuResourceLocation : "(null)", FMU_UNIT_RESOURCE);
        free_instance(inst);
        return NULL;
    }
    path = fmu_join(inst->resources, FMU_UNIT_RESOURCE);
    if (path == NULL || !fmu_resource_read(path, &inst->resource, inst->reason,
                                           sizeof inst->reason)) {
        log_raw(functions, name, "fmi2Instantiate: %s", path == NULL ? "out of memory" :
                inst->reason);
        free(path);
        free_instance(inst);
        return NULL;
    }
    free(path);
    if (strcmp(inst->resource.kind, UNIT_MODEL.kind) != 0) {
        log_raw(functions, name, "fmi2Instantiate: the resource is for a %s unit, this binary "
                "is the %s unit", inst->resource.kind, UNIT_MODEL.kind);
        free_instance(inst);
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, inst->resource.guid) != 0) {
        log_raw(functions, name, "fmi2Instantiate: GUID %s does not match the resource's %s "
                "(modelDescription.xml and resources from different builds)",
                fmuGUID != NULL ? fmuGUID : "(null)", inst->resource.guid);
        free_instance(inst);
        return NULL;
    }
    inst->model = UNIT_MODEL.load(&inst->resource, inst->reason, sizeof inst->reason);
    if (inst->model == NULL) {
        log_raw(functions, name, "fmi2Instantiate: resources/%s: %s", FMU_UNIT_RESOURCE,
                inst->reason);
        free_instance(inst);
        return NULL;
    }
    apply_start_values(inst);
    inst->state = ST_INSTANTIATED;
    LOG_CALL(inst, "fmi2Instantiate(GUID = %s, resources = %s)", fmuGUID, inst->resources);
    return inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return;
    LOG_CALL(inst, "fmi2FreeInstance");
    free_instance(inst);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    Instance *inst = (Instance *)c;
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2SetupExperiment(startTime = %g)", startTime);
    REQUIRE_STATE(inst, "fmi2SetupExperiment", ST_INSTANTIATED);
    if (!isfinite(startTime))
        return refuse(inst, "fmi2SetupExperiment: the start time must be finite, got %g",
                      startTime);
    inst->start_time = startTime;
    inst->time = startTime;
    drop_unit(inst);
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2EnterInitializationMode");
    REQUIRE_STATE(inst, "fmi2EnterInitializationMode", ST_INSTANTIATED);
    inst->state = ST_INITIALIZATION;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    const char *bad;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2ExitInitializationMode");
    REQUIRE_STATE(inst, "fmi2ExitInitializationMode", ST_INITIALIZATION);
    if (!build(inst)) return fail(inst, "fmi2ExitInitializationMode: %s", inst->reason);
    if ((bad = non_finite_output(inst)) != NULL)
        return fail(inst, "fmi2ExitInitializationMode: output %s is not finite", bad);
    inst->time = inst->start_time;
    inst->state = ST_STEP_COMPLETE;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2Terminate");
    REQUIRE_STATE(inst, "fmi2Terminate", ST_STEP_COMPLETE | ST_ERROR);
    inst->state = ST_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2Reset");
    drop_unit(inst);
    apply_start_values(inst);
    inst->start_time = inst->time = 0.0;
    inst->state = ST_INSTANTIATED;
    return fmi2OK;
}

/* ------------------------------------------------------------------ variables */
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_ARRAYS(inst, "fmi2GetReal", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        long slot = find_slot(vr[i], UNIT_REAL);
        if (slot < 0) return refuse(inst, "fmi2GetReal: unknown value reference %u", vr[i]);
        if (VARIABLES[slot].causality == UNIT_OUTPUT) {
            if (inst->state == ST_INSTANTIATED || inst->state == ST_ERROR)
                return refuse(inst, "fmi2GetReal: output %s not available in state %s",
                              VARIABLES[slot].name, state_name(inst->state));
            if (inst->state == ST_INITIALIZATION && !build(inst))
                return refuse(inst, "fmi2GetReal: %s", inst->reason);
        }
        value[i] = inst->slots[slot];
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_ARRAYS(inst, "fmi2SetReal", nvr, vr, value);
    REQUIRE_STATE(inst, "fmi2SetReal", ST_INSTANTIATED | ST_INITIALIZATION | ST_STEP_COMPLETE);
    for (i = 0; i < nvr; i++) {
        long slot = find_slot(vr[i], UNIT_REAL);
        const UnitVariable *v;
        if (slot < 0) return refuse(inst, "fmi2SetReal: unknown value reference %u", vr[i]);
        v = &VARIABLES[slot];
        if (v->causality == UNIT_OUTPUT)
            return refuse(inst, "fmi2SetReal: %s is an output", v->name);
        if (v->causality == UNIT_PARAMETER && inst->state == ST_STEP_COMPLETE)
            return refuse(inst, "fmi2SetReal: parameter %s is fixed after initialization",
                          v->name);
        if (!isfinite(value[i]))
            return refuse(inst, "fmi2SetReal: %s must be finite, got %g", v->name, value[i]);
        if (v->causality == UNIT_PARAMETER && inst->slots[slot] != value[i]) drop_unit(inst);
        inst->slots[slot] = value[i];
    }
    return fmi2OK;
}

static fmi2Status no_variables(Instance *inst, const char *function, const char *type,
                               size_t nvr)
{
    if (inst == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    return refuse(inst, "%s: this FMU has no %s variables", function, type);
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    (void)vr;
    (void)value;
    return no_variables((Instance *)c, "fmi2GetInteger", "Integer", nvr);
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    (void)vr;
    (void)value;
    return no_variables((Instance *)c, "fmi2SetInteger", "Integer", nvr);
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (!has_type(UNIT_BOOLEAN)) return no_variables(inst, "fmi2GetBoolean", "Boolean", nvr);
    REQUIRE_ARRAYS(inst, "fmi2GetBoolean", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        long slot = find_slot(vr[i], UNIT_BOOLEAN);
        if (slot < 0) return refuse(inst, "fmi2GetBoolean: unknown value reference %u", vr[i]);
        value[i] = inst->slots[slot] != 0.0 ? fmi2True : fmi2False;
    }
    return fmi2OK;
}

/* Boolean parameters (the only Booleans of the units): as fmi2SetReal's parameters. */
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    if (!has_type(UNIT_BOOLEAN)) return no_variables(inst, "fmi2SetBoolean", "Boolean", nvr);
    REQUIRE_ARRAYS(inst, "fmi2SetBoolean", nvr, vr, value);
    REQUIRE_STATE(inst, "fmi2SetBoolean", ST_INSTANTIATED | ST_INITIALIZATION |
                  ST_STEP_COMPLETE);
    for (i = 0; i < nvr; i++) {
        long slot = find_slot(vr[i], UNIT_BOOLEAN);
        double number = value[i] ? 1.0 : 0.0;
        if (slot < 0) return refuse(inst, "fmi2SetBoolean: unknown value reference %u", vr[i]);
        if (inst->state == ST_STEP_COMPLETE)
            return refuse(inst, "fmi2SetBoolean: parameter %s is fixed after initialization",
                          VARIABLES[slot].name);
        if (inst->slots[slot] != number) drop_unit(inst);
        inst->slots[slot] = number;
    }
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    (void)vr;
    (void)value;
    return no_variables((Instance *)c, "fmi2GetString", "String", nvr);
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    (void)vr;
    (void)value;
    return no_variables((Instance *)c, "fmi2SetString", "String", nvr);
}

/* ------------------------------------------------------------------ unsupported */
static fmi2Status unsupported(fmi2Component c, const char *function)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    return refuse(inst, "%s: not supported by this FMU", function);
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2GetFMUstate");
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2SetFMUstate");
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return unsupported(c, "fmi2FreeFMUstate");
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)FMUstate;
    (void)size;
    return unsupported(c, "fmi2SerializedFMUstateSize");
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte bytes[],
                                 size_t size)
{
    (void)FMUstate;
    (void)bytes;
    (void)size;
    return unsupported(c, "fmi2SerializeFMUstate");
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    (void)serializedState;
    (void)size;
    (void)FMUstate;
    return unsupported(c, "fmi2DeSerializeFMUstate");
}

fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference vUnknown_ref[],
                                        size_t nUnknown, const fmi2ValueReference vKnown_ref[],
                                        size_t nKnown, const fmi2Real dvKnown[],
                                        fmi2Real dvUnknown[])
{
    (void)vUnknown_ref;
    (void)nUnknown;
    (void)vKnown_ref;
    (void)nKnown;
    (void)dvKnown;
    (void)dvUnknown;
    return unsupported(c, "fmi2GetDirectionalDerivative");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[])
{
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2SetRealInputDerivatives");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[])
{
    (void)vr;
    (void)nvr;
    (void)order;
    (void)value;
    return unsupported(c, "fmi2GetRealOutputDerivatives");
}

/* ------------------------------------------------------------------ stepping */
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    Instance *inst = (Instance *)c;
    double h = communicationStepSize;
    const char *bad;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2DoStep(t = %.17g, h = %.17g)", currentCommunicationPoint, h);
    REQUIRE_STATE(inst, "fmi2DoStep", ST_STEP_COMPLETE);
    if (!isfinite(currentCommunicationPoint))
        return fail(inst, "fmi2DoStep: the communication point must be finite, got %g",
                    currentCommunicationPoint);
    if (!(isfinite(h) && h > 0.0))
        return fail(inst, "fmi2DoStep: the communication step must be finite and positive, "
                    "got %g s", h);
    if (h > FMU_MAX_STEP)
        return fail(inst, "fmi2DoStep: the communication step %g s is larger than %g s",
                    h, FMU_MAX_STEP);
    inst->reason[0] = '\0';
    if (!UNIT_MODEL.step(inst->unit, inst->slots, h, inst->reason, sizeof inst->reason))
        return fail(inst, "fmi2DoStep: %s", inst->reason);
    UNIT_MODEL.outputs(inst->unit, inst->slots);
    if ((bad = non_finite_output(inst)) != NULL)
        return fail(inst, "fmi2DoStep(t = %g, h = %g): output %s is not finite after the step",
                    currentCommunicationPoint, h, bad);
    inst->time = currentCommunicationPoint + h;
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) { return unsupported(c, "fmi2CancelStep"); }

static fmi2Status no_status(fmi2Component c, const char *function)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    return refuse(inst, "%s: the FMU steps synchronously, there is no pending status",
                  function);
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetStatus");
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    Instance *inst = (Instance *)c;
    if (inst != NULL && s == fmi2LastSuccessfulTime && value != NULL) {
        *value = inst->time;
        return fmi2OK;
    }
    return no_status(c, "fmi2GetRealStatus");
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetIntegerStatus");
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetBooleanStatus");
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    return no_status(c, "fmi2GetStringStatus");
}
