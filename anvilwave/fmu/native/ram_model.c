/*
 * ram_model.c -- the rod ram (anvilwave/hammer/ram.py) as a generic native unit (unit_model.h).
 *
 * The numerics of ram.py, operation for operation (compile without floating-point
 * contraction): stable_time_step (Gershgorin, the smaller of the two bounds), the sub-step
 * count of pile/model.py substeps, max(1, ceil(h / dt_stable - 1e-9)), and ram_advance, the
 * leapfrog sweep with the toe force held over the communication step. The parameters and
 * their checks are those of fmu/units/ram.py (RamSlave.build_component, start_component).
 *
 * Resource arrays (fmu_common.h): mass (n) [kg], top first; stiffness (n - 1) [N/m];
 * total_mass (1) [kg], the hammer's ram mass as Python sums it; impact_velocity (1) [m/s],
 * the hammer's at its rated energy. A modal ram (hammer/modal_ram.py ModalRamUnit) has also
 * modal_omega (m) [rad/s], the rigid-body mode 0 first, modal_participation (m) [kg^-1/2] at
 * the toe and modal_participation_gravity (1) [kg^1/2] of the rigid mode: every mode exact
 * over the step for the held force (no sub-steps); its toe sum runs in the loop's order where
 * the numba kernel may reassociate it, so the two agree to rounding. Optional:
 * default_experiment (3) [s], start, stop and step of the FMU's DefaultExperiment (checked,
 * unused by the ram).
 *
 * Variables (value references of the pythonfmu Ram unit): parameters v_impact [m/s] (0: the
 * hammer's), mass [kg] (0: the hammer's; else the segment masses are scaled to it), gravity
 * [m/s^2], contact_displacement [m], contact_time [s], contact_mid_step (Boolean, default
 * on); input F_toe [N]; outputs u_toe [m], v_toe [m/s] (states, no feedthrough).
 *
 * Start (fmu/units/ram.py RamSlave.start_component and advance, the same operations): with
 * contact_mid_step the first contact falls in the middle of the third communication step,
 * whatever the start time and step: until the first fmi2DoStep every mass is at
 * contact_displacement - v_impact OUT_OF_REACH_TIME (out of reach of any contact), and at the
 * first fmi2DoStep (step h) the unit starts again from contact_displacement - v_impact
 * (FIRST_CONTACT_STEPS h) before it steps. With it off the toe reaches contact_displacement at
 * contact_time: u = contact_displacement + v_impact (t_s - contact_time) at the start time t_s.
 * The default_experiment resource is checked but not used.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unit_model.h"

#define MAX_SUBSTEPS 1.0e8 /* more sub-steps in one communication step: refused */
#define FIRST_CONTACT_STEPS 2.5 /* steps from the start to the first contact (fmu/units/ram.py) */
#define OUT_OF_REACH_TIME 1.0 /* free flight to the contact before the first step [s] */

enum {
    V_IMPACT, MASS, GRAVITY, CONTACT_DISPLACEMENT, CONTACT_TIME, CONTACT_MID_STEP, F_TOE, U_TOE,
    V_TOE
};

static const UnitVariable VARIABLES[] = {
    {1, UNIT_PARAMETER, "v_impact", 0.0, UNIT_REAL, NULL},
    {2, UNIT_PARAMETER, "mass", 0.0, UNIT_REAL, NULL},
    {3, UNIT_PARAMETER, "gravity", 9.81, UNIT_REAL, NULL},
    {4, UNIT_PARAMETER, "contact_displacement", 0.0, UNIT_REAL, NULL},
    {5, UNIT_PARAMETER, "contact_time", 0.0, UNIT_REAL, NULL},
    {6, UNIT_PARAMETER, "contact_mid_step", 1.0, UNIT_BOOLEAN, NULL},
    {7, UNIT_INPUT, "F_toe", 0.0, UNIT_REAL, NULL},
    {8, UNIT_OUTPUT, "u_toe", 0.0, UNIT_REAL, NULL},
    {9, UNIT_OUTPUT, "v_toe", 0.0, UNIT_REAL, NULL},
};

