/*
 * pile_soil_model.c -- the Smith pile with its soil (anvilwave/pile/kernels.py, model.py,
 * static.py) as a generic native unit (unit_model.h).
 *
 * The numerics of the Python kernels, operation for operation (compile without
 * floating-point contraction): static_equilibrium (the active-set iteration on the
 * tridiagonal system, solved as LAPACK dgtsv does, which scipy's solve_banded calls),
 * stable_time_step, the sub-step count max(1, ceil(h / dt_stable - 1e-9)), the sweep of
 * pile_advance (_pile_sweep and _soil_spring, without the work sums the FMU does not output),
 * head_displacement, head_velocity, gauge_force, gauge_velocity and update_stress_extremes.
 * The parameters and their checks are those of fmu/units/pile_soil.py for static_head_load
 * and gravity; the pile sections, discretisation and soil model are fixed by the build (its
 * kernel arrays are the resource).
 *
 * Resource arrays (fmu_common.h), the kernel arrays of pile/model.py PileSoil.arrays(), row
 * by row: pile (3 N: mass [kg], stiffness [N/m], dashpot [N s/m] of the spring below each
 * mass), soil (5 (N + 1): capacity [N], tension [N], stiffness [N/m], Smith damping [s/m],
 * dashpot [N s/m]; column N the toe), probes (5: gauge spring, its weight, gauge mass, its
 * weight, head extrapolation) and stress_factor (N - 1) [N/m^3].
 *
 * Variables (value references of the pythonfmu PileSoil unit): parameters static_head_load
 * [N], gravity [m/s^2]; input F_head [N]; outputs u_head, v_head, F_gauge, v_gauge,
 * u_head_total, u_pile_toe, max_compression_stress, max_tension_stress (states).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unit_model.h"

#define MAX_SUBSTEPS 1.0e8
#define MAX_ITERATIONS 200

enum {
    STATIC_HEAD_LOAD, GRAVITY, F_HEAD, U_HEAD, V_HEAD, F_GAUGE, V_GAUGE, U_HEAD_TOTAL,
    U_PILE_TOE, MAX_COMPRESSION_STRESS, MAX_TENSION_STRESS
};

static const UnitVariable VARIABLES[] = {
    {1, UNIT_PARAMETER, "static_head_load", 0.0, UNIT_REAL, NULL},
    {2, UNIT_PARAMETER, "gravity", 9.81, UNIT_REAL, NULL},
    {17, UNIT_INPUT, "F_head", 0.0, UNIT_REAL, NULL},
    {18, UNIT_OUTPUT, "u_head", 0.0, UNIT_REAL, NULL},
    {19, UNIT_OUTPUT, "v_head", 0.0, UNIT_REAL, NULL},
    {20, UNIT_OUTPUT, "F_gauge", 0.0, UNIT_REAL, NULL},
    {21, UNIT_OUTPUT, "v_gauge", 0.0, UNIT_REAL, NULL},
    {22, UNIT_OUTPUT, "u_head_total", 0.0, UNIT_REAL, NULL},
    {23, UNIT_OUTPUT, "u_pile_toe", 0.0, UNIT_REAL, NULL},
    {24, UNIT_OUTPUT, "max_compression_stress", 0.0, UNIT_REAL, NULL},
    {25, UNIT_OUTPUT, "max_tension_stress", 0.0, UNIT_REAL, NULL},
};

enum { CAPACITY, TENSION, STIFFNESS, SMITH, DASHPOT };
enum { GAUGE_SPRING, GAUGE_SPRING_WEIGHT, GAUGE_MASS, GAUGE_MASS_WEIGHT, HEAD_EXTRAPOLATION };

typedef struct {
    size_t n;
    double *mass, *k, *c;   /* (n): masses, springs and dashpots below each mass */
    double *soil[5];        /* (n + 1) each */
    double probes[5];
    double *stress_factor;  /* (n - 1) */
    double *block;          /* the storage of all of them */
} PileModel;

typedef struct {
    const PileModel *m;
    size_t n;
    double *weight, *inverse_mass, *yield_down, *yield_up; /* (n), (n), (n + 1), (n + 1) */
    size_t first_soil;
    double *u, *v, *offset; /* (n), (n), (n + 1) */
    double face0, stable_step, h, n_sub;
    double extremes[2];
    double *block;
} PileState;

static void free_model(void *p)
{
    PileModel *m = (PileModel *)p;
    if (m == NULL) return;
    free(m->block);
    free(m);
}

