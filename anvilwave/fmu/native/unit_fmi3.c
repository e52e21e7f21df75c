/*
 * unit_fmi3.c -- the FMI 3.0 co-simulation layer of every native unit (Ram, PileSoil, Anvil,
 * AnvilLumped), compiled into the same binary as the FMI 2.0 layer (unit_fmu.c): the fmi3
 * functions over the same instance (unit_core.c, unit_core.h), one model (unit_model.h), one
 * resource (resources/anvilwave_unit.txt, whose GUID is the FMI 3.0 instantiationToken).
 *
 * The variables of the FMI 2.0 unit (Float64 for the Reals, Boolean, String) and the
 * independent variable time (the model's time_vr); the same rules and messages. Co-simulation
 * only, no event mode, no intermediate update, no FMU state, scalars only: the other functions
 * return fmi3Error with the reason logged.
 */
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "unit_core.h"

#define STATUS(x) ((fmi3Status)(x))

static void log_fmi3(const Unit *u, int status, const char *category, const char *message)
{
    fmi3LogMessageCallback logger = (fmi3LogMessageCallback)u->host.callback;
    if (logger != NULL) logger(u->host.environment, (fmi3Status)status, category, message);
}

static void set_host(UnitHost *host, fmi3InstanceEnvironment environment,
                     fmi3LogMessageCallback logMessage)
{
    host->log = log_fmi3;
    host->callback = (void (*)(void))logMessage;
    host->environment = environment;
}

/* An instantiation refused before there is an instance. */
static fmi3Instance refuse_instantiation(const char *name, fmi3InstanceEnvironment environment,
                                         fmi3LogMessageCallback logMessage, const char *message)
{
    Unit quiet;
    memset(&quiet, 0, sizeof quiet);
    set_host(&quiet.host, environment, logMessage);
    quiet.name = (char *)(name != NULL ? name : "");
    unit_log(&quiet, UNIT_STATUS_ERROR, "logStatusError", "%s", message);
    return NULL;
}

static fmi3Status unsupported(fmi3Instance instance, const char *function)
{
    return STATUS(unit_unsupported((Unit *)instance, function, "(co-simulation, no event "
                                   "mode, no FMU state)"));
}

/* Scalar variables only: as many values as value references. */
static int scalars(fmi3Instance instance, const char *function, size_t nValueReferences,
                   size_t nValues)
{
    if (nValues == nValueReferences) return 1;
    unit_log((Unit *)instance, UNIT_STATUS_ERROR, "logStatusError", "%s: %lu values for %lu "
             "value references (scalars only)", function, (unsigned long)nValues,
             (unsigned long)nValueReferences);
    return 0;
}

/* ------------------------------------------------------------------ life cycle */
const char *fmi3GetVersion(void) { return fmi3Version; }

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn,
                               size_t nCategories, const fmi3String categories[])
{
    return STATUS(unit_set_debug_logging((Unit *)instance, "fmi3SetDebugLogging", loggingOn,
                                         nCategories, categories));
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
    UnitHost host;
    Unit *u;
    char *folder;
    size_t n;
    (void)visible;
    (void)earlyReturnAllowed;
    (void)requiredIntermediateVariables;
    (void)nRequiredIntermediateVariables;
    (void)intermediateUpdate;
    if (eventModeUsed)
        return refuse_instantiation(instanceName, instanceEnvironment, logMessage,
                                    "fmi3InstantiateCoSimulation: this FMU has no event mode");
    set_host(&host, instanceEnvironment, logMessage);
    /* the resource path ends with a separator (FMI 3.0); the core takes the folder */
    folder = fmu_copy_string(resourcePath != NULL ? resourcePath : "");
    if (folder == NULL) return NULL;
    n = strlen(folder);
    while (n > 1 && (folder[n - 1] == '/' || folder[n - 1] == '\\')) folder[--n] = '\0';
    u = unit_instantiate("fmi3InstantiateCoSimulation", instanceName, "instantiation token",
                         instantiationToken, folder, &host, loggingOn);
    free(folder);
    return u;
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
    return refuse_instantiation(instanceName, instanceEnvironment, logMessage,
                                "fmi3InstantiateModelExchange: this FMU supports "
                                "co-simulation only");
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
    return refuse_instantiation(instanceName, instanceEnvironment, logMessage,
                                "fmi3InstantiateScheduledExecution: this FMU supports "
                                "co-simulation only");
}

void fmi3FreeInstance(fmi3Instance instance) { unit_free((Unit *)instance); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
    const char *function = "fmi3EnterInitializationMode";
    int status = unit_setup((Unit *)instance, function, startTime);
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    if (status != UNIT_STATUS_OK) return STATUS(status);
    return STATUS(unit_enter_initialization((Unit *)instance, function));
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
    return STATUS(unit_exit_initialization((Unit *)instance, "fmi3ExitInitializationMode"));
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
    return STATUS(unit_terminate((Unit *)instance, "fmi3Terminate"));
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
    return STATUS(unit_reset((Unit *)instance, "fmi3Reset"));
}

