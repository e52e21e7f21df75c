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
 * FMI hygiene: fmi2Instantiate refuses (NULL, with an fmi2Error message) a GUID other than the
 * one of this FMU (resources/anvilwave_guid.txt, GUID_FILE, written by the build: the GUID of
 * modelDescription.xml, derived from the FMU's content), and a call made in a state that FMI 2.0
 * does not allow it in (e.g. fmi2Terminate or fmi2DoStep before initialization) returns
 * fmi2Error with the reason and is not forwarded.
 *
 * Python in a host that is not Python: see "the Python runtime" below (libpython of the
 * Python that built the FMU, loaded and initialized before pythonfmu, never finalized).
 *
 * Build (done by fmu/fmi_build.py):
 *   cc -shared -fPIC -O2 -fvisibility=hidden -o X.so this.c -ldl -lpthread
 */

#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <pthread.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <wchar.h>

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
static char load_error[8192] = "";

/* ---- the Python runtime, for hosts that are not Python ----
 *
 * pythonfmu's library calls the Python C API but is not linked with libpython: in a Python
 * process (fmpy, libcosimpy) the interpreter's symbols are already there; a C host has none
 * ("undefined symbol: _Py_NoneStruct"). Before loading that library the shim
 *
 * 1. looks for the C API in the process (Py_IsInitialized); if it is there, uses it;
 * 2. otherwise loads the libpython of the Python that built the FMU, which the build records
 *    in resources/anvilwave_python.txt (RUNTIME_FILE: executable, library, version, site
 *    directories), with RTLD_GLOBAL (its symbols resolve pythonfmu's) and RTLD_NODELETE (it is
 *    never unloaded). When that Python is gone, the first pythonX.Y (the recorded version) on
 *    the PATH is taken, with the libpythonX.Y.so beside it (../lib) or on the library path;
 * 3. if the interpreter is not initialized, initializes it (no signal handlers) with that
 *    executable as program name: for a venv's python, sys.prefix is the venv and its
 *    site-packages (with the .pth files of editable installs) are on sys.path, so anvilwave
 *    imports; the recorded site directories are added too. Then it releases the GIL.
 *
 * The interpreter is never finalized. pythonfmu 0.7.0, when it finds Python uninitialized,
 * initializes it on a thread of its own and finalizes it there when its state is released
 * (see release_pythonfmu). A finalized interpreter cannot be brought back for the extension
 * modules the units import (numpy refuses a second initialization in one process), and these
 * stay loaded with their threads (OpenBLAS, numba) whatever Python does. Initialized by the
 * shim first, Python is left alone by pythonfmu: the process exits with the interpreter alive,
 * and a host may free and instantiate the FMU again as often as it likes.
 */
#define RUNTIME_FILE "anvilwave_python.txt"
#define RUNTIME_TEXT 8192

typedef struct {
    char executable[4096];
    char library[4096];
    char version[32];
    char sites[RUNTIME_TEXT]; /* site directories, one a line */
} Runtime;

typedef int (*IsInitializedFunction)(void);

static int python_ready = 0;
static char python_note[8192] = ""; /* a warning for the host (another Python was taken) */
static pthread_mutex_t load_lock = PTHREAD_MUTEX_INITIALIZER;

static int hex_value(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

/* The resources folder of a file URI (file:///p, file:/p, file://localhost/p; %XX decoded). */
static void resource_folder(const char *uri, char *out, size_t size)
{
    const char *p = uri != NULL ? uri : "";
    size_t j = 0;
    if (strncmp(p, "file://localhost/", 17) == 0) p += 16;
    else if (strncmp(p, "file:///", 8) == 0) p += 7;
    else if (strncmp(p, "file:/", 6) == 0) p += 5;
    for (; *p != '\0' && j + 1 < size; p++) {
        if (p[0] == '%' && hex_value(p[1]) >= 0 && hex_value(p[2]) >= 0) {
            out[j++] = (char)(16 * hex_value(p[1]) + hex_value(p[2]));
            p += 2;
        } else {
            out[j++] = *p;
        }
    }
    while (j > 1 && out[j - 1] == '/') j--;
    out[j] = '\0';
}

/* resources/RUNTIME_FILE: "key = value" lines (executable, library, version, site ...). */
static int read_runtime(const char *resources, Runtime *rt)
{
    char path[4200], line[4200];
    FILE *file;
    memset(rt, 0, sizeof *rt);
    snprintf(path, sizeof path, "%.4000s/%s", resources, RUNTIME_FILE);
    file = fopen(path, "r");
    if (file == NULL) {
        snprintf(load_error, sizeof load_error, "%.4000s: %s (the FMU was built without it: "
                 "rebuild it with anvilwave)", path, strerror(errno));
        return 0;
    }
    while (fgets(line, sizeof line, file) != NULL) {
        char *eq = strchr(line, '='), *key = line, *value, *end;
        if (line[0] == '#' || eq == NULL) continue;
        *eq = '\0';
        value = eq + 1;
        while (*key == ' ') key++;
        for (end = eq; end > key && end[-1] == ' '; end--) end[-1] = '\0';
        while (*value == ' ') value++;
        value[strcspn(value, "\r\n")] = '\0';
        if (strcmp(key, "executable") == 0)
            snprintf(rt->executable, sizeof rt->executable, "%s", value);
        else if (strcmp(key, "library") == 0)
            snprintf(rt->library, sizeof rt->library, "%s", value);
        else if (strcmp(key, "version") == 0)
            snprintf(rt->version, sizeof rt->version, "%s", value);
        else if (strcmp(key, "site") == 0 && strlen(rt->sites) + strlen(value) + 2 <
                 sizeof rt->sites) {
            strcat(rt->sites, value);
            strcat(rt->sites, "\n");
        }
    }
    fclose(file);
    return 1;
}

/* The first "python<version>" on the PATH, into out; 0 if none. */
static int python_on_path(const char *version, char *out, size_t size)
{
    const char *path = getenv("PATH"), *p;
    if (path == NULL || version[0] == '\0') return 0;
    for (p = path; *p != '\0';) {
        size_t n = strcspn(p, ":");
        snprintf(out, size, "%.*s/python%s", (int)n, p, version);
        if (n > 0 && access(out, X_OK) == 0) return 1;
        p += n;
        if (*p == ':') p++;
    }
    return 0;
}

/* dlopen a libpython for the global namespace, kept for the life of the process. */
static void *open_python(const char *library)
{
    return dlopen(library, RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE);
}

/* libpython<version> of an executable found on the PATH: ../lib beside its real path, else the
 * library path. */
static void *python_library_of(const char *executable, const char *version, char *used,
                               size_t size)
{
    char real[4096], *slash;
    void *handle;
    static const char *names[] = {"lib/libpython%s.so.1.0", "lib/libpython%s.so"};
    size_t i;
    if (realpath(executable, real) != NULL && (slash = strrchr(real, '/')) != NULL) {
        *slash = '\0';
        slash = strrchr(real, '/');
        if (slash != NULL) slash[1] = '\0';
        for (i = 0; i < sizeof names / sizeof names[0]; i++) {
            char name[64];
            snprintf(name, sizeof name, names[i], version);
            snprintf(used, size, "%.4000s%s", real, name);
            if ((handle = open_python(used)) != NULL) return handle;
        }
    }
    snprintf(used, size, "libpython%s.so.1.0", version);
    return open_python(used);
}

/* Python code (for PyRun_SimpleString) that adds the site directories of rt->sites. */
static void site_code(const Runtime *rt, char *code, size_t size)
{
    const char *p = rt->sites;
    size_t j;
    j = (size_t)snprintf(code, size, "import os, site, sys\nfor d in [");
    while (*p != '\0' && j + 16 < size) {
        size_t n = strcspn(p, "\n");
        code[j++] = '\'';
        for (; n > 0 && j + 8 < size; n--, p++) {
            if (*p == '\\' || *p == '\'') code[j++] = '\\';
            code[j++] = *p;
        }
        code[j++] = '\'';
        code[j++] = ',';
        if (*p == '\n') p++;
    }
    snprintf(code + j, size - j, "]:\n    if os.path.isdir(d) and d not in sys.path:\n"
             "        site.addsitedir(d)\n");
}

/* Make the Python C API available and initialized (see the comment above); 1 when ready,
 * 0 with the reason in load_error. */
static int ensure_python(const char *resource_uri)
{
    typedef wchar_t *(*DecodeFunction)(const char *, size_t *);
    typedef void (*SetNameFunction)(const wchar_t *);
    typedef void (*InitializeFunction)(int);
    typedef void *(*SaveThreadFunction)(void);
    typedef int (*RunFunction)(const char *);
    char resources[4096], used[4096], code[RUNTIME_TEXT * 2 + 256];
    const char *executable = NULL;
    IsInitializedFunction is_initialized;
    Runtime rt;
    void *python = NULL;
    if (python_ready) return 1;
    *(void **)(&is_initialized) = dlsym(RTLD_DEFAULT, "Py_IsInitialized");
    resource_folder(resource_uri, resources, sizeof resources);
    if (is_initialized == NULL) { /* a host without Python: load the FMU's */
        if (!read_runtime(resources, &rt)) return 0;
        if (rt.library[0] == '\0' && rt.executable[0] == '\0') {
            snprintf(load_error, sizeof load_error, "%.999s/%s names no Python", resources,
                     RUNTIME_FILE);
            return 0;
        }
        if (rt.library[0] != '\0' && access(rt.library, R_OK) == 0) {
            python = open_python(rt.library);
            if (python == NULL) {
                const char *reason = dlerror();
                snprintf(load_error, sizeof load_error, "cannot load %.999s (the libpython "
                         "of %.999s, which built this FMU): %.999s", rt.library, rt.executable,
                         reason ? reason : "?");
                return 0;
            }
            executable = rt.executable;
        } else {
            char found[4096];
            if (!python_on_path(rt.version, found, sizeof found)) {
                snprintf(load_error, sizeof load_error, "this FMU runs its unit in Python "
                         "%.99s with anvilwave installed: the Python that built it (%.999s, "
                         "library %.999s) is gone and no python%.99s is on the PATH",
                         rt.version, rt.executable,
                         rt.library[0] ? rt.library : "none: a static build", rt.version);
                return 0;
            }
            python = python_library_of(found, rt.version, used, sizeof used);
            if (python == NULL) {
                const char *reason = dlerror();
                snprintf(load_error, sizeof load_error, "the Python that built this FMU "
                         "(%.999s) is gone; %.999s on the PATH has no loadable libpython%.99s "
                         "(%.999s): %.999s", rt.executable, found, rt.version, used,
                         reason ? reason : "?");
                return 0;
            }
            snprintf(python_note, sizeof python_note, "the Python that built this FMU (%.999s) "
                     "is gone: running its unit in %.999s from the PATH (library %.999s)",
                     rt.executable, found, used);
            memcpy(rt.executable, found, sizeof found);
            rt.sites[0] = '\0'; /* the recorded site directories belong to the other Python */
            executable = rt.executable;
        }
        *(void **)(&is_initialized) = dlsym(python, "Py_IsInitialized");
        if (is_initialized == NULL) {
            snprintf(load_error, sizeof load_error, "%.999s is not a libpython (no "
                     "Py_IsInitialized)", rt.library);
            return 0;
        }
    } else {
        rt.sites[0] = '\0';
    }
    if (!is_initialized()) {
        DecodeFunction decode;
        SetNameFunction set_name;
        InitializeFunction initialize;
        SaveThreadFunction save_thread;
        RunFunction run;
        *(void **)(&decode) = dlsym(RTLD_DEFAULT, "Py_DecodeLocale");
        *(void **)(&set_name) = dlsym(RTLD_DEFAULT, "Py_SetProgramName");
        *(void **)(&initialize) = dlsym(RTLD_DEFAULT, "Py_InitializeEx");
        *(void **)(&save_thread) = dlsym(RTLD_DEFAULT, "PyEval_SaveThread");
        *(void **)(&run) = dlsym(RTLD_DEFAULT, "PyRun_SimpleString");
        if (initialize == NULL || save_thread == NULL || run == NULL) {
            snprintf(load_error, sizeof load_error, "the Python C API lacks Py_InitializeEx, "
                     "PyEval_SaveThread or PyRun_SimpleString");
            return 0;
        }
        if (executable != NULL && executable[0] != '\0' && decode != NULL && set_name != NULL) {
            /* kept for the life of the interpreter, as Py_SetProgramName requires */
            wchar_t *name = decode(executable, NULL);
            if (name != NULL) set_name(name);
        }
        initialize(0);
        if (rt.sites[0] != '\0') {
            site_code(&rt, code, sizeof code);
            run(code);
        }
        save_thread(); /* the GIL is released; pythonfmu takes it per call */
    }
    python_ready = 1;
    return 1;
}


/* pythonfmu 0.7.0 keeps its Python state in a static std::shared_ptr (pyState) and releases it
 * twice when its library goes: once by the C++ destructor of the static, registered with
 * __cxa_atexit when the library is loaded, and once more by its ELF destructor
 * (onLibraryUnload -> finalizePythonInterpreter: pyState = nullptr), which runs after the first
 * on the destroyed object: the state's control block is freed twice. Its library is never
 * unloaded by dlclose (its STB_GNU_UNIQUE symbols make it RTLD_NODELETE), so both run at exit,
 * and the corrupted heap aborts the host in a later free() ("free(): corrupted unsorted
 * chunks", e.g. in libgfortran's destructor). The shim releases the state first, through the
 * library's own finalizePythonInterpreter, when it is unloaded itself or at exit (an atexit
 * handler registered after pythonfmu's static, so it runs before it): both later releases
 * then find an empty pointer. A new instance after that simply makes a new state. */
typedef void (*ReleaseFunction)(void);
static ReleaseFunction release_state = NULL;

static void release_pythonfmu(void)
{
    ReleaseFunction release = release_state;
    release_state = NULL;
    if (release != NULL) release();
}

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
    *(void **)(&release_state) = dlsym(inner_handle, "finalizePythonInterpreter");
    if (release_state != NULL) atexit(release_pythonfmu);
    return 1;
}

__attribute__((destructor)) static void unload_inner(void)
{
    release_pythonfmu();
    if (inner_handle != NULL) dlclose(inner_handle);
    inner_handle = NULL;
}

/* ---- one instance ---- */
enum { INSTANTIATED, INITIALIZATION, STEPPING, TERMINATED };
static const char *STATE_NAMES[] = {"instantiated", "initialization mode", "stepping",
                                    "terminated"};
#define GUID_FILE "anvilwave_guid.txt"

typedef struct {
    fmi2Component inner;
    int state;                   /* INSTANTIATED .. TERMINATED (FMI 2.0 co-simulation states) */
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

/* fmi2Error (logged) unless the instance is in one of the states of the mask (1 << state). */
static int refused(fmi2Component c, const char *call, int allowed)
{
    Shim *s = (Shim *)c;
    char message[256];  /* formatted here: the names hold no '%' for the host's printf */
    if (s == NULL) return 1;
    if (allowed & (1 << s->state)) return 0;
    snprintf(message, sizeof message, "%s is not allowed in the state '%s' (FMI 2.0 call "
             "sequence)", call, STATE_NAMES[s->state]);
    if (s->host.logger != NULL)
        s->host.logger(s->host.componentEnvironment, "", fmi2Error, "", message);
    return 1;
}

#define IN_STATES(c, call, allowed)                                                              \
    do {                                                                                         \
        if (refused(c, call, allowed)) return fmi2Error;                                         \
    } while (0)
#define ANY_STATE ((1 << INSTANTIATED) | (1 << INITIALIZATION) | (1 << STEPPING) |             \
                   (1 << TERMINATED))

/* The FMU's own GUID (resources/GUID_FILE); 1 when it matches or the file is absent. */
static int guid_matches(const char *resource_uri, const char *guid, char *expected,
                        size_t size)
{
    char resources[4096], path[4200];
    FILE *f;
    size_t n;
    expected[0] = '\0';
    if (resource_uri == NULL) return 1;
    resource_folder(resource_uri, resources, sizeof resources);
    snprintf(path, sizeof path, "%.4000s/%s", resources, GUID_FILE);
    f = fopen(path, "r");
    if (f == NULL) return 1;
    n = fread(expected, 1, size - 1, f);
    fclose(f);
    expected[n] = '\0';
    while (n > 0 && (expected[n - 1] == '\n' || expected[n - 1] == '\r' ||
                     expected[n - 1] == ' '))
        expected[--n] = '\0';
    return guid != NULL && strcmp(guid, expected) == 0;
}

EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }

EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType,
                                     fmi2String fmuGUID, fmi2String fmuResourceLocation,
                                     const fmi2CallbackFunctions *functions,
                                     fmi2Boolean visible, fmi2Boolean loggingOn)
{
    Shim *s;
    int python, loaded = 0;
    char expected[256], message[700];
    if (functions == NULL) return NULL;
    if (!guid_matches(fmuResourceLocation, fmuGUID, expected, sizeof expected)) {
        snprintf(message, sizeof message, "wrong GUID %.200s: this FMU is %.200s (instantiate "
                 "it with the GUID of its modelDescription.xml)", fmuGUID ? fmuGUID : "(null)",
                 expected);
        for (char *p = message; *p; p++)
            if (*p == '%') *p = '?';  /* the host's logger takes it as a printf format */
        if (functions->logger != NULL)
            functions->logger(functions->componentEnvironment, instanceName, fmi2Error, "",
                              message);
        return NULL;
    }
    pthread_mutex_lock(&load_lock);
    python = ensure_python(fmuResourceLocation);
    if (python) loaded = load_inner();
    pthread_mutex_unlock(&load_lock);
    if (!loaded) {
        if (functions->logger != NULL)
            functions->logger(functions->componentEnvironment, instanceName, fmi2Fatal, "",
                              python ? "cannot load " INNER_LIBRARY ": %s"
                                     : "cannot start Python: %s", load_error);
        return NULL;
    }
    if (python_note[0] != '\0' && functions->logger != NULL)
        functions->logger(functions->componentEnvironment, instanceName, fmi2Warning, "",
                          "%s", python_note);
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
    IN_STATES(c, "fmi2SetupExperiment", 1 << INSTANTIATED);
    FORWARD(c, SetupExperiment(C(c), toleranceDefined, tolerance, startTime, stopTimeDefined,
                               stopTime));
}

