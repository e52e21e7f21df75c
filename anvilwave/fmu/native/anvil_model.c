/*
 * anvil_model.c -- the anvilwave anvil in plain C99 (see anvil_model.h).
 *
 * Each function names the Python function it reproduces; the floating-point operations are
 * written in the same order as there (the Python kernels are compiled without fast-math).
 */
#include "anvil_model.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GLIBC__) && defined(__x86_64__)
/* exp from glibc's first x86-64 symbol version, so that the binary loads on glibc 2.14 and
 * and later like the Ram and PileSoil binaries (the default, exp@GLIBC_2.29, differs from it
 * only in its errno handling: both wrap the same implementation and give the same result). */
__asm__(".symver exp,exp@GLIBC_2.2.5");
#endif

/* The resource stores IEEE 754 binary64 numbers. */
typedef char anvil_double_is_binary64[(sizeof(double) == 8 && DBL_MANT_DIG == 53) ? 1 : -1];

#define ANVIL_INITIAL_STEP 1e-5 /* [s], the step AnvilUnit prepares before the first one */

static void set_error(char *error, size_t size, const char *format, ...)
{
    va_list args;
    if (error == NULL || size == 0) return;
    va_start(args, format);
    vsnprintf(error, size, format, args);
    va_end(args);
}

/* ------------------------------------------------------------------ modal-data resource */
static uint32_t read_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) |
           ((uint32_t)p[3] << 24);
}

static double read_f64(const unsigned char *p)
{
    uint64_t bits = 0;
    double value;
    int i;
    for (i = 7; i >= 0; i--) bits = (bits << 8) | (uint64_t)p[i];
    memcpy(&value, &bits, sizeof value);
    return value;
}

static int all_finite(const double *x, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(x[i])) return 0;
    return 1;
}

/* The rules of anvil_rom/modalfile.py check_modal_data, plus omega = 2 pi f. */
static int check_modal_data(const AnvilModalData *d, char *error, size_t size)
{
    const double *f = d->frequencies;
    const double *G = d->elastic_flexibility;
    size_t n = d->n_modes, j;
    double gmax, expected;
    if (!all_finite(f, n)) {
        set_error(error, size, "frequencies: must be finite");
        return 0;
    }
    if (f[0] != 0.0) {
        set_error(error, size, "frequencies: must start with the rigid-body mode (0 Hz) "
                               "followed by positive ascending frequencies");
        return 0;
    }
    for (j = 1; j < n; j++) {
        if (!(f[j] > 0.0) || f[j] < f[j - 1]) {
            set_error(error, size, "frequencies: must start with the rigid-body mode (0 Hz) "
                                   "followed by positive ascending frequencies (mode %lu: %g Hz)",
                      (unsigned long)j, f[j]);
            return 0;
        }
    }
    if (!all_finite(d->omega, n) || d->omega[0] != 0.0) {
        set_error(error, size, "omega: must be finite, 0 for the rigid-body mode");
        return 0;
    }
    for (j = 1; j < n; j++) {
        double w = 2.0 * 3.14159265358979323846 * f[j];
        if (!(fabs(d->omega[j] - w) <= 1e-12 * w)) {
            set_error(error, size, "omega: must be 2 pi times the frequency (mode %lu: %.17g "
                                   "rad/s for %.17g Hz)", (unsigned long)j, d->omega[j], f[j]);
            return 0;
        }
    }
    if (!all_finite(d->participation_ram, n)) {
        set_error(error, size, "participation_ram: must hold one finite value per mode (%lu)",
                  (unsigned long)n);
        return 0;
    }
    if (!all_finite(d->participation_pile, n)) {
        set_error(error, size, "participation_pile: must hold one finite value per mode (%lu)",
                  (unsigned long)n);
        return 0;
    }
    if (!all_finite(d->participation_gravity, n)) {
        set_error(error, size, "participation_gravity: must hold one finite value per mode "
                               "(%lu)", (unsigned long)n);
        return 0;
    }
    gmax = 0.0;
    for (j = 0; j < 4; j++)
        if (fabs(G[j]) > gmax) gmax = fabs(G[j]);
    if (!all_finite(G, 4) || fabs(G[1] - G[2]) > 1e-9 * gmax) {
        set_error(error, size, "elastic_flexibility: must be a finite symmetric 2x2 matrix [m/N]");
        return 0;
    }
    if (!(isfinite(d->total_mass) && d->total_mass > 0.0)) {
        set_error(error, size, "total_mass: must be positive [kg], got %g", d->total_mass);
        return 0;
    }
    if (!(isfinite(d->fmax) && d->fmax >= f[n - 1] * (1 - 1e-9))) {
        set_error(error, size, "fmax: must be at least the highest stored frequency [Hz], "
                               "got %g", d->fmax);
        return 0;
    }
    if (!(0.0 <= d->damping_ratio && d->damping_ratio < 1.0)) {
        set_error(error, size, "damping_ratio: must be in [0, 1), got %g", d->damping_ratio);
        return 0;
    }
    expected = sqrt(d->total_mass);
    if (fabs(fabs(d->participation_gravity[0]) - expected) > 1e-6 * expected) {
        set_error(error, size, "participation_gravity: rigid-body entry must equal "
                               "sqrt(total_mass) for mass-normalised modes");
        return 0;
    }
    return 1;
}

/* The ring rules of anvil_rom/modalfile.py (_check_rings; the binary has no ring area to add
 * up to): positive areas, finite participations that add up, area-weighted, to the pile
 * ring's, a finite symmetric flexibility. */
