/*
 * fmi2_status_shim.c -- FMI 2.0 co-simulation pass-through that reports logged errors.
 *
 * Why: pythonfmu 0.7.0 has no way for a Python slave to return fmi2Error. A Python exception
 * becomes fmi2Fatal (and pythonfmu drops its reference to the slave, so the instance is unsafe
 * afterwards); do_step returning False becomes fmi2Discard; every other call returns fmi2OK.
 * The anvilwave slaves therefore never raise: they log the reason with status fmi2Error.
 *
 * What: this library is the FMU's binaries/<platform>/<modelIdentifier>.so. It loads the
 * pythonfmu library shipped next to it (pythonfmu-export.so), forwards every FMI call to it and,
 * when the slave logged a message with status >= fmi2Error during a call that returned less than
 * fmi2Error, returns fmi2Error instead. Nothing else changes: values, states and the call
 * sequence are pythonfmu's.
 *
 * Logging: pythonfmu only calls the logger when debug logging is on, so the inner instance is
 * always created with loggingOn = fmi2True; the shim forwards warnings and errors to the host
 * always and other messages only while the host has debug logging on (fmi2SetDebugLogging is
 * recorded, not forwarded; categories are not filtered). Forwarded messages have '%' doubled
 * because the host logger treats the message as a printf format.
 *
 * Build (done by fmu/fmi_build.py): cc -shared -fPIC -O2 -fvisibility=hidden -o X.so this.c -ldl
 */

#define _GNU_SOURCE
#include <dlfcn.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EXPORT __attribute__((visibility("default")))
#define INNER_LIBRARY "pythonfmu-export.so"

/* ---- FMI 2.0 types (fmi2TypesPlatform.h / fmi2FunctionTypes.h) ---- */
typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
typedef char fmi2Byte;

typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum {
    fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated
} fmi2StatusKind;

typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String,
                                   fmi2String, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t, size_t);
typedef void (*fmi2CallbackFreeMemory)(void *);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);

typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

/* ---- the inner (pythonfmu) library ---- */
#define INNER_FUNCTIONS(X)                                                                       \
    X(fmi2Component, Instantiate, (fmi2String, fmi2Type, fmi2String, fmi2String,                \
                                   const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean))    \
    X(void, FreeInstance, (fmi2Component))                                                      \
    X(fmi2Status, SetupExperiment, (fmi2Component, fmi2Boolean, fmi2Real, fmi2Real,             \
                                    fmi2Boolean, fmi2Real))                                      \
    X(fmi2Status, EnterInitializationMode, (fmi2Component))                                     \
    X(fmi2Status, ExitInitializationMode, (fmi2Component))                                      \
    X(fmi2Status, Terminate, (fmi2Component))                                                   \
    X(fmi2Status, Reset, (fmi2Component))                                                       \
    X(fmi2Status, GetReal, (fmi2Component, const fmi2ValueReference *, size_t, fmi2Real *))     \
    X(fmi2Status, GetInteger, (fmi2Component, const fmi2ValueReference *, size_t,               \
                               fmi2Integer *))                                                  \
    X(fmi2Status, GetBoolean, (fmi2Component, const fmi2ValueReference *, size_t,               \
                               fmi2Boolean *))                                                  \
    X(fmi2Status, GetString, (fmi2Component, const fmi2ValueReference *, size_t, fmi2String *)) \
    X(fmi2Status, SetReal, (fmi2Component, const fmi2ValueReference *, size_t,                  \
                            const fmi2Real *))                                                  \
    X(fmi2Status, SetInteger, (fmi2Component, const fmi2ValueReference *, size_t,               \
                               const fmi2Integer *))                                            \
    X(fmi2Status, SetBoolean, (fmi2Component, const fmi2ValueReference *, size_t,               \
                               const fmi2Boolean *))                                            \
    X(fmi2Status, SetString, (fmi2Component, const fmi2ValueReference *, size_t,                \
                              const fmi2String *))                                              \
    X(fmi2Status, GetFMUstate, (fmi2Component, fmi2FMUstate *))                                 \
    X(fmi2Status, SetFMUstate, (fmi2Component, fmi2FMUstate))                                   \
    X(fmi2Status, FreeFMUstate, (fmi2Component, fmi2FMUstate *))                                \
    X(fmi2Status, SerializedFMUstateSize, (fmi2Component, fmi2FMUstate, size_t *))              \
    X(fmi2Status, SerializeFMUstate, (fmi2Component, fmi2FMUstate, fmi2Byte[], size_t))         \
    X(fmi2Status, DeSerializeFMUstate, (fmi2Component, const fmi2Byte[], size_t,                \
                                        fmi2FMUstate *))                                        \
    X(fmi2Status, GetDirectionalDerivative, (fmi2Component, const fmi2ValueReference[], size_t, \
                                             const fmi2ValueReference[], size_t,                \
                                             const fmi2Real[], fmi2Real[]))                     \
    X(fmi2Status, SetRealInputDerivatives, (fmi2Component, const fmi2ValueReference[], size_t,  \
                                            const fmi2Integer[], const fmi2Real[]))             \
    X(fmi2Status, GetRealOutputDerivatives, (fmi2Component, const fmi2ValueReference[], size_t, \
                                             const fmi2Integer[], fmi2Real[]))                  \
    X(fmi2Status, DoStep, (fmi2Component, fmi2Real, fmi2Real, fmi2Boolean))                     \
    X(fmi2Status, CancelStep, (fmi2Component))                                                  \
    X(fmi2Status, GetStatus, (fmi2Component, const fmi2StatusKind, fmi2Status *))               \
    X(fmi2Status, GetRealStatus, (fmi2Component, const fmi2StatusKind, fmi2Real *))             \
    X(fmi2Status, GetIntegerStatus, (fmi2Component, const fmi2StatusKind, fmi2Integer *))       \
    X(fmi2Status, GetBooleanStatus, (fmi2Component, const fmi2StatusKind, fmi2Boolean *))       \
    X(fmi2Status, GetStringStatus, (fmi2Component, const fmi2StatusKind, fmi2String *))