/* ------------------------------------------------------------------ variables */
fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3GetFloat64", nValueReferences, nValues)) return fmi3Error;
    return STATUS(unit_get_real((Unit *)instance, "fmi3GetFloat64", valueReferences,
                                nValueReferences, values, 1));
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3SetFloat64", nValueReferences, nValues)) return fmi3Error;
    return STATUS(unit_set_real((Unit *)instance, "fmi3SetFloat64", valueReferences,
                                nValueReferences, values));
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Boolean values[], size_t nValues)
{
    size_t i;
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3GetBoolean", nValueReferences, nValues)) return fmi3Error;
    for (i = 0; i < nValueReferences; i++) { /* fmi3Boolean is a bool, the core's an int */
        int value;
        int status = unit_get_boolean((Unit *)instance, "fmi3GetBoolean", &valueReferences[i],
                                      1, &value);
        if (status != UNIT_STATUS_OK) return STATUS(status);
        values[i] = value ? fmi3True : fmi3False;
    }
    return fmi3OK;
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Boolean values[], size_t nValues)
{
    size_t i;
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3SetBoolean", nValueReferences, nValues)) return fmi3Error;
    for (i = 0; i < nValueReferences; i++) {
        int value = values[i] ? 1 : 0;
        int status = unit_set_boolean((Unit *)instance, "fmi3SetBoolean", &valueReferences[i],
                                      1, &value);
        if (status != UNIT_STATUS_OK) return STATUS(status);
    }
    return fmi3OK;
}

fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3String values[], size_t nValues)
{
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3GetString", nValueReferences, nValues)) return fmi3Error;
    return STATUS(unit_get_string((Unit *)instance, "fmi3GetString", valueReferences,
                                  nValueReferences, values));
}

fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3String values[], size_t nValues)
{
    if (instance == NULL) return fmi3Error;
    if (!scalars(instance, "fmi3SetString", nValueReferences, nValues)) return fmi3Error;
    return STATUS(unit_set_string((Unit *)instance, "fmi3SetString", valueReferences,
                                  nValueReferences, values));
}

/* ------------------------------------------------------------------ stepping */
fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
    Unit *u = (Unit *)instance;
    int status;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (u == NULL) return fmi3Error;
    if (eventHandlingNeeded != NULL) *eventHandlingNeeded = fmi3False;
    if (terminateSimulation != NULL) *terminateSimulation = fmi3False;
    if (earlyReturn != NULL) *earlyReturn = fmi3False;
    status = unit_do_step(u, "fmi3DoStep", currentCommunicationPoint, communicationStepSize);
    if (lastSuccessfulTime != NULL) *lastSuccessfulTime = u->time;
    return STATUS(status);
}

/* ------------------------------------------------------------------ not supported */
/* The types the units have no variables of: fmi3Get<T> and fmi3Set<T> refuse any. */
#define NO_VARIABLES(T)                                                                          \
    fmi3Status fmi3Get##T(fmi3Instance instance, const fmi3ValueReference valueReferences[],   \
                          size_t nValueReferences, fmi3##T values[], size_t nValues)           \
    {                                                                                            \
        (void)valueReferences;                                                                   \
        (void)values;                                                                            \
        (void)nValues;                                                                           \
        return STATUS(unit_no_variables((Unit *)instance, "fmi3Get" #T, #T,                     \
                                        nValueReferences));                                      \
    }                                                                                            \
    fmi3Status fmi3Set##T(fmi3Instance instance, const fmi3ValueReference valueReferences[],   \
                          size_t nValueReferences, const fmi3##T values[], size_t nValues)     \
    {                                                                                            \
        (void)valueReferences;                                                                   \
        (void)values;                                                                            \
        (void)nValues;                                                                           \
        return STATUS(unit_no_variables((Unit *)instance, "fmi3Set" #T, #T,                     \
                                        nValueReferences));                                      \
    }

NO_VARIABLES(Float32)
NO_VARIABLES(Int8)
NO_VARIABLES(UInt8)
NO_VARIABLES(Int16)
NO_VARIABLES(UInt16)
NO_VARIABLES(Int32)
NO_VARIABLES(UInt32)
NO_VARIABLES(Int64)
NO_VARIABLES(UInt64)

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues)
{
    (void)valueReferences;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return STATUS(unit_no_variables((Unit *)instance, "fmi3GetBinary", "Binary",
                                    nValueReferences));
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
    (void)valueReferences;
    (void)valueSizes;
    (void)values;
    (void)nValues;
    return STATUS(unit_no_variables((Unit *)instance, "fmi3SetBinary", "Binary",
                                    nValueReferences));
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
    (void)valueReferences;
    (void)values;
    return STATUS(unit_no_variables((Unit *)instance, "fmi3GetClock", "Clock",
                                    nValueReferences));
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
    (void)valueReferences;
    (void)values;
    return STATUS(unit_no_variables((Unit *)instance, "fmi3SetClock", "Clock",
                                    nValueReferences));
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
    return unsupported(instance, "fmi3EnterEventMode");
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