typedef struct {
    size_t n;
    double *mass;      /* (n) [kg] */
    double *stiffness; /* (n - 1) [N/m] */
    double total_mass, impact_velocity;
    /* a modal ram: its toe modes, the rigid-body mode first (n_modes 0: a rod) */
    size_t n_modes;
    double *omega, *participation; /* (n_modes) [rad/s], [kg^-1/2] */
    double participation_gravity;  /* of the rigid-body mode [kg^1/2] */
} RamModel;

/* hammer/modal_ram.py ModalRamUnit: the two-step modal state */
typedef struct {
    size_t n;
    double *a, *force, *p, *omega; /* (n): 2 cos(w h), c p_toe, p_toe, w */
    double gravity_load;           /* c p_grav g of the rigid mode */
    double p_grav, gravity;
    double *q, *q_old;             /* (n): t_n and t_n-1 (swapped every step) */
    double u, v, h;
    int started;
    double start_u, start_v;
} ModalState;

typedef struct {
    size_t n;
    double *weight, *inverse_mass, *stiffness, *u, *v; /* (n), (n), (n - 1), (n), (n) */
    double stable_step, h;
    double n_sub;
    ModalState *modal; /* a modal ram: this instead of the chain */
    int placed;        /* the free flight placed for the first contact (contact_mid_step) */
    double contact_displacement, velocity; /* [m], [m/s] */
} RamState;

static void free_model(void *p)
{
    RamModel *m = (RamModel *)p;
    if (m == NULL) return;
    free(m->mass);
    free(m->stiffness);
    free(m->omega);
    free(m->participation);
    free(m);
}

static double *copy_array(const double *values, size_t n)
{
    double *copy = (double *)malloc((n > 0 ? n : 1) * sizeof(double));
    if (copy != NULL && n > 0) memcpy(copy, values, n * sizeof(double));
    return copy;
}