#define DECLARE_POINTER(ret, name, args) ret(*name) args;
static struct { INNER_FUNCTIONS(DECLARE_POINTER) } inner;
static void *inner_handle = NULL;
static char load_error[1024] = "";

static int load_inner(void)
{
    Dl_info info;
    char path[4096];
    char *slash;
    if (inner_handle != NULL) return 1;
    if (dladdr((void *)&load_inner, &info) == 0 || info.dli_fname == NULL) {
        strcpy(load_error, "cannot locate the FMU binary");
        return 0;
    }
    snprintf(path, sizeof(path) - sizeof(INNER_LIBRARY), "%s", info.dli_fname);
    slash = strrchr(path, '/');
    if (slash == NULL) path[0] = '\0'; else slash[1] = '\0';
    strcat(path, INNER_LIBRARY);
    inner_handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (inner_handle == NULL) {
        const char *reason = dlerror();
        snprintf(load_error, sizeof(load_error), "%s", reason ? reason : path);
        return 0;
    }
#define LOAD_POINTER(ret, name, args)                                                            \
    *(void **)(&inner.name) = dlsym(inner_handle, "fmi2" #name);                                 \
    if (inner.name == NULL) {                                                                    \
        strcpy(load_error, "pythonfmu library lacks fmi2" #name);                                \
        dlclose(inner_handle);                                                                   \
        inner_handle = NULL;                                                                     \
        return 0;                                                                                \
    }
    INNER_FUNCTIONS(LOAD_POINTER)
    return 1;
}

__attribute__((destructor)) static void unload_inner(void)
{
    if (inner_handle != NULL) dlclose(inner_handle);
    inner_handle = NULL;
}

/* ---- one instance ---- */
typedef struct {
    fmi2Component inner;
    fmi2CallbackFunctions host;  /* the host's callbacks */
    fmi2CallbackFunctions mine;  /* given to pythonfmu: logger = shim_logger, environment = us */
    int logging_on;
    int error_logged;            /* a message with status >= fmi2Error since the call began */
} Shim;

static void shim_logger(fmi2ComponentEnvironment environment, fmi2String instanceName,
                        fmi2Status status, fmi2String category, fmi2String message, ...)
{
    Shim *s = (Shim *)environment;
    size_t n, i, j;
    char *escaped;
    if (s == NULL) return;
    if (status >= fmi2Error) s->error_logged = 1;
    if (s->host.logger == NULL || (status < fmi2Warning && !s->logging_on)) return;
    if (message == NULL) message = "";
    n = strlen(message);
    escaped = (char *)malloc(2 * n + 1);
    if (escaped == NULL) return;
    for (i = 0, j = 0; i < n; i++) {
        escaped[j++] = message[i];
        if (message[i] == '%') escaped[j++] = '%';
    }
    escaped[j] = '\0';
    s->host.logger(s->host.componentEnvironment, instanceName, status,
                   category ? category : "", escaped);
    free(escaped);
}

#define FORWARD(c, call)                                                                         \
    do {                                                                                         \
        Shim *s_ = (Shim *)(c);                                                                  \
        fmi2Status status_;                                                                      \
        if (s_ == NULL) return fmi2Error;                                                        \
        s_->error_logged = 0;                                                                    \
        status_ = inner.call;                                                                    \
        if (status_ < fmi2Error && s_->error_logged) status_ = fmi2Error;                        \
        return status_;                                                                          \
    } while (0)

#define C(c) (((Shim *)(c))->inner)

EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }

EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType,
                                     fmi2String fmuGUID, fmi2String fmuResourceLocation,
                                     const fmi2CallbackFunctions *functions,
                                     fmi2Boolean visible, fmi2Boolean loggingOn)
{
    Shim *s;
    if (functions == NULL) return NULL;
    if (!load_inner()) {
        if (functions->logger != NULL)
            functions->logger(functions->componentEnvironment, instanceName, fmi2Fatal, "",
                              "cannot load " INNER_LIBRARY ": %s", load_error);
        return NULL;
    }
    s = (Shim *)calloc(1, sizeof(Shim));
    if (s == NULL) return NULL;
    s->host = *functions;
    s->mine = *functions;
    s->mine.logger = shim_logger;
    s->mine.componentEnvironment = s;
    s->logging_on = loggingOn;
    s->inner = inner.Instantiate(instanceName, fmuType, fmuGUID, fmuResourceLocation, &s->mine,
                                 visible, 1);
    if (s->inner == NULL) {
        free(s);
        return NULL;
    }
    return s;
}

