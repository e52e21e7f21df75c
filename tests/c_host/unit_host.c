/*
 * unit_host.c -- run one native anvilwave unit with a constant input, portable: dlopen on
 * POSIX, LoadLibrary on Windows (cross-compiled with mingw-w64 and run under Wine to check
 * the shipped win64 binaries).
 *
 *   unit_host <binary> <resources_uri> <guid> <vr_in> <input> <vr_out1> <vr_out2> <steps> <h>
 *
 * Prints the two outputs after the steps ("%.17g %.17g") and "unit_host: ok"; exit 1 on an
 * FMI error.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#define OPEN(path) ((void *)LoadLibraryA(path))
#define SYMBOL(lib, name) ((void *)GetProcAddress((HMODULE)(lib), name))
#else
#include <dlfcn.h>
#define OPEN(path) dlopen(path, RTLD_NOW | RTLD_LOCAL)
#define SYMBOL(lib, name) dlsym(lib, name)
#endif

#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    va_list args;
    (void)env;
    (void)category;
    fprintf(stderr, "[%s status %d] ", name, (int)status);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static const fmi2CallbackFunctions CALLBACKS = {logger, calloc, free, NULL, NULL};

#define LOAD(type, var, name)                                                                    \
    type *var;                                                                                   \
    *(void **)(&var) = SYMBOL(lib, name);                                                        \
    if (var == NULL) {                                                                           \
        fprintf(stderr, "unit_host: no %s\n", name);                                             \
        return 1;                                                                                \
    }

int main(int argc, char **argv)
{
    void *lib;
    fmi2Component c;
    fmi2ValueReference in, out[2];
    double input, h, values[2];
    long steps, n;
    if (argc != 10) {
        fprintf(stderr, "usage: see unit_host.c\n");
        return 2;
    }
    lib = OPEN(argv[1]);
    if (lib == NULL) {
        fprintf(stderr, "unit_host: cannot load %s\n", argv[1]);
        return 1;
    }
    {
        LOAD(fmi2InstantiateTYPE, instantiate, "fmi2Instantiate")
        LOAD(fmi2SetupExperimentTYPE, setup, "fmi2SetupExperiment")
        LOAD(fmi2EnterInitializationModeTYPE, enter, "fmi2EnterInitializationMode")
        LOAD(fmi2ExitInitializationModeTYPE, exit_init, "fmi2ExitInitializationMode")
        LOAD(fmi2SetRealTYPE, set, "fmi2SetReal")
        LOAD(fmi2GetRealTYPE, get, "fmi2GetReal")
        LOAD(fmi2DoStepTYPE, step, "fmi2DoStep")
        LOAD(fmi2TerminateTYPE, terminate, "fmi2Terminate")
        LOAD(fmi2FreeInstanceTYPE, free_instance, "fmi2FreeInstance")
        in = (fmi2ValueReference)strtoul(argv[4], NULL, 10);
        input = strtod(argv[5], NULL);
        out[0] = (fmi2ValueReference)strtoul(argv[6], NULL, 10);
        out[1] = (fmi2ValueReference)strtoul(argv[7], NULL, 10);
        steps = strtol(argv[8], NULL, 10);
        h = strtod(argv[9], NULL);
        c = instantiate("unit", fmi2CoSimulation, argv[3], argv[2], &CALLBACKS, fmi2False,
                        fmi2False);
        if (c == NULL) return 1;
        if (setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) > fmi2Warning ||
            enter(c) > fmi2Warning || exit_init(c) > fmi2Warning)
            return 1;
        for (n = 0; n < steps; n++)
            if (set(c, &in, 1, &input) > fmi2Warning || step(c, n * h, h, fmi2True) > fmi2Warning)
                return 1;
        if (get(c, out, 2, values) > fmi2Warning || terminate(c) > fmi2Warning) return 1;
        free_instance(c);
    }
    printf("%.17g %.17g\nunit_host: ok\n", values[0], values[1]);
    return 0;
}