static void *load(const FmuResource *res, const char *resources, char *reason,
                  size_t reason_size)
{
    (void)resources;
    size_t n, nk, one_a, one_b, i;
    const double *mass = fmu_resource_array(res, "mass", &n);
    const double *stiffness = fmu_resource_array(res, "stiffness", &nk);
    const double *total = fmu_resource_array(res, "total_mass", &one_a);
    const double *velocity = fmu_resource_array(res, "impact_velocity", &one_b);
    RamModel *m;
    if (mass == NULL || n < 1 || stiffness == NULL || nk != n - 1 || total == NULL ||
        one_a != 1 || velocity == NULL || one_b != 1) {
        snprintf(reason, reason_size, "a ram needs the arrays mass (n >= 1), stiffness (n - 1), "
                 "total_mass (1) and impact_velocity (1)");
        return NULL;
    }
    for (i = 0; i < n; i++)
        if (!(mass[i] > 0.0)) {
            snprintf(reason, reason_size, "mass[%lu] must be positive", (unsigned long)i);
            return NULL;
        }
    for (i = 0; i < nk; i++)
        if (!(stiffness[i] > 0.0)) {
            snprintf(reason, reason_size, "stiffness[%lu] must be positive", (unsigned long)i);
            return NULL;
        }
    m = (RamModel *)calloc(1, sizeof *m);
    if (m == NULL) return NULL;
    m->n = n;
    m->mass = copy_array(mass, n);
    m->stiffness = copy_array(stiffness, nk);
    m->total_mass = total[0];
    m->impact_velocity = velocity[0];
    {
        size_t n_experiment;
        const double *experiment = fmu_resource_array(res, "default_experiment",
                                                      &n_experiment);
        if (experiment != NULL && (n_experiment != 3 || !(experiment[2] > 0.0))) {
            free_model(m);
            snprintf(reason, reason_size, "default_experiment must be (start, stop, step) with "
                     "a positive step");
            return NULL;
        }
    }
    if (m->mass == NULL || m->stiffness == NULL) {
        free_model(m);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    {
        size_t n_omega, n_p, n_g;
        const double *omega = fmu_resource_array(res, "modal_omega", &n_omega);
        const double *p = fmu_resource_array(res, "modal_participation", &n_p);
        const double *g = fmu_resource_array(res, "modal_participation_gravity", &n_g);
        if (omega == NULL) return m;
        if (n_omega < 1 || p == NULL || n_p != n_omega || g == NULL || n_g != 1 ||
            omega[0] != 0.0 || p[0] == 0.0) {
            free_model(m);
            snprintf(reason, reason_size, "a modal ram needs modal_omega (the rigid mode 0 "
                     "first), modal_participation (as many, p[0] != 0) and "
                     "modal_participation_gravity (1)");
            return NULL;
        }
        m->n_modes = n_omega;
        m->omega = copy_array(omega, n_omega);
        m->participation = copy_array(p, n_omega);
        m->participation_gravity = g[0];
        if (m->omega == NULL || m->participation == NULL) {
            free_model(m);
            snprintf(reason, reason_size, "out of memory");
            return NULL;
        }
    }
    return m;
}

/* ram.py stable_time_step */
static double stable_time_step(const double *mass, const double *stiffness, size_t n)
{
    double row_sum = 0.0, disc = 0.0, omega2;
    size_t i;
    for (i = 0; i < n; i++) {
        double k_sum = 0.0, off = 0.0, a, b;
        if (i > 0) {
            k_sum += stiffness[i - 1];
            off += stiffness[i - 1] / (sqrt(mass[i - 1]) * sqrt(mass[i]));
        }
        if (i < n - 1) {
            k_sum += stiffness[i];
            off += stiffness[i] / (sqrt(mass[i]) * sqrt(mass[i + 1]));
        }
        a = 2.0 * k_sum / mass[i];
        b = k_sum / mass[i] + off;
        if (a > row_sum) row_sum = a;
        if (b > disc) disc = b;
    }
    omega2 = row_sum < disc ? row_sum : disc;
    if (omega2 == 0.0) return INFINITY;
    return 2.0 / sqrt(omega2);
}

static void free_modal(ModalState *m)
{
    if (m == NULL) return;
    free(m->a);
    free(m->force);
    free(m->p);
    free(m->omega);
    free(m->q);
    free(m->q_old);
    free(m);
}

/* modal_ram.py ModalRamUnit._coefficients (rom.py modal_transition, undamped) */
static void modal_coefficients(ModalState *m, double h)
{
    size_t j;
    for (j = 0; j < m->n; j++) {
        double w = m->omega[j], a, c;
        if (w == 0.0) {
            a = 2.0;
            c = h * h;
        } else {
            a = 2.0 * 1.0 * cos(w * h);
            c = (1.0 - a - -1.0) / (w * w);
        }
        m->a[j] = a;
        m->force[j] = c * m->p[j];
        if (j == 0) m->gravity_load = c * m->p_grav * m->gravity;
    }
    m->h = h;
}

static void *start_modal(const RamModel *model, double gravity, double u0, double velocity,
                         char *reason, size_t reason_size)
{
    size_t n = model->n_modes;
    RamState *s = (RamState *)calloc(1, sizeof *s);
    ModalState *m = (ModalState *)calloc(1, sizeof *m);
    if (s == NULL || m == NULL) {
        free(s);
        free(m);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    s->modal = m;
    m->n = n;
    m->a = (double *)calloc(n, sizeof(double));
    m->force = (double *)calloc(n, sizeof(double));
    m->p = copy_array(model->participation, n);
    m->omega = copy_array(model->omega, n);
    m->q = (double *)calloc(n, sizeof(double));
    m->q_old = (double *)calloc(n, sizeof(double));
    if (m->a == NULL || m->force == NULL || m->p == NULL || m->omega == NULL || m->q == NULL ||
        m->q_old == NULL) {
        free_modal(m);
        free(s);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    m->p_grav = model->participation_gravity;
    m->gravity = gravity;
    m->h = NAN;
    /* fmu/units/ram.py ModalRamState: the two-step state needs the step, set at the first */
    m->start_u = m->u = u0;
    m->start_v = m->v = velocity;
    return s;
}

/* modal_ram.py ModalRamUnit.start / set_step and modal_ram_advance */
static void step_modal(ModalState *m, double toe_force, double h)
{
    size_t j;
    double u = 0.0, *swap;
    if (!m->started) {
        if (h != m->h) modal_coefficients(m, h);
        for (j = 0; j < m->n; j++) m->q[j] = m->q_old[j] = 0.0;
        m->q[0] = m->start_u / m->p[0];
        m->q_old[0] = (m->start_u - h * m->start_v) / m->p[0];
        m->u = m->start_u;
        m->v = m->start_v;
        m->started = 1;
    } else if (h != m->h) {
        for (j = 0; j < m->n; j++) m->q_old[j] = m->q[j] - h * (m->q[j] - m->q_old[j]) / m->h;
        modal_coefficients(m, h);
    }
    m->q_old[0] -= m->gravity_load;
    for (j = 0; j < m->n; j++) {
        double x = m->a[j] * m->q[j] - m->q_old[j] - m->force[j] * toe_force;
        m->q_old[j] = x;
        u += m->p[j] * x;
    }
    swap = m->q;
    m->q = m->q_old;
    m->q_old = swap;
    m->v = (u - m->u) / h;
    m->u = u;
}

static void free_state(void *p)
{
    RamState *s = (RamState *)p;
    if (s == NULL) return;
    free_modal(s->modal);
    free(s->weight);
    free(s->inverse_mass);
    free(s->stiffness);
    free(s->u);
    free(s->v);
    free(s);
}

static void *start_rod(const RamModel *m, double gravity, int scale, double ratio, double u0,
                       double velocity, char *reason, size_t reason_size);

static void *start(void *p, const double *slots, char *const *strings,
                   double start_time, char *reason, size_t reason_size)
{
    (void)strings;
    const RamModel *m = (const RamModel *)p;
    double gravity = slots[GRAVITY], wanted = slots[MASS], velocity = slots[V_IMPACT];
    double ratio = 1.0, u0, offset;
    int scale = 0, placed;
    RamState *s;
    if (!(gravity >= 0.0 && gravity <= 20.0)) {
        snprintf(reason, reason_size, "gravity: must be in [0, 20] m/s^2, got %g", gravity);
        return NULL;
    }
    if (!(wanted >= 0.0)) {
        snprintf(reason, reason_size, "mass: must be positive (or 0: the hammer's), got %g kg",
                 wanted);
        return NULL;
    }
    if (wanted > 0.0 && wanted != m->total_mass) {
        if (m->n_modes > 0) {
            snprintf(reason, reason_size, "mass: a modal ram keeps its own mass (%.6g kg): give "
                     "0, got %g kg", m->total_mass, wanted);
            return NULL;
        }
        scale = 1;
        ratio = wanted / m->total_mass;
    }
    if (velocity == 0.0) velocity = m->impact_velocity;
    if (!(velocity > 0.0 && velocity <= 50.0)) {
        snprintf(reason, reason_size, "v_impact: must be in (0, 50] m/s, got %g", velocity);
        return NULL;
    }
    placed = slots[CONTACT_MID_STEP] == 0.0;
    if (placed)
        offset = start_time - slots[CONTACT_TIME];
    else /* until the first step tells h (header) */
        offset = -OUT_OF_REACH_TIME;
    u0 = slots[CONTACT_DISPLACEMENT] + velocity * offset;
    if (m->n_modes > 0) {
        s = (RamState *)start_modal(m, gravity, u0, velocity, reason, reason_size);
        if (s == NULL) return NULL;
    } else {
        s = start_rod(m, gravity, scale, ratio, u0, velocity, reason, reason_size);
        if (s == NULL) return NULL;
    }
    s->placed = placed;
    s->contact_displacement = slots[CONTACT_DISPLACEMENT];
    s->velocity = velocity;
    return s;
}

static void *start_rod(const RamModel *m, double gravity, int scale, double ratio, double u0,
                       double velocity, char *reason, size_t reason_size)
{
    size_t i, n = m->n;
    RamState *s = (RamState *)calloc(1, sizeof *s);
    if (s == NULL) return NULL;
    s->n = n;
    s->weight = (double *)malloc(n * sizeof(double));
    s->inverse_mass = (double *)malloc(n * sizeof(double));
    s->stiffness = copy_array(m->stiffness, n - 1);
    s->u = (double *)malloc(n * sizeof(double));
    s->v = (double *)malloc(n * sizeof(double));
    if (s->weight == NULL || s->inverse_mass == NULL || s->stiffness == NULL || s->u == NULL ||
        s->v == NULL) {
        free_state(s);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    /* the scaled masses live in inverse_mass until the stable step is known */
    for (i = 0; i < n; i++) s->inverse_mass[i] = scale ? m->mass[i] * ratio : m->mass[i];
    s->stable_step = stable_time_step(s->inverse_mass, s->stiffness, n);
    for (i = 0; i < n; i++) {
        double mass = s->inverse_mass[i];
        s->weight[i] = mass * gravity;
        s->inverse_mass[i] = 1.0 / mass;
    }
    for (i = 0; i < n; i++) {
        s->u[i] = u0;
        s->v[i] = velocity;
    }
    s->h = NAN;
    s->n_sub = 1.0;
    return s;
}

static void outputs(void *p, double *slots, double time)
{
    (void)time;
    const RamState *s = (const RamState *)p;
    if (s->modal != NULL) {
        slots[U_TOE] = s->modal->u;
        slots[V_TOE] = s->modal->v;
        return;
    }
    slots[U_TOE] = s->u[s->n - 1];
    slots[V_TOE] = s->v[s->n - 1];
}

/* ram.py ram_advance */
static int step(void *p, const double *slots, double time, double h, char *reason,
                size_t reason_size)
{
    (void)time;
    RamState *s = (RamState *)p;
    double toe_force = slots[F_TOE], dt;
    size_t last, i;
    long k, n_sub;
    if (!s->placed) { /* the first contact in the middle of the third step (header) */
        double u0 = s->contact_displacement - s->velocity * (FIRST_CONTACT_STEPS * h);
        if (s->modal != NULL) {
            s->modal->start_u = s->modal->u = u0;
            s->modal->start_v = s->modal->v = s->velocity;
        } else {
            for (i = 0; i < s->n; i++) {
                s->u[i] = u0;
                s->v[i] = s->velocity;
            }
        }
        s->placed = 1;
    }
    if (s->modal != NULL) {
        step_modal(s->modal, toe_force, h);
        return 1;
    }
    last = s->n - 1;
    if (h != s->h) {
        double n = ceil(h / s->stable_step - 1e-9);
        if (!(n <= MAX_SUBSTEPS)) {
            snprintf(reason, reason_size, "the step %g s needs %g sub-steps of at most %g s "
                     "(more than %g)", h, n, s->stable_step, MAX_SUBSTEPS);
            return 0;
        }
        s->n_sub = n > 1.0 ? n : 1.0;
        s->h = h;
    }
    n_sub = (long)s->n_sub;
    dt = h / s->n_sub;
    for (k = 0; k < n_sub; k++) {
        double from_above = 0.0, v_new;
        for (i = 0; i < last; i++) {
            double spring = s->stiffness[i] * (s->u[i] - s->u[i + 1]);
            v_new = s->v[i] + dt * (from_above + s->weight[i] - spring) * s->inverse_mass[i];
            s->v[i] = v_new;
            s->u[i] += dt * v_new;
            from_above = spring;
        }
        v_new = s->v[last] + dt * (from_above + s->weight[last] - toe_force) *
                                 s->inverse_mass[last];
        s->v[last] = v_new;
        s->u[last] += dt * v_new;
    }
    return 1;
}

static const UnitModel MODEL = {"Ram", VARIABLES, sizeof VARIABLES / sizeof VARIABLES[0],
                                0, 0, load, free_model, start, free_state, outputs, step,
                                NULL, NULL};

const UnitModel *const UNIT_MODELS[] = {&MODEL};
const size_t N_UNIT_MODELS = 1;