EXPORT void fmi2FreeInstance(fmi2Component c)
{
    Shim *s = (Shim *)c;
    if (s == NULL) return;
    inner.FreeInstance(s->inner);
    free(s);
}

EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                                      const fmi2String categories[])
{
    (void)nCategories;
    (void)categories;
    if (c == NULL) return fmi2Error;
    ((Shim *)c)->logging_on = loggingOn;
    return fmi2OK;
}

EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                                      fmi2Real tolerance, fmi2Real startTime,
                                      fmi2Boolean stopTimeDefined, fmi2Real stopTime)
{
    FORWARD(c, SetupExperiment(C(c), toleranceDefined, tolerance, startTime, stopTimeDefined,
                               stopTime));
}

EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    FORWARD(c, EnterInitializationMode(C(c)));
}

EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    FORWARD(c, ExitInitializationMode(C(c)));
}

EXPORT fmi2Status fmi2Terminate(fmi2Component c) { FORWARD(c, Terminate(C(c))); }

EXPORT fmi2Status fmi2Reset(fmi2Component c) { FORWARD(c, Reset(C(c))); }

EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                              fmi2Real value[])
{
    FORWARD(c, GetReal(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                 fmi2Integer value[])
{
    FORWARD(c, GetInteger(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                 fmi2Boolean value[])
{
    FORWARD(c, GetBoolean(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                fmi2String value[])
{
    FORWARD(c, GetString(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                              const fmi2Real value[])
{
    FORWARD(c, SetReal(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                 const fmi2Integer value[])
{
    FORWARD(c, SetInteger(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                 const fmi2Boolean value[])
{
    FORWARD(c, SetBoolean(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                const fmi2String value[])
{
    FORWARD(c, SetString(C(c), vr, nvr, value));
}

EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    FORWARD(c, GetFMUstate(C(c), state));
}

EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate state)
{
    FORWARD(c, SetFMUstate(C(c), state));
}

EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state)
{
    FORWARD(c, FreeFMUstate(C(c), state));
}

EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size)
{
    FORWARD(c, SerializedFMUstateSize(C(c), state, size));
}

EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[],
                                        size_t size)
{
    FORWARD(c, SerializeFMUstate(C(c), state, bytes, size));
}

EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size,
                                          fmi2FMUstate *state)
{
    FORWARD(c, DeSerializeFMUstate(C(c), bytes, size, state));
}

EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c,
                                               const fmi2ValueReference vUnknown_ref[],
                                               size_t nUnknown,
                                               const fmi2ValueReference vKnown_ref[],
                                               size_t nKnown, const fmi2Real dvKnown[],
                                               fmi2Real dvUnknown[])
{
    FORWARD(c, GetDirectionalDerivative(C(c), vUnknown_ref, nUnknown, vKnown_ref, nKnown,
                                        dvKnown, dvUnknown));
}

EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                              size_t nvr, const fmi2Integer order[],
                                              const fmi2Real value[])
{
    FORWARD(c, SetRealInputDerivatives(C(c), vr, nvr, order, value));
}

EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                               size_t nvr, const fmi2Integer order[],
                                               fmi2Real value[])
{
    FORWARD(c, GetRealOutputDerivatives(C(c), vr, nvr, order, value));
}

EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                             fmi2Real communicationStepSize,
                             fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    FORWARD(c, DoStep(C(c), currentCommunicationPoint, communicationStepSize,
                      noSetFMUStatePriorToCurrentPoint));
}

EXPORT fmi2Status fmi2CancelStep(fmi2Component c) { FORWARD(c, CancelStep(C(c))); }

EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    FORWARD(c, GetStatus(C(c), s, value));
}

EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    FORWARD(c, GetRealStatus(C(c), s, value));
}

EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s,
                                       fmi2Integer *value)
{
    FORWARD(c, GetIntegerStatus(C(c), s, value));
}

EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s,
                                       fmi2Boolean *value)
{
    FORWARD(c, GetBooleanStatus(C(c), s, value));
}

EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    FORWARD(c, GetStringStatus(C(c), s, value));
}
