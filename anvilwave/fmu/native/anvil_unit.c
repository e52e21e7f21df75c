/*
 * anvil_unit.c -- the anvilwave anvil as a native unit (unit_model.h): the Mode Displacement
 * Method ROM (model identifier "Anvil") and the rigid lumped mass ("AnvilLumped") in one
 * binary, picked by the kind of resources/anvilwave_unit.txt.
 *
 * Interface (DESIGN.md, the contract; the same names, value references, types and causalities
 * as the pythonfmu Anvil / AnvilLumped units, so either can be swapped in, and as
 * fmu/native_build.py anvil_variables): the value reference of a variable is its position in
 * the table below. Inputs u_ram [m], v_ram [m/s] (ram toe), u_pile [m], v_pile [m/s] (pile
 * head); outputs F_ram, F_pile [N] (contact forces, compression positive) and u_top,
 * u_bottom [m] (interface displacements); z down.
 *
 * What a build makes particular is the resource: the kind, the GUID and the start value of
 * every Real and Boolean parameter (fmu_common.h; Booleans 0 or 1). The ROM's modes are the
 * binary modal-data resource (anvil_model.h) named by the String parameter modal_data_file,
 * whose start value is always the embedded "modal_data.bin" (the build refuses another); a
 * relative name is looked up in the FMU's resources folder. The file is read when the unit is
 * built (at the end of initialization), again only when modal_data_file names another one.
 *
 * Behaviour (that of fmu/units/anvil.py):
 * - The forces are a direct feedthrough of the inputs: reading an output evaluates them from
 *   the inputs set at the current communication point. A step holds these forces over the
 *   step and advances the modes by the exact per-mode recurrence (anvil_model.h). The
 *   recurrence is unconditionally stable, so the unit takes any communication step h in one
 *   step, as the Python unit does; a change of h rescales the two-step state
 *   (anvil_unit_set_step).
 * - At the end of initialization the anvil rests on the pile in static equilibrium under
 *   gravity (start_at_rest) with the pile head at initial_pile_head_displacement [m].
 * - Input extrapolation (Boolean parameter input_extrapolation, for Jacobi-type masters that
 *   read the forces after the step, with the inputs of the step before): the operations of
 *   fmu/coupling.py (InputExtrapolation, extrapolated_input), in the same order. Inputs set
 *   at a new communication point keep the velocities of the point before (the neighbours'
 *   accelerations); the outputs use the inputs extrapolated to the unit's time; a step steps
 *   with the forces at the step start and keeps their difference to the forces of the last
 *   output read since the step before as an impulse correction of the force outputs, except
 *   when that output came from the start time's inputs: then it steps with the forces of
 *   that output, with no correction. With ram_toe_mass [kg] > 0 (Real parameter, default 0)
 *   the ram's extrapolation adds the toe's response to the change of the F_ram output it
 *   holds since the inputs (extrapolated_input). With inputs set at the unit's time before
 *   the outputs are read (the DESIGN.md order), nothing changes.
 * - A bad parameter value or modal-data file, a failed ring contact problem: the model's
 *   reason, reported by the FMI layer (unit_core.h) as an error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "anvil_model.h"
#include "unit_model.h"

/* The ROM's own parameters (slots 0 to 3), the lumped anvil's (slot 0), then the common
 * variables from slot ROM_BASE or LUMPED_BASE. */
enum { MODAL_DATA_FILE, FMAX, DAMPING_RATIO, STATIC_CORRECTION, ROM_BASE };
enum { MASS, LUMPED_BASE };
enum {
    RAM_CONTACT_STIFFNESS, PILE_CONTACT_STIFFNESS, RAM_CONTACT_DAMPING, PILE_CONTACT_DAMPING,
    GRAVITY, START_AT_REST, INITIAL_PILE_HEAD_DISPLACEMENT, INPUT_EXTRAPOLATION,
    U_RAM, V_RAM, U_PILE, V_PILE, F_RAM, F_PILE, U_TOP, U_BOTTOM, RAM_TOE_MASS, N_COMMON
};

#define MODAL_RESOURCE "modal_data.bin"