static void *load(const FmuResource *res, const char *resources, char *reason,
                  size_t reason_size)
{
    (void)resources;
    size_t n_pile, n_soil, n_probes, n_stress, n, i, r;
    const double *pile = fmu_resource_array(res, "pile", &n_pile);
    const double *soil = fmu_resource_array(res, "soil", &n_soil);
    const double *probes = fmu_resource_array(res, "probes", &n_probes);
    const double *stress = fmu_resource_array(res, "stress_factor", &n_stress);
    PileModel *m;
    double *p;
    n = n_pile / 3;
    if (pile == NULL || n < 2 || n_pile != 3 * n || soil == NULL || n_soil != 5 * (n + 1) ||
        probes == NULL || n_probes != 5 || stress == NULL || n_stress != n - 1) {
        snprintf(reason, reason_size, "a pile needs the arrays pile (3 N, N >= 2), soil "
                 "(5 (N + 1)), probes (5) and stress_factor (N - 1)");
        return NULL;
    }
    for (i = 0; i < n; i++)
        if (!(pile[i] > 0.0)) {
            snprintf(reason, reason_size, "pile mass %lu must be positive", (unsigned long)i);
            return NULL;
        }
    if (!(probes[GAUGE_SPRING] >= 0.0 && probes[GAUGE_SPRING] + 1.0 < (double)n &&
          probes[GAUGE_MASS] >= 0.0 && probes[GAUGE_MASS] < (double)n)) {
        snprintf(reason, reason_size, "the gauge lies outside the pile");
        return NULL;
    }
    m = (PileModel *)calloc(1, sizeof *m);
    if (m == NULL) return NULL;
    m->block = (double *)malloc((3 * n + 5 * (n + 1) + (n - 1)) * sizeof(double));
    if (m->block == NULL) {
        free(m);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    m->n = n;
    p = m->block;
    memcpy(p, pile, 3 * n * sizeof(double));
    m->mass = p;
    m->k = p + n;
    m->c = p + 2 * n;
    p += 3 * n;
    memcpy(p, soil, 5 * (n + 1) * sizeof(double));
    for (r = 0; r < 5; r++) m->soil[r] = p + r * (n + 1);
    p += 5 * (n + 1);
    memcpy(p, stress, (n - 1) * sizeof(double));
    m->stress_factor = p;
    memcpy(m->probes, probes, sizeof m->probes);
    return m;
}

/* kernels.py stable_time_step */
static double stable_time_step(const PileModel *m)
{
    const double *mass = m->mass, *k = m->k, *c = m->c;
    double *const *soil = m->soil;
    size_t n = m->n, i;
    double dt_min = INFINITY;
    for (i = 0; i < n; i++) {
        double k_diag = soil[STIFFNESS][i];
        double c_diag = soil[DASHPOT][i] + soil[SMITH][i] * soil[CAPACITY][i];
        double omega2 = 0.0, beta = 0.0, dt;
        long j;
        if (i == n - 1) {
            k_diag += soil[STIFFNESS][n];
            c_diag += soil[DASHPOT][n] + soil[SMITH][n] * soil[CAPACITY][n];
        }
        for (j = (long)i - 1; j <= (long)i; j++) {
            if (j >= 0 && j < (long)n - 1) {
                double coupling = 1.0 / sqrt(mass[j] * mass[j + 1]);
                omega2 += k[j] / mass[i] + k[j] * coupling;
                beta += 0.5 * (c[j] / mass[i] + c[j] * coupling);
            }
        }
        omega2 += k_diag / mass[i];
        beta += 0.5 * c_diag / mass[i];
        dt = omega2 + beta > 0.0 ? 2.0 / (sqrt(omega2 + beta * beta) + beta) : INFINITY;
        if (dt < dt_min) dt_min = dt;
    }
    return dt_min;
}

/* The tridiagonal solve of LAPACK dgtsv (one right-hand side), in place: dl, d, du the
 * sub-, main and super-diagonal (n - 1, n, n - 1), b the right-hand side, then the solution.
 * 0 when singular. */
static int gtsv(size_t n, double *dl, double *d, double *du, double *b)
{
    size_t i;
    double fact, temp;
    for (i = 0; i + 2 < n; i++) {
        if (fabs(d[i]) >= fabs(dl[i])) {
            if (d[i] == 0.0) return 0;
            fact = dl[i] / d[i];
            d[i + 1] = d[i + 1] - fact * du[i];
            b[i + 1] = b[i + 1] - fact * b[i];
            dl[i] = 0.0;
        } else {
            fact = d[i] / dl[i];
            d[i] = dl[i];
            temp = d[i + 1];
            d[i + 1] = du[i] - fact * temp;
            dl[i] = du[i + 1];
            du[i + 1] = -fact * dl[i];
            du[i] = temp;
            temp = b[i];
            b[i] = b[i + 1];
            b[i + 1] = temp - fact * b[i + 1];
        }
    }
    if (n > 1) {
        i = n - 2;
        if (fabs(d[i]) >= fabs(dl[i])) {
            if (d[i] == 0.0) return 0;
            fact = dl[i] / d[i];
            d[i + 1] = d[i + 1] - fact * du[i];
            b[i + 1] = b[i + 1] - fact * b[i];
        } else {
            fact = d[i] / dl[i];
            d[i] = dl[i];
            temp = d[i + 1];
            d[i + 1] = du[i] - fact * temp;
            du[i] = temp;
            temp = b[i];
            b[i] = b[i + 1];
            b[i + 1] = temp - fact * b[i + 1];
        }
    }
    if (d[n - 1] == 0.0) return 0;
    b[n - 1] = b[n - 1] / d[n - 1];
    if (n > 1) b[n - 2] = (b[n - 2] - du[n - 2] * b[n - 1]) / d[n - 2];
    for (i = n - 2; i-- > 0;) b[i] = (b[i] - du[i] * b[i + 1] - dl[i] * b[i + 2]) / d[i];
    return 1;
}

/* static.py static_equilibrium into s->u, s->offset; 0 with the reason. */
static int static_equilibrium(PileState *s, double head_force, double gravity, char *reason,
                              size_t reason_size)
{
    const PileModel *m = s->m;
    size_t n = m->n, i;
    const double *k = m->k, *k_soil = m->soil[STIFFNESS], *capacity = m->soil[CAPACITY];
    double *work, *loads, *dl, *d, *du, *x;
    char *plastic;
    int any = 0, iteration, converged = 0;
    work = (double *)malloc(5 * n * sizeof(double));
    plastic = (char *)calloc(n + 1, 1);
    if (work == NULL || plastic == NULL) {
        free(work);
        free(plastic);
        snprintf(reason, reason_size, "out of memory");
        return 0;
    }
    loads = work;
    dl = work + n;
    d = work + 2 * n;
    du = work + 3 * n;
    x = work + 4 * n;
    for (i = 0; i < n; i++) loads[i] = m->mass[i] * gravity;
    loads[0] += head_force;
    for (i = 0; i < n; i++) any |= loads[i] != 0.0;
    for (i = 0; i <= n; i++) s->offset[i] = 0.0;
    if (!any) {
        for (i = 0; i < n; i++) s->u[i] = 0.0;
        free(work);
        free(plastic);
        return 1;
    }
    for (iteration = 0; iteration < MAX_ITERATIONS; iteration++) {
        int elastic = 0, newly = 0;
        for (i = 0; i < n; i++) {
            double ks = plastic[i] ? 0.0 : k_soil[i];
            d[i] = 0.0;
            if (i < n - 1) d[i] += k[i];
            if (i > 0) d[i] += k[i - 1];
            d[i] += ks;
            elastic |= ks != 0.0;
            x[i] = loads[i] - (plastic[i] ? capacity[i] : 0.0);
        }
        d[n - 1] += plastic[n] ? 0.0 : k_soil[n];
        elastic |= !plastic[n] && k_soil[n] != 0.0;
        x[n - 1] -= plastic[n] ? capacity[n] : 0.0;
        for (i = 0; i + 1 < n; i++) {
            du[i] = -k[i];
            dl[i] = -k[i];
        }
        if (!elastic) {
            snprintf(reason, reason_size, "the static loads exceed the soil capacity (or there "
                     "is no soil): no static equilibrium");
            break;
        }
        if (!gtsv(n, dl, d, du, x)) {
            snprintf(reason, reason_size, "static equilibrium: singular stiffness matrix");
            break;
        }
        for (i = 0; i <= n; i++) {
            double force = k_soil[i] * x[i < n ? i : n - 1];
            if (!plastic[i] && force > capacity[i] * (1.0 + 1e-12) && k_soil[i] > 0.0) {
                plastic[i] = 1;
                newly = 1;
            }
        }
        if (!newly) {
            converged = 1;
            break;
        }
    }
    if (converged) {
        for (i = 0; i < n; i++) s->u[i] = x[i];
        for (i = 0; i <= n; i++)
            s->offset[i] = plastic[i] ? x[i < n ? i : n - 1] -
                                            (k_soil[i] > 0.0 ? capacity[i] / k_soil[i] : 0.0)
                                      : 0.0;
    } else if (iteration == MAX_ITERATIONS) {
        snprintf(reason, reason_size, "static equilibrium did not converge");
    }
    free(work);
    free(plastic);
    return converged;
}

static void free_state(void *p)
{
    PileState *s = (PileState *)p;
    if (s == NULL) return;
    free(s->block);
    free(s);
}

static void update_stress_extremes(PileState *s)
{
    size_t i;
    for (i = 0; i + 1 < s->n; i++) {
        double stress = s->m->stress_factor[i] * (s->u[i] - s->u[i + 1]);
        if (stress > s->extremes[0]) s->extremes[0] = stress;
        if (stress < s->extremes[1]) s->extremes[1] = stress;
    }
}

static double head_displacement(const PileState *s)
{
    return s->u[0] + s->m->probes[HEAD_EXTRAPOLATION] * (s->u[0] - s->u[1]);
}

static void *start(void *p, const double *slots, char *const *strings,
                   double start_time, char *reason, size_t reason_size)
{
    (void)strings;
    const PileModel *m = (const PileModel *)p;
    double head_load = slots[STATIC_HEAD_LOAD], gravity = slots[GRAVITY];
    size_t n = m->n, i;
    PileState *s;
    (void)start_time;
    if (!(head_load >= 0.0)) {
        snprintf(reason, reason_size, "static_head_load: must be at least 0 N, got %g",
                 head_load);
        return NULL;
    }
    if (!(gravity >= 0.0 && gravity <= 20.0)) {
        snprintf(reason, reason_size, "gravity: must be in [0, 20] m/s^2, got %g", gravity);
        return NULL;
    }
    s = (PileState *)calloc(1, sizeof *s);
    if (s == NULL) return NULL;
    s->block = (double *)malloc((5 * n + 3 * (n + 1)) * sizeof(double));
    if (s->block == NULL) {
        free(s);
        snprintf(reason, reason_size, "out of memory");
        return NULL;
    }
    s->m = m;
    s->n = n;
    s->weight = s->block;
    s->inverse_mass = s->block + n;
    s->u = s->block + 2 * n;
    s->v = s->block + 3 * n;
    s->yield_down = s->block + 4 * n;
    s->yield_up = s->yield_down + (n + 1);
    s->offset = s->yield_up + (n + 1);
    /* pile/kernels.py sweep_arrays */
    for (i = 0; i < n; i++) {
        s->weight[i] = m->mass[i] * gravity;
        s->inverse_mass[i] = 1.0 / m->mass[i];
        s->v[i] = 0.0;
    }
    s->first_soil = n - 1;
    for (i = 0; i <= n; i++) {
        double k = m->soil[STIFFNESS][i];
        s->yield_down[i] = k > 0.0 ? m->soil[CAPACITY][i] / k : 0.0;
        s->yield_up[i] = k > 0.0 ? m->soil[TENSION][i] / k : 0.0;
        if (k > 0.0 && i < s->first_soil) s->first_soil = i;
    }
    if (!static_equilibrium(s, head_load, gravity, reason, reason_size)) {
        free_state(s);
        return NULL;
    }
    s->face0 = head_displacement(s);
    s->stable_step = stable_time_step(m);
    s->extremes[0] = s->extremes[1] = 0.0;
    update_stress_extremes(s);
    s->h = NAN;
    s->n_sub = 1.0;
    return s;
}

static double spring_force(const PileState *s, size_t j)
{
    return s->m->k[j] * (s->u[j] - s->u[j + 1]) + s->m->c[j] * (s->v[j] - s->v[j + 1]);
}

static void outputs(void *p, double *slots, double time)
{
    (void)time;
    const PileState *s = (const PileState *)p;
    const double *probes = s->m->probes;
    double face = head_displacement(s), force, w;
    size_t j;
    slots[U_HEAD] = face - s->face0;
    slots[V_HEAD] = s->v[0] + probes[HEAD_EXTRAPOLATION] * (s->v[0] - s->v[1]);
    j = (size_t)probes[GAUGE_SPRING];
    w = probes[GAUGE_SPRING_WEIGHT];
    force = spring_force(s, j);
    if (w > 0.0) force = (1.0 - w) * force + w * spring_force(s, j + 1);
    slots[F_GAUGE] = force;
    j = (size_t)probes[GAUGE_MASS];
    w = probes[GAUGE_MASS_WEIGHT];
    slots[V_GAUGE] = w > 0.0 ? (1.0 - w) * s->v[j] + w * s->v[j + 1] : s->v[j];
    slots[U_HEAD_TOTAL] = face;
    slots[U_PILE_TOE] = s->u[s->n - 1];
    slots[MAX_COMPRESSION_STRESS] = s->extremes[0];
    slots[MAX_TENSION_STRESS] = s->extremes[1];
}

/* kernels.py _soil_spring (stiffness > 0): the static and damping resistance [N]; the
 * plastic offset updated in place. */
static void soil_spring(double u, double v, double *offset, double capacity, double tension,
                        double stiffness, double smith, double dashpot, double yield_down,
                        double yield_up, double *rs, double *rd)
{
    double r = stiffness * (u - *offset), d;
    if (r > capacity) {
        r = capacity;
        *offset = u - yield_down;
    } else if (r < -tension) {
        if (tension > 0.0) {
            r = -tension;
            *offset = u + yield_up;
        } else {
            *rs = 0.0;
            *rd = 0.0;
            return;
        }
    }
    d = (smith * fabs(r) + dashpot) * v;
    if (tension <= 0.0 && r + d < 0.0) d = -r;
    *rs = r;
    *rd = d;
}

/* kernels.py _pile_sweep: one leapfrog sub-step of dt [s], top to toe. */
static void sweep(PileState *s, double head_force, double dt)
{
    const PileModel *m = s->m;
    const double *weight = s->weight, *inverse_mass = s->inverse_mass, *k = m->k, *c = m->c;
    double *const *soil = m->soil;
    double *u = s->u, *v = s->v, *offset = s->offset;
    size_t n = s->n, last = n - 1, i;
    size_t free_end = s->first_soil < last ? s->first_soil : last;
    double spring_above = head_force, dash_above = 0.0, rs, rd, force, v_new;
    for (i = 0; i < free_end; i++) {
        double spring_below = k[i] * (u[i] - u[i + 1]);
        double dash_below = c[i] * (v[i] - v[i + 1]);
        force = weight[i] + spring_above + dash_above - spring_below - dash_below;
        v_new = v[i] + dt * force * inverse_mass[i];
        v[i] = v_new;
        u[i] += dt * v_new;
        spring_above = spring_below;
        dash_above = dash_below;
    }
    for (i = free_end; i < last; i++) {
        double spring_below = k[i] * (u[i] - u[i + 1]);
        double dash_below = c[i] * (v[i] - v[i + 1]);
        rs = 0.0;
        rd = 0.0;
        if (soil[STIFFNESS][i] > 0.0)
            soil_spring(u[i], v[i], &offset[i], soil[CAPACITY][i], soil[TENSION][i],
                        soil[STIFFNESS][i], soil[SMITH][i], soil[DASHPOT][i], s->yield_down[i],
                        s->yield_up[i], &rs, &rd);
        force = weight[i] + spring_above + dash_above - spring_below - dash_below - rs - rd;
        v_new = v[i] + dt * force * inverse_mass[i];
        v[i] = v_new;
        u[i] += dt * v_new;
        spring_above = spring_below;
        dash_above = dash_below;
    }
    rs = 0.0;
    rd = 0.0;
    if (soil[STIFFNESS][last] > 0.0)
        soil_spring(u[last], v[last], &offset[last], soil[CAPACITY][last], soil[TENSION][last],
                    soil[STIFFNESS][last], soil[SMITH][last], soil[DASHPOT][last],
                    s->yield_down[last], s->yield_up[last], &rs, &rd);
    if (soil[STIFFNESS][n] > 0.0) {
        double ts, td;
        soil_spring(u[last], v[last], &offset[n], soil[CAPACITY][n], soil[TENSION][n],
                    soil[STIFFNESS][n], soil[SMITH][n], soil[DASHPOT][n], s->yield_down[n],
                    s->yield_up[n], &ts, &td);
        rs += ts;
        rd += td;
    }
    force = weight[last] + spring_above + dash_above - 0.0 - 0.0 - rs - rd;
    v_new = v[last] + dt * force * inverse_mass[last];
    v[last] = v_new;
    u[last] += dt * v_new;
}

static int step(void *p, const double *slots, double time, double h, char *reason,
                size_t reason_size)
{
    (void)time;
    PileState *s = (PileState *)p;
    double dt;
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
    for (k = 0; k < n_sub; k++) sweep(s, slots[F_HEAD], dt);
    update_stress_extremes(s);
    return 1;
}

static const UnitModel MODEL = {"PileSoil", VARIABLES, sizeof VARIABLES / sizeof VARIABLES[0],
                                0, 0, load, free_model, start, free_state, outputs, step,
                                NULL, NULL};

const UnitModel *const UNIT_MODELS[] = {&MODEL};
const size_t N_UNIT_MODELS = 1;
