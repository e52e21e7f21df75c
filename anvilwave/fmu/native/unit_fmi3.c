/*
 * unit_fmi3.c -- the FMI 3.0 co-simulation layer of the generic native units (Ram, PileSoil),
 * compiled into the same binary as the FMI 2.0 layer (unit_fmu.c): the fmi3 functions next to
 * the fmi2 ones, one model (unit_model.h), one resource (resources/anvilwave_unit.txt, whose
 * GUID is the FMI 3.0 instantiationToken).
 *
 * The same behaviour as unit_fmu.c: the Float64 variables of the unit plus the independent
 * variable time (value reference 0); fmi3SetFloat64 refuses non-finite values, parameters
 * after initialization, outputs and unknown value references; fmi3DoStep refuses a
 * non-finite, non-positive or too large step and reports non-finite outputs; errors go to
 * the logMessage callback with the reason and return fmi3Error. Co-simulation only, no event
 * mode, no intermediate update, no FMU state: the other functions return fmi3Error with the
 * reason. Nothing here aborts or exits the host; no global mutable state.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "fmu_common.h"
#include "unit_model.h"

#define TIME_VR 0

typedef enum { S3_INSTANTIATED, S3_INITIALIZATION, S3_STEP, S3_TERMINATED, S3_ERROR } State3;

typedef struct {
    char *name;
    fmi3InstanceEnvironment environment;
    fmi3LogMessageCallback logger;
    int logging_on;
    State3 state;
    FmuResource resource;
    void *model;
    void *unit;
    double *slots;
    double start_time, time;
    char reason[FMU_MESSAGE_SIZE];
} Instance3;

static const char *STATE_NAMES[] = {"instantiated", "initialization mode", "step mode",
                                    "terminated", "error"};

static void log3(fmi3LogMessageCallback logger, fmi3InstanceEnvironment environment,
                 const char *name, fmi3Status status, const char *category, const char *format,
                 va_list args)
{
    char message[FMU_MESSAGE_SIZE];
    int n;
    if (logger == NULL) return;
    n = snprintf(message, sizeof message, "%s %s: ", UNIT_MODEL.kind, name);
    if (n < 0 || (size_t)n >= sizeof message) n = 0;
    vsnprintf(message + n, sizeof message - (size_t)n, format, args);
    logger(environment, status, category, message);
}

static fmi3Status refuse(Instance3 *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log3(inst->logger, inst->environment, inst->name, fmi3Error, "logStatusError", format,
         args);
    va_end(args);
    return fmi3Error;
}

static fmi3Status fail(Instance3 *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log3(inst->logger, inst->environment, inst->name, fmi3Error, "logStatusError", format,
         args);
    va_end(args);
    inst->state = S3_ERROR;
    return fmi3Error;
}

static void log_instantiate(fmi3LogMessageCallback logger, fmi3InstanceEnvironment environment,
                            const char *name, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log3(logger, environment, name, fmi3Error, "logStatusError", format, args);
    va_end(args);
}

static fmi3Status unsupported(fmi3Instance instance, const char *function)
{
    Instance3 *inst = (Instance3 *)instance;
    if (inst == NULL) return fmi3Error;
    return refuse(inst, "%s: not supported by this FMU (co-simulation, Float64 variables)",
                  function);
}

#define REQUIRE(inst, function, condition)                                                       \
    do {                                                                                         \
        if (!(condition))                                                                        \
            return refuse((inst), "%s: not allowed in state %s", (function),                    \
                          STATE_NAMES[(inst)->state]);                                           \
    } while (0)

/* The slot of a variable of this type, -1 when there is none. */
static long find_slot(fmi3ValueReference vr, UnitType type)
{
    size_t i;
    for (i = 0; i < UNIT_MODEL.n_variables; i++)
        if (UNIT_MODEL.variables[i].vr == vr && UNIT_MODEL.variables[i].type == type)
            return (long)i;
    return -1;
}

