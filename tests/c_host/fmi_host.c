/*
 * fmi_host.c -- a small, generic FMI 2.0 co-simulation host in plain C (no Python), used by
 * tests/test_native_anvil.py to run an FMU the way a non-Python tool does.
 *
 * It loads the binary of an unzipped FMU with dlopen, instantiates several instances, sets
 * parameters, initializes them and steps them in lock-step with prescribed input signals,
 * then resets them, runs the same again and compares the two runs bit for bit; finally it
 * terminates and frees the instances and unloads the binary. Exit status 0 means: every FMI
 * call returned fmi2OK (or fmi2Warning), no error was logged, the rerun after fmi2Reset gave
 * bitwise the same outputs, and instances with the same parameters gave the same outputs.
 *
 * usage: fmi_host FMU_DIR MODEL_IDENTIFIER GUID [options]
 *   --inputs VR,VR,...        Real inputs set before each step
 *   --outputs VR,VR,...       Real outputs read after setting the inputs, before the step
 *   --real VR=VALUE           Real parameter set before initialization (repeatable)
 *   --boolean VR=0|1          Boolean parameter (repeatable)
 *   --string VR=TEXT          String parameter (repeatable)
 *   --signal VR=c0,c1,c2,a,b,f
 *                             input VR at time t: c0 + c1 t + c2 t^2 + a sin(2 pi f t)
 *                             + b cos(2 pi f t) (an input without a signal is 0)
 *   --steps N                 communication steps per run (default 20000)
 *   --step-size H             communication step [s] (default 1e-6)
 *   --start-time T            [s] (default 0); t_n = T + n H, from the step count
 *   --instances N             instances run side by side (default 2)
 *   --csv PATH                time, inputs and outputs of the first instance's first run
 *                             (%.17g, so the numbers read back exactly)
 *
 * Any FMU with Real inputs and outputs fits (Anvil, AnvilLumped, Ram, PileSoil ...).
 * Build: cc -std=c99 -O2 -I fmu/native -o fmi_host tests/c_host/fmi_host.c -ldl -lm
 * (fmu/native holds the FMI 2.0 headers).
 */
#define _XOPEN_SOURCE 700

#include <dlfcn.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi2FunctionTypes.h"

#define MAX_VARIABLES 64
#define MAX_PARAMETERS 64
#define MAX_INSTANCES 16
#define TWO_PI 6.283185307179586

typedef struct {
    fmi2GetTypesPlatformTYPE *GetTypesPlatform;
    fmi2GetVersionTYPE *GetVersion;
    fmi2InstantiateTYPE *Instantiate;
    fmi2FreeInstanceTYPE *FreeInstance;
    fmi2SetupExperimentTYPE *SetupExperiment;
    fmi2EnterInitializationModeTYPE *EnterInitializationMode;
    fmi2ExitInitializationModeTYPE *ExitInitializationMode;
    fmi2TerminateTYPE *Terminate;
    fmi2ResetTYPE *Reset;
    fmi2GetRealTYPE *GetReal;
    fmi2SetRealTYPE *SetReal;
    fmi2SetBooleanTYPE *SetBoolean;
    fmi2SetStringTYPE *SetString;
    fmi2DoStepTYPE *DoStep;
} Api;

typedef struct {
    char kind; /* 'r', 'b', 's' */
    fmi2ValueReference vr;
    double real;
    fmi2Boolean boolean;
    const char *string;
} Parameter;

typedef struct {
    double c0, c1, c2, a, b, f;
} Signal;

static int errors_logged = 0;

static void logger(fmi2ComponentEnvironment environment, fmi2String instanceName,
                   fmi2Status status, fmi2String category, fmi2String message, ...)
{
    static const char *names[] = {"OK", "Warning", "Discard", "Error", "Fatal", "Pending"};
    va_list args;
    (void)environment;
    if (status >= fmi2Error) errors_logged++;
    fprintf(stderr, "[%s] %s (%s): ", (unsigned)status < 6 ? names[status] : "?",
            instanceName ? instanceName : "", category ? category : "");
    va_start(args, message);
    vfprintf(stderr, message ? message : "", args);
    va_end(args);
    fputc('\n', stderr);
}

static int check(fmi2Status status, const char *call, int instance)
{
    if (status == fmi2OK || status == fmi2Warning) return 1;
    fprintf(stderr, "fmi_host: %s of instance %d returned status %d\n", call, instance + 1,
            (int)status);
    return 0;
}