static int check_rings(const AnvilModalData *d, char *error, size_t size)
{
    size_t K = d->n_rings, n = d->n_modes, j, k, m = K + 1;
    double area = 0.0, pmax = 0.0, gmax = 0.0;
    if (K == 0) return 1;
    for (k = 0; k < K; k++) {
        if (!(isfinite(d->ring_areas[k]) && d->ring_areas[k] > 0.0)) {
            set_error(error, size, "ring_areas: must hold two or more positive ring areas [m^2]");
            return 0;
        }
        area += d->ring_areas[k];
    }
    if (!all_finite(d->participation_rings, K * n)) {
        set_error(error, size, "participation_rings: must be finite");
        return 0;
    }
    for (j = 0; j < n; j++)
        if (fabs(d->participation_pile[j]) > pmax) pmax = fabs(d->participation_pile[j]);
    for (j = 0; j < n; j++) {
        double combined = 0.0;
        for (k = 0; k < K; k++)
            combined += d->ring_areas[k] / area * d->participation_rings[k * n + j];
        if (fabs(combined - d->participation_pile[j]) > 1e-9 * pmax) {
            set_error(error, size, "participation_rings: area-weighted, must add up to "
                                   "participation_pile (mode %lu)", (unsigned long)j);
            return 0;
        }
    }
    for (j = 0; j < m * m; j++)
        if (fabs(d->ring_flexibility[j]) > gmax) gmax = fabs(d->ring_flexibility[j]);
    if (!all_finite(d->ring_flexibility, m * m)) goto asymmetric;
    for (j = 0; j < m; j++)
        for (k = 0; k < j; k++)
            if (fabs(d->ring_flexibility[j * m + k] - d->ring_flexibility[k * m + j]) >
                1e-9 * gmax) goto asymmetric;
    return 1;
asymmetric:
    set_error(error, size, "ring_flexibility: must be a finite symmetric %lux%lu matrix [m/N]",
              (unsigned long)m, (unsigned long)m);
    return 0;
}

int anvil_modal_data_read(const char *path, AnvilModalData *data, char *error, size_t size)
{
    unsigned char header[ANVIL_MODAL_HEADER_BYTES];
    unsigned char *body = NULL;
    AnvilModalData d;
    FILE *file;
    long length;
    uint32_t version, n;
    unsigned long long expected;
    size_t i, j, got;
    int ok = 0;

    memset(&d, 0, sizeof d);
    if (path == NULL || path[0] == '\0') {
        set_error(error, size, "no modal-data file named");
        return 0;
    }
    file = fopen(path, "rb");
    if (file == NULL) {
        if (errno == ENOENT)
            set_error(error, size, "modal-data file not found");
        else
            set_error(error, size, "cannot open the modal-data file (%s)", strerror(errno));
        return 0;
    }
    if (fseek(file, 0, SEEK_END) != 0 || (length = ftell(file)) < 0 ||
        fseek(file, 0, SEEK_SET) != 0) {
        set_error(error, size, "cannot read the modal-data file (not a regular file?)");
        goto done;
    }
    if ((unsigned long)length < ANVIL_MODAL_HEADER_BYTES ||
        fread(header, 1, ANVIL_MODAL_HEADER_BYTES, file) != ANVIL_MODAL_HEADER_BYTES) {
        set_error(error, size, "not an anvilwave modal-data file (%ld bytes, shorter than the "
                               "%u-byte header)", length, ANVIL_MODAL_HEADER_BYTES);
        goto done;
    }
    if (memcmp(header, ANVIL_MODAL_MAGIC, sizeof ANVIL_MODAL_MAGIC) != 0) {
        set_error(error, size, "not an anvilwave modal-data file (it does not start with "
                               "\"%s\"; a .npz file must be converted by the FMU build)",
                  ANVIL_MODAL_MAGIC);
        goto done;
    }
    version = read_u32(header + 16);
    if (version != ANVIL_MODAL_VERSION && version != ANVIL_MODAL_VERSION_RINGS) {
        set_error(error, size, "format version %lu is not supported (this FMU reads versions "
                               "%u and %u)", (unsigned long)version, ANVIL_MODAL_VERSION,
                  ANVIL_MODAL_VERSION_RINGS);
        goto done;
    }
    n = read_u32(header + 20);
    if (n == 0) {
        set_error(error, size, "frequencies: must hold at least the rigid-body mode (n = 0)");
        goto done;
    }
    expected = ANVIL_MODAL_HEADER_BYTES + (unsigned long long)ANVIL_MODAL_BYTES_PER_MODE * n;
    if (version == ANVIL_MODAL_VERSION_RINGS) {
        unsigned char trailer[8];
        unsigned long long rings_bytes;
        if ((unsigned long long)length < expected + 8 || fseek(file, (long)expected, SEEK_SET)
            != 0 || fread(trailer, 1, 8, file) != 8) {
            set_error(error, size, "malformed modal-data file: no ring count after its %lu "
                                   "modes", (unsigned long)n);
            goto done;
        }
        d.n_rings = read_u32(trailer);
        if (d.n_rings < 2 || d.n_rings > 64) {
            set_error(error, size, "ring_areas: a version 2 file holds 2 to 64 rings, got %lu",
                      (unsigned long)d.n_rings);
            goto done;
        }
        rings_bytes = 8ull * (d.n_rings * (unsigned long long)n + (d.n_rings + 1) *
                              (d.n_rings + 1) + d.n_rings);
        if ((unsigned long long)length != expected + 8 + rings_bytes) {
            set_error(error, size, "malformed modal-data file: %ld bytes, expected %llu for %lu "
                                   "modes and %lu rings", length, expected + 8 + rings_bytes,
                      (unsigned long)n, (unsigned long)d.n_rings);
            goto done;
        }
        d.ring_block = (double *)malloc((size_t)rings_bytes);
        body = (unsigned char *)malloc((size_t)rings_bytes);
        if (d.ring_block == NULL || body == NULL ||
            fread(body, 1, (size_t)rings_bytes, file) != (size_t)rings_bytes) {
            set_error(error, size, "malformed modal-data file: cannot read its rings");
            goto done;
        }
        for (i = 0; i < (size_t)(rings_bytes / 8); i++) d.ring_block[i] = read_f64(body + 8 * i);
        free(body);
        body = NULL;
        d.participation_rings = d.ring_block;
        d.ring_flexibility = d.ring_block + d.n_rings * (size_t)n;
        d.ring_areas = d.ring_flexibility + (d.n_rings + 1) * (d.n_rings + 1);
        if (fseek(file, ANVIL_MODAL_HEADER_BYTES, SEEK_SET) != 0) {
            set_error(error, size, "cannot read the modal-data file");
            goto done;
        }
    } else if ((unsigned long long)length != expected) {
        set_error(error, size, "malformed modal-data file: %ld bytes, expected %llu for %lu "
                               "modes", length, expected, (unsigned long)n);
        goto done;
    }
    body = (unsigned char *)malloc((size_t)(expected - ANVIL_MODAL_HEADER_BYTES));
    d.block = (double *)malloc(5 * (size_t)n * sizeof(double));
    if (body == NULL || d.block == NULL) {
        set_error(error, size, "out of memory for %lu modes", (unsigned long)n);
        goto done;
    }
    got = fread(body, 1, (size_t)(expected - ANVIL_MODAL_HEADER_BYTES), file);
    if (got != (size_t)(expected - ANVIL_MODAL_HEADER_BYTES)) {
        set_error(error, size, "malformed modal-data file: cannot read its %lu modes",
                  (unsigned long)n);
        goto done;
    }
    d.n_modes = n;
    d.total_mass = read_f64(header + 24);
    d.fmax = read_f64(header + 32);
    d.damping_ratio = read_f64(header + 40);
    for (j = 0; j < 4; j++) d.elastic_flexibility[j] = read_f64(header + 48 + 8 * j);
    for (i = 0; i < 5 * (size_t)n; i++) d.block[i] = read_f64(body + 8 * i);
    d.frequencies = d.block;
    d.omega = d.block + n;
    d.participation_ram = d.block + 2 * (size_t)n;
    d.participation_pile = d.block + 3 * (size_t)n;
    d.participation_gravity = d.block + 4 * (size_t)n;
    ok = check_modal_data(&d, error, size) && check_rings(&d, error, size);
done:
    fclose(file);
    free(body);
    if (ok) {
        *data = d;
    } else {
        free(d.block);
        free(d.ring_block);
    }
    return ok;
}