static void start_values(Instance3 *inst)
{
    size_t i;
    for (i = 0; i < UNIT_MODEL.n_variables; i++) {
        const UnitVariable *v = &UNIT_MODEL.variables[i];
        double value = v->start;
        if (v->causality == UNIT_PARAMETER) fmu_resource_start(&inst->resource, v->name, &value);
        inst->slots[i] = v->causality == UNIT_OUTPUT ? 0.0 : value;
    }
}

static void drop_unit(Instance3 *inst)
{
    if (inst->unit != NULL) UNIT_MODEL.free_state(inst->unit);
    inst->unit = NULL;
}

static int build(Instance3 *inst)
{
    if (inst->unit != NULL) return 1;
    inst->reason[0] = '\0';
    inst->unit = UNIT_MODEL.start(inst->model, inst->slots, inst->start_time, inst->reason,
                                  sizeof inst->reason);
    if (inst->unit == NULL) return 0;
    UNIT_MODEL.outputs(inst->unit, inst->slots);
    return 1;
}

static const char *non_finite_output(const Instance3 *inst)
{
    size_t i;
    for (i = 0; i < UNIT_MODEL.n_variables; i++)
        if (UNIT_MODEL.variables[i].causality == UNIT_OUTPUT && !isfinite(inst->slots[i]))
            return UNIT_MODEL.variables[i].name;
    return NULL;
}

static void free3(Instance3 *inst)
{
    if (inst == NULL) return;
    drop_unit(inst);
    if (inst->model != NULL) UNIT_MODEL.free_model(inst->model);
    fmu_resource_free(&inst->resource);
    free(inst->slots);
    free(inst->name);
    free(inst);
}