#define COMMON(vr)                                                                               \
    {(vr) + 0, UNIT_PARAMETER, "ram_contact_stiffness", 0.0, UNIT_REAL, NULL},                   \
    {(vr) + 1, UNIT_PARAMETER, "pile_contact_stiffness", 0.0, UNIT_REAL, NULL},              \
    {(vr) + 2, UNIT_PARAMETER, "ram_contact_damping", 0.0, UNIT_REAL, NULL},                 \
    {(vr) + 3, UNIT_PARAMETER, "pile_contact_damping", 0.0, UNIT_REAL, NULL},                \
    {(vr) + 4, UNIT_PARAMETER, "gravity", 9.81, UNIT_REAL, NULL},                            \
    {(vr) + 5, UNIT_PARAMETER, "start_at_rest", 1.0, UNIT_BOOLEAN, NULL},                    \
    {(vr) + 6, UNIT_PARAMETER, "initial_pile_head_displacement", 0.0, UNIT_REAL, NULL},      \
    {(vr) + 7, UNIT_PARAMETER, "input_extrapolation", 0.0, UNIT_BOOLEAN, NULL},              \
    {(vr) + 8, UNIT_INPUT, "u_ram", 0.0, UNIT_REAL, NULL},                                   \
    {(vr) + 9, UNIT_INPUT, "v_ram", 0.0, UNIT_REAL, NULL},                                   \
    {(vr) + 10, UNIT_INPUT, "u_pile", 0.0, UNIT_REAL, NULL},                                 \
    {(vr) + 11, UNIT_INPUT, "v_pile", 0.0, UNIT_REAL, NULL},                                 \
    {(vr) + 12, UNIT_OUTPUT, "F_ram", 0.0, UNIT_REAL, NULL},                                 \
    {(vr) + 13, UNIT_OUTPUT, "F_pile", 0.0, UNIT_REAL, NULL},                                \
    {(vr) + 14, UNIT_OUTPUT, "u_top", 0.0, UNIT_REAL, NULL},                                 \
    {(vr) + 15, UNIT_OUTPUT, "u_bottom", 0.0, UNIT_REAL, NULL},                             \
    {(vr) + 16, UNIT_PARAMETER, "ram_toe_mass", 0.0, UNIT_REAL, NULL}

static const UnitVariable ROM_VARIABLES[] = {
    {MODAL_DATA_FILE, UNIT_PARAMETER, "modal_data_file", 0.0, UNIT_STRING, MODAL_RESOURCE},
    {FMAX, UNIT_PARAMETER, "fmax", 0.0, UNIT_REAL, NULL},
    {DAMPING_RATIO, UNIT_PARAMETER, "damping_ratio", 0.0, UNIT_REAL, NULL},
    {STATIC_CORRECTION, UNIT_PARAMETER, "static_correction", 0.0, UNIT_BOOLEAN, NULL},
    COMMON(ROM_BASE),
};

static const UnitVariable LUMPED_VARIABLES[] = {
    {MASS, UNIT_PARAMETER, "mass", 0.0, UNIT_REAL, NULL},
    COMMON(LUMPED_BASE),
};

typedef struct {
    int lumped;
    char *resources;     /* the resources folder */
    AnvilModalData data; /* the modal data last read, from data_path (ROM) */
    char *data_path;
} AnvilModel;

typedef struct {
    size_t base; /* the slot of the first common variable */
    int extrapolation;
    AnvilUnit unit;
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
    double ram_toe_mass;  /* the ram toe's mass for a force step [kg]; 0: none */
    double output_ram;    /* F_ram output of the last evaluation, corrected [N] */
    double sent_output;   /* ... of the last one read since the last step [N] */
    double held;          /* the F_ram output the ram holds over the last step [N] */
    double ram_forces[2]; /* F_ram over the step that gave the inputs and since them [N] */
    /* before the first contact (Python: approach_input) */
    int touched;       /* the ram contact has carried a force */
    double last_step;  /* the last communication step [s]; 0: none yet */
    int outputs_valid; /* evaluated from the current inputs and state */
    double outputs[4]; /* F_ram, F_pile, u_top, u_bottom of that evaluation [N, m] */
} AnvilState;

