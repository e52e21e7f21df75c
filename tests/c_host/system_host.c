/*
 * system_host.c -- a plain C master for the three-unit system (Ram, Anvil, PileSoil) in the
 * DESIGN.md exchange order of anvilwave/fmu/fmi_master.py (BlowMaster, one blow): no Python.
 *
 *   system_host <ram_dir> <ram_guid> <anvil_dir> <anvil_id> <anvil_guid> <pile_dir>
 *               <pile_guid> <steps> <h> <csv>
 *               --vr <ram: F_toe,u_toe,v_toe,contact_displacement,contact_time,
 *                          contact_mid_step>
 *               --vr <anvil: u_ram,v_ram,u_pile,v_pile,F_ram,F_pile,u_top,u_bottom,
 *                            initial_pile_head_displacement>
 *               --vr <pile: F_head,u_head,v_head>
 *
 * Start (as BlowMaster._start_blow): the pile at rest at t0 = -h/2; the anvil resting on the
 * pile head; the ram in free flight towards the anvil top face, touching it at t0 + h/2
 * (contact_time given, contact_mid_step off).
 * Each step: outputs of ram and pile -> anvil inputs -> contact forces -> forces to ram and
 * pile -> every unit steps. Writes t, F_ram, F_pile [s, N, N] per communication point to csv;
 * prints the peak forces; exit 0 on success, 1 on any FMI error (reasons on stderr).
 */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

typedef struct {
    void *dll;
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2TerminateTYPE *terminate;
    fmi2GetRealTYPE *get;
    fmi2SetRealTYPE *set;
    fmi2SetBooleanTYPE *set_boolean;
    fmi2DoStepTYPE *step;
    fmi2Component c;
} Unit;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    va_list args;
    (void)env;
    (void)category;
    if (status == fmi2OK) return;
    fprintf(stderr, "[%s status %d] ", name, (int)status);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static const fmi2CallbackFunctions CALLBACKS = {logger, calloc, free, NULL, NULL};

