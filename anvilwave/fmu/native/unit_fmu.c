/*
 * unit_fmu.c -- the FMI 2.0 co-simulation layer of every native unit (Ram, PileSoil, Anvil,
 * AnvilLumped): the fmi2 functions over the instance of unit_core.c (life cycle, variables,
 * errors: unit_core.h) and the model of unit_model.h.
 *
 * fmi2Instantiate takes the resources folder from fmuResourceLocation (a file URI) and the GUID
 * as the instantiation token. Reals through fmi2GetReal/fmi2SetReal, Boolean parameters through
 * fmi2GetBoolean/fmi2SetBoolean, String parameters through fmi2GetString/fmi2SetString; no
 * Integers. Co-simulation only, no FMU state, no derivatives, no asynchronous steps: those
 * functions return fmi2Error with the reason logged.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "unit_core.h"

/* The host's fmi2CallbackLogger; a % in the message is escaped, since hosts treat the message
 * as a printf format. */
static void log_fmi2(const Unit *u, int status, const char *category, const char *message)
{
    fmi2CallbackLogger logger = (fmi2CallbackLogger)u->host.callback;
    char escaped[2 * FMU_MESSAGE_SIZE];
    size_t i, j;
    if (logger == NULL) return;
    for (i = 0, j = 0; message[i] != '\0' && j + 2 < sizeof escaped; i++) {
        escaped[j++] = message[i];
        if (message[i] == '%') escaped[j++] = '%';
    }
    escaped[j] = '\0';
    logger(u->host.environment, u->name, (fmi2Status)status, category, escaped);
}

#define STATUS(x) ((fmi2Status)(x))

/* ------------------------------------------------------------------ inquiry, life cycle */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    return STATUS(unit_set_debug_logging((Unit *)c, "fmi2SetDebugLogging", loggingOn,
                                         nCategories, categories));
}

fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                              fmi2String fmuResourceLocation,
                              const fmi2CallbackFunctions *functions, fmi2Boolean visible,
                              fmi2Boolean loggingOn)
{
    UnitHost host;
    Unit *u;
    char *resources;
    (void)visible;
    if (functions == NULL) return NULL;
    host.log = log_fmi2;
    host.callback = (void (*)(void))functions->logger;
    host.environment = functions->componentEnvironment;
    if (fmuType != fmi2CoSimulation) {
        Unit quiet;
        memset(&quiet, 0, sizeof quiet);
        quiet.host = host;
        quiet.name = (char *)(instanceName != NULL ? instanceName : "");
        unit_log(&quiet, UNIT_STATUS_ERROR, "logStatusError", "fmi2Instantiate: this FMU "
                 "supports co-simulation only (fmuType = %d)", (int)fmuType);
        return NULL;
    }
    resources = fmu_resource_folder(fmuResourceLocation);
    if (resources == NULL) return NULL;
    u = unit_instantiate("fmi2Instantiate", instanceName, "GUID", fmuGUID, resources, &host,
                         loggingOn);
    free(resources);
    return u;
}

void fmi2FreeInstance(fmi2Component c) { unit_free((Unit *)c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                               fmi2Real tolerance, fmi2Real startTime,
                               fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    return STATUS(unit_setup((Unit *)c, "fmi2SetupExperiment", startTime));
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    return STATUS(unit_enter_initialization((Unit *)c, "fmi2EnterInitializationMode"));
}

fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    return STATUS(unit_exit_initialization((Unit *)c, "fmi2ExitInitializationMode"));
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    return STATUS(unit_terminate((Unit *)c, "fmi2Terminate"));
}

fmi2Status fmi2Reset(fmi2Component c) { return STATUS(unit_reset((Unit *)c, "fmi2Reset")); }

/* ------------------------------------------------------------------ variables */
fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    return STATUS(unit_get_real((Unit *)c, "fmi2GetReal", vr, nvr, value, 0));
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    return STATUS(unit_set_real((Unit *)c, "fmi2SetReal", vr, nvr, value));
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    (void)vr;
    (void)value;
    return STATUS(unit_no_variables((Unit *)c, "fmi2GetInteger", "Integer", nvr));
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    (void)vr;
    (void)value;
    return STATUS(unit_no_variables((Unit *)c, "fmi2SetInteger", "Integer", nvr));
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    return STATUS(unit_get_boolean((Unit *)c, "fmi2GetBoolean", vr, nvr, value));
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    return STATUS(unit_set_boolean((Unit *)c, "fmi2SetBoolean", vr, nvr, value));
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    return STATUS(unit_get_string((Unit *)c, "fmi2GetString", vr, nvr, value));
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    return STATUS(unit_set_string((Unit *)c, "fmi2SetString", vr, nvr, value));
}

/* ------------------------------------------------------------------ stepping */
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    (void)noSetFMUStatePriorToCurrentPoint;
    return STATUS(unit_do_step((Unit *)c, "fmi2DoStep", currentCommunicationPoint,
                               communicationStepSize));
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    return STATUS(unit_unsupported((Unit *)c, "fmi2CancelStep", "(fmi2DoStep never returns "
                                   "fmi2Pending)"));
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    Unit *u = (Unit *)c;
    if (u != NULL && s == fmi2LastSuccessfulTime && value != NULL) {
        *value = u->time;
        return fmi2OK;
    }
    return STATUS(unit_unsupported(u, "fmi2GetRealStatus", "(only fmi2LastSuccessfulTime: the "
                                   "FMU steps synchronously)"));
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    if (c != NULL && s == fmi2Terminated && value != NULL) {
        *value = fmi2False; /* a unit never asks to end the simulation */
        return fmi2OK;
    }
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetBooleanStatus", "(only fmi2Terminated: "
                                   "the FMU steps synchronously)"));
}

/* ------------------------------------------------------------------ not supported */
#define SYNCHRONOUS "(the FMU steps synchronously, there is no pending status)"
#define NO_STATE "(canGetAndSetFMUstate = false)"
#define NO_SERIALIZE "(canSerializeFMUstate = false)"

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)s;
    (void)value;
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetStatus", SYNCHRONOUS));
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetIntegerStatus", SYNCHRONOUS));
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetStringStatus", SYNCHRONOUS));
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetFMUstate", NO_STATE));
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    (void)FMUstate;
    return STATUS(unit_unsupported((Unit *)c, "fmi2SetFMUstate", NO_STATE));
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    return STATUS(unit_unsupported((Unit *)c, "fmi2FreeFMUstate", NO_STATE));
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)FMUstate;
    (void)size;
    return STATUS(unit_unsupported((Unit *)c, "fmi2SerializedFMUstateSize", NO_SERIALIZE));
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte bytes[],
                                 size_t size)
{
    (void)FMUstate;
    (void)bytes;
    (void)size;
    return STATUS(unit_unsupported((Unit *)c, "fmi2SerializeFMUstate", NO_SERIALIZE));
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    (void)serializedState;
    (void)size;
    (void)FMUstate;
    return STATUS(unit_unsupported((Unit *)c, "fmi2DeSerializeFMUstate", NO_SERIALIZE));
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
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetDirectionalDerivative",
                                   "(providesDirectionalDerivative = false)"));
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    if (c != NULL && nvr == 0) return fmi2OK;
    return STATUS(unit_unsupported((Unit *)c, "fmi2SetRealInputDerivatives",
                                   "(canInterpolateInputs = false)"));
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    if (c != NULL && nvr == 0) return fmi2OK;
    return STATUS(unit_unsupported((Unit *)c, "fmi2GetRealOutputDerivatives",
                                   "(maxOutputDerivativeOrder = 0)"));
}