void anvil_modal_data_free(AnvilModalData *data)
{
    if (data == NULL) return;
    free(data->block);
    free(data->ring_block);
    memset(data, 0, sizeof *data);
}

/* ------------------------------------------------------------------ parameters */
int anvil_check_parameters(const AnvilContact *contact, double gravity,
                           double initial_pile_head_displacement, char *error, size_t size)
{
    /* ContactParameters.__post_init__: stiffnesses positive, dashpots >= 0, all finite */
    if (!(isfinite(contact->ram_stiffness) && contact->ram_stiffness > 0.0)) {
        set_error(error, size, "ram_contact_stiffness: must be positive [N/m], got %g",
                  contact->ram_stiffness);
        return 0;
    }
    if (!(isfinite(contact->pile_stiffness) && contact->pile_stiffness > 0.0)) {
        set_error(error, size, "pile_contact_stiffness: must be positive [N/m], got %g",
                  contact->pile_stiffness);
        return 0;
    }
    if (!(isfinite(contact->ram_damping) && contact->ram_damping >= 0.0)) {
        set_error(error, size, "ram_contact_damping: must be >= 0 [N s/m], got %g",
                  contact->ram_damping);
        return 0;
    }
    if (!(isfinite(contact->pile_damping) && contact->pile_damping >= 0.0)) {
        set_error(error, size, "pile_contact_damping: must be >= 0 [N s/m], got %g",
                  contact->pile_damping);
        return 0;
    }
    if (!isfinite(gravity)) {
        set_error(error, size, "gravity: must be finite [m/s^2], got %g", gravity);
        return 0;
    }
    if (!isfinite(initial_pile_head_displacement)) {
        set_error(error, size, "initial_pile_head_displacement: must be finite [m], got %g",
                  initial_pile_head_displacement);
        return 0;
    }
    return 1;
}


/* ------------------------------------------------------------------ the pile port in rings */
static void interface(const AnvilUnit *unit, double *ut, double *vt, double *ub, double *vb);

/* anvil_rom/rings.py _solve_active: F_a = A_aa^-1 g_a (elimination without pivoting), F = 0
 * elsewhere; work m x (m + 1). */
