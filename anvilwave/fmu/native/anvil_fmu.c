/*
 * anvil_fmu.c -- the anvilwave anvil as a native FMI 2.0 co-simulation FMU (no Python).
 *
 * Interface (DESIGN.md, the contract; the same names, value references, types and causalities
 * as the pythonfmu Anvil / AnvilLumped units, so either can be swapped in): inputs u_ram [m],
 * v_ram [m/s] (ram toe), u_pile [m], v_pile [m/s] (pile head); outputs F_ram, F_pile [N]
 * (contact forces, compression positive) and u_top, u_bottom [m] (interface displacements);
 * z down. The parameters and their value references come from anvil_config.h, written by
 * fmu/native_build.py together with modelDescription.xml.
 *
 * Behaviour (that of fmu/units/anvil.py):
 * - The forces are a direct feedthrough of the inputs: fmi2GetReal evaluates them from the
 *   inputs set at the current communication point. fmi2DoStep holds these forces over the step
 *   and advances the modes by the exact per-mode recurrence (anvil_model.h). The recurrence is
 *   unconditionally stable, so the unit takes any communication step h in one step, as the
 *   Python unit does (its stable limit is unbounded: there is nothing to sub-step); a change
 *   of h rescales the two-step state (anvil_unit_set_step).
 * - At the end of initialization the anvil rests on the pile in static equilibrium under
 *   gravity (start_at_rest) with the pile head at initial_pile_head_displacement [m].
 * - Input extrapolation (Boolean parameter input_extrapolation, for Jacobi-type masters that
 *   read the forces after the step, with the inputs of the step before): the operations of
 *   fmu/coupling.py (InputExtrapolation, extrapolated_input), in the same order. Inputs set
 *   at a new communication point keep the velocities of the point before (the neighbours'
 *   accelerations); the outputs use the inputs extrapolated to the unit's time; fmi2DoStep
 *   steps with the forces at the step start and keeps their difference to the forces of the
 *   last output read since the step before as an impulse correction of the force outputs,
 *   except when that output came from the start time's inputs: then it steps with the forces
 *   of that output, with no correction.
 *   With inputs set at the unit's time before the outputs are read (the DESIGN.md order),
 *   nothing changes.
 * - The ROM reads its modes from the modal-data resource named by the String parameter
 *   modal_data_file (a relative name is looked up in the FMU's resources folder, given by
 *   fmuResourceLocation). fmi2Instantiate reads the embedded file; another file named before
 *   initialization is read at fmi2ExitInitializationMode.
 * - A bad parameter value or modal-data file, a non-positive step, a call out of sequence:
 *   the function returns fmi2Error and the reason goes to the logger callback (errors and
 *   warnings always; category logCalls traces the calls when debug logging is on). After an
 *   fmi2Error in initialization or stepping the instance refuses to step until fmi2Reset;
 *   fmi2Reset restores the build's start values. Nothing here aborts or exits the host.
 * - No global mutable state: any number of instances in one process.
 *
 * Build (fmu/native_build.py): cc -shared -fPIC -O2 -ffp-contract=off -fvisibility=hidden
 *   -std=c99 -I. -o <modelIdentifier>.so anvil_fmu.c anvil_model.c fmu_common.c -lm
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_common.h"
#include "anvil_model.h"
#include "anvil_fmu.h"
#include "anvil_config.h"

#if !defined(ANVIL_LUMPED) || !defined(ANVIL_GUID) || !defined(ANVIL_MODEL_IDENTIFIER)
#error "anvil_config.h must define ANVIL_LUMPED, ANVIL_GUID and ANVIL_MODEL_IDENTIFIER"
#endif

#define N_VARIABLES (sizeof ANVIL_VARIABLES / sizeof ANVIL_VARIABLES[0])
#define MESSAGE_SIZE FMU_MESSAGE_SIZE

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
    int logging_on; /* debug logging (fmi2SetDebugLogging, loggingOn) */
    int log_calls;  /* category logCalls */
    State state;
    char *resources; /* the resources folder as a path, "" when the host gave none */
    double real[ANVIL_N_SLOTS];
    fmi2Boolean boolean[ANVIL_N_SLOTS];
    char *modal_data_file;
    AnvilModalData data; /* the modal data last read, from data_path */
    char *data_path;
    AnvilUnit unit;
    int built;         /* unit made from the current parameters */
    int outputs_valid; /* outputs computed from the current inputs and state */
    double time;       /* current communication point [s] */
    /* input extrapolation (input_extrapolation) */
    double input_start;          /* the start time [s]: no acceleration across it */
    double input_time;           /* when the inputs were last set [s] */
    double input_interval;       /* from the point before to input_time [s]; 0: none */
    double previous_velocity[2]; /* v_ram, v_pile at the point before [m/s] */
    double correction[2];        /* impulse correction of F_ram, F_pile [N] */
    double evaluated[2];         /* forces of the last output evaluation, uncorrected [N] */
    double sent[2];              /* ... of the last output read since the last step [N] */
    int has_evaluated, has_sent;
    int evaluated_at_start, sent_at_start; /* from the start time's inputs */
    /* before the first contact (Python: approach_input) */
    int touched;                 /* the ram contact has carried a force */
    double last_step;            /* the last communication step [s]; 0: none yet */
    char reason[MESSAGE_SIZE];
} Instance;