/* ------------------------------------------------------------------ the model */
static void *load(const FmuResource *res, const char *resources, char *reason,
                  size_t reason_size, int lumped)
{
    AnvilModel *m = (AnvilModel *)calloc(1, sizeof *m);
    (void)res;
    if (m == NULL || (m->resources = fmu_copy_string(resources)) == NULL) {
        free(m);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    m->lumped = lumped;
    return m;
}

static void *load_rom(const FmuResource *res, const char *resources, char *reason,
                      size_t reason_size)
{
    return load(res, resources, reason, reason_size, 0);
}

static void *load_lumped(const FmuResource *res, const char *resources, char *reason,
                         size_t reason_size)
{
    return load(res, resources, reason, reason_size, 1);
}

static void free_model(void *p)
{
    AnvilModel *m = (AnvilModel *)p;
    anvil_modal_data_free(&m->data);
    free(m->data_path);
    free(m->resources);
    free(m);
}

/* The modal data named by modal_data_file (absolute as is, relative inside the resources),
 * read unless it is the file read last; 0 with the reason. */
static int load_modal_data(AnvilModel *m, const char *name, char *reason, size_t reason_size)
{
    AnvilModalData data;
    char error[FMU_MESSAGE_SIZE / 4];
    char *path = fmu_is_absolute(name) ? fmu_copy_string(name) : fmu_join(m->resources, name);
    if (path == NULL) {
        snprintf(reason, reason_size, "out of memory");
        return 0;
    }
    if (m->data_path != NULL && strcmp(path, m->data_path) == 0) {
        free(path);
        return 1;
    }
    if (!anvil_modal_data_read(path, &data, error, sizeof error)) {
        snprintf(reason, reason_size, "modal_data_file: %s: %s", path, error);
        free(path);
        return 0;
    }
    anvil_modal_data_free(&m->data);
    free(m->data_path);
    m->data = data;
    m->data_path = path;
    return 1;
}

/* ------------------------------------------------------------------ input extrapolation */
/* Python: extrapolated_input. A neighbour's (displacement [m], velocity [m/s]) age [s] after it
 * was received; velocity is its half-step value, previous_velocity the one received interval
 * [s] earlier (interval 0: no acceleration); with a toe mass [kg] > 0 plus the toe's response
 * to the change of the contact force [N] from force (over the step that gave velocity) to
 * force_after (since). */
static void extrapolated_input(double displacement, double velocity, double previous_velocity,
                               double age, double interval, double force, double force_after,
                               double toe_mass, double *u, double *v)
{
    double acceleration, change;
    if (age == 0.0) {
        *u = displacement;
        *v = velocity;
        return;
    }
    acceleration = interval > 0.0 ? (velocity - previous_velocity) / interval : 0.0;
    *u = displacement + age * (velocity + 0.5 * interval * acceleration) +
         0.5 * acceleration * age * age;
    *v = velocity + acceleration * age;
    if (toe_mass > 0.0) {
        change = -(force_after - force) * age / toe_mass;
        *u = *u + age * change;
        *v = *v + change;
    }
}

/* Python: InputExtrapolation(time), a fresh state at the unit's time (and the approach's:
 * AnvilSlaveBase.start_component). */
static void start_extrapolation(AnvilState *s, double time)
{
    s->touched = 0;
    s->last_step = 0.0;
    s->input_start = time;
    s->input_time = time;
    s->input_interval = 0.0;
    s->previous_velocity[0] = s->previous_velocity[1] = 0.0;
    s->correction[0] = s->correction[1] = 0.0;
    s->has_evaluated = s->has_sent = 0;
    s->evaluated_at_start = s->sent_at_start = 0;
    s->output_ram = s->sent_output = s->held = 0.0;
    s->ram_forces[0] = s->ram_forces[1] = 0.0;
}

/* Python: InputExtrapolation.note_inputs, before new inputs are stored (the unit's hook
 * inputs_set). While the point before is the start time the interval is 0 (no
 * acceleration): inputs there are a master's initial values (e.g. the zeros of fmpy's SSP
 * runner), not the neighbours' states. */
static void inputs_set(void *p, const double *slots, double time)
{
    AnvilState *s = (AnvilState *)p;
    const double *r = slots + s->base;
    s->outputs_valid = 0;
    if (!s->extrapolation) return;
    if (time > s->input_time) {
        s->previous_velocity[0] = r[V_RAM];
        s->previous_velocity[1] = r[V_PILE];
        s->ram_forces[0] = s->held;
        s->input_interval = s->input_time > s->input_start ? time - s->input_time : 0.0;
        s->input_time = time;
    }
}

/* Python: AnvilSlaveBase.get_real: the forces a host read since the last step. */
static void outputs_read(void *p)
{
    AnvilState *s = (AnvilState *)p;
    if (!s->extrapolation || !s->has_evaluated) return;
    s->sent[0] = s->evaluated[0];
    s->sent[1] = s->evaluated[1];
    s->has_sent = 1;
    s->sent_at_start = s->evaluated_at_start;
    s->sent_output = s->output_ram;
}

/* Python: approach_input and AnvilSlaveBase.approached. Until the ram contact has carried a
 * force, after a step h a toe open by more than it closes in one step is taken out of reach
 * (1 m above the top face, at its velocity): the contact dashpot's lead across the gap starts
 * at most a step before the first contact, as in the engine. */
static void approach_input(AnvilState *s, double *u_ram, double *v_ram)
{
    double u_top, v_top, gap;
    if (s->touched || s->last_step == 0.0) return;
    anvil_unit_outputs(&s->unit, 0.0, 0.0, &u_top, &v_top, NULL, NULL);
    gap = u_top - *u_ram;
    if (gap > 0.0 && gap > (*v_ram - v_top) * s->last_step) {
        *u_ram = u_top - 1.0;
        *v_ram = v_top;
    }
}

/* Python: InputExtrapolation.extrapolated, the inputs at the unit's time. */
static void extrapolated_inputs(const AnvilState *s, const double *r, double time,
                                double *u_ram, double *v_ram, double *u_pile, double *v_pile)
{
    double age = time - s->input_time;
    extrapolated_input(r[U_RAM], r[V_RAM], s->previous_velocity[0], age, s->input_interval,
                       s->ram_forces[0], s->ram_forces[1], s->ram_toe_mass, u_ram, v_ram);
    extrapolated_input(r[U_PILE], r[V_PILE], s->previous_velocity[1], age, s->input_interval,
                       0.0, 0.0, 0.0, u_pile, v_pile);
}

/* ------------------------------------------------------------------ the unit */
/* The component from the parameters (Python: build_component + start_component). */
static void *start(void *p, const double *slots, char *const *strings, double start_time,
                   char *reason, size_t reason_size)
{
    AnvilModel *m = (AnvilModel *)p;
    size_t base = m->lumped ? LUMPED_BASE : ROM_BASE;
    const double *r = slots + base;
    AnvilContact contact;
    AnvilState *s;
    int ok;
    contact.ram_stiffness = r[RAM_CONTACT_STIFFNESS];
    contact.ram_damping = r[RAM_CONTACT_DAMPING];
    contact.pile_stiffness = r[PILE_CONTACT_STIFFNESS];
    contact.pile_damping = r[PILE_CONTACT_DAMPING];
    if (!anvil_check_parameters(&contact, r[GRAVITY], r[INITIAL_PILE_HEAD_DISPLACEMENT],
                                reason, reason_size))
        return NULL;
    if (!(isfinite(r[RAM_TOE_MASS]) && r[RAM_TOE_MASS] >= 0.0)) { /* check_ram_toe_mass */
        snprintf(reason, reason_size, "ram_toe_mass: must be >= 0 [kg], got %g", r[RAM_TOE_MASS]);
        return NULL;
    }
    if (!m->lumped && !load_modal_data(m, strings[MODAL_DATA_FILE], reason, reason_size))
        return NULL;
    if ((s = (AnvilState *)calloc(1, sizeof *s)) == NULL) {
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    if (m->lumped)
        ok = anvil_unit_rigid(&s->unit, slots[MASS], &contact, r[GRAVITY], reason,
                              reason_size);
    else
        ok = anvil_unit_modal(&s->unit, &m->data, slots[FMAX], slots[DAMPING_RATIO],
                              slots[STATIC_CORRECTION] != 0.0, &contact, r[GRAVITY], reason,
                              reason_size);
    if (!ok) {
        free(s);
        return NULL;
    }
    if (r[START_AT_REST] != 0.0)
        anvil_unit_rest_on_pile(&s->unit, r[INITIAL_PILE_HEAD_DISPLACEMENT]);
    s->base = base;
    s->extrapolation = r[INPUT_EXTRAPOLATION] != 0.0;
    start_extrapolation(s, start_time);
    s->ram_toe_mass = r[RAM_TOE_MASS];
    return s;
}

static void free_state(void *p)
{
    AnvilState *s = (AnvilState *)p;
    anvil_unit_free(&s->unit);
    free(s);
}

/* Python: anvil_outputs (forces, then the displacements under them); with input extrapolation
 * (Python: AnvilSlaveBase.compute_outputs) at the inputs extrapolated to the unit's time, the
 * forces plus the impulse correction. */
static void evaluate(AnvilState *s, const double *slots, double time)
{
    const double *r = slots + s->base;
    double force_ram, force_pile, u_top, u_bottom;
    double u_ram = r[U_RAM], v_ram = r[V_RAM], u_pile = r[U_PILE], v_pile = r[V_PILE];
    if (s->extrapolation)
        extrapolated_inputs(s, r, time, &u_ram, &v_ram, &u_pile, &v_pile);
    approach_input(s, &u_ram, &v_ram);
    anvil_unit_forces(&s->unit, u_ram, v_ram, u_pile, v_pile, &force_ram, &force_pile);
    anvil_unit_outputs(&s->unit, force_ram, force_pile, &u_top, NULL, &u_bottom, NULL);
    s->outputs[0] = force_ram;
    s->outputs[1] = force_pile;
    s->outputs[2] = u_top;
    s->outputs[3] = u_bottom;
    if (s->extrapolation) {
        s->evaluated[0] = force_ram;
        s->evaluated[1] = force_pile;
        s->has_evaluated = 1;
        s->evaluated_at_start = s->input_time == s->input_start;
        s->outputs[0] += s->correction[0];
        s->outputs[1] += s->correction[1];
        s->output_ram = s->outputs[0];
    }
    s->outputs_valid = 1;
}

static void outputs(void *p, double *slots, double time)
{
    AnvilState *s = (AnvilState *)p;
    double *r = slots + s->base;
    evaluate(s, slots, time);
    r[F_RAM] = s->outputs[0];
    r[F_PILE] = s->outputs[1];
    r[U_TOP] = s->outputs[2];
    r[U_BOTTOM] = s->outputs[3];
}

static int step(void *p, const double *slots, double time, double h, char *reason,
                size_t reason_size)
{
    AnvilState *s = (AnvilState *)p;
    double force_ram, force_pile;
    if (s->extrapolation) {
        /* Python: AnvilSlaveBase.advance and InputExtrapolation.stepped */
        const double *r = slots + s->base;
        double u_ram, v_ram, u_pile, v_pile;
        extrapolated_inputs(s, r, time, &u_ram, &v_ram, &u_pile, &v_pile);
        approach_input(s, &u_ram, &v_ram);
        anvil_unit_forces(&s->unit, u_ram, v_ram, u_pile, v_pile, &force_ram, &force_pile);
        if (s->has_sent && s->sent_at_start) { /* Python: InputExtrapolation.step_forces */
            force_ram = s->sent[0];
            force_pile = s->sent[1];
        }
        if (s->has_sent) {
            s->correction[0] = force_ram - s->sent[0];
            s->correction[1] = force_pile - s->sent[1];
            s->held = s->sent_output;
        } else {
            s->correction[0] = s->correction[1] = 0.0;
        }
        if (time == s->input_time) s->ram_forces[1] = s->held;
        s->has_sent = 0;
    } else {
        if (!s->outputs_valid) evaluate(s, slots, time);
        force_ram = s->outputs[0];
        force_pile = s->outputs[1];
    }
    anvil_unit_set_step(&s->unit, h);
    anvil_unit_step(&s->unit, force_ram, force_pile);
    if (force_ram > 0.0) s->touched = 1;
    s->last_step = h;
    s->outputs_valid = 0;
    if (s->unit.lcp_failed) {
        snprintf(reason, reason_size, "the rings' contact problem found no solution in %lu "
                 "pivots (pile_port_rings)", (unsigned long)(50 * (s->unit.K + 1)));
        return 0;
    }
    return 1;
}

static const UnitModel ROM = {"Anvil", ROM_VARIABLES,
                              sizeof ROM_VARIABLES / sizeof ROM_VARIABLES[0],
                              ROM_BASE + N_COMMON, 1, load_rom, free_model, start, free_state,
                              outputs, step, inputs_set, outputs_read};

static const UnitModel LUMPED = {"AnvilLumped", LUMPED_VARIABLES,
                                 sizeof LUMPED_VARIABLES / sizeof LUMPED_VARIABLES[0],
                                 LUMPED_BASE + N_COMMON, 1, load_lumped, free_model, start,
                                 free_state, outputs, step, inputs_set, outputs_read};

const UnitModel *const UNIT_MODELS[] = {&ROM, &LUMPED};
const size_t N_UNIT_MODELS = 2;