static void solve_active(size_t m, const double *A, const double *g, double *F,
                         const double *active, double *work)
{
    size_t i, j, idx = 0, jdx, size, r, c, q;
    size_t w = m + 1;
    for (i = 0; i < m; i++) {
        F[i] = 0.0;
        if (active[i] != 0.0) {
            jdx = 0;
            for (j = 0; j < m; j++)
                if (active[j] != 0.0) work[idx * w + jdx++] = A[i * m + j];
            work[idx * w + m] = g[i];
            idx++;
        }
    }
    size = idx;
    for (q = 0; q < size; q++) {
        double pivot = work[q * w + q];
        for (r = q + 1; r < size; r++) {
            double factor = work[r * w + q] / pivot;
            for (c = q; c < size; c++) work[r * w + c] -= factor * work[q * w + c];
            work[r * w + m] -= factor * work[q * w + m];
        }
    }
    for (q = size; q-- > 0;) {
        double total = work[q * w + m];
        for (c = q + 1; c < size; c++) total -= work[q * w + c] * work[c * w + m];
        work[q * w + m] = total / work[q * w + q];
    }
    idx = 0;
    for (i = 0; i < m; i++)
        if (active[i] != 0.0) F[i] = work[idx++ * w + m];
}

/* anvil_rom/rings.py contact_lcp: Murty's least-index pivoting from the given set; 1 when
 * solved, 0 when the pivots ran out (the last set's forces stand; Python raises) */
static int contact_lcp(size_t m, const double *A, const double *g, double *F, double *active,
                        double *work)
{
    size_t pivots, i, j;
    for (pivots = 0; pivots < 50 * m; pivots++) {
        long flip = -1;
        solve_active(m, A, g, F, active, work);
        for (i = 0; i < m; i++) {
            if (active[i] != 0.0) {
                if (F[i] < 0.0) {
                    flip = (long)i;
                    break;
                }
            } else {
                double w = -g[i];
                for (j = 0; j < m; j++) w += A[i * m + j] * F[j];
                if (w < 0.0) {
                    flip = (long)i;
                    break;
                }
            }
        }
        if (flip < 0) return 1;
        active[flip] = 1.0 - active[flip];
    }
    return 0; /* not reached for a positive definite A (Murty 1974) */
}

/* anvil_rom/rings.py ring_interface: the rings' modal (u, v) */
static void ring_interface(AnvilUnit *unit)
{
    size_t n = unit->n, k, j;
    double inverse_step = 1.0 / unit->h;
    for (k = 0; k < unit->K; k++) {
        double u = 0.0, v = 0.0;
        const double *pk = unit->rp + k * n;
        for (j = 0; j < n; j++) {
            u += pk[j] * unit->q[j];
            v += pk[j] * ((unit->q[j] - unit->q_prev[j]) * inverse_step);
        }
        unit->ring_u[k] = u;
        unit->ring_v[k] = v;
    }
}

/* Python: AnvilUnit._ring_forces, the ring forces for a held pile force */
static void ring_forces(AnvilUnit *unit, double force_ram, double force_pile)
{
    size_t k;
    double total = 0.0;
    for (k = 1; k <= unit->K; k++) total += unit->F[k];
    if (total > 0.0) {
        double ratio = force_pile / total;
        for (k = 1; k <= unit->K; k++) unit->F[k] = unit->F[k] * ratio;
    } else {
        for (k = 1; k <= unit->K; k++) unit->F[k] = force_pile * unit->W[k - 1];
    }
    unit->F[0] = force_ram;
}

/* Gaussian elimination with partial pivoting of the n x n system M x = b (in place: M, b) */
static void solve_dense(size_t n, double *M, double *b)
{
    size_t c, r, q, best;
    for (c = 0; c < n; c++) {
        best = c;
        for (r = c + 1; r < n; r++)
            if (fabs(M[r * n + c]) > fabs(M[best * n + c])) best = r;
        if (best != c) {
            double t;
            for (q = 0; q < n; q++) {
                t = M[c * n + q]; M[c * n + q] = M[best * n + q]; M[best * n + q] = t;
            }
            t = b[c]; b[c] = b[best]; b[best] = t;
        }
        for (r = c + 1; r < n; r++) {
            double factor = M[r * n + c] / M[c * n + c];
            for (q = c; q < n; q++) M[r * n + q] -= factor * M[c * n + q];
            b[r] -= factor * b[c];
        }
    }
    for (c = n; c-- > 0;) {
        double total = b[c];
        for (q = c + 1; q < n; q++) total -= M[c * n + q] * b[q];
        b[c] = total / M[c * n + c];
    }
}