static int parse_list(const char *text, fmi2ValueReference *out, int max)
{
    int n = 0;
    const char *p = text;
    while (*p != '\0') {
        char *end;
        unsigned long value = strtoul(p, &end, 10);
        if (end == p || n == max || value > UINT_MAX) return -1;
        out[n++] = (fmi2ValueReference)value;
        p = end;
        if (*p == ',') p++;
        else if (*p != '\0') return -1;
    }
    return n;
}

static int parse_vr(const char *text, fmi2ValueReference *vr, const char **rest)
{
    char *end;
    unsigned long value = strtoul(text, &end, 10);
    if (end == text || *end != '=' || value > UINT_MAX) return 0;
    *vr = (fmi2ValueReference)value;
    *rest = end + 1;
    return 1;
}

static int parse_double(const char *text, double *value)
{
    char *end;
    *value = strtod(text, &end);
    return end != text && *end == '\0';
}

static void *load(void *handle, const char *name, int *missing)
{
    void *f = dlsym(handle, name);
    if (f == NULL) {
        fprintf(stderr, "fmi_host: the binary does not export %s\n", name);
        (*missing)++;
    }
    return f;
}

/* file:// URI of a folder (characters outside [A-Za-z0-9-._~/] percent-encoded) */
static char *file_uri(const char *path)
{
    static const char *keep = "-._~/";
    size_t n = strlen(path), i, j;
    char *uri = (char *)malloc(3 * n + 8);
    if (uri == NULL) return NULL;
    strcpy(uri, "file://");
    for (i = 0, j = 7; i < n; i++) {
        unsigned char c = (unsigned char)path[i];
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
            strchr(keep, c) != NULL) {
            uri[j++] = (char)c;
        } else {
            sprintf(uri + j, "%%%02X", c);
            j += 3;
        }
    }
    uri[j] = '\0';
    return uri;
}

static double signal_value(const Signal *s, double t)
{
    return s->c0 + s->c1 * t + s->c2 * t * t + s->a * sin(TWO_PI * s->f * t) +
           s->b * cos(TWO_PI * s->f * t);
}