/* ------------------------------------------------------------------ helpers
 * strings, logging and the resource location: fmu_common.c (shared with the Ram and PileSoil
 * units) */
#define copy_string fmu_copy_string

static void log_va(fmi2CallbackLogger logger, fmi2ComponentEnvironment environment,
                   const char *name, fmi2Status status, const char *category,
                   const char *format, va_list args)
{
    fmu_log_va(logger, environment, ANVIL_MODEL_IDENTIFIER, name, status, category, format,
               args);
}

static void log_raw(const fmi2CallbackFunctions *functions, const char *name, fmi2Status status,
                    const char *category, const char *format, ...)
{
    va_list args;
    if (functions == NULL) return;
    va_start(args, format);
    log_va(functions->logger, functions->componentEnvironment, name, status, category, format,
           args);
    va_end(args);
}

static void log_message(Instance *inst, fmi2Status status, const char *category,
                        const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(inst->logger, inst->environment, inst->name, status, category, format, args);
    va_end(args);
}

#define LOG_CALL(inst, ...)                                                                      \
    do {                                                                                         \
        if ((inst)->logging_on && (inst)->log_calls)                                             \
            log_message((inst), fmi2OK, "logCalls", __VA_ARGS__);                                \
    } while (0)

/* An error that ends the instance's run: logged, state error, fmi2Error. */
static fmi2Status fail(Instance *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(inst->logger, inst->environment, inst->name, fmi2Error, "logStatusError", format,
           args);
    va_end(args);
    inst->state = ST_ERROR;
    return fmi2Error;
}

/* A call the instance refuses (out of sequence, unknown variable ...): logged, fmi2Error,
 * the state is kept. */