/* anvil_rom/rings.py ring_static_rest and AnvilUnit._rest_on_rings */
static void rest_on_rings(AnvilUnit *unit, double pile_head_displacement, double weight)
{
    size_t K = unit->K, n = unit->n, m = K + 1, j, k, l, iteration;
    double *G = unit->rest; /* scratch allocated with the unit (unit_rings) */
    double *M = G + K * K;
    double *x = M + m * m;
    double *forces = x + m;
    double *overlap = forces + K;
    double *active = overlap + K;
    double u0 = 0.0;
    for (k = 0; k < K; k++) {
        active[k] = 1.0;
        for (l = 0; l < K; l++) {
            double sum = 0.0;
            for (j = 0; j < n; j++) {
                double w = unit->omega[j];
                if (!(w > 0.0)) continue;
                sum += (unit->rp[k * n + j] / (w * w)) * unit->rp[l * n + j];
            }
            G[k * K + l] = sum + unit->R[(k + 1) * m + l + 1];
        }
    }
    for (iteration = 0; iteration < 4 * K; iteration++) {
        size_t a = 0, idx[64], r, c;
        long worst = -1;
        for (k = 0; k < K; k++)
            if (active[k] != 0.0) idx[a++] = k;
        for (r = 0; r <= a; r++)
            for (c = 0; c <= a; c++) M[r * (a + 1) + c] = 0.0;
        for (r = 0; r < a; r++) {
            for (c = 0; c < a; c++) M[r * (a + 1) + c] = G[idx[r] * K + idx[c]];
            M[r * (a + 1) + r] += 1.0 / (unit->k_pile * unit->W[idx[r]]);
            M[r * (a + 1) + a] = -1.0;
            M[a * (a + 1) + r] = 1.0;
            x[r] = 0.0;
        }
        x[a] = weight;
        solve_dense(a + 1, M, x);
        for (k = 0; k < K; k++) forces[k] = 0.0;
        for (r = 0; r < a; r++) forces[idx[r]] = x[r];
        u0 = x[a];
        for (k = 0; k < K; k++) {
            double sum = 0.0;
            for (l = 0; l < K; l++) sum += G[k * K + l] * forces[l];
            overlap[k] = u0 - sum;
        }
        for (k = 0; k < K; k++)
            if (worst < 0 || forces[k] < forces[worst]) worst = (long)k;
        if (forces[worst] < 0.0) {
            active[worst] = 0.0;
            continue;
        }
        worst = -1;
        for (k = 0; k < K; k++)
            if (active[k] == 0.0 && overlap[k] > 0.0
                && (worst < 0 || overlap[k] > overlap[worst]))
                worst = (long)k;
        if (worst < 0) break;
        active[worst] = 1.0;
    }
    for (j = 0; j < n; j++) {
        double w = unit->omega[j];
        unit->q[j] = 0.0;
        if (w > 0.0) {
            double load = 0.0;
            for (k = 0; k < K; k++) load += forces[k] * unit->rp[k * n + j];
            unit->q[j] = -load / (w * w);
        }
    }
    unit->q[0] = (u0 + pile_head_displacement) / unit->rp[0];
    for (j = 0; j < n; j++) unit->q_prev[j] = unit->q[j];
    unit->F[0] = 0.0;
    unit->active[0] = 0.0;
    for (k = 0; k < K; k++) {
        unit->F[k + 1] = forces[k];
        unit->active[k + 1] = forces[k] > 0.0 ? 1.0 : 0.0;
    }
}

/* anvil_rom/rings.py ring_unit_outputs: the contact problem of the rings */
static void ring_contact(AnvilUnit *unit, double u_ram, double v_ram, double u_pile,
                         double v_pile, double *force_ram, double *force_pile)
{
    size_t K = unit->K, m = K + 1, k;
    double ut, vt, ub, vb, total = 0.0;
    interface(unit, &ut, &vt, &ub, &vb); /* modal_interface */
    ring_interface(unit);
    unit->g[0] = u_ram - ut;
    unit->g[0] += unit->T[0] * (v_ram - vt);
    for (k = 0; k < K; k++) {
        unit->g[1 + k] = unit->ring_u[k] - u_pile;
        unit->g[1 + k] += unit->T[1 + k] * (unit->ring_v[k] - v_pile);
    }
    if (!contact_lcp(m, unit->A, unit->g, unit->F, unit->active, unit->work))
        unit->lcp_failed = 1;
    for (k = 1; k < m; k++) total += unit->F[k];
    *force_ram = unit->F[0];
    *force_pile = total;
}

/* Python: AnvilUnit._ring_outputs (ring_faces) */
static void ring_outputs(AnvilUnit *unit, double force_ram, double force_pile, double *u_top,
                         double *v_top, double *u_bottom, double *v_bottom)
{
    size_t K = unit->K, m = K + 1, k, l;
    double ut, vt, mean_u, mean_v, ub = 0.0, vb = 0.0;
    ring_forces(unit, force_ram, force_pile);
    ring_interface(unit);
    interface(unit, &ut, &vt, &mean_u, &mean_v); /* modal_interface (the ring's mean unused) */
    ut += unit->R[0] * unit->F[0];
    for (k = 1; k < m; k++) ut -= unit->R[k] * unit->F[k];
    for (k = 1; k < m; k++) {
        double u = unit->ring_u[k - 1] + unit->R[k * m] * unit->F[0];
        for (l = 1; l < m; l++) u -= unit->R[k * m + l] * unit->F[l];
        ub += unit->W[k - 1] * u;
        vb += unit->W[k - 1] * unit->ring_v[k - 1];
    }
    if (u_top != NULL) *u_top = ut;
    if (v_top != NULL) *v_top = vt;
    if (u_bottom != NULL) *u_bottom = ub;
    if (v_bottom != NULL) *v_bottom = vb;
}

/* anvil_rom/rings.py ring_unit_advance, the ring forces held */
static void ring_step(AnvilUnit *unit, double force_ram, double force_pile)
{
    size_t n = unit->n, K = unit->K, j, k;
    double g = unit->gravity;
    ring_forces(unit, force_ram, force_pile);
    for (j = 0; j < n; j++) {
        double f = unit->p_ram[j] * force_ram + unit->p_grav[j] * g, q_new;
        for (k = 0; k < K; k++) f -= unit->rp[k * n + j] * unit->F[1 + k];
        q_new = unit->coef_a[j] * unit->q[j] + unit->coef_b[j] * unit->q_prev[j] +
                unit->coef_c[j] * f;
        unit->q_prev[j] = unit->q[j];
        unit->q[j] = q_new;
    }
}

