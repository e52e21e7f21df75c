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
 * the hammer's at its rated energy.
 *
 * Variables (value references of the pythonfmu Ram unit): parameters v_impact [m/s] (0: the
 * hammer's), mass [kg] (0: the hammer's; else the segment masses are scaled to it), gravity
 * [m/s^2], contact_displacement [m], contact_time [s]; input F_toe [N]; outputs u_toe [m],
 * v_toe [m/s] (states, no feedthrough).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unit_model.h"

#define MAX_SUBSTEPS 1.0e8 /* more sub-steps in one communication step: refused */

enum { V_IMPACT, MASS, GRAVITY, CONTACT_DISPLACEMENT, CONTACT_TIME, F_TOE, U_TOE, V_TOE };

static const UnitVariable VARIABLES[] = {
    {1, UNIT_PARAMETER, "v_impact", 0.0},
    {2, UNIT_PARAMETER, "mass", 0.0},
    {3, UNIT_PARAMETER, "gravity", 9.81},
    {4, UNIT_PARAMETER, "contact_displacement", 0.0},
    {5, UNIT_PARAMETER, "contact_time", 0.0},
    {6, UNIT_INPUT, "F_toe", 0.0},
    {7, UNIT_OUTPUT, "u_toe", 0.0},
    {8, UNIT_OUTPUT, "v_toe", 0.0},
};

typedef struct {
    size_t n;
    double *mass;      /* (n) [kg] */
    double *stiffness; /* (n - 1) [N/m] */
    double total_mass, impact_velocity;
} RamModel;

typedef struct {
    size_t n;
    double *weight, *inverse_mass, *stiffness, *u, *v; /* (n), (n), (n - 1), (n), (n) */
    double stable_step, h;
    double n_sub;
} RamState;

static void free_model(void *p)
{
    RamModel *m = (RamModel *)p;
    if (m == NULL) return;
    free(m->mass);
    free(m->stiffness);
    free(m);
}

static double *copy_array(const double *values, size_t n)
{
    double *copy = (double *)malloc((n > 0 ? n : 1) * sizeof(double));
    if (copy != NULL && n > 0) memcpy(copy, values, n * sizeof(double));
    return copy;
}

static void *load(const FmuResource *res, char *reason, size_t reason_size)
{
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
    if (m->mass == NULL || m->stiffness == NULL) {
        free_model(m);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
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

static void free_state(void *p)
{
    RamState *s = (RamState *)p;
    if (s == NULL) return;
    free(s->weight);
    free(s->inverse_mass);
    free(s->stiffness);
    free(s->u);
    free(s->v);
    free(s);
}

static void *start(const void *p, const double *slots, double start_time, char *reason,
                   size_t reason_size)
{
    const RamModel *m = (const RamModel *)p;
    double gravity = slots[GRAVITY], wanted = slots[MASS], velocity = slots[V_IMPACT];
    double ratio = 1.0, u0;
    int scale = 0;
    size_t i, n = m->n;
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
        scale = 1;
        ratio = wanted / m->total_mass;
    }
    if (velocity == 0.0) velocity = m->impact_velocity;
    if (!(velocity > 0.0 && velocity <= 50.0)) {
        snprintf(reason, reason_size, "v_impact: must be in (0, 50] m/s, got %g", velocity);
        return NULL;
    }
    s = (RamState *)calloc(1, sizeof *s);
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
    u0 = slots[CONTACT_DISPLACEMENT] + velocity * (start_time - slots[CONTACT_TIME]);
    for (i = 0; i < n; i++) {
        s->u[i] = u0;
        s->v[i] = velocity;
    }
    s->h = NAN;
    s->n_sub = 1.0;
    return s;
}

static void outputs(const void *p, double *slots)
{
    const RamState *s = (const RamState *)p;
    slots[U_TOE] = s->u[s->n - 1];
    slots[V_TOE] = s->v[s->n - 1];
}

/* ram.py ram_advance */
static int step(void *p, const double *slots, double h, char *reason, size_t reason_size)
{
    RamState *s = (RamState *)p;
    double toe_force = slots[F_TOE], dt;
    size_t last = s->n - 1, i;
    long k, n_sub;
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

const UnitModel UNIT_MODEL = {"Ram", VARIABLES, sizeof VARIABLES / sizeof VARIABLES[0],
                              load, free_model, start, free_state, outputs, step};