/* a forwarded call that moves the instance to `next` when it did not fail */
#define FORWARD_TO(c, call, next)                                                                \
    do {                                                                                         \
        Shim *s_ = (Shim *)(c);                                                                  \
        fmi2Status status_;                                                                      \
        s_->error_logged = 0;                                                                    \
        status_ = inner.call;                                                                    \
        if (status_ < fmi2Error && s_->error_logged) status_ = fmi2Error;                        \
        if (status_ <= fmi2Warning) s_->state = (next);                                          \
        return status_;                                                                          \
    } while (0)

EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c)
{
    IN_STATES(c, "fmi2EnterInitializationMode", 1 << INSTANTIATED);
    FORWARD_TO(c, EnterInitializationMode(C(c)), INITIALIZATION);
}

EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c)
{
    IN_STATES(c, "fmi2ExitInitializationMode", 1 << INITIALIZATION);
    FORWARD_TO(c, ExitInitializationMode(C(c)), STEPPING);
}

EXPORT fmi2Status fmi2Terminate(fmi2Component c)
{
    IN_STATES(c, "fmi2Terminate", 1 << STEPPING);
    FORWARD_TO(c, Terminate(C(c)), TERMINATED);
}

EXPORT fmi2Status fmi2Reset(fmi2Component c)
{
    IN_STATES(c, "fmi2Reset", ANY_STATE);
    FORWARD_TO(c, Reset(C(c)), INSTANTIATED);
}

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
    IN_STATES(c, "fmi2DoStep", 1 << STEPPING);
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