#define CHECK(call)                                                                              \
    do {                                                                                         \
        if ((call) > fmi2Warning) {                                                              \
            fprintf(stderr, "system_host: %s failed (line %d)\n", #call, __LINE__);             \
            return 1;                                                                            \
        }                                                                                        \
    } while (0)

static int load(Unit *u, const char *dir, const char *id, const char *guid, const char *name)
{
    char path[4096], uri[4200];
    snprintf(path, sizeof path, "%s/binaries/linux64/%s.so", dir, id);
    u->dll = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (u->dll == NULL) {
        fprintf(stderr, "system_host: %s\n", dlerror());
        return 0;
    }
#define SYM(field, symbol) *(void **)(&u->field) = dlsym(u->dll, symbol)
    SYM(instantiate, "fmi2Instantiate");
    SYM(free_instance, "fmi2FreeInstance");
    SYM(setup, "fmi2SetupExperiment");
    SYM(enter, "fmi2EnterInitializationMode");
    SYM(exit_init, "fmi2ExitInitializationMode");
    SYM(terminate, "fmi2Terminate");
    SYM(get, "fmi2GetReal");
    SYM(set, "fmi2SetReal");
    SYM(set_boolean, "fmi2SetBoolean");
    SYM(step, "fmi2DoStep");
    if (!u->instantiate || !u->free_instance || !u->setup || !u->enter || !u->exit_init ||
        !u->terminate || !u->get || !u->set || !u->set_boolean || !u->step) {
        fprintf(stderr, "system_host: %s lacks FMI functions\n", path);
        return 0;
    }
    snprintf(uri, sizeof uri, "file://%s/resources", dir);
    u->c = u->instantiate(name, fmi2CoSimulation, guid, uri, &CALLBACKS, fmi2False, fmi2False);
    if (u->c == NULL) fprintf(stderr, "system_host: %s: fmi2Instantiate failed\n", name);
    return u->c != NULL;
}

static int parse_vrs(const char *text, fmi2ValueReference *vr, int n)
{
    int i;
    char *end;
    for (i = 0; i < n; i++) {
        vr[i] = (fmi2ValueReference)strtoul(text, &end, 10);
        if (end == text) return 0;
        text = *end == ',' ? end + 1 : end;
    }
    return 1;
}

int main(int argc, char **argv)
{
    Unit ram, anvil, pile;
    fmi2ValueReference rv[6], av[9], pv[3];
    long steps, n;
    double h, t0, head, top, row[12], peak_ram = 0.0, peak_pile = 0.0, value;
    FILE *csv;
    if (argc != 17 || strcmp(argv[11], "--vr") || strcmp(argv[13], "--vr") ||
        strcmp(argv[15], "--vr") || !parse_vrs(argv[12], rv, 6) || !parse_vrs(argv[14], av, 9) ||
        !parse_vrs(argv[16], pv, 3)) {
        fprintf(stderr, "usage: see system_host.c\n");
        return 2;
    }
    steps = strtol(argv[8], NULL, 10);
    h = strtod(argv[9], NULL);
    t0 = -0.5 * h;
    memset(&ram, 0, sizeof ram);
    memset(&anvil, 0, sizeof anvil);
    memset(&pile, 0, sizeof pile);
    if (!load(&ram, argv[1], "Ram", argv[2], "ram") ||
        !load(&anvil, argv[3], argv[4], argv[5], "anvil") ||
        !load(&pile, argv[6], "PileSoil", argv[7], "pile"))
        return 1;
    csv = fopen(argv[10], "w");
    if (csv == NULL) return 1;
    fprintf(csv, "time,F_ram,F_pile\n");
    /* pile at rest */
    CHECK(pile.setup(pile.c, fmi2False, 0.0, t0, fmi2False, 0.0));
    CHECK(pile.enter(pile.c));
    CHECK(pile.exit_init(pile.c));
    CHECK(pile.get(pile.c, &pv[1], 1, &head));
    /* the anvil resting on the pile head */
    CHECK(anvil.setup(anvil.c, fmi2False, 0.0, t0, fmi2False, 0.0));
    CHECK(anvil.enter(anvil.c));
    CHECK(anvil.set(anvil.c, &av[8], 1, &head));
    CHECK(anvil.exit_init(anvil.c));
    row[0] = head - 1.0;
    row[1] = 0.0;
    row[2] = head;
    row[3] = 0.0;
    CHECK(anvil.set(anvil.c, av, 4, row));
    CHECK(anvil.get(anvil.c, &av[6], 1, &top));
    /* the ram touching the top face at t0 + h / 2 */
    CHECK(ram.setup(ram.c, fmi2False, 0.0, t0, fmi2False, 0.0));
    CHECK(ram.enter(ram.c));
    CHECK(ram.set(ram.c, &rv[3], 1, &top));
    value = t0 + 0.5 * h;
    CHECK(ram.set(ram.c, &rv[4], 1, &value));
    {
        fmi2Boolean off = fmi2False;
        CHECK(ram.set_boolean(ram.c, &rv[5], 1, &off));
    }
    CHECK(ram.exit_init(ram.c));
    /* row: u_toe v_toe | u_head v_head | F_ram F_pile u_top u_bottom */
    for (n = 0; n <= steps; n++) {
        double t = t0 + (double)n * h;
        CHECK(ram.get(ram.c, &rv[1], 2, &row[0]));
        CHECK(pile.get(pile.c, &pv[1], 2, &row[2]));
        CHECK(anvil.set(anvil.c, av, 4, row));
        CHECK(anvil.get(anvil.c, &av[4], 4, &row[4]));
        fprintf(csv, "%.17g,%.17g,%.17g\n", t, row[4], row[5]);
        if (row[4] > peak_ram) peak_ram = row[4];
        if (row[5] > peak_pile) peak_pile = row[5];
        if (n == steps) break;
        CHECK(ram.set(ram.c, &rv[0], 1, &row[4]));
        CHECK(pile.set(pile.c, &pv[0], 1, &row[5]));
        CHECK(ram.step(ram.c, t, h, fmi2True));
        CHECK(anvil.step(anvil.c, t, h, fmi2True));
        CHECK(pile.step(pile.c, t, h, fmi2True));
    }
    fclose(csv);
    CHECK(ram.terminate(ram.c));
    CHECK(anvil.terminate(anvil.c));
    CHECK(pile.terminate(pile.c));
    ram.free_instance(ram.c);
    anvil.free_instance(anvil.c);
    pile.free_instance(pile.c);
    dlclose(ram.dll);
    dlclose(anvil.dll);
    dlclose(pile.dll);
    printf("peak F_ram %.17g N, peak F_pile %.17g N\nsystem_host: ok\n", peak_ram, peak_pile);
    return 0;
}