/* ------------------------------------------------------------------ implemented */
const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn,
                               size_t nCategories, const fmi3String categories[])
{
    Instance3 *inst = (Instance3 *)instance;
    (void)nCategories;
    (void)categories;
    if (inst == NULL) return fmi3Error;
    inst->logging_on = loggingOn ? 1 : 0;
    return fmi3OK;
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    const char *name = instanceName != NULL ? instanceName : "";
    Instance3 *inst;
    char *path;
    size_t n;
    (void)visible;
    (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables;
    (void)intermediateUpdate;
    if (eventModeUsed) {
        log_instantiate(logMessage, instanceEnvironment, name,
                        "fmi3InstantiateCoSimulation: this FMU has no event mode");
        return NULL;
    }
    if (resourcePath == NULL || resourcePath[0] == '\0') {
        log_instantiate(logMessage, instanceEnvironment, name, "fmi3InstantiateCoSimulation: "
                        "no resource path: this unit reads its model from resources/%s",
                        FMU_UNIT_RESOURCE);
        return NULL;
    }
    inst = (Instance3 *)calloc(1, sizeof *inst);
    if (inst == NULL) return NULL;
    inst->name = fmu_copy_string(name);
    inst->slots = (double *)calloc(UNIT_MODEL.n_variables, sizeof(double));
    inst->environment = instanceEnvironment;
    inst->logger = logMessage;
    inst->logging_on = loggingOn ? 1 : 0;
    n = strlen(resourcePath);
    /* the resource path ends with a separator (FMI 3.0); tolerate one without */
    path = (char *)malloc(n + strlen(FMU_UNIT_RESOURCE) + 2);
    if (inst->name == NULL || inst->slots == NULL || path == NULL) {
        free(path);
        free3(inst);
        return NULL;
    }
    snprintf(path, n + strlen(FMU_UNIT_RESOURCE) + 2, "%s%s%s", resourcePath,
             (resourcePath[n - 1] == '/' || resourcePath[n - 1] == '\\') ? "" : "/",
             FMU_UNIT_RESOURCE);
    if (!fmu_resource_read(path, &inst->resource, inst->reason, sizeof inst->reason)) {
        log_instantiate(logMessage, instanceEnvironment, name,
                        "fmi3InstantiateCoSimulation: %s", inst->reason);
        free(path);
        free3(inst);
        return NULL;
    }
    free(path);
    if (strcmp(inst->resource.kind, UNIT_MODEL.kind) != 0 || instantiationToken == NULL ||
        strcmp(instantiationToken, inst->resource.guid) != 0) {
        log_instantiate(logMessage, instanceEnvironment, name, "fmi3InstantiateCoSimulation: "
                        "instantiation token %s (%s unit) does not match the resource's %s (%s "
                        "unit): modelDescription.xml and resources from different builds",
                        instantiationToken != NULL ? instantiationToken : "(null)",
                        UNIT_MODEL.kind, inst->resource.guid, inst->resource.kind);
        free3(inst);
        return NULL;
    }
    inst->model = UNIT_MODEL.load(&inst->resource, inst->reason, sizeof inst->reason);
    if (inst->model == NULL) {
        log_instantiate(logMessage, instanceEnvironment, name,
                        "fmi3InstantiateCoSimulation: resources/%s: %s", FMU_UNIT_RESOURCE,
                        inst->reason);
        free3(inst);
        return NULL;
    }
    start_values(inst);
    inst->state = S3_INSTANTIATED;
    return inst;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName,
                                          fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    log_instantiate(logMessage, instanceEnvironment, instanceName != NULL ? instanceName : "",
                    "fmi3InstantiateModelExchange: this FMU supports co-simulation only");
    return NULL;
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption)
{
    (void)instantiationToken;
    (void)resourcePath;
    (void)visible;
    (void)loggingOn;
    (void)clockUpdate;
    (void)lockPreemption;
    (void)unlockPreemption;
    log_instantiate(logMessage, instanceEnvironment, instanceName != NULL ? instanceName : "",
                    "fmi3InstantiateScheduledExecution: this FMU supports co-simulation only");
    return NULL;
}

void fmi3FreeInstance(fmi3Instance instance) { free3((Instance3 *)instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    Instance3 *inst = (Instance3 *)instance;
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    if (inst == NULL) return fmi3Error;
    REQUIRE(inst, "fmi3EnterInitializationMode", inst->state == S3_INSTANTIATED);
    if (!isfinite(startTime))
        return refuse(inst, "fmi3EnterInitializationMode: the start time must be finite");
    inst->start_time = inst->time = startTime;
    drop_unit(inst);
    inst->state = S3_INITIALIZATION;
    return fmi3OK;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    Instance3 *inst = (Instance3 *)instance;
    const char *bad;
    if (inst == NULL) return fmi3Error;
    REQUIRE(inst, "fmi3ExitInitializationMode", inst->state == S3_INITIALIZATION);
    if (!build(inst)) return fail(inst, "fmi3ExitInitializationMode: %s", inst->reason);
    if ((bad = non_finite_output(inst)) != NULL)
        return fail(inst, "fmi3ExitInitializationMode: output %s is not finite", bad);
    inst->state = S3_STEP;
    return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    Instance3 *inst = (Instance3 *)instance;
    if (inst == NULL) return fmi3Error;
    REQUIRE(inst, "fmi3Terminate", inst->state == S3_STEP || inst->state == S3_ERROR);
    inst->state = S3_TERMINATED;
    return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    Instance3 *inst = (Instance3 *)instance;
    if (inst == NULL) return fmi3Error;
    drop_unit(inst);
    start_values(inst);
    inst->start_time = inst->time = 0.0;
    inst->state = S3_INSTANTIATED;
    return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
    Instance3 *inst = (Instance3 *)instance;
    size_t i;
    if (inst == NULL) return fmi3Error;
    if (nValues != nValueReferences)
        return refuse(inst, "fmi3GetFloat64: %lu values for %lu value references (scalars "
                      "only)", (unsigned long)nValues, (unsigned long)nValueReferences);
    for (i = 0; i < nValueReferences; i++) {
        long slot;
        if (valueReferences[i] == TIME_VR) {
            values[i] = inst->time;
            continue;
        }
        slot = find_slot(valueReferences[i], UNIT_REAL);
        if (slot < 0)
            return refuse(inst, "fmi3GetFloat64: unknown value reference %u",
                          valueReferences[i]);
        if (UNIT_MODEL.variables[slot].causality == UNIT_OUTPUT) {
            if (inst->state == S3_INSTANTIATED || inst->state == S3_ERROR)
                return refuse(inst, "fmi3GetFloat64: output %s not available in state %s",
                              UNIT_MODEL.variables[slot].name, STATE_NAMES[inst->state]);
            if (inst->state == S3_INITIALIZATION && !build(inst))
                return refuse(inst, "fmi3GetFloat64: %s", inst->reason);
        }
        values[i] = inst->slots[slot];
    }
    return fmi3OK;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
    Instance3 *inst = (Instance3 *)instance;
    size_t i;
    if (inst == NULL) return fmi3Error;
    REQUIRE(inst, "fmi3SetFloat64", inst->state == S3_INSTANTIATED ||
                                        inst->state == S3_INITIALIZATION ||
                                        inst->state == S3_STEP);
    if (nValues != nValueReferences)
        return refuse(inst, "fmi3SetFloat64: %lu values for %lu value references (scalars "
                      "only)", (unsigned long)nValues, (unsigned long)nValueReferences);
    for (i = 0; i < nValueReferences; i++) {
        long slot = find_slot(valueReferences[i], UNIT_REAL);
        const UnitVariable *v;
        if (slot < 0)
            return refuse(inst, "fmi3SetFloat64: value reference %u cannot be set",
                          valueReferences[i]);
        v = &UNIT_MODEL.variables[slot];
        if (v->causality == UNIT_OUTPUT)
            return refuse(inst, "fmi3SetFloat64: %s is an output", v->name);
        if (v->causality == UNIT_PARAMETER && inst->state == S3_STEP)
            return refuse(inst, "fmi3SetFloat64: parameter %s is fixed after initialization",
                          v->name);
        if (!isfinite(values[i]))
            return refuse(inst, "fmi3SetFloat64: %s must be finite, got %g", v->name,
                          values[i]);
        if (v->causality == UNIT_PARAMETER && inst->slots[slot] != values[i]) drop_unit(inst);
        inst->slots[slot] = values[i];
    }
    return fmi3OK;
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    Instance3 *inst = (Instance3 *)instance;
    double h = communicationStepSize;
    const char *bad;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (inst == NULL) return fmi3Error;
    if (eventHandlingNeeded != NULL) *eventHandlingNeeded = fmi3False;
    if (terminateSimulation != NULL) *terminateSimulation = fmi3False;
    if (earlyReturn != NULL) *earlyReturn = fmi3False;
    if (lastSuccessfulTime != NULL) *lastSuccessfulTime = inst->time;
    REQUIRE(inst, "fmi3DoStep", inst->state == S3_STEP);
    if (!isfinite(currentCommunicationPoint))
        return fail(inst, "fmi3DoStep: the communication point must be finite");
    if (!(isfinite(h) && h > 0.0))
        return fail(inst, "fmi3DoStep: the communication step must be finite and positive, "
                    "got %g s", h);
    if (h > FMU_MAX_STEP)
        return fail(inst, "fmi3DoStep: the communication step %g s is larger than %g s", h,
                    FMU_MAX_STEP);
    inst->reason[0] = '\0';
    if (!UNIT_MODEL.step(inst->unit, inst->slots, h, inst->reason, sizeof inst->reason))
        return fail(inst, "fmi3DoStep: %s", inst->reason);
    UNIT_MODEL.outputs(inst->unit, inst->slots);
    if ((bad = non_finite_output(inst)) != NULL)
        return fail(inst, "fmi3DoStep(t = %g, h = %g): output %s is not finite after the step",
                    currentCommunicationPoint, h, bad);
    inst->time = currentCommunicationPoint + h;
    if (lastSuccessfulTime != NULL) *lastSuccessfulTime = inst->time;
    return fmi3OK;
}

/* ------------------------------------------------------------------ not supported */
fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterEventMode");
}

fmi3Status fmi3GetFloat32(fmi3Instance instance,
                          const fmi3ValueReference valueReferences[],
                          size_t nValueReferences,
                          fmi3Float32 values[],
                          size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetFloat32");
}

fmi3Status fmi3GetInt8(fmi3Instance instance,
                       const fmi3ValueReference valueReferences[],
                       size_t nValueReferences,
                       fmi3Int8 values[],
                       size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetInt8");
}

fmi3Status fmi3GetUInt8(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        fmi3UInt8 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetUInt8");
}

fmi3Status fmi3GetInt16(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        fmi3Int16 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetInt16");
}

fmi3Status fmi3GetUInt16(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         fmi3UInt16 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetUInt16");
}

fmi3Status fmi3GetInt32(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        fmi3Int32 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetInt32");
}

fmi3Status fmi3GetUInt32(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         fmi3UInt32 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetUInt32");
}

fmi3Status fmi3GetInt64(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        fmi3Int64 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetInt64");
}

fmi3Status fmi3GetUInt64(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         fmi3UInt64 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetUInt64");
}

fmi3Status fmi3GetBoolean(fmi3Instance instance,
                          const fmi3ValueReference valueReferences[],
                          size_t nValueReferences,
                          fmi3Boolean values[],
                          size_t nValues)
{
    Instance3 *inst = (Instance3 *)instance;
    size_t i;
    if (inst == NULL) return fmi3Error;
    if (nValues != nValueReferences)
        return refuse(inst, "fmi3GetBoolean: %lu values for %lu value references (scalars "
                      "only)", (unsigned long)nValues, (unsigned long)nValueReferences);
    for (i = 0; i < nValueReferences; i++) {
        long slot = find_slot(valueReferences[i], UNIT_BOOLEAN);
        if (slot < 0)
            return refuse(inst, "fmi3GetBoolean: unknown value reference %u",
                          valueReferences[i]);
        values[i] = inst->slots[slot] != 0.0;
    }
    return fmi3OK;
}

fmi3Status fmi3GetString(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         fmi3String values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetString");
}

fmi3Status fmi3GetBinary(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         size_t valueSizes[],
                         fmi3Binary values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetBinary");
}

fmi3Status fmi3GetClock(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        fmi3Clock values[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    return unsupported(instance, "fmi3GetClock");
}

fmi3Status fmi3SetFloat32(fmi3Instance instance,
                          const fmi3ValueReference valueReferences[],
                          size_t nValueReferences,
                          const fmi3Float32 values[],
                          size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetFloat32");
}

fmi3Status fmi3SetInt8(fmi3Instance instance,
                       const fmi3ValueReference valueReferences[],
                       size_t nValueReferences,
                       const fmi3Int8 values[],
                       size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetInt8");
}

fmi3Status fmi3SetUInt8(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        const fmi3UInt8 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetUInt8");
}

fmi3Status fmi3SetInt16(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        const fmi3Int16 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetInt16");
}

fmi3Status fmi3SetUInt16(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         const fmi3UInt16 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetUInt16");
}

fmi3Status fmi3SetInt32(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        const fmi3Int32 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetInt32");
}

fmi3Status fmi3SetUInt32(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         const fmi3UInt32 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetUInt32");
}

fmi3Status fmi3SetInt64(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        const fmi3Int64 values[],
                        size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetInt64");
}

fmi3Status fmi3SetUInt64(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         const fmi3UInt64 values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetUInt64");
}

/* Boolean parameters (the only Booleans of the units): as fmi3SetFloat64's parameters. */
fmi3Status fmi3SetBoolean(fmi3Instance instance,
                          const fmi3ValueReference valueReferences[],
                          size_t nValueReferences,
                          const fmi3Boolean values[],
                          size_t nValues)
{
    Instance3 *inst = (Instance3 *)instance;
    size_t i;
    if (inst == NULL) return fmi3Error;
    REQUIRE(inst, "fmi3SetBoolean", inst->state == S3_INSTANTIATED ||
                                        inst->state == S3_INITIALIZATION ||
                                        inst->state == S3_STEP);
    if (nValues != nValueReferences)
        return refuse(inst, "fmi3SetBoolean: %lu values for %lu value references (scalars "
                      "only)", (unsigned long)nValues, (unsigned long)nValueReferences);
    for (i = 0; i < nValueReferences; i++) {
        long slot = find_slot(valueReferences[i], UNIT_BOOLEAN);
        double number = values[i] ? 1.0 : 0.0;
        if (slot < 0)
            return refuse(inst, "fmi3SetBoolean: value reference %u cannot be set",
                          valueReferences[i]);
        if (inst->state == S3_STEP)
            return refuse(inst, "fmi3SetBoolean: parameter %s is fixed after initialization",
                          UNIT_MODEL.variables[slot].name);
        if (inst->slots[slot] != number) drop_unit(inst);
        inst->slots[slot] = number;
    }
    return fmi3OK;
}

fmi3Status fmi3SetString(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         const fmi3String values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetString");
}

fmi3Status fmi3SetBinary(fmi3Instance instance,
                         const fmi3ValueReference valueReferences[],
                         size_t nValueReferences,
                         const size_t valueSizes[],
                         const fmi3Binary values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3SetBinary");
}

fmi3Status fmi3SetClock(fmi3Instance instance,
                        const fmi3ValueReference valueReferences[],
                        size_t nValueReferences,
                        const fmi3Clock values[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)values;
    return unsupported(instance, "fmi3SetClock");
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t* nDependencies)
{
    (void)valueReference;
    (void)nDependencies;
    return unsupported(instance, "fmi3GetNumberOfVariableDependencies");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance,
                                       fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
    (void)dependent;
    (void)elementIndicesOfDependent;
    (void)independents;
    (void)elementIndicesOfIndependents;
    (void)dependencyKinds;
    (void)nDependencies;
    return unsupported(instance, "fmi3GetVariableDependencies");
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState* FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3GetFMUState");
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3SetFMUState");
}

fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState* FMUState)
{
    (void)FMUState;
    return unsupported(instance, "fmi3FreeFMUState");
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance,
                                      fmi3FMUState FMUState,
                                      size_t* size)
{
    (void)FMUState;
    (void)size;
    return unsupported(instance, "fmi3SerializedFMUStateSize");
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance,
                                 fmi3FMUState FMUState,
                                 fmi3Byte serializedState[],
                                 size_t size)
{
    (void)FMUState;
    (void)serializedState;
    (void)size;
    return unsupported(instance, "fmi3SerializeFMUState");
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance,
                                   const fmi3Byte serializedState[],
                                   size_t size,
                                   fmi3FMUState* FMUState)
{
    (void)serializedState;
    (void)size;
    (void)FMUState;
    return unsupported(instance, "fmi3DeserializeFMUState");
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance,
                                        const fmi3ValueReference unknowns[],
                                        size_t nUnknowns,
                                        const fmi3ValueReference knowns[],
                                        size_t nKnowns,
                                        const fmi3Float64 seed[],
                                        size_t nSeed,
                                        fmi3Float64 sensitivity[],
                                        size_t nSensitivity)
{
    (void)unknowns;
    (void)nUnknowns;
    (void)knowns;
    (void)nKnowns;
    (void)seed;
    (void)nSeed;
    (void)sensitivity;
    (void)nSensitivity;
    return unsupported(instance, "fmi3GetDirectionalDerivative");
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance,
                                    const fmi3ValueReference unknowns[],
                                    size_t nUnknowns,
                                    const fmi3ValueReference knowns[],
                                    size_t nKnowns,
                                    const fmi3Float64 seed[],
                                    size_t nSeed,
                                    fmi3Float64 sensitivity[],
                                    size_t nSensitivity)
{
    (void)unknowns;
    (void)nUnknowns;
    (void)knowns;
    (void)nKnowns;
    (void)seed;
    (void)nSeed;
    (void)sensitivity;
    (void)nSensitivity;
    return unsupported(instance, "fmi3GetAdjointDerivative");
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterConfigurationMode");
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3ExitConfigurationMode");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences,
                                  fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)intervals;
    (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalDecimal");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences,
                                   fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[],
                                   fmi3IntervalQualifier qualifiers[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    (void)qualifiers;
    return unsupported(instance, "fmi3GetIntervalFraction");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance,
                               const fmi3ValueReference valueReferences[],
                               size_t nValueReferences,
                               fmi3Float64 shifts[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)shifts;
    return unsupported(instance, "fmi3GetShiftDecimal");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance,
                                const fmi3ValueReference valueReferences[],
                                size_t nValueReferences,
                                fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3GetShiftFraction");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences,
                                  const fmi3Float64 intervals[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)intervals;
    return unsupported(instance, "fmi3SetIntervalDecimal");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences,
                                   const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3SetIntervalFraction");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance,
                               const fmi3ValueReference valueReferences[],
                               size_t nValueReferences,
                               const fmi3Float64 shifts[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)shifts;
    return unsupported(instance, "fmi3SetShiftDecimal");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance,
                                const fmi3ValueReference valueReferences[],
                                size_t nValueReferences,
                                const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[])
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)counters;
    (void)resolutions;
    return unsupported(instance, "fmi3SetShiftFraction");
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EvaluateDiscreteStates");
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance,
                                    fmi3Boolean* discreteStatesNeedUpdate,
                                    fmi3Boolean* terminateSimulation,
                                    fmi3Boolean* nominalsOfContinuousStatesChanged,
                                    fmi3Boolean* valuesOfContinuousStatesChanged,
                                    fmi3Boolean* nextEventTimeDefined,
                                    fmi3Float64* nextEventTime)
{
    (void)discreteStatesNeedUpdate;
    (void)terminateSimulation;
    (void)nominalsOfContinuousStatesChanged;
    (void)valuesOfContinuousStatesChanged;
    (void)nextEventTimeDefined;
    (void)nextEventTime;
    return unsupported(instance, "fmi3UpdateDiscreteStates");
}

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterContinuousTimeMode");
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean* enterEventMode,
                                       fmi3Boolean* terminateSimulation)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    (void)enterEventMode;
    (void)terminateSimulation;
    return unsupported(instance, "fmi3CompletedIntegratorStep");
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
    (void)time;
    return unsupported(instance, "fmi3SetTime");
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance,
                                   const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates;
    (void)nContinuousStates;
    return unsupported(instance, "fmi3SetContinuousStates");
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance,
                                             fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
    (void)derivatives;
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStateDerivatives");
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance,
                                  fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
    (void)eventIndicators;
    (void)nEventIndicators;
    return unsupported(instance, "fmi3GetEventIndicators");
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance,
                                   fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
    (void)continuousStates;
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetContinuousStates");
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance,
                                             fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
    (void)nominals;
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNominalsOfContinuousStates");
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t* nEventIndicators)
{
    (void)nEventIndicators;
    return unsupported(instance, "fmi3GetNumberOfEventIndicators");
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t* nContinuousStates)
{
    (void)nContinuousStates;
    return unsupported(instance, "fmi3GetNumberOfContinuousStates");
}

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterStepMode");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences,
                                    const fmi3Int32 orders[],
                                    fmi3Float64 values[],
                                    size_t nValues)
{
    (void)valueReferences;
    (void)nValueReferences;
    (void)orders;
    (void)values;
    (void)nValues;
    return unsupported(instance, "fmi3GetOutputDerivatives");
}

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance,
                                      fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
    (void)clockReference;
    (void)activationTime;
    return unsupported(instance, "fmi3ActivateModelPartition");
}