static fmi2Status refuse(Instance *inst, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    log_va(inst->logger, inst->environment, inst->name, fmi2Error, "logStatusError", format,
           args);
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

static const AnvilVariable *find_variable(fmi2ValueReference vr)
{
    size_t i;
    if (vr < N_VARIABLES && ANVIL_VARIABLES[vr].vr == vr) return &ANVIL_VARIABLES[vr];
    for (i = 0; i < N_VARIABLES; i++)
        if (ANVIL_VARIABLES[i].vr == vr) return &ANVIL_VARIABLES[i];
    return NULL;
}

static const char *type_name(AnvilType type)
{
    return type == ANVIL_REAL ? "Real" : type == ANVIL_BOOLEAN ? "Boolean" : "String";
}

#define resource_folder fmu_resource_folder
#define is_absolute fmu_is_absolute

#if !ANVIL_LUMPED
/* The file a modal_data_file value names: absolute as is, relative inside the resources. */
static char *resolve(const Instance *inst, const char *name, int *no_resources)
{
    char *path;
    size_t n;
    *no_resources = 0;
    if (is_absolute(name)) return copy_string(name);
    if (inst->resources[0] == '\0') {
        *no_resources = 1;
        return NULL;
    }
    n = strlen(inst->resources) + strlen(name) + 2;
    path = (char *)malloc(n);
    if (path != NULL) snprintf(path, n, "%s/%s", inst->resources, name);
    return path;
}

/* The modal data named by modal_data_file, read unless it is the file read last. */
static int load_modal_data(Instance *inst)
{
    AnvilModalData data;
    char reason[MESSAGE_SIZE / 4];
    int no_resources;
    char *path = resolve(inst, inst->modal_data_file, &no_resources);
    if (path == NULL) {
        if (no_resources)
            snprintf(inst->reason, sizeof inst->reason, "modal_data_file: %s: a relative name, "
                     "but the host gave no resource location", inst->modal_data_file);
        else
            snprintf(inst->reason, sizeof inst->reason, "out of memory");
        return 0;
    }
    if (inst->data_path != NULL && strcmp(path, inst->data_path) == 0) {
        free(path);
        return 1;
    }
    if (!anvil_modal_data_read(path, &data, reason, sizeof reason)) {
        snprintf(inst->reason, sizeof inst->reason, "modal_data_file: %s: %s", path, reason);
        free(path);
        return 0;
    }
    anvil_modal_data_free(&inst->data);
    free(inst->data_path);
    inst->data = data;
    inst->data_path = path;
    return 1;
}
#endif

/* Python: extrapolated_input. A neighbour's (displacement [m], velocity [m/s]) age [s] after it
 * was received; velocity is its half-step value, previous_velocity the one received interval
 * [s] earlier (interval 0: no acceleration). */
static void extrapolated_input(double displacement, double velocity, double previous_velocity,
                               double age, double interval, double *u, double *v)
{
    double acceleration;
    if (age == 0.0) {
        *u = displacement;
        *v = velocity;
        return;
    }
    acceleration = interval > 0.0 ? (velocity - previous_velocity) / interval : 0.0;
    *u = displacement + age * (velocity + 0.5 * interval * acceleration) +
         0.5 * acceleration * age * age;
    *v = velocity + acceleration * age;
}

static int extrapolating(const Instance *inst)
{
    return inst->built && inst->boolean[ANVIL_INPUT_EXTRAPOLATION];
}

/* Python: InputExtrapolation(time), a fresh state at the unit's time (and the approach's:
 * AnvilSlaveBase.start_component). */
static void start_extrapolation(Instance *inst)
{
    inst->touched = 0;
    inst->last_step = 0.0;
    inst->input_start = inst->time;
    inst->input_time = inst->time;
    inst->input_interval = 0.0;
    inst->previous_velocity[0] = inst->previous_velocity[1] = 0.0;
    inst->correction[0] = inst->correction[1] = 0.0;
    inst->has_evaluated = inst->has_sent = 0;
    inst->evaluated_at_start = inst->sent_at_start = 0;
}

/* Python: InputExtrapolation.note_inputs, before new inputs are stored. While the point before
 * is the start time the interval is 0 (no acceleration): inputs there are a master's initial
 * values (e.g. the zeros of fmpy's SSP runner), not the neighbours' states. */
static void note_inputs(Instance *inst)
{
    if (inst->time > inst->input_time) {
        inst->previous_velocity[0] = inst->real[ANVIL_V_RAM];
        inst->previous_velocity[1] = inst->real[ANVIL_V_PILE];
        inst->input_interval = inst->input_time > inst->input_start ?
                               inst->time - inst->input_time : 0.0;
        inst->input_time = inst->time;
    }
}

/* Python: approach_input and AnvilSlaveBase.approached. Until the ram contact has carried a
 * force, after a step h a toe open by more than it closes in one step is taken out of reach
 * (1 m above the top face, at its velocity): the contact dashpot's lead across the gap starts
 * at most a step before the first contact, as in the engine. */
static void approach_input(Instance *inst, double *u_ram, double *v_ram)
{
    double u_top, v_top, gap;
    if (inst->touched || inst->last_step == 0.0) return;
    anvil_unit_outputs(&inst->unit, 0.0, 0.0, &u_top, &v_top, NULL, NULL);
    gap = u_top - *u_ram;
    if (gap > 0.0 && gap > (*v_ram - v_top) * inst->last_step) {
        *u_ram = u_top - 1.0;
        *v_ram = v_top;
    }
}

/* Python: InputExtrapolation.extrapolated, the inputs at the unit's time. */
static void extrapolated_inputs(const Instance *inst, double *u_ram, double *v_ram,
                                double *u_pile, double *v_pile)
{
    const double *r = inst->real;
    double age = inst->time - inst->input_time;
    extrapolated_input(r[ANVIL_U_RAM], r[ANVIL_V_RAM], inst->previous_velocity[0], age,
                       inst->input_interval, u_ram, v_ram);
    extrapolated_input(r[ANVIL_U_PILE], r[ANVIL_V_PILE], inst->previous_velocity[1], age,
                       inst->input_interval, u_pile, v_pile);
}

static void drop_unit(Instance *inst)
{
    if (inst->built) anvil_unit_free(&inst->unit);
    inst->built = 0;
    inst->outputs_valid = 0;
}

/* The component from the current parameters (Python: build_component + start_component);
 * 0 with the reason in inst->reason. */
static int build(Instance *inst)
{
    const double *r = inst->real;
    AnvilContact contact;
    int ok;
    if (inst->built) return 1;
    contact.ram_stiffness = r[ANVIL_RAM_CONTACT_STIFFNESS];
    contact.ram_damping = r[ANVIL_RAM_CONTACT_DAMPING];
    contact.pile_stiffness = r[ANVIL_PILE_CONTACT_STIFFNESS];
    contact.pile_damping = r[ANVIL_PILE_CONTACT_DAMPING];
    if (!anvil_check_parameters(&contact, r[ANVIL_GRAVITY],
                                r[ANVIL_INITIAL_PILE_HEAD_DISPLACEMENT], inst->reason,
                                sizeof inst->reason))
        return 0;
#if ANVIL_LUMPED
    ok = anvil_unit_rigid(&inst->unit, r[ANVIL_MASS], &contact, r[ANVIL_GRAVITY], inst->reason,
                          sizeof inst->reason);
#else
    if (!load_modal_data(inst)) return 0;
    ok = anvil_unit_modal(&inst->unit, &inst->data, r[ANVIL_FMAX], r[ANVIL_DAMPING_RATIO],
                          inst->boolean[ANVIL_STATIC_CORRECTION], &contact, r[ANVIL_GRAVITY],
                          inst->reason, sizeof inst->reason);
#endif
    if (!ok) return 0;
    if (inst->boolean[ANVIL_START_AT_REST])
        anvil_unit_rest_on_pile(&inst->unit, r[ANVIL_INITIAL_PILE_HEAD_DISPLACEMENT]);
    inst->built = 1;
    inst->outputs_valid = 0;
    start_extrapolation(inst);
    return 1;
}

/* Python: anvil_outputs (forces, then the displacements under them); with input extrapolation
 * (Python: AnvilSlaveBase.compute_outputs) at the inputs extrapolated to the unit's time, the
 * forces plus the impulse correction. */
static void compute_outputs(Instance *inst)
{
    double *r = inst->real;
    double force_ram, force_pile, u_top, u_bottom;
    double u_ram = r[ANVIL_U_RAM], v_ram = r[ANVIL_V_RAM], u_pile = r[ANVIL_U_PILE],
           v_pile = r[ANVIL_V_PILE];
    if (extrapolating(inst)) extrapolated_inputs(inst, &u_ram, &v_ram, &u_pile, &v_pile);
    approach_input(inst, &u_ram, &v_ram);
    anvil_unit_forces(&inst->unit, u_ram, v_ram, u_pile, v_pile, &force_ram, &force_pile);
    anvil_unit_outputs(&inst->unit, force_ram, force_pile, &u_top, NULL, &u_bottom, NULL);
    r[ANVIL_F_RAM] = force_ram;
    r[ANVIL_F_PILE] = force_pile;
    r[ANVIL_U_TOP] = u_top;
    r[ANVIL_U_BOTTOM] = u_bottom;
    if (extrapolating(inst)) {
        inst->evaluated[0] = force_ram;
        inst->evaluated[1] = force_pile;
        inst->has_evaluated = 1;
        inst->evaluated_at_start = inst->input_time == inst->input_start;
        r[ANVIL_F_RAM] += inst->correction[0];
        r[ANVIL_F_PILE] += inst->correction[1];
    }
    inst->outputs_valid = 1;
}

/* Start values of the build; state instantiated. 0 when out of memory. */
static int apply_start_values(Instance *inst)
{
    size_t i;
    drop_unit(inst);
    for (i = 0; i < ANVIL_N_SLOTS; i++) {
        inst->real[i] = NAN;
        inst->boolean[i] = fmi2False;
    }
    for (i = 0; i < N_VARIABLES; i++) {
        const AnvilVariable *v = &ANVIL_VARIABLES[i];
        if (v->type == ANVIL_REAL && v->causality != ANVIL_OUTPUT)
            inst->real[v->slot] = v->real_start;
        else if (v->type == ANVIL_BOOLEAN)
            inst->boolean[v->slot] = v->boolean_start ? fmi2True : fmi2False;
        else if (v->type == ANVIL_STRING && v->slot == ANVIL_MODAL_DATA_FILE) {
            char *copy = copy_string(v->string_start);
            if (copy == NULL) return 0;
            free(inst->modal_data_file);
            inst->modal_data_file = copy;
        }
    }
    inst->state = ST_INSTANTIATED;
    inst->time = 0.0;
    return 1;
}

static void free_instance(Instance *inst)
{
    if (inst == NULL) return;
    drop_unit(inst);
    anvil_modal_data_free(&inst->data);
    free(inst->data_path);
    free(inst->modal_data_file);
    free(inst->resources);
    free(inst->name);
    free(inst);
}

/* ------------------------------------------------------------------ inquiry, logging */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }

const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn, size_t nCategories,
                               const fmi2String categories[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    inst->logging_on = loggingOn ? 1 : 0;
    if (nCategories == 0) {
        inst->log_calls = inst->logging_on;
        return fmi2OK;
    }
    if (categories == NULL) return refuse(inst, "fmi2SetDebugLogging: null category array");
    for (i = 0; i < nCategories; i++) {
        const char *name = categories[i] != NULL ? categories[i] : "(null)";
        if (strcmp(name, "logCalls") == 0)
            inst->log_calls = inst->logging_on;
        else if (strcmp(name, "logStatusError") != 0 && strcmp(name, "logStatusWarning") != 0)
            return refuse(inst, "fmi2SetDebugLogging: unknown log category \"%s\" (categories: "
                          "logStatusError, logStatusWarning, logCalls)", name);
    }
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
    (void)visible;
    if (functions == NULL) return NULL;
    if (name[0] == '\0') {
        log_raw(functions, name, fmi2Error, "logStatusError",
                "fmi2Instantiate: the instance name is missing");
        return NULL;
    }
    if (fmuType != fmi2CoSimulation) {
        log_raw(functions, name, fmi2Error, "logStatusError",
                "fmi2Instantiate: this FMU supports co-simulation only (fmuType = %d)",
                (int)fmuType);
        return NULL;
    }
    if (fmuGUID == NULL || strcmp(fmuGUID, ANVIL_GUID) != 0) {
        log_raw(functions, name, fmi2Error, "logStatusError",
                "fmi2Instantiate: GUID %s does not match this binary's %s (modelDescription.xml "
                "and binary from different builds)", fmuGUID != NULL ? fmuGUID : "(null)",
                ANVIL_GUID);
        return NULL;
    }
    inst = (Instance *)calloc(1, sizeof *inst);
    if (inst == NULL) return NULL;
    inst->name = copy_string(name);
    inst->resources = resource_folder(fmuResourceLocation);
    inst->logger = functions->logger;
    inst->environment = functions->componentEnvironment;
    inst->logging_on = loggingOn ? 1 : 0;
    inst->log_calls = inst->logging_on;
    if (inst->name == NULL || inst->resources == NULL || !apply_start_values(inst)) {
        log_raw(functions, name, fmi2Error, "logStatusError", "fmi2Instantiate: out of memory");
        free_instance(inst);
        return NULL;
    }
    LOG_CALL(inst, "fmi2Instantiate(GUID = %s, resources = %s)", fmuGUID, inst->resources);
#if !ANVIL_LUMPED
    /* the embedded modal data; a problem is reported again (as an error) at initialization */
    if (!load_modal_data(inst))
        log_message(inst, fmi2Warning, "logStatusWarning", "fmi2Instantiate: %s", inst->reason);
#endif
    return inst;
}