/* ------------------------------------------------------------------ the unit */
static int allocate_unit(AnvilUnit *unit, size_t n, const AnvilContact *contact, double gravity,
                         char *error, size_t size)
{
    memset(unit, 0, sizeof *unit);
    unit->block = (double *)calloc(9 * n, sizeof(double));
    if (unit->block == NULL) {
        set_error(error, size, "out of memory for %lu modes", (unsigned long)n);
        return 0;
    }
    unit->n = n;
    unit->omega = unit->block;
    unit->p_ram = unit->block + n;
    unit->p_pile = unit->block + 2 * n;
    unit->p_grav = unit->block + 3 * n;
    unit->coef_a = unit->block + 4 * n;
    unit->coef_b = unit->block + 5 * n;
    unit->coef_c = unit->block + 6 * n;
    unit->q = unit->block + 7 * n;
    unit->q_prev = unit->block + 8 * n;
    unit->k_ram = contact->ram_stiffness;
    unit->c_ram = contact->ram_damping;
    unit->k_pile = contact->pile_stiffness;
    unit->c_pile = contact->pile_damping;
    unit->gravity = gravity;
    unit->h = 0.0; /* no step yet */
    return 1;
}

/* ModalAnvil.from_modal_data's rings (kept participations, residual_flexibility between the
 * ram face and the rings) and AnvilUnit._ring_arrays (A = ring_matrix, T, area shares). */
static int unit_rings(AnvilUnit *unit, const AnvilModalData *data, double fmax,
                      int static_correction, char *error, size_t size)
{
    size_t K = data->n_rings, n = data->n_modes, m = K + 1, j, k, a, b;
    double total = 0.0;
    double *p;
    /* the rest's scratch (rest_on_rings): G (K x K), the bordered matrix (m x m), its
     * solution (m), the forces, the overlaps and the active set (K each) */
    unit->ring_block = (double *)calloc(K * unit->n + 2 * m * m + 4 * m + 3 * K + m * (m + 1)
                                        + K * K + m * m + m + 3 * K, sizeof(double));
    if (unit->ring_block == NULL) {
        set_error(error, size, "out of memory for %lu rings", (unsigned long)K);
        return 0;
    }
    p = unit->ring_block;
    unit->K = K;
    unit->rp = p; p += K * unit->n;
    unit->A = p; p += m * m;
    unit->R = p; p += m * m;
    unit->T = p; p += m;
    unit->F = p; p += m;
    unit->active = p; p += m;
    unit->g = p; p += m;
    unit->W = p; p += K;
    unit->ring_u = p; p += K;
    unit->ring_v = p; p += K;
    unit->work = p; p += m * (m + 1);
    unit->rest = p;
    for (k = 0; k < K; k++) {
        size_t kept = 0;
        for (j = 0; j < n; j++) {
            if (!(data->frequencies[j] <= fmax)) continue;
            unit->rp[k * unit->n + kept] = data->participation_rings[k * n + j];
            kept++;
        }
    }
    if (static_correction) {
        /* R = G - (P / omega^2) P^T over the kept flexible modes, ports (ram, rings) */
        for (a = 0; a < m; a++) {
            for (b = 0; b < m; b++) {
                double sum = 0.0;
                for (j = 0; j < unit->n; j++) {
                    double w = unit->omega[j], w2, pa, pb;
                    if (!(w > 0.0)) continue;
                    w2 = w * w;
                    pa = a == 0 ? unit->p_ram[j] : unit->rp[(a - 1) * unit->n + j];
                    pb = b == 0 ? unit->p_ram[j] : unit->rp[(b - 1) * unit->n + j];
                    sum += (pa / w2) * pb;
                }
                unit->R[a * m + b] = data->ring_flexibility[a * m + b] - sum;
            }
        }
    }
    for (k = 0; k < K; k++) total += data->ring_areas[k];
    for (k = 0; k < K; k++) unit->W[k] = data->ring_areas[k] / total;
    for (a = 0; a < m; a++) {
        for (b = 0; b < m; b++) {
            double sign = (a == 0) == (b == 0) ? 1.0 : -1.0;
            unit->A[a * m + b] = sign * unit->R[a * m + b];
        }
    }
    unit->A[0] += 1.0 / unit->k_ram;
    for (k = 0; k < K; k++) unit->A[(k + 1) * m + k + 1] += 1.0 / (unit->k_pile * unit->W[k]);
    unit->T[0] = unit->c_ram / unit->k_ram;
    for (k = 0; k < K; k++) unit->T[k + 1] = unit->c_pile / unit->k_pile;
    return 1;
}

