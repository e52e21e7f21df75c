/*
 * anvil_model.h -- the anvilwave anvil in plain C99: the Mode Displacement Method ROM (or the
 * rigid lumped mass) with its two compression-only contacts, and the reader of the binary
 * modal-data resource. No FMI here; anvil_unit.c maps the FMI variables onto these functions.
 *
 * The numerics are those of anvil_rom/rom.py and anvil_rom/unit.py (ModalAnvil, AnvilUnit and
 * their kernels modal_transition, modal_step, modal_interface, anvil_contact_forces,
 * contact_force, rest_on_pile), operation for operation and in the same order, so that the
 * native FMU gives the numbers of the Python units (compile without floating-point
 * contraction, -ffp-contract=off, and without -ffast-math). Each mode j:
 *
 *     q_j(n+1) = a_j q_j(n) + b_j q_j(n-1) + c_j (p_ram_j F_ram - p_pile_j F_pile + p_grav_j g)
 *     a = 2 exp(-xi w h) cos(w_d h),  b = -exp(-2 xi w h),  c = (1 - a - b) / w^2
 *     (rigid mode w = 0: a = 2, b = -1, c = h^2)
 *
 * exact for free damped vibration and for a held force at any step h (unconditionally
 * stable). u_top = sum p_ram_j q_j, u_bottom = sum p_pile_j q_j, velocities are the half-step
 * values (q(n) - q(n-1)) / h; with the static correction the residual flexibility R of the
 * truncated modes adds u_top += R00 F_ram - R01 F_pile, u_bottom += R01 F_ram - R11 F_pile.
 * Units: SI (m, s, kg, N); z down, compression positive.
 *
 * Modal-data resource, format "anvilwave-modal" (binary) version 1, all numbers little-endian
 * (written by fmu/native_build.py, readable by any producer that follows this table):
 *
 *   offset        size   content
 *   0             16     magic: the ASCII bytes "anvilwave-modal" and one NUL byte
 *   16            4      uint32 format version (1)
 *   20            4      uint32 n, number of modes (>= 1); mode 0 is the axial rigid-body mode
 *   24            8      float64 total_mass [kg]
 *   32            8      float64 fmax, frequency content the modes were computed for [Hz]
 *   40            8      float64 damping_ratio, default modal damping ratio [-]
 *   48            32     float64 elastic_flexibility G00, G01, G10, G11: inertia-relief
 *                        flexibility between the ram face and the pile ring, all flexible
 *                        modes [m/N] (row-major 2x2, symmetric)
 *   80            8 n    float64 frequencies [Hz], ascending, frequencies[0] = 0
 *   80 + 8 n      8 n    float64 omega [rad/s] = 2 pi frequencies (stored so that a ROM whose
 *                        circular frequencies are given keeps them bit for bit)
 *   80 + 16 n     8 n    float64 participation_ram  = b_ram^T phi_j [kg^-1/2]
 *   80 + 24 n     8 n    float64 participation_pile = b_pile^T phi_j [kg^-1/2]
 *   80 + 32 n     8 n    float64 participation_gravity = phi_j^T M e_z [kg^1/2]
 *
 * The file is exactly 80 + 40 n bytes. The reader checks the header, the size and the same
 * rules as anvil_rom/modalfile.py (check_modal_data); a file that breaks one is refused with
 * the reason, never read in part.
 *
 * Version 2 (a pile port split into K >= 2 rings across the wall, anvil_rom/rings.py) is
 * version 1's layout followed by
 *
 *   80 + 40 n     4      uint32 K, number of rings (>= 2)
 *   84 + 40 n     4      uint32 0 (reserved)
 *   88 + 40 n     8 K n  float64 participation_rings, ring by ring (inner ring first) [kg^-1/2]
 *   ...           8 (K+1)^2  float64 ring_flexibility between the ram face and the rings,
 *                        row-major, all flexible modes [m/N]
 *   ...           8 K    float64 ring_areas [m^2]
 *
 * With rings the unit's pile contact is K compression-only contacts (the pile contact spring
 * and dashpot shared by ring area) and, with the ram contact, one linear complementarity
 * problem per evaluation (anvil_rom/rings.py contact_lcp: Murty's least-index pivoting from
 * the last evaluation's contact set); F_pile is the rings' sum and u_bottom their
 * area-weighted mean, as the Python unit (AnvilUnit with rings).
 */
#ifndef ANVIL_MODEL_H
#define ANVIL_MODEL_H

#include <stddef.h>

#define ANVIL_MODAL_MAGIC "anvilwave-modal" /* 15 characters + NUL = 16 bytes */
#define ANVIL_MODAL_VERSION 1u
#define ANVIL_MODAL_VERSION_RINGS 2u
#define ANVIL_MODAL_HEADER_BYTES 80u
#define ANVIL_MODAL_BYTES_PER_MODE 40u

/* The content of a modal-data resource (one allocation, block, holds the five arrays). */
typedef struct {
    size_t n_modes;
    double total_mass;             /* [kg] */
    double fmax;                   /* [Hz] */
    double damping_ratio;          /* [-] */
    double elastic_flexibility[4]; /* [m/N], row-major 2x2 */
    double *frequencies;           /* [Hz] */
    double *omega;                 /* [rad/s] */
    double *participation_ram;     /* [kg^-1/2] */
    double *participation_pile;    /* [kg^-1/2] */
    double *participation_gravity; /* [kg^1/2] */
    double *block;
    size_t n_rings;                /* K rings of the pile port (0: one port, version 1) */
    double *participation_rings;   /* K x n, ring by ring [kg^-1/2] */
    double *ring_flexibility;      /* (K+1) x (K+1), row-major [m/N] */
    double *ring_areas;            /* K [m^2] */
    double *ring_block;            /* one allocation for the three */
} AnvilModalData;