void fmi2FreeInstance(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return;
    LOG_CALL(inst, "fmi2FreeInstance");
    free_instance(inst);
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                               fmi2Real startTime, fmi2Boolean stopTimeDefined,
                               fmi2Real stopTime)
{
    Instance *inst = (Instance *)c;
    (void)toleranceDefined;
    (void)tolerance;
    (void)stopTimeDefined;
    (void)stopTime;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2SetupExperiment(startTime = %.17g)", startTime);
    REQUIRE_STATE(inst, "fmi2SetupExperiment", ST_INSTANTIATED);
    if (!isfinite(startTime)) return refuse(inst, "fmi2SetupExperiment: startTime must be finite");
    inst->time = startTime;
    if (inst->built) start_extrapolation(inst); /* Python rebuilds its component here */
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
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2ExitInitializationMode");
    REQUIRE_STATE(inst, "fmi2ExitInitializationMode", ST_INITIALIZATION);
    if (!build(inst)) return fail(inst, "initialization: %s", inst->reason);
    inst->state = ST_STEP_COMPLETE;
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2Terminate");
    REQUIRE_STATE(inst, "fmi2Terminate", ST_STEP_COMPLETE | ST_TERMINATED | ST_ERROR);
    if (inst->state != ST_ERROR) inst->state = ST_TERMINATED;
    return fmi2OK;
}