int anvil_unit_modal(AnvilUnit *unit, const AnvilModalData *data, double fmax,
                     double damping_ratio, int static_correction, const AnvilContact *contact,
                     double gravity, char *error, size_t size)
{
    /* ModalAnvil.from_modal_data (the FMU parameter fmax = 0 keeps all stored modes) */
    const double *f = data->frequencies;
    size_t n = data->n_modes, kept = 0, j, k;
    if (fmax == 0.0) fmax = data->fmax;
    if (!(isfinite(fmax) && fmax > 0.0)) {
        set_error(error, size, "fmax: must be positive (0 keeps all modes of the file), got %g Hz",
                  fmax);
        return 0;
    }
    if (fmax > data->fmax * (1 + 1e-12)) {
        set_error(error, size, "fmax: %g Hz exceeds the %g Hz the modes were computed for; "
                               "recompute the modes", fmax, data->fmax);
        return 0;
    }
    if (n < 2 || fmax < f[1]) {
        if (n > 1)
            set_error(error, size, "fmax: %g Hz is below the first flexible mode (%.1f Hz): the "
                                   "ROM would be a rigid body; use the lumped anvil for that",
                      fmax, f[1]);
        else
            set_error(error, size, "fmax: %g Hz is below the first flexible mode (none at or "
                                   "below the %g Hz computed): the ROM would be a rigid body; "
                                   "use the lumped anvil for that", fmax, data->fmax);
        return 0;
    }
    if (!(0.0 <= damping_ratio && damping_ratio < 1.0)) {
        set_error(error, size, "damping_ratio: must be in [0, 1), got %g", damping_ratio);
        return 0;
    }
    for (j = 0; j < n; j++)
        if (f[j] <= fmax) kept++;
    if (!allocate_unit(unit, kept, contact, gravity, error, size)) return 0;
    for (j = 0, k = 0; j < n; j++) {
        if (!(f[j] <= fmax)) continue;
        unit->omega[k] = data->omega[j];
        unit->p_ram[k] = data->participation_ram[j];
        unit->p_pile[k] = data->participation_pile[j];
        unit->p_grav[k] = data->participation_gravity[j];
        k++;
    }
    unit->damping_ratio = damping_ratio;
    unit->total_mass = data->total_mass;
    if (static_correction) {
        /* residual_flexibility: R = G - (P / omega^2) P^T over the kept flexible modes */
        double s00 = 0.0, s01 = 0.0, s11 = 0.0;
        for (k = 0; k < kept; k++) {
            double w = unit->omega[k], w2;
            if (!(w > 0.0)) continue;
            w2 = w * w;
            s00 += (unit->p_ram[k] / w2) * unit->p_ram[k];
            s01 += (unit->p_ram[k] / w2) * unit->p_pile[k];
            s11 += (unit->p_pile[k] / w2) * unit->p_pile[k];
        }
        unit->r00 = data->elastic_flexibility[0] - s00;
        unit->r01 = data->elastic_flexibility[1] - s01;
        unit->r11 = data->elastic_flexibility[3] - s11;
    }
    if (data->n_rings > 0 && !unit_rings(unit, data, fmax, static_correction, error, size)) {
        anvil_unit_free(unit);
        return 0;
    }
    anvil_unit_set_step(unit, ANVIL_INITIAL_STEP);
    return 1;
}

int anvil_unit_rigid(AnvilUnit *unit, double mass, const AnvilContact *contact, double gravity,
                     char *error, size_t size)
{
    /* ModalAnvil.rigid: one rigid-body mode of the mass */
    double s;
    if (!(isfinite(mass) && mass > 0.0)) {
        set_error(error, size, "mass: must be positive, got %g kg", mass);
        return 0;
    }
    if (!allocate_unit(unit, 1, contact, gravity, error, size)) return 0;
    s = 1.0 / sqrt(mass);
    unit->omega[0] = 0.0;
    unit->p_ram[0] = s;
    unit->p_pile[0] = s;
    unit->p_grav[0] = sqrt(mass);
    unit->damping_ratio = 0.0;
    unit->total_mass = mass;
    anvil_unit_set_step(unit, ANVIL_INITIAL_STEP);
    return 1;
}

void anvil_unit_free(AnvilUnit *unit)
{
    if (unit == NULL) return;
    free(unit->block);
    free(unit->ring_block);
    memset(unit, 0, sizeof *unit);
}

void anvil_unit_rest_on_pile(AnvilUnit *unit, double pile_head_displacement)
{
    /* AnvilUnit.rest_on_pile with ModalAnvil.static_modal_coordinates(0, weight) */
    size_t n = unit->n, j;
    double force_pile = unit->total_mass * unit->gravity;
    double u_bottom_target, u_bottom_flex, dot = 0.0;
    if (unit->K > 0) {
        rest_on_rings(unit, pile_head_displacement, force_pile);
        return;
    }
    for (j = 0; j < n; j++) {
        double w = unit->omega[j];
        unit->q[j] = 0.0;
        if (w > 0.0) {
            double load = unit->p_ram[j] * 0.0 - unit->p_pile[j] * force_pile;
            unit->q[j] = load / (w * w);
        }
    }
    u_bottom_target = pile_head_displacement + force_pile / unit->k_pile;
    for (j = 0; j < n; j++) dot += unit->p_pile[j] * unit->q[j];
    u_bottom_flex = dot - unit->r11 * force_pile;
    unit->q[0] = (u_bottom_target - u_bottom_flex) / unit->p_pile[0];
    for (j = 0; j < n; j++) unit->q_prev[j] = unit->q[j];
}