/* Read and check a modal-data resource. Returns 1 on success; 0 with the reason in error
 * (data untouched) when the file is missing, unreadable or breaks a rule. */
int anvil_modal_data_read(const char *path, AnvilModalData *data, char *error, size_t size);
void anvil_modal_data_free(AnvilModalData *data);

/* Penalty contacts: compression-only springs [N/m] with dashpots [N s/m]. */
typedef struct {
    double ram_stiffness;
    double ram_damping;
    double pile_stiffness;
    double pile_damping;
} AnvilContact;

/* Check contact parameters, gravity [m/s^2] and the initial pile head displacement [m]
 * (anvil_rom/unit.py ContactParameters rules). Returns 1, or 0 with the reason in error. */
int anvil_check_parameters(const AnvilContact *contact, double gravity,
                           double initial_pile_head_displacement, char *error, size_t size);

/* The anvil with its contacts (AnvilUnit): per-mode data, step coefficients and state. */
typedef struct {
    size_t n;          /* modes */
    double *omega;     /* [rad/s] */
    double *p_ram;     /* [kg^-1/2] */
    double *p_pile;    /* [kg^-1/2] */
    double *p_grav;    /* [kg^1/2] */
    double *coef_a;    /* step coefficients for the step h */
    double *coef_b;
    double *coef_c;
    double *q;         /* modal coordinates at t_n */
    double *q_prev;    /* at t_n-1 */
    double *block;     /* one allocation for the arrays above */
    double k_ram, c_ram, k_pile, c_pile; /* contacts */
    double r00, r01, r11; /* residual flexibility (static correction) [m/N], 0 without */
    double gravity;       /* [m/s^2] */
    double h;             /* step the coefficients are for [s] */
    double damping_ratio; /* [-] */
    double total_mass;    /* [kg] */
    /* the pile port in rings (K = 0: one port); the arrays in ring_block */
    size_t K;
    double *rp;           /* K x n kept ring participations, ring by ring */
    double *A, *R;        /* (K+1) x (K+1): diag(1/k) + D R D, and the residual R */
    double *T;            /* K+1 dashpot ratios c / k (ram, rings) */
    double *W;            /* K ring area shares */
    double *F;            /* K+1 contact forces of the last evaluation (ram, rings) */
    double *ring_u, *ring_v; /* K rings' modal displacement and velocity */
    double *active;       /* K+1 contact set of the last evaluation (1: in contact) */
    double *g;            /* K+1 overlaps (scratch) */
    double *work;         /* (K+1) x (K+2) elimination (scratch) */
    double *rest;         /* the rest on the rings (scratch, allocated with the unit) */
    double *ring_block;
    int lcp_failed;       /* 1 once a contact problem ended without a solution (the host
                           * reports it; not reached for a positive definite A) */
} AnvilUnit;

/* The ROM from modal data (ModalAnvil.from_modal_data + AnvilUnit): modes up to fmax [Hz]
 * (fmax = 0: all stored modes), damping ratio [-], static correction on / off. The step is
 * set to 1e-5 s and the state to zero, as AnvilUnit does. Returns 1, or 0 with the reason. */
int anvil_unit_modal(AnvilUnit *unit, const AnvilModalData *data, double fmax,
                     double damping_ratio, int static_correction, const AnvilContact *contact,
                     double gravity, char *error, size_t size);

/* The rigid lumped-mass anvil (ModalAnvil.rigid): mass [kg]. Returns 1, or 0 with the reason. */
int anvil_unit_rigid(AnvilUnit *unit, double mass, const AnvilContact *contact, double gravity,
                     char *error, size_t size);

void anvil_unit_free(AnvilUnit *unit);

/* Static equilibrium on the pile under gravity, ram not touching (AnvilUnit.rest_on_pile):
 * sets the state; the pile head is at pile_head_displacement [m]. */
void anvil_unit_rest_on_pile(AnvilUnit *unit, double pile_head_displacement);

/* Step coefficients for the step h [s]; the two-step state is rescaled so that the
 * half-step velocity is kept across a change of step (AnvilUnit.set_step). */
void anvil_unit_set_step(AnvilUnit *unit, double h);

/* Contact forces (F_ram, F_pile) [N] for the neighbour states (feedthrough); with rings
 * F_pile is their sum and the ring forces are kept for anvil_unit_outputs / anvil_unit_step. */
void anvil_unit_forces(AnvilUnit *unit, double u_ram, double v_ram, double u_pile,
                       double v_pile, double *force_ram, double *force_pile);

/* (u_top, v_top, u_bottom, v_bottom) [m, m/s] under the interface forces [N], static
 * correction included (any pointer may be NULL). With rings the pile force is split as the
 * ring forces of the last anvil_unit_forces (by area if they were all zero). */
void anvil_unit_outputs(AnvilUnit *unit, double force_ram, double force_pile,
                        double *u_top, double *v_top, double *u_bottom, double *v_bottom);

/* Advance the modes over the current step h with the forces [N] held. */
void anvil_unit_step(AnvilUnit *unit, double force_ram, double force_pile);

#endif /* ANVIL_MODEL_H */