fmi2Status fmi2Reset(fmi2Component c)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2Reset");
    if (!apply_start_values(inst)) return fail(inst, "fmi2Reset: out of memory");
    return fmi2OK;
}

/* ------------------------------------------------------------------ variables */
#define GET_STATES (ST_INSTANTIATED | ST_INITIALIZATION | ST_STEP_COMPLETE | ST_TERMINATED | \
                    ST_ERROR)
#define SET_STATES (ST_INSTANTIATED | ST_INITIALIZATION | ST_STEP_COMPLETE)

static const AnvilVariable *typed_variable(Instance *inst, const char *function,
                                           fmi2ValueReference vr, AnvilType type)
{
    const AnvilVariable *v = find_variable(vr);
    if (v == NULL || v->type != type) {
        if (v == NULL)
            refuse(inst, "%s: no variable has value reference %u", function, vr);
        else
            refuse(inst, "%s: value reference %u is %s, a %s variable", function, vr, v->name,
                   type_name(v->type));
        return NULL;
    }
    return v;
}

/* A parameter may change until initialization ends; a new value rebuilds the component. */
static fmi2Status check_parameter_change(Instance *inst, const AnvilVariable *v)
{
    if (inst->state == ST_STEP_COMPLETE)
        return fail(inst, "parameter %s is fixed: it cannot change after initialization",
                    v->name);
    drop_unit(inst);
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2GetReal", GET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2GetReal", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        const AnvilVariable *v = typed_variable(inst, "fmi2GetReal", vr[i], ANVIL_REAL);
        if (v == NULL) return fmi2Error;
        if (v->causality == ANVIL_OUTPUT && !inst->outputs_valid) {
            if (!inst->built) {
                if (!(inst->state & (ST_INSTANTIATED | ST_INITIALIZATION)))
                    return refuse(inst, "fmi2GetReal: %s is not available: the instance failed "
                                  "(see the previous error); reset or free it", v->name);
                if (!build(inst)) return fail(inst, "outputs: %s", inst->reason);
            }
            compute_outputs(inst);
        }
        value[i] = inst->real[v->slot];
    }
    if (extrapolating(inst) && inst->has_evaluated) { /* Python: AnvilSlaveBase.get_real */
        inst->sent[0] = inst->evaluated[0];
        inst->sent[1] = inst->evaluated[1];
        inst->has_sent = 1;
        inst->sent_at_start = inst->evaluated_at_start;
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                       const fmi2Real value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2SetReal", SET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2SetReal", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        const AnvilVariable *v = typed_variable(inst, "fmi2SetReal", vr[i], ANVIL_REAL);
        if (v == NULL) return fmi2Error;
        if (v->causality == ANVIL_OUTPUT)
            return refuse(inst, "fmi2SetReal: %s is an output: it cannot be set", v->name);
        if (v->causality == ANVIL_PARAMETER) {
            if (check_parameter_change(inst, v) != fmi2OK) return fmi2Error;
            LOG_CALL(inst, "fmi2SetReal: %s = %.17g", v->name, value[i]);
        } else {
            if (extrapolating(inst)) note_inputs(inst);
            inst->outputs_valid = 0;
        }
        inst->real[v->slot] = value[i];
    }
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Integer value[])
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    REQUIRE_ARRAYS(inst, "fmi2GetInteger", nvr, vr, value);
    if (nvr > 0) return refuse(inst, "fmi2GetInteger: no Integer variable has value reference %u "
                               "(this FMU has none)", vr[0]);
    return fmi2OK;
}

fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Integer value[])
{
    Instance *inst = (Instance *)c;
    if (inst == NULL) return fmi2Error;
    REQUIRE_ARRAYS(inst, "fmi2SetInteger", nvr, vr, value);
    if (nvr > 0) return refuse(inst, "fmi2SetInteger: no Integer variable has value reference %u "
                               "(this FMU has none)", vr[0]);
    return fmi2OK;
}

fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2GetBoolean", GET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2GetBoolean", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        const AnvilVariable *v = typed_variable(inst, "fmi2GetBoolean", vr[i], ANVIL_BOOLEAN);
        if (v == NULL) return fmi2Error;
        value[i] = inst->boolean[v->slot];
    }
    return fmi2OK;
}

fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                          const fmi2Boolean value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2SetBoolean", SET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2SetBoolean", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        const AnvilVariable *v = typed_variable(inst, "fmi2SetBoolean", vr[i], ANVIL_BOOLEAN);
        if (v == NULL) return fmi2Error;
        if (check_parameter_change(inst, v) != fmi2OK) return fmi2Error;
        LOG_CALL(inst, "fmi2SetBoolean: %s = %d", v->name, value[i] ? 1 : 0);
        inst->boolean[v->slot] = value[i] ? fmi2True : fmi2False;
    }
    return fmi2OK;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         fmi2String value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2GetString", GET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2GetString", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        const AnvilVariable *v = typed_variable(inst, "fmi2GetString", vr[i], ANVIL_STRING);
        if (v == NULL) return fmi2Error;
        value[i] = inst->modal_data_file;
    }
    return fmi2OK;
}

fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                         const fmi2String value[])
{
    Instance *inst = (Instance *)c;
    size_t i;
    if (inst == NULL) return fmi2Error;
    REQUIRE_STATE(inst, "fmi2SetString", SET_STATES);
    REQUIRE_ARRAYS(inst, "fmi2SetString", nvr, vr, value);
    for (i = 0; i < nvr; i++) {
        char *copy;
        const AnvilVariable *v = typed_variable(inst, "fmi2SetString", vr[i], ANVIL_STRING);
        if (v == NULL) return fmi2Error;
        if (value[i] == NULL)
            return refuse(inst, "fmi2SetString: %s: null string", v->name);
        if (check_parameter_change(inst, v) != fmi2OK) return fmi2Error;
        LOG_CALL(inst, "fmi2SetString: %s = %s", v->name, value[i]);
        copy = copy_string(value[i]);
        if (copy == NULL) return fail(inst, "fmi2SetString: out of memory");
        free(inst->modal_data_file);
        inst->modal_data_file = copy;
    }
    return fmi2OK;
}

/* ------------------------------------------------------------------ not supported */
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2GetFMUstate: not supported (canGetAndSetFMUstate = false)");
}

fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate)
{
    (void)FMUstate;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2SetFMUstate: not supported (canGetAndSetFMUstate = false)");
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate)
{
    (void)FMUstate;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2FreeFMUstate: not supported (canGetAndSetFMUstate = false)");
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate, size_t *size)
{
    (void)FMUstate;
    (void)size;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2SerializedFMUstateSize: not supported "
                  "(canSerializeFMUstate = false)");
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate, fmi2Byte bytes[],
                                 size_t size)
{
    (void)FMUstate;
    (void)bytes;
    (void)size;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2SerializeFMUstate: not supported "
                  "(canSerializeFMUstate = false)");
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte serializedState[],
                                   size_t size, fmi2FMUstate *FMUstate)
{
    (void)serializedState;
    (void)size;
    (void)FMUstate;
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2DeSerializeFMUstate: not supported "
                  "(canSerializeFMUstate = false)");
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
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2GetDirectionalDerivative: not supported "
                  "(providesDirectionalDerivative = false)");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                       size_t nvr, const fmi2Integer order[],
                                       const fmi2Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    if (c == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    return refuse((Instance *)c, "fmi2SetRealInputDerivatives: not supported "
                  "(canInterpolateInputs = false)");
}

fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[],
                                        size_t nvr, const fmi2Integer order[],
                                        fmi2Real value[])
{
    (void)vr;
    (void)order;
    (void)value;
    if (c == NULL) return fmi2Error;
    if (nvr == 0) return fmi2OK;
    return refuse((Instance *)c, "fmi2GetRealOutputDerivatives: not supported "
                  "(maxOutputDerivativeOrder = 0)");
}