void anvil_unit_set_step(AnvilUnit *unit, double h)
{
    /* AnvilUnit.set_step with modal_transition(omega, damping_ratio, h) */
    size_t n = unit->n, j;
    double zeta = unit->damping_ratio;
    if (h == unit->h) return;
    if (unit->h != 0.0) {
        double ratio = h / unit->h;
        for (j = 0; j < n; j++)
            unit->q_prev[j] = unit->q[j] - (unit->q[j] - unit->q_prev[j]) * ratio;
    }
    for (j = 0; j < n; j++) {
        double w = unit->omega[j], wd, decay, a, b;
        if (w == 0.0) {
            unit->coef_a[j] = 2.0;
            unit->coef_b[j] = -1.0;
            unit->coef_c[j] = h * h;
            continue;
        }
        wd = w * sqrt(1.0 - zeta * zeta);
        decay = exp(-zeta * w * h);
        a = 2.0 * decay * cos(wd * h);
        b = -decay * decay;
        unit->coef_a[j] = a;
        unit->coef_b[j] = b;
        unit->coef_c[j] = (1.0 - a - b) / (w * w);
    }
    unit->h = h;
}

/* modal_interface: modal part of (u_top, v_top, u_bottom, v_bottom) */
static void interface(const AnvilUnit *unit, double *ut, double *vt, double *ub, double *vb)
{
    size_t j;
    double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
    for (j = 0; j < unit->n; j++) {
        double qd = (unit->q[j] - unit->q_prev[j]) / unit->h;
        a += unit->p_ram[j] * unit->q[j];
        b += unit->p_ram[j] * qd;
        c += unit->p_pile[j] * unit->q[j];
        d += unit->p_pile[j] * qd;
    }
    *ut = a;
    *vt = b;
    *ub = c;
    *vb = d;
}

/* contact_force: compression-only penalty contact */
static double contact_force(double penetration, double rate, double stiffness, double damping)
{
    double force;
    if (penetration <= 0.0) return 0.0;
    force = stiffness * penetration + damping * rate;
    return force > 0.0 ? force : 0.0;
}

void anvil_unit_forces(AnvilUnit *unit, double u_ram, double v_ram, double u_pile,
                       double v_pile, double *force_ram, double *force_pile)
{
    /* modal_unit_forces -> anvil_contact_forces */
    double ut, vt, ub, vb, g_ram, g_pile, a11, a22, det, f_ram, f_pile;
    double r00 = unit->r00, r01 = unit->r01, r11 = unit->r11;
    double k_ram = unit->k_ram, c_ram = unit->c_ram, k_pile = unit->k_pile;
    double c_pile = unit->c_pile;
    if (unit->K > 0) {
        ring_contact(unit, u_ram, v_ram, u_pile, v_pile, force_ram, force_pile);
        return;
    }
    interface(unit, &ut, &vt, &ub, &vb);
    if (r00 == 0.0 && r01 == 0.0 && r11 == 0.0) {
        *force_ram = contact_force(u_ram - ut, v_ram - vt, k_ram, c_ram);
        *force_pile = contact_force(ub - u_pile, vb - v_pile, k_pile, c_pile);
        return;
    }
    /* static correction: the 2x2 linear complementarity problem, active sets in turn */
    g_ram = u_ram - ut + c_ram / k_ram * (v_ram - vt);
    g_pile = ub - u_pile + c_pile / k_pile * (vb - v_pile);
    a11 = 1.0 / k_ram + r00;
    a22 = 1.0 / k_pile + r11;
    det = a11 * a22 - r01 * r01;
    f_ram = (a22 * g_ram + r01 * g_pile) / det;
    f_pile = (a11 * g_pile + r01 * g_ram) / det;
    if (f_ram > 0.0 && f_pile > 0.0) {
        *force_ram = f_ram;
        *force_pile = f_pile;
        return;
    }
    f_ram = g_ram / a11;
    if (f_ram > 0.0 && g_pile + r01 * f_ram <= 0.0) {
        *force_ram = f_ram;
        *force_pile = 0.0;
        return;
    }
    f_pile = g_pile / a22;
    if (f_pile > 0.0 && g_ram + r01 * f_pile <= 0.0) {
        *force_ram = 0.0;
        *force_pile = f_pile;
        return;
    }
    *force_ram = 0.0;
    *force_pile = 0.0;
}

void anvil_unit_outputs(AnvilUnit *unit, double force_ram, double force_pile,
                        double *u_top, double *v_top, double *u_bottom, double *v_bottom)
{
    /* modal_unit_outputs */
    double ut, vt, ub, vb;
    if (unit->K > 0) {
        ring_outputs(unit, force_ram, force_pile, u_top, v_top, u_bottom, v_bottom);
        return;
    }
    interface(unit, &ut, &vt, &ub, &vb);
    ut += unit->r00 * force_ram - unit->r01 * force_pile;
    ub += unit->r01 * force_ram - unit->r11 * force_pile;
    if (u_top != NULL) *u_top = ut;
    if (v_top != NULL) *v_top = vt;
    if (u_bottom != NULL) *u_bottom = ub;
    if (v_bottom != NULL) *v_bottom = vb;
}

void anvil_unit_step(AnvilUnit *unit, double force_ram, double force_pile)
{
    /* modal_unit_step -> modal_step */
    size_t j;
    double g = unit->gravity;
    if (unit->K > 0) {
        ring_step(unit, force_ram, force_pile);
        return;
    }
    for (j = 0; j < unit->n; j++) {
        double f = unit->p_ram[j] * force_ram - unit->p_pile[j] * force_pile +
                   unit->p_grav[j] * g;
        double q_new = unit->coef_a[j] * unit->q[j] + unit->coef_b[j] * unit->q_prev[j] +
                       unit->coef_c[j] * f;
        unit->q_prev[j] = unit->q[j];
        unit->q[j] = q_new;
    }
}