static uint64_t fnv1a(const double *x, size_t n)
{
    const unsigned char *bytes = (const unsigned char *)x;
    uint64_t hash = 1469598103934665603ULL;
    size_t i;
    for (i = 0; i < n * sizeof(double); i++) {
        hash ^= bytes[i];
        hash *= 1099511628211ULL;
    }
    return hash;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int usage(void)
{
    fprintf(stderr, "usage: fmi_host FMU_DIR MODEL_IDENTIFIER GUID [--inputs VR,...] "
                    "[--outputs VR,...] [--real VR=V] [--boolean VR=0|1] [--string VR=S] "
                    "[--signal VR=c0,c1,c2,a,b,f] [--steps N] [--step-size H] "
                    "[--start-time T] [--instances N] [--csv PATH]\n");
    return 2;
}

int main(int argc, char **argv)
{
    fmi2ValueReference inputs[MAX_VARIABLES], outputs[MAX_VARIABLES];
    Signal signals[MAX_VARIABLES];
    Parameter parameters[MAX_PARAMETERS];
    fmi2Component instances[MAX_INSTANCES];
    fmi2CallbackFunctions callbacks;
    int n_inputs = 0, n_outputs = 0, n_parameters = 0, n_instances = 2;
    long n_steps = 20000;
    double h = 1e-6, t0 = 0.0;
    const char *csv = NULL;
    char folder[PATH_MAX], library[PATH_MAX + 64], resources[PATH_MAX + 16];
    char *uri;
    void *handle;
    Api api;
    double *results[2][MAX_INSTANCES] = {{NULL}};
    double *input_values;
    double step_time = 0.0;
    int missing = 0, ok = 1, i, k, run;
    long n;

    if (argc < 4) return usage();
    memset(signals, 0, sizeof signals);
    for (i = 4; i < argc; i++) {
        const char *option = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL, *rest;
        fmi2ValueReference vr;
        if (value == NULL) return usage();
        i++;
        if (strcmp(option, "--inputs") == 0) {
            if ((n_inputs = parse_list(value, inputs, MAX_VARIABLES)) < 0) return usage();
        } else if (strcmp(option, "--outputs") == 0) {
            if ((n_outputs = parse_list(value, outputs, MAX_VARIABLES)) < 0) return usage();
        } else if (strcmp(option, "--real") == 0 || strcmp(option, "--boolean") == 0 ||
                   strcmp(option, "--string") == 0) {
            Parameter *p = &parameters[n_parameters];
            if (n_parameters == MAX_PARAMETERS || !parse_vr(value, &vr, &rest)) return usage();
            p->kind = option[2];
            p->vr = vr;
            if (p->kind == 'r' && !parse_double(rest, &p->real)) return usage();
            if (p->kind == 'b') p->boolean = strcmp(rest, "0") != 0;
            p->string = rest;
            n_parameters++;
        } else if (strcmp(option, "--signal") == 0) {
            Signal s;
            int found = -1;
            if (!parse_vr(value, &vr, &rest) ||
                sscanf(rest, "%lf,%lf,%lf,%lf,%lf,%lf", &s.c0, &s.c1, &s.c2, &s.a, &s.b, &s.f)
                    != 6)
                return usage();
            for (k = 0; k < n_inputs; k++)
                if (inputs[k] == vr) found = k;
            if (found < 0) {
                fprintf(stderr, "fmi_host: --signal %u: not in --inputs (give --inputs first)\n",
                        vr);
                return 2;
            }
            signals[found] = s;
        } else if (strcmp(option, "--steps") == 0) {
            n_steps = strtol(value, NULL, 10);
        } else if (strcmp(option, "--step-size") == 0) {
            if (!parse_double(value, &h)) return usage();
        } else if (strcmp(option, "--start-time") == 0) {
            if (!parse_double(value, &t0)) return usage();
        } else if (strcmp(option, "--instances") == 0) {
            n_instances = atoi(value);
        } else if (strcmp(option, "--csv") == 0) {
            csv = value;
        } else {
            return usage();
        }
    }
    if (n_steps < 1 || n_instances < 1 || n_instances > MAX_INSTANCES || !(h > 0.0))
        return usage();

    if (realpath(argv[1], folder) == NULL) {
        fprintf(stderr, "fmi_host: no such folder: %s\n", argv[1]);
        return 1;
    }
    snprintf(library, sizeof library, "%s/binaries/linux64/%s.so", folder, argv[2]);
    snprintf(resources, sizeof resources, "%s/resources", folder);
    uri = file_uri(resources);
    handle = dlopen(library, RTLD_NOW | RTLD_LOCAL);
    if (handle == NULL) {
        fprintf(stderr, "fmi_host: cannot load %s: %s\n", library, dlerror());
        free(uri);
        return 1;
    }
#define LOAD(name) *(void **)(&api.name) = load(handle, "fmi2" #name, &missing)
    LOAD(GetTypesPlatform);
    LOAD(GetVersion);
    LOAD(Instantiate);
    LOAD(FreeInstance);
    LOAD(SetupExperiment);
    LOAD(EnterInitializationMode);
    LOAD(ExitInitializationMode);
    LOAD(Terminate);
    LOAD(Reset);
    LOAD(GetReal);
    LOAD(SetReal);
    LOAD(SetBoolean);
    LOAD(SetString);
    LOAD(DoStep);
    if (missing > 0 || uri == NULL) {
        dlclose(handle);
        free(uri);
        return 1;
    }
    if (strcmp(api.GetVersion(), "2.0") != 0 || strcmp(api.GetTypesPlatform(), "default") != 0) {
        fprintf(stderr, "fmi_host: not an FMI 2.0 \"default\" platform binary\n");
        dlclose(handle);
        free(uri);
        return 1;
    }

    memset(&callbacks, 0, sizeof callbacks);
    callbacks.logger = logger;
    callbacks.allocateMemory = calloc;
    callbacks.freeMemory = free;
    for (k = 0; k < n_instances; k++) {
        char name[32];
        snprintf(name, sizeof name, "instance%d", k + 1);
        instances[k] = api.Instantiate(name, fmi2CoSimulation, argv[3], uri, &callbacks,
                                       fmi2False, fmi2False);
        if (instances[k] == NULL) {
            fprintf(stderr, "fmi_host: fmi2Instantiate of %s failed\n", name);
            while (k-- > 0) api.FreeInstance(instances[k]);
            dlclose(handle);
            free(uri);
            return 1;
        }
    }
    input_values = (double *)calloc((size_t)n_steps * (size_t)(n_inputs + 1), sizeof(double));
    for (run = 0; run < 2; run++)
        for (k = 0; k < n_instances; k++)
            results[run][k] = (double *)calloc((size_t)n_steps * (size_t)(n_outputs + 1),
                                               sizeof(double));

    for (run = 0; run < 2 && ok; run++) {
        double start;
        for (k = 0; k < n_instances && ok; k++) {
            fmi2Component c = instances[k];
            if (run == 1) ok = ok && check(api.Reset(c), "fmi2Reset", k);
            ok = ok && check(api.SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0),
                             "fmi2SetupExperiment", k);
            for (i = 0; i < n_parameters && ok; i++) {
                Parameter *p = &parameters[i];
                if (p->kind == 'r')
                    ok = check(api.SetReal(c, &p->vr, 1, &p->real), "fmi2SetReal", k);
                else if (p->kind == 'b')
                    ok = check(api.SetBoolean(c, &p->vr, 1, &p->boolean), "fmi2SetBoolean", k);
                else
                    ok = check(api.SetString(c, &p->vr, 1, &p->string), "fmi2SetString", k);
            }
            ok = ok && check(api.EnterInitializationMode(c), "fmi2EnterInitializationMode", k);
            ok = ok && check(api.ExitInitializationMode(c), "fmi2ExitInitializationMode", k);
        }
        start = now();
        for (n = 0; n < n_steps && ok; n++) {
            double t = t0 + (double)n * h;
            double *u = input_values + n * (n_inputs + 1);
            u[0] = t;
            for (i = 0; i < n_inputs; i++) u[i + 1] = signal_value(&signals[i], t);
            for (k = 0; k < n_instances && ok; k++) {
                double *y = results[run][k] + n * (n_outputs + 1);
                y[0] = t;
                ok = check(api.SetReal(instances[k], inputs, (size_t)n_inputs, u + 1),
                           "fmi2SetReal", k);
                ok = ok && check(api.GetReal(instances[k], outputs, (size_t)n_outputs, y + 1),
                                 "fmi2GetReal", k);
                ok = ok && check(api.DoStep(instances[k], t, h, fmi2True), "fmi2DoStep", k);
            }
        }
        if (run == 0) step_time = (now() - start) / ((double)n_steps * n_instances);
    }

    if (ok && errors_logged == 0) {
        size_t count = (size_t)n_steps * (size_t)(n_outputs + 1);
        printf("fmi_host: %s, %d instances x %ld steps of %g s, %d inputs, %d outputs\n",
               argv[2], n_instances, n_steps, h, n_inputs, n_outputs);
        for (k = 0; k < n_instances; k++) {
            const double *last = results[0][k] + (n_steps - 1) * (n_outputs + 1);
            int same = memcmp(results[0][k], results[1][k], count * sizeof(double)) == 0;
            printf("instance%d: outputs checksum %016llx; last outputs", k + 1,
                   (unsigned long long)fnv1a(results[0][k], count));
            for (i = 0; i < n_outputs; i++) printf(" %.17g", last[i + 1]);
            printf("\ninstance%d: rerun after fmi2Reset bitwise identical: %s\n", k + 1,
                   same ? "yes" : "NO");
            if (!same) ok = 0;
            if (k > 0 && memcmp(results[0][k], results[0][0], count * sizeof(double)) != 0) {
                printf("instance%d: differs from instance1 (same parameters)\n", k + 1);
                ok = 0;
            }
        }
        printf("fmi_host: %.3f us per instance step (set inputs, get outputs, fmi2DoStep)\n",
               1e6 * step_time);
    }
    if (ok && csv != NULL) {
        FILE *file = fopen(csv, "w");
        if (file == NULL) {
            fprintf(stderr, "fmi_host: cannot write %s\n", csv);
            ok = 0;
        } else {
            fprintf(file, "time");
            for (i = 0; i < n_inputs; i++) fprintf(file, ",in%u", inputs[i]);
            for (i = 0; i < n_outputs; i++) fprintf(file, ",out%u", outputs[i]);
            fputc('\n', file);
            for (n = 0; n < n_steps; n++) {
                const double *u = input_values + n * (n_inputs + 1);
                const double *y = results[0][0] + n * (n_outputs + 1);
                fprintf(file, "%.17g", u[0]);
                for (i = 0; i < n_inputs; i++) fprintf(file, ",%.17g", u[i + 1]);
                for (i = 0; i < n_outputs; i++) fprintf(file, ",%.17g", y[i + 1]);
                fputc('\n', file);
            }
            fclose(file);
        }
    }

    for (k = 0; k < n_instances; k++) {
        if (ok) ok = check(api.Terminate(instances[k]), "fmi2Terminate", k);
        api.FreeInstance(instances[k]);
    }
    for (run = 0; run < 2; run++)
        for (k = 0; k < n_instances; k++) free(results[run][k]);
    free(input_values);
    free(uri);
    if (dlclose(handle) != 0) {
        fprintf(stderr, "fmi_host: dlclose failed: %s\n", dlerror());
        ok = 0;
    }
    if (errors_logged > 0) ok = 0;
    printf("fmi_host: %s\n", ok ? "ok" : "FAILED");
    return ok ? 0 : 1;
}