/* ------------------------------------------------------------------ stepping */
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                      fmi2Real communicationStepSize,
                      fmi2Boolean noSetFMUStatePriorToCurrentPoint)
{
    Instance *inst = (Instance *)c;
    double h = communicationStepSize;
    (void)noSetFMUStatePriorToCurrentPoint;
    if (inst == NULL) return fmi2Error;
    LOG_CALL(inst, "fmi2DoStep(t = %.17g, h = %.17g)", currentCommunicationPoint, h);
    if (inst->state == ST_ERROR)
        return fail(inst, "step at t = %.9g s: failed earlier (see the previous error): reset "
                    "or free it", currentCommunicationPoint);
    REQUIRE_STATE(inst, "fmi2DoStep", ST_STEP_COMPLETE);
    if (!(isfinite(h) && h > 0.0))
        return fail(inst, "step at t = %.9g s: communication step: must be positive, got %g s",
                    currentCommunicationPoint, h);
    if (h > FMU_MAX_STEP)
        return fail(inst, "step at t = %.9g s: communication step %g s is larger than %g s",
                    currentCommunicationPoint, h, FMU_MAX_STEP);
    if (extrapolating(inst)) {
        /* Python: AnvilSlaveBase.advance and InputExtrapolation.stepped */
        double u_ram, v_ram, u_pile, v_pile, force_ram, force_pile;
        extrapolated_inputs(inst, &u_ram, &v_ram, &u_pile, &v_pile);
        approach_input(inst, &u_ram, &v_ram);
        anvil_unit_forces(&inst->unit, u_ram, v_ram, u_pile, v_pile, &force_ram, &force_pile);
        if (inst->has_sent && inst->sent_at_start) { /* Python: InputExtrapolation.step_forces */
            force_ram = inst->sent[0];
            force_pile = inst->sent[1];
        }
        if (inst->has_sent) {
            inst->correction[0] = force_ram - inst->sent[0];
            inst->correction[1] = force_pile - inst->sent[1];
        } else {
            inst->correction[0] = inst->correction[1] = 0.0;
        }
        inst->has_sent = 0;
        anvil_unit_set_step(&inst->unit, h);
        anvil_unit_step(&inst->unit, force_ram, force_pile);
        if (force_ram > 0.0) inst->touched = 1;
    } else {
        if (!inst->outputs_valid) compute_outputs(inst);
        anvil_unit_set_step(&inst->unit, h);
        anvil_unit_step(&inst->unit, inst->real[ANVIL_F_RAM], inst->real[ANVIL_F_PILE]);
        if (inst->real[ANVIL_F_RAM] > 0.0) inst->touched = 1;
    }
    inst->last_step = h;
    inst->outputs_valid = 0;
    if (inst->unit.lcp_failed)
        return fail(inst, "step at t = %.9g s: the rings' contact problem found no solution in "
                    "%lu pivots (pile_port_rings)", currentCommunicationPoint,
                    (unsigned long)(50 * (inst->unit.K + 1)));
    inst->time = currentCommunicationPoint + h;
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c)
{
    if (c == NULL) return fmi2Error;
    return refuse((Instance *)c, "fmi2CancelStep: not supported (fmi2DoStep never returns "
                  "fmi2Pending)");
}

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value)
{
    (void)s;
    (void)value;
    if (c == NULL) return fmi2Error;
    return fmi2Discard; /* fmi2DoStep is never asynchronous */
}

fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *value)
{
    Instance *inst = (Instance *)c;
    if (inst == NULL || value == NULL) return fmi2Error;
    if (s != fmi2LastSuccessfulTime) return fmi2Discard;
    *value = inst->time;
    return fmi2OK;
}

fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *value)
{
    (void)s;
    (void)value;
    return c == NULL ? fmi2Error : fmi2Discard;
}

fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *value)
{
    if (c == NULL || value == NULL) return fmi2Error;
    if (s != fmi2Terminated) return fmi2Discard;
    *value = fmi2False; /* the anvil never asks to end the simulation */
    return fmi2OK;
}

fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *value)
{
    (void)s;
    (void)value;
    return c == NULL ? fmi2Error : fmi2Discard;
}
