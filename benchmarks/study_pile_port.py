"""The anvil-pile port study: what the pile-head force's 1.6-4 kHz band levels need.

Run: python benchmarks/study_pile_port.py [--out results/study_pile_port]

The ROM's anvil meets the pile through one port: a uniform pressure on the pile ring, whose
mean displacement closes one contact on the head of a 1D pile. On Table 1 its pile-head force
is within 0.9 dB of the FEA's in every one-third-octave band up to 1.26 kHz and 1.7-8.4 dB
high from 1.6 to 4 kHz. This study isolates the interfaces: the reference FEA is run with its
ram-anvil contact force recorded node by node, and that force drives every variant (the ram
and its contact are out of the comparison); only the anvil's ports and the pile head change:

* ``rings K``: the anvil ROM (Table 1's anvil, fmax 5 kHz or ``--fmax``, static correction)
  loaded by the FEA's resultant ram force as a uniform pressure on the ram face (the ROM's
  ram port), with the pile ring split into K equal-width rings, each a uniform pressure of
  its own (its own modal participations, the residual flexibility between all ports) and its
  own compression-only contact on the flat head of the 1D pile (stiffness: the pile's top half
  segment, shared by ring area). The K ring forces are one linear complementarity problem per
  step (:func:`anvilwave.anvil_rom.rings.contact_lcp`). K = 1 is the ROM's port. The engine runs
  this
  variant with the modal ram and its own ram force as ``[anvil] pile_port_rings``.
* ``FEA ram pressure``: the ram face split into six annuli, each loaded by the FEA's nodal
  ram contact forces that fall on it: the FEA's own pressure distribution instead of a uniform
  one.
* ``tube L``: the six rings on an axisymmetric FE tube of the pile's section and length L
  (free-free modes to 15 kHz, static correction, six top ring ports and its bottom section),
  whose top can tilt and dish; its bottom section is tied to the 1D pile below (a two-way
  spring of the pile's half segment); the ring contacts are penalties like the FEA's.
* ``head rotation``: the six rings on the 1D pile whose head's wall section can rotate about
  its mid-surface (ring k's pile displacement u_head + theta e_k): theta is massless, the
  ring forces' moment against the shell edge's moment impedance
  (:func:`shell_edge_moment_impedance`, the closed form of a semi-infinite shell, checked
  against a finite model): its static value 2 pi R beta D (:func:`shell_edge_rotation_stiffness`,
  checked against an FE tube) as a spring in parallel with Maxwell branches fitted to the rest
  from 400 Hz to 8 kHz (:func:`maxwell_ladder`; above the 210 Hz ring frequency the wall
  radiates a bending wave and the impedance tends to the plate strip's C sqrt(i w));
  ``static head spring``: the static edge stiffness alone. No parameter is fitted to the FEA.
  In the FEA the pile top turns with the returning anvil (to 90 % of its ~4 mrad within
  0.25 ms), so the wall closes from edge to edge; a flat 1D head cannot turn, and only the
  inner ring of the others closes.

A prescribed ram force cannot take up the anvil's vibration: the real ram's face absorbs part
of it. The ``closed:`` variants therefore put the ram in the loop (:func:`run_closed_loop`): the
system's ram as its own modes to the same fmax (:func:`ram_face_ports`), striking at the impact
velocity, its residual flexibility the contact spring and the ram-impedance dashpot beside it,
as in the engine; with one ram port and one pile ring this is the engine's blow
(tests/test_study_pile_port.py). Then, one at a time: six rings on the head that turns; the
wall's local flexibility under the rings (:func:`wall_local_flexibility`, a static FE tube,
the part the 1D head and its rotation leave out); the ram face and the anvil's ram face in six
annuli, each a compression-only contact; and the same without the contact dashpot. These run
at 0.125 and 0.0625 m segments (the step scaled), with gravity (the anvil starts at rest on
the rings).

Last, ``closed: the FEA's pile``: the 1D pile is replaced by the reference FEA's own pile, its
tube as a ring kernel (:func:`anvilwave.pile.head_kernel.ring_kernel`: its mesh, one element per
ring,
three rings across the wall) with the FEA's penalty contacts
(:func:`anvilwave.pile.head_kernel.tube_contact_stiffness`), under one ram port, the ram face in six
annuli, in two halves of its radius, as a disc and its outer sixth (the rim), and in six annuli
without the contact dashpot. Every interface is then the FEA's, and what remains is the anvil's
and the ram's Mode Displacement Method.

The pile is a 1D rod (0.125 m segments), the step 5 us, unless stated. Printed per variant:
the band level deviations from the FEA [dB] from 1 to 4 kHz, the largest up to 1.26 kHz and up
to 4 kHz, and the peak pile force in the 5 kHz band against the FEA's (study.json also holds
every band and, for the closed loop, the ram's peak). Writes study.json and the FEA's
pile-head force (fea.csv); about a minute (2-3 min with ``--fmax 10000``).
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np
import scipy.sparse.linalg as sla

from anvilwave.analyses.compare import ModelRun, band_levels, band_limited, fea_config, without_soil
from anvilwave.anvil_rom.fem.elasticity import annulus_vectors, assemble, face_load_vector
from anvilwave.anvil_rom.fem.geometry import Interfaces, Material
from anvilwave.anvil_rom.fem.mesh import mesh_outline, split_outline_at_interfaces, to_skfem
from anvilwave.anvil_rom.fem.modes import elastic_flexibility, free_free_modes
from anvilwave.anvil_rom.rings import contact_lcp, ring_static_rest
from anvilwave.anvil_rom.rom import modal_transition, residual_flexibility
from anvilwave.config.system import load_system
from anvilwave.fea.bodies import ContactSet
from anvilwave.fea.impact import build_impact_model
from anvilwave.fea.solver import integrate
from anvilwave.hammer.modal_ram import default_mesh_size, ram_outline
from anvilwave.output.tables import write_csv
from anvilwave.pile.head_kernel import ring_kernel, tube_contact_stiffness

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
PATCHES = 6
"""Equal-width patches across the pile wall; the rings are groups of them."""
FMAX_ANVIL = 5000.0
FMAX_TUBE = 15000.0
SEGMENT = 0.125
STEP = 5e-6
TOL = 1e-6
BAND = 5000.0
CLOSED_SEGMENTS = (0.125, 0.0625)
"""[m] pile segments of the closed-loop variants (the step scales with them)."""
LADDER_BAND = (400.0, 8000.0)
"""[Hz] where the head rotation's Maxwell ladder follows the shell edge's impedance (below,
the impedance dips to zero at the ring frequency, which springs and dashpots cannot follow)."""


@dataclasses.dataclass
class Ports:
    """Modal ports of a body: participations P (ports, modes), residual flexibility R (ports,
    ports) [m/N], circular frequencies omega, the patch areas [m^2] of its ring ports and, for
    a pile tube, its length [m]."""

    P: np.ndarray
    R: np.ndarray
    omega: np.ndarray
    areas: np.ndarray
    length: float = 0.0


def _ports(model, loads, fmax):
    modes = free_free_modes(model, fmax)
    B = np.column_stack(loads)
    P = B.T @ modes.shapes
    G = elastic_flexibility(model, B)
    G = 0.5 * (G + G.T)
    omega = 2.0 * np.pi * np.asarray(modes.frequencies)
    return P, residual_flexibility(G, omega, *P), omega


def _patch_loads(model, z, r_in, r_out, count=PATCHES):
    B, areas = annulus_vectors(model, z, r_in, r_out, count)
    return list(B.T), areas


def anvil_ports(cfg, r_in, r_out, ram_radius, fmax=FMAX_ANVIL) -> Ports:
    """Table 1's anvil with ports (its modes to ``fmax`` [Hz]): the whole ram face, its PATCHES
    equal-width annuli, then the PATCHES patches of the pile ring."""
    spec = cfg.anvil.spec
    outline = np.asarray(spec.outline, float).copy()
    outline[:, 1] -= outline[:, 1].min()
    height = outline[:, 1].max()
    outline = split_outline_at_interfaces(
        outline, Interfaces(ram_radius, 0.5 * (r_in + r_out), r_out - r_in))
    sizes = np.full(len(outline), spec.mesh_size)
    ring = (np.abs(outline[:, 1] - height) < 1e-9) & (
        (np.abs(outline[:, 0] - r_in) < 1e-9) | (np.abs(outline[:, 0] - r_out) < 1e-9))
    sizes[ring] = (r_out - r_in) / PATCHES
    divisions = {}
    for i, (a, b) in enumerate(zip(outline, np.roll(outline, -1, axis=0), strict=True)):
        lo, hi = sorted((a[0], b[0]))
        if (abs(a[1] - height) < 1e-9 and abs(b[1] - height) < 1e-9
                and abs(lo - r_in) < 1e-9 and abs(hi - r_out) < 1e-9):
            divisions[i] = PATCHES
        if abs(a[1]) < 1e-9 and abs(b[1]) < 1e-9 and lo < 1e-9 and abs(hi - ram_radius) < 1e-9:
            divisions[i] = 3 * PATCHES
    model = assemble(to_skfem(mesh_outline(outline, None, point_sizes=sizes,
                                           edge_divisions=divisions)), spec.material)
    b_ram, _ = face_load_vector(model, lambda r, z: (np.abs(z) < TOL) & (r <= ram_radius + TOL))
    ram_loads, _ = _patch_loads(model, 0.0, 0.0, ram_radius)
    loads, areas = _patch_loads(model, height, r_in, r_out)
    P, R, omega = _ports(model, [b_ram] + ram_loads + loads, fmax)
    return Ports(P, R, omega, areas)


def tube_ports(material, r_in, r_out, length) -> Ports:
    """A pile tube of ``length`` [m]: the PATCHES top patches and the bottom section as ports."""
    outline = np.array([[r_in, 0.0], [r_out, 0.0], [r_out, length], [r_in, length]])
    size = (r_out - r_in) / 3
    mesh = mesh_outline(outline, None,
                        point_sizes=np.array([(r_out - r_in) / PATCHES] * 2 + [size] * 2),
                        edge_divisions={0: PATCHES, 2: 3})
    model = assemble(to_skfem(mesh), material)
    loads, areas = _patch_loads(model, 0.0, r_in, r_out)
    bottom, _ = face_load_vector(model, lambda r, z: np.abs(z - length) < TOL)
    P, R, omega = _ports(model, loads + [bottom], FMAX_TUBE)
    return Ports(P, R, omega, areas, float(length))


def ram_face_ports(cfg, fmax=FMAX_ANVIL) -> Ports:
    """The system's ram (its sections, its modes to ``fmax`` [Hz] on the modal ram's mesh for
    that fmax) with its toe face as ports: the whole face, then its PATCHES equal-width
    annuli (the anvil's ram annuli, :func:`anvil_ports`)."""
    ram = cfg.hammer.ram
    material = Material(ram.elastic_modulus, cfg.anvil.spec.material.poisson_ratio, ram.density)
    outline = ram_outline(ram.sections)
    toe = outline[:, 1].max()
    radius = 0.5 * ram.toe_diameter
    divisions = {i: 3 * PATCHES for i, (a, b) in enumerate(
        zip(outline, np.roll(outline, -1, axis=0), strict=True))
        if abs(a[1] - toe) < 1e-9 and abs(b[1] - toe) < 1e-9}
    size = default_mesh_size(ram.sections, material, fmax)
    model = assemble(to_skfem(mesh_outline(outline, None, point_sizes=np.full(len(outline), size),
                                           edge_divisions=divisions)), material)
    b_toe, _ = face_load_vector(model, lambda r, z: np.abs(z - toe) < TOL)
    loads, areas = _patch_loads(model, toe, 0.0, radius)
    P, R, omega = _ports(model, [b_toe] + loads, fmax)
    return Ports(P, R, omega, areas)


def held_tube_flexibility(model, loads: np.ndarray, length: float) -> np.ndarray:
    """Static flexibility [m/N] between ``loads`` (n_dof, k) of an axisymmetric tube model
    whose bottom (z = ``length``) is held axially: loads^T K^-1 loads on the rest."""
    free = {int(d): i for i, d in enumerate(np.asarray(model.free_dofs))}
    bottom = [free[int(d)] for d in model.node_dofs[
        np.abs(model.node_coordinates[:, 1] - length) < 1e-9, 1] if int(d) in free]
    keep = np.setdiff1d(np.arange(model.n_dof), bottom)
    u = np.zeros_like(loads)
    u[keep] = sla.splu(model.stiffness.tocsc()[keep][:, keep].tocsc()).solve(
        np.ascontiguousarray(loads[keep]))
    return loads.T @ u


def wall_local_flexibility(material, r_in, r_out, length=4.0, per_patch=4) -> np.ndarray:
    """The pile wall's local flexibility under its PATCHES top patches [m/N]: what the 1D head
    with its rotation (uniform and linear displacement across the wall) leaves out.

    A static axisymmetric FE tube of the pile section (``length`` [m], its bottom held
    axially; the edge's bending decays within 1 / beta = 0.6 m) with ``per_patch`` quadratic
    elements across each patch at the top gives the patches' flexibility C; its part
    orthogonal to the uniform and the linear patterns, (I - Q) C (I - Q) with Q the
    projection on them, is the local one: symmetric, positive semi-definite, zero for a
    uniform pressure and for a pure edge moment, so the head keeps its 1D impedance and its
    rotation. Converged at second order in the element size (tests/test_study_pile_port.py).
    It is frequency-independent where it matters: the same projection of the receptance of an
    FE tube with an absorbing layer and one element per patch (a frequency-domain check, not in
    this study) agreed with this static one at ``per_patch`` = 1 within 5 % from 0.5 to
    4 kHz."""
    outline = np.array([[r_in, 0.0], [r_out, 0.0], [r_out, length], [r_in, length]])
    wall = r_out - r_in
    top = per_patch * PATCHES
    model = assemble(to_skfem(mesh_outline(
        outline, None, point_sizes=np.array([wall / top] * 2 + [4 * wall / PATCHES] * 2),
        edge_divisions={0: top, 2: PATCHES})), material)
    loads, _ = annulus_vectors(model, 0.0, r_in, r_out, PATCHES)
    C = held_tube_flexibility(model, loads, length)
    edges = np.linspace(r_in, r_out, PATCHES + 1)
    V = np.column_stack([np.ones(PATCHES), 0.5 * (edges[:-1] + edges[1:])])
    Q = np.eye(PATCHES) - V @ np.linalg.solve(V.T @ V, V.T)
    local = Q @ C @ Q
    return 0.5 * (local + local.T)


def shell_edge_rotation_stiffness(E: float, nu: float, radius: float, wall: float) -> float:
    """Static moment stiffness [N m/rad] of the edge of a long cylindrical shell under an edge
    moment (free shear), over the circumference: 2 pi R beta D with beta^4 = 3 (1 - nu^2) /
    (R t)^2 and D = E t^3 / (12 (1 - nu^2)) (Timoshenko & Woinowsky-Krieger 1959, sec. 115)."""
    D = E * wall**3 / (12.0 * (1.0 - nu**2))
    beta = (3.0 * (1.0 - nu**2) / (radius * wall) ** 2) ** 0.25
    return 2.0 * np.pi * radius * beta * D


def shell_edge_moment_impedance(omega, E: float, nu: float, rho: float, radius: float,
                                wall: float, loss: float = 0.0) -> np.ndarray:
    """Edge moment impedance M / theta [N m/rad] over the circumference of a semi-infinite
    cylindrical shell in axisymmetric bending with a free-shear edge, at circular frequencies
    ``omega`` [rad/s] (time factor exp(i w t)). The wall is a beam on the hoop foundation,
    D w^(4) + (E t / R^2) w - rho t w^2 w = 0 (Timoshenko & Woinowsky-Krieger 1959, sec. 114,
    with the inertia added): w = A exp(-k1 x) + B exp(-k2 x) with the two roots of
    k^4 = (rho t w^2 - E t / R^2) / D that decay (above the ring frequency: the one that decays
    and the one that carries the wave away), and Q(0) = 0 gives M / theta = 2 pi R D k1 k2 /
    (k1 + k2). At w = 0 it is 2 pi R beta D (:func:`shell_edge_rotation_stiffness`); well above
    the ring frequency sqrt(E / rho) / (2 pi R) (210 Hz for 8 m) it tends to C sqrt(i w),
    C = 2 pi R D (rho t / D)^(1/4) / sqrt 2 (the plate strip); at the ring frequency it
    vanishes. ``loss``: a hysteretic loss factor on D and the foundation (for a check against
    a damped finite model)."""
    D = E * wall**3 / (12.0 * (1.0 - nu**2)) * (1.0 + 1j * loss)
    foundation = E * wall / radius**2 * (1.0 + 1j * loss)
    omega = np.asarray(omega, float)
    fourth = np.asarray((rho * wall * omega**2 - foundation) / D, complex) ** 0.25
    roots = fourth[..., None] * np.array([1.0, 1j, -1.0, -1j])
    # decaying: Re k > 0; of a propagating pair (Re k = 0) the outgoing one, exp(-i kappa x)
    key = np.where(np.abs(roots.real) > 1e-9 * np.abs(roots), roots.real, roots.imag)
    order = np.argsort(-key, axis=-1)[..., :2]
    k1, k2 = np.moveaxis(np.take_along_axis(roots, order, axis=-1), -1, 0)
    return 2.0 * np.pi * radius * D * k1 * k2 / (k1 + k2)


def maxwell_branches(w, tau: np.ndarray) -> np.ndarray:
    """Impedance per unit spring of Maxwell branches (a spring in series with a dashpot of
    time constant tau_i) at circular frequencies w: i w tau_i / (1 + i w tau_i), (w, tau)."""
    wt = 1j * np.outer(w, tau)
    return wt / (1.0 + wt)


def maxwell_ladder(target, tau: np.ndarray, f_lo: float, f_hi: float
                   ) -> tuple[np.ndarray, float]:
    """Maxwell branches (spring k_i in series with a dashpot k_i tau_i) whose summed impedance
    sum k_i i w tau_i / (1 + i w tau_i) approximates ``target(w)`` from f_lo to f_hi [Hz]
    (non-negative least squares on the relative error): (k_i, largest relative error)."""
    from scipy.optimize import nnls

    w = 2.0 * np.pi * np.logspace(np.log10(f_lo), np.log10(f_hi), 200)
    z = target(w)
    branches = maxwell_branches(w, tau)
    norm = np.abs(z)[:, None]
    k, _ = nnls(np.vstack([branches.real / norm, branches.imag / norm]),
                np.r_[z.real / norm[:, 0], z.imag / norm[:, 0]])
    return k, float(np.max(np.abs(branches @ k - z) / norm[:, 0]))


@dataclasses.dataclass
class HeadRotation:
    """The pile head's wall section rotating about its mid-surface: ring k's pile displacement
    is u_head + theta e_k; theta is massless, the ring forces' moment against the shell edge's
    impedance: a static spring in parallel with a ladder of Maxwell branches."""

    offsets: np.ndarray  # e_k [m]
    static: float        # [N m/rad]
    springs: np.ndarray  # ladder k_i [N m/rad]
    tau: np.ndarray      # ladder tau_i [s]


def relax_ladder(rotation: HeadRotation, phi, forces, total: float, decay) -> np.ndarray:
    """The ladder's dashpot states after a step with theta held: theta = (e . F + sum k_i
    phi_i) / (static + sum k_i) from the ring ``forces``, each phi_i relaxing towards it with
    ``decay`` = exp(-h / tau_i)."""
    theta = (rotation.offsets @ forces + rotation.springs @ phi) / total
    return theta + (phi - theta) * decay


def pile_step(u, v, head: float, k_seg: float, mass: float, step: float,
              support: float = 0.0) -> None:
    """One explicit step of the 1D pile (lumped segments, in place): ``head`` [N] pushes the top
    mass down, ``support`` [N] holds the bottom one up."""
    force = np.zeros(u.size)
    stretch = k_seg * np.diff(u)
    force[:-1] += stretch
    force[1:] -= stretch
    force[0] += head
    force[-1] -= support
    v += step * force / mass
    u += step * v


def run_variant(anvil: Ports, groups, ram_ports, ram_force, duration, pile,
                tube: Ports | None = None, rotation: HeadRotation | None = None):
    """Pile-head force history [N] (sampled every 2 steps) of one variant: ``groups`` of pile
    patches make the rings, ``ram_ports`` are the anvil's ram ports used (row indices of
    anvil.P) and ``ram_force(t)`` their forces [N]."""
    E, rho, area, wall, length = pile
    K = len(groups)
    n_ram = len(ram_ports)
    first = anvil.P.shape[0] - anvil.areas.size  # the first pile patch's port
    # ports -> the ram ports used, then the rings (uniform pressure over each group of patches)
    Ta = np.zeros((n_ram + K, anvil.P.shape[0]))
    Ta[np.arange(n_ram), ram_ports] = 1.0
    Ta[n_ram:] = _group_rows(anvil, first, groups, anvil.areas)
    Pa, Ra = Ta @ anvil.P, Ta @ anvil.R @ Ta.T
    ring_area = np.array([anvil.areas[g].sum() for g in groups])
    if tube is not None:
        n_patch = tube.areas.size
        Tt = np.zeros((K + 1, n_patch + 1))
        Tt[K, n_patch] = 1.0
        for i, g in enumerate(groups):
            Tt[i, g] = tube.areas[g] / tube.areas[g].sum()
        Pt, Rt = Tt @ tube.P, Tt @ tube.R @ Tt.T
    n = int(round((length - (0.0 if tube is None else tube.length)) / SEGMENT))
    mass = rho * area * SEGMENT
    k_seg = E * area / SEGMENT
    rings = slice(n_ram, n_ram + K)
    if tube is None:  # the pile's top half segment, shared by ring area
        k_ring = 2.0 * k_seg * ring_area / area
        M = np.diag(1.0 / k_ring) + Ra[rings, rings]
        if rotation is not None:  # theta = (e . F + sum k_i phi_i) / K, in the LCP
            total = rotation.static + rotation.springs.sum()
            M = M + np.outer(rotation.offsets, rotation.offsets) / total
            phi = np.zeros(rotation.tau.size)
            decay = np.exp(-STEP / rotation.tau)
    else:  # a penalty like the FEA's (E / a patch width, per area), the tube's flexibility
        k_ring = E / (wall / PATCHES) * ring_area
        M = np.diag(1.0 / k_ring) + Ra[rings, rings] + Rt[:K, :K]
        k_tie = 2.0 * k_seg
        ct = modal_transition(tube.omega, 0.0, STEP)
        qt = np.zeros(tube.omega.size)
        qt_prev = qt.copy()
    ca = modal_transition(anvil.omega, 0.0, STEP)
    qa = np.zeros(anvil.omega.size)
    qa_prev = qa.copy()
    u = np.zeros(n)
    v = np.zeros(n)
    F = np.zeros(K)
    active = np.zeros(K)  # the contact set, from step to step
    work = np.zeros((K, K + 1))
    steps = int(round(duration / STEP))
    out = np.zeros(steps // 2 + 1)
    for s in range(steps + 1):
        fr = ram_force(s * STEP)
        g = Pa[rings] @ qa + Ra[rings, :n_ram] @ fr
        tie = 0.0
        if tube is None:
            g -= u[0]
            if rotation is not None:
                g -= rotation.offsets * (rotation.springs @ phi) / total
        else:
            u_bottom = Pt[K] @ qt + Rt[K, :K] @ F
            tie = k_tie * (u_bottom - u[0])
            g -= Pt[:K] @ qt - Rt[:K, K] * tie
        contact_lcp(M, g, F, active, work)
        if rotation is not None:  # the ladder's dashpots move with theta held over the step
            phi = relax_ladder(rotation, phi, F, total, decay)
        if s % 2 == 0:
            out[s // 2] = F.sum()
        f = Pa[:n_ram].T @ fr - Pa[rings].T @ F
        qn = ca[:, 0] * qa + ca[:, 1] * qa_prev + ca[:, 2] * f
        qa_prev, qa = qa, qn
        head = F.sum()
        if tube is not None:
            f = Pt[:K].T @ F - Pt[K] * tie
            qn = ct[:, 0] * qt + ct[:, 1] * qt_prev + ct[:, 2] * f
            qt_prev, qt = qt, qn
            head = tie
        pile_step(u, v, head, k_seg, mass, STEP)
    return out


def _group_rows(ports: Ports, first: int, groups, areas: np.ndarray) -> np.ndarray:
    """(groups, ports) rows that combine ``ports``' patches from ``first`` on, of ``areas``
    [m^2], into uniform pressures over each group (area weights)."""
    T = np.zeros((len(groups), ports.P.shape[0]))
    for i, g in enumerate(groups):
        T[i, [first + k for k in g]] = areas[g] / areas[g].sum()
    return T


def run_closed_loop(anvil: Ports, ram: Ports, groups, ram_groups, impact_velocity: float,
                    damping: float, duration: float, pile, rotation: HeadRotation | None = None,
                    local: np.ndarray | None = None, segment: float = SEGMENT,
                    step: float = STEP, gravity: float = 0.0, kernel: np.ndarray | None = None,
                    contact: np.ndarray | None = None):
    """(pile-head force, ram force) histories [N], sampled every 10 us, of the ram, the
    anvil and the 1D pile in one loop: the ram's own modes (``ram``, :func:`ram_face_ports`) strike
    at ``impact_velocity`` [m/s]. ``ram_groups`` are groups of the ram face's annuli, each one
    compression-only contact between the ram's and the anvil's annuli (one group: the ROM's
    uniform ram port); the ram's residual flexibility is the contact spring, as for the
    modal ram unit, and a dashpot ``damping`` [N s/m] (shared by area) acts beside it, folded
    in as the unit folds it (the overlap rate times c / k, k the spring). ``groups`` of pile
    patches make the rings, on the flat head of the 1D pile (their springs the top half
    segment's shares), turning with ``rotation`` and, with ``local`` (PATCHES x PATCHES,
    :func:`wall_local_flexibility`), with the wall's local flexibility between them. Every
    contact is one complementarity problem per step. With ``gravity`` [m/s^2] the anvil starts
    at rest on the rings under its weight (:func:`anvilwave.anvil_rom.rings.ring_static_rest`, with
    the
    head's static edge spring and the local flexibility), the pile compressed by that weight
    and held at its bottom by a constant force, the ram falling and its face touching the
    anvil's first annulus, as in the engine and the FEA; without, the anvil and the pile start
    unloaded.

    With a ``kernel`` (steps, K, K) [m/N] (:func:`anvilwave.pile.head_kernel.ring_kernel`, at this
    ``step``) the pile is that kernel instead of the 1D rod: the rings' displacements are sum_k
    kernel[k] F_(n-k) from their rest, kernel[0] in the complementarity problem, and the ring
    contacts are the springs ``contact`` (K,) [N/m]
    (:func:`anvilwave.pile.head_kernel.tube_contact_stiffness`); under gravity the rings rest on a
    flat
    head (the pile's static flexibility under the anvil's weight, 3 MN, is left out)."""
    E, rho, area, _, length = pile
    J, K = len(ram_groups), len(groups)
    # the anvil's ram annuli and the ram's face annuli are the same annuli (ram.areas)
    first = anvil.P.shape[0] - anvil.areas.size  # the first pile patch's port
    Ta = np.vstack([_group_rows(anvil, 1, ram_groups, ram.areas),
                    _group_rows(anvil, first, groups, anvil.areas)])
    Tr = _group_rows(ram, 1, ram_groups, ram.areas)
    Pa, Ra = Ta @ anvil.P, Ta @ anvil.R @ Ta.T
    Pr, Rr = Tr @ ram.P, Tr @ ram.R @ Tr.T
    ring_area = np.array([anvil.areas[g].sum() for g in groups])
    face_area = np.array([ram.areas[g].sum() for g in ram_groups])
    n = int(round(length / segment))
    mass = rho * area * segment
    k_seg = E * area / segment
    sign = np.r_[np.ones(J), -np.ones(K)]  # the rings push the anvil up, the ram down
    A = sign[:, None] * Ra * sign[None, :]
    A[:J, :J] += Rr
    if kernel is None:
        springs = 2.0 * k_seg * ring_area / area  # the top half segment, shared by ring area
    else:
        springs = np.asarray(contact, float)
        n = 0  # no 1D pile
    A[J:, J:] += np.diag(1.0 / springs)
    if local is not None:  # the patches' flexibility seen by the rings (their area weights)
        A[J:, J:] += Ta[J:, first:] @ local @ Ta[J:, first:].T
    if rotation is not None:
        total = rotation.static + rotation.springs.sum()
        A[J:, J:] += np.outer(rotation.offsets, rotation.offsets) / total
        phi = np.zeros(rotation.tau.size)
        decay = np.exp(-step / rotation.tau)
    fold = damping * face_area / face_area.sum() * np.diag(Rr)
    ca = modal_transition(anvil.omega, 0.0, step)
    cr = modal_transition(ram.omega, 0.0, step)
    qa, qr = np.zeros(anvil.omega.size), np.zeros(ram.omega.size)
    rigid_a = int(np.flatnonzero(anvil.omega == 0.0)[0])
    rigid = int(np.flatnonzero(ram.omega == 0.0)[0])
    # gravity on the rigid modes: phi^T M g e_z = g / p for a participation p = 1 / sqrt(m)
    weight_a = np.zeros(anvil.omega.size)
    weight_a[rigid_a] = gravity / Pa[0, rigid_a]
    weight_r = np.zeros(ram.omega.size)
    weight_r[rigid] = gravity / Pr[0, rigid]
    u, v = np.zeros(n), np.zeros(n)
    F = np.zeros(J + K)
    support = 0.0
    if gravity > 0.0:  # the anvil at rest on the rings, the pile compressed by its weight
        support = gravity / Pa[0, rigid_a] ** 2  # the anvil's weight [N]
        rest = A[J:, J:] - np.diag(1.0 / springs)  # the rings' residual, local, rotation
        if rotation is not None:  # the ladder relaxed: the static edge spring alone
            rest += np.outer(rotation.offsets, rotation.offsets) * (
                1.0 / rotation.static - 1.0 / total)
        F[J:], u0 = ring_static_rest(anvil.omega, Pa[J:], springs, rest, support)
        flexible = anvil.omega > 0.0
        qa[flexible] = -(F[J:] @ Pa[J:, flexible]) / anvil.omega[flexible] ** 2
        qa[rigid_a] = u0 / Pa[J, rigid_a]
        u -= np.arange(n) * support / k_seg
        if rotation is not None:
            phi[:] = rotation.offsets @ F[J:] / rotation.static
    if kernel is not None:  # the pile's head is flat at 0 under the rest forces
        A[J:, J:] += kernel[0]  # acts at once
        rest_force = F[J:].copy()
        history = np.zeros((int(round(duration / step)) + 1, K))
    # the ram's face touches the anvil's highest annulus (at rest: modal part and residual)
    face = np.min(Pa[:J] @ qa - Ra[:J, J:] @ F[J:])
    qr[rigid] = face / Pr[0, rigid]
    qa_prev = qa.copy()
    qr_prev = qr.copy()
    qr_prev[rigid] -= step * impact_velocity / Pr[0, rigid]  # the face at impact_velocity
    active = (F > 0.0).astype(float)
    work = np.zeros((J + K, J + K + 1))
    g = np.zeros(J + K)
    steps = int(round(duration / step))
    every = max(1, int(round(1e-5 / step)))
    out = np.zeros((steps // every + 1, 2))
    for s in range(steps + 1):
        g[:J] = Pr @ qr - Pa[:J] @ qa + fold * (Pr @ (qr - qr_prev) - Pa[:J] @ (qa - qa_prev)
                                                ) / step
        if kernel is None:
            g[J:] = Pa[J:] @ qa - u[0]
        else:  # kernel[0] F_n is in A
            m = min(s, kernel.shape[0] - 1)
            g[J:] = Pa[J:] @ qa + kernel[0] @ rest_force - np.einsum(
                "kij,kj->i", kernel[1:m + 1], history[s - 1::-1][:m])
        if rotation is not None:
            g[J:] -= rotation.offsets * (rotation.springs @ phi) / total
        contact_lcp(A, g, F, active, work)
        if kernel is not None:
            history[s] = F[J:] - rest_force
        if rotation is not None:  # the ladder's dashpots move with theta held over the step
            phi = relax_ladder(rotation, phi, F[J:], total, decay)
        if s % every == 0:
            out[s // every] = F[J:].sum(), F[:J].sum()
        qn = ca[:, 0] * qa + ca[:, 1] * qa_prev + ca[:, 2] * (
            Pa[:J].T @ F[:J] - Pa[J:].T @ F[J:] + weight_a)
        qa_prev, qa = qa, qn
        qn = cr[:, 0] * qr + cr[:, 1] * qr_prev + cr[:, 2] * (weight_r - Pr.T @ F[:J])
        qr_prev, qr = qr, qn
        if kernel is None:
            pile_step(u, v, F[J:].sum(), k_seg, mass, step, support)
    return out, every * step


def instrumented_fea(cfg, duration: float | None = None) -> dict:
    """The reference FEA of ``cfg`` (for ``duration`` [s], default the system's) with the
    contact force of every node pair: "time [s]", the ram face's "ram_radii [m]" and
    "ram_forces [N]" (t, nodes), the pile top's "pile_radii [m]" and "pile_forces [N]", and
    the pile top's area-weighted mean "pile_head_velocity [m/s]"."""
    config = fea_config(cfg)
    if duration is not None:
        config = dataclasses.replace(config, duration=duration)
    model = build_impact_model(config)
    system = model.system
    ram, pile = system.contacts

    def pairs(contact):
        return [ContactSet(f"{contact.name}_{i}", *(getattr(contact, f)[i:i + 1] for f in (
            "upper_dofs", "lower_dofs", "stiffness", "damping", "gap", "radii")))
            for i in range(contact.radii.size)]

    system.contacts = pairs(ram) + pairs(pile)
    tr = integrate(system, config.duration, config.output_interval,
                   safety=config.time_step_safety)
    forces = tr.contact_force
    return {"time [s]": tr.time, "ram_radii [m]": ram.radii,
            "ram_forces [N]": forces[:, :ram.radii.size], "pile_radii [m]": pile.radii,
            "pile_forces [N]": forces[:, ram.radii.size:],
            "pile_head_velocity [m/s]": tr.probes["pile_head_velocity"]}


def annulus_weights(radii, edges):
    """(nodes, annuli) shares of each node's force: a node on an edge splits half and half."""
    W = np.zeros((radii.size, edges.size - 1))
    for i, r in enumerate(radii):
        k = min(int(np.searchsorted(edges, r, side="right")) - 1, edges.size - 2)
        if 0 < k and abs(r - edges[k]) < 1e-9:
            W[i, k - 1] = W[i, k] = 0.5
        else:
            W[i, k] = 1.0
    return W


def _row(run: ModelRun, fea: ModelRun, fea_columns, t_fea) -> dict:
    """A variant's band level deviations from the FEA (valid bands), their largest up to 1.26
    and up to 4 kHz, and its peak pile force in the BAND against the FEA's."""
    spectra = band_levels({"model": run, "fea": fea}, BAND)
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool)
    deviation = np.array([np.nan if d is None else d
                          for d in spectra["deviation_from_fea [dB]"]["model"]])
    key = "anvil_pile_force [N]"
    peak = (band_limited(run.columns, key, t_fea, BAND).max()
            / band_limited(fea_columns, key, t_fea, BAND).max() - 1.0)
    return {"band_centre_frequency [Hz]": centre[valid].tolist(),
            "deviation_from_fea [dB]": deviation[valid].tolist(),
            "max_deviation_to_1259_Hz [dB]": float(np.nanmax(np.abs(
                deviation[valid & (centre <= 1259.0 * 1.01)]))),
            "max_deviation_to_3981_Hz [dB]": float(np.nanmax(np.abs(
                deviation[valid & (centre <= 3981.0 * 1.01)]))),
            "peak_pile_force_error_5kHz [-]": peak, "wall_time [s]": run.wall_time}


DOCS_BANDS = (1000.0, 1259.0, 1585.0, 1995.0, 2512.0, 3162.0, 3981.0)
"""[Hz] the one-third-octave bands of docs/validation.md's tables (nominal centres)."""
FMAX_DOCS = (FMAX_ANVIL, 10000.0)
"""[Hz] the fmax of the docs' runs: the default and ``--fmax 10000``."""
OPEN_ROWS = {
    "1 ring (the ROM's port)": "rings 1", "2 rings": "rings 2", "3 rings": "rings 3",
    "6 rings": "rings 6", "6 rings, FEA ram pressure": "rings 6, FEA ram pressure",
    "6 rings, 8 m tube head": "rings 6 + tube 8 m",
    "6 rings, 8 m tube head, FEA ram pressure": "rings 6 + tube 8 m, FEA ram",
    "6 rings, static head spring only": "rings 6 + static head spring",
    "6 rings, head rotation": "rings 6 + head rotation",
    "6 rings, head rotation, FEA ram pressure": "rings 6 + head rotation, FEA ram",
}
"""The rows of the docs' first table (the FEA's ram force prescribed): label -> variant."""
CLOSED_ROWS = {
    "the ROM's ports (one ram port, one ring)": "closed: rings 1 (the ROM's ports)",
    "6 rings + head rotation": "closed: rings 6 + head rotation",
    "+ the wall's local flexibility": "closed: + wall's local flexibility",
    "+ the ram face in 6 annuli": "closed: + ram face in 6 annuli",
    "the same, no ram contact dashpot": "closed: the same, no ram contact dashpot",
}
"""The rows of the docs' closed-loop table (1D pile), at every CLOSED_SEGMENTS."""
FEA_PILE_ROWS = {
    "one ram port (the ROM's)": "one ram port", "ram face in 6 annuli": "ram face in 6 annuli",
    "ram face in 2 halves of its radius": "ram face in 2 halves",
    "ram face as a disc and its outer sixth (rim)": "ram face as disc + rim",
    "the same, no ram contact dashpot": "6 annuli, no dashpot",
}
"""The rows of the docs' table of the FEA's pile: label -> variant (after its prefix)."""


def _bands(row: dict) -> list[float]:
    """A variant's deviations [dB] in the bands of :data:`DOCS_BANDS`."""
    centre = np.array(row["band_centre_frequency [Hz]"])
    out = []
    for f in DOCS_BANDS:
        (i,) = np.flatnonzero(np.abs(centre / f - 1.0) < 0.01)
        out.append(row["deviation_from_fea [dB]"][i])
    return out


def docs_tables(rows: dict, rows_10k: dict, wall_elements: int = 3) -> dict:
    """docs/validation.md's three tables from the rows of a run at the default fmax and of
    one at 10 kHz (study.json)."""
    bands = [f"{f:.0f}" for f in DOCS_BANDS]
    peaks = ["peak pile (5 kHz band)", "peak ram (5 kHz band)"]
    open_table = {"columns": ["variant", *bands, "peak (5 kHz band)"],
                  "formats": [None, *["dB+"] * len(bands), "pct+"],
                  "rows": [[label, *_bands(rows[key]), rows[key]["peak_pile_force_error_5kHz [-]"]]
                           for label, key in OPEN_ROWS.items()]}
    closed = {"columns": ["variant, ram in the loop", "segments", *bands, "max ≤ 1.26 kHz",
                          *peaks],
              "formats": [None, None, *["dB+"] * len(bands), "f1", "pct+", "pct+"],
              "rows": []}
    for segment in CLOSED_SEGMENTS:
        for label, key in CLOSED_ROWS.items():
            r = rows[f"{key}, {segment:g} m"]
            closed["rows"].append([label, f"{segment:g} m", *_bands(r),
                                   r["max_deviation_to_1259_Hz [dB]"],
                                   r["peak_pile_force_error_5kHz [-]"],
                                   r["peak_ram_force_error_5kHz [-]"]])
    prefix = f"closed: the FEA's pile ({wall_elements} rings), "
    fea_pile = {"columns": [f"the FEA's pile ({wall_elements} rings), ram in the loop", "fmax",
                            *bands, "max 50 Hz-4 kHz", *peaks],
                "formats": [None, None, *["dB+"] * len(bands), "f1", "pct+", "pct+"],
                "rows": []}
    for fmax, run in zip(FMAX_DOCS, (rows, rows_10k), strict=True):
        for label, key in FEA_PILE_ROWS.items():
            r = run[prefix + key]
            fea_pile["rows"].append([label, f"{fmax / 1e3:g} kHz", *_bands(r),
                                     r["max_deviation_to_3981_Hz [dB]"],
                                     r["peak_pile_force_error_5kHz [-]"],
                                     r["peak_ram_force_error_5kHz [-]"]])
    return {"open_loop": open_table, "closed_loop": closed, "fea_pile": fea_pile}


def write_docs(system: Path, rows: dict, rows_10k: dict, command: str | None = None) -> None:
    """docs/data/study_pile_port.json from the rows of the two runs (default fmax, 10 kHz)."""
    # lazy: benchmarks/doc_data.py is on the path when this runs as a script, not when the
    # tests load this file by its path (tests/study_loop.py, tests/test_study_pile_port.py)
    from doc_data import system_inputs, write_doc_data

    write_doc_data("study_pile_port", about="the anvil-pile port study: band levels of the "
                   "pile-head force against the FEA per interface variant (docs/validation.md, "
                   "\"What the 1.6-4 kHz bands need\", \"The ram in the loop\", \"The FEA's "
                   "own pile under the ROM\")", inputs=system_inputs(system),
                   tables=docs_tables(rows, rows_10k),
                   values={f"fmax {f:g} Hz": r for f, r in zip(FMAX_DOCS, (rows, rows_10k),
                                                               strict=True)},
                   command=command)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--system", type=Path, default=EXAMPLES / "table1.toml")
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "study_pile_port")
    parser.add_argument("--fmax", type=float, default=FMAX_ANVIL,
                        help="modes of the anvil and the ram up to this frequency [Hz]")
    parser.add_argument("--docs", action="store_true",
                        help="run at the default fmax and at 10 kHz (OUT/fmax_5000, "
                             "OUT/fmax_10000) and write docs/data/study_pile_port.json")
    parser.add_argument("--docs-from", type=Path, nargs=2, metavar=("STUDY_JSON", "STUDY_10K"),
                        help="only rewrite docs/data/study_pile_port.json from the study.json "
                             "of an earlier run at the default fmax and of one at --fmax 10000")
    args = parser.parse_args()
    if args.docs_from is not None:
        write_docs(args.system, *(json.loads(p.read_text()) for p in args.docs_from),
                   command="python benchmarks/study_pile_port.py --docs")
        return
    if args.docs:
        runs = [run_study(args.system, args.out / f"fmax_{f:.0f}", f) for f in FMAX_DOCS]
        write_docs(args.system, *runs)
        return
    run_study(args.system, args.out, args.fmax)


def run_study(system: Path, out: Path, fmax: float) -> dict:
    """Every variant of the study (module docstring) on ``system`` with the anvil's and the
    ram's modes to ``fmax`` [Hz]; writes study.json and fea.csv in ``out``, prints the table and
    returns study.json's rows."""
    out.mkdir(parents=True, exist_ok=True)
    cfg = without_soil(load_system(system))
    start = time.perf_counter()
    record = instrumented_fea(cfg)
    t_fea, node_radii, node_forces = (record[k] for k in ("time [s]", "ram_radii [m]",
                                                          "ram_forces [N]"))
    pile_force = record["pile_forces [N]"].sum(axis=1)
    print(f"FEA ({time.perf_counter() - start:.1f} s)", flush=True)
    ram_radius = 0.5 * cfg.hammer.ram.toe_diameter
    annuli = node_forces @ annulus_weights(node_radii, np.linspace(0.0, ram_radius,
                                                                    PATCHES + 1))
    resultant = node_forces.sum(axis=1)
    fea_columns = {"time [s]": t_fea, "anvil_pile_force [N]": pile_force}
    write_csv(fea_columns, out / "fea.csv")
    fea = ModelRun("fea", fea_columns, float("nan"), {})

    def uniform(t):
        return np.array([np.interp(t, t_fea, resultant)])

    def distributed(t):
        return np.array([np.interp(t, t_fea, f) for f in annuli.T])

    section = cfg.pile_soil.pile.sections[0]
    r_out = 0.5 * section.outer_diameter
    r_in = r_out - section.wall_thickness
    material = cfg.anvil.spec.material
    pile = (material.youngs_modulus, material.density, np.pi * (r_out**2 - r_in**2),
            r_out - r_in, cfg.pile_soil.pile.length)
    start = time.perf_counter()
    anvil = anvil_ports(cfg, r_in, r_out, ram_radius, fmax)
    print(f"anvil ports: {anvil.omega.size} modes to {fmax:g} Hz "
          f"({time.perf_counter() - start:.1f} s)", flush=True)
    rings = {1: [[0, 1, 2, 3, 4, 5]], 2: [[0, 1, 2], [3, 4, 5]], 3: [[0, 1], [2, 3], [4, 5]],
             6: [[k] for k in range(PATCHES)]}
    whole, annular = [0], list(range(1, PATCHES + 1))
    variants = {f"rings {k}": (groups, whole, uniform, None) for k, groups in rings.items()}
    variants["rings 1, FEA ram pressure"] = (rings[1], annular, distributed, None)
    variants["rings 6, FEA ram pressure"] = (rings[6], annular, distributed, None)
    for length in (4.0, 8.0):
        tube = tube_ports(material, r_in, r_out, length)
        variants[f"rings 6 + tube {length:g} m"] = (rings[6], whole, uniform, tube)
        variants[f"rings 6 + tube {length:g} m, FEA ram"] = (rings[6], annular, distributed,
                                                              tube)
    # the pile head's rotation against the shell edge's moment impedance (six rings)
    edges = np.linspace(r_in, r_out, PATCHES + 1)
    offsets = 0.5 * (edges[:-1] + edges[1:]) - 0.5 * (r_in + r_out)
    tau = 1.0 / (2.0 * np.pi * np.logspace(1.0, np.log10(8e4), 16))
    E, nu = material.youngs_modulus, material.poisson_ratio
    mid = 0.5 * (r_in + r_out)

    def edge(w):
        return shell_edge_moment_impedance(w, E, nu, material.density, mid, r_out - r_in)

    static = float(edge(0.0).real)
    ladder, _ = maxwell_ladder(lambda w: edge(w) - static, tau, *LADDER_BAND)
    w = 2.0 * np.pi * np.logspace(np.log10(LADDER_BAND[0]), np.log10(LADDER_BAND[1]), 200)
    fitted = static + maxwell_branches(w, tau) @ ladder
    error = float(np.max(np.abs(fitted / edge(w) - 1.0)))
    rotation = HeadRotation(offsets, static, ladder, tau)
    print(f"pile head: static edge stiffness {rotation.static:.3g} N m/rad, the shell edge's "
          f"impedance as that spring and {tau.size} Maxwell branches within {100 * error:.0f} % "
          f"from {LADDER_BAND[0]:g} Hz to {LADDER_BAND[1]:g} Hz", flush=True)
    variants["rings 6 + static head spring"] = (rings[6], whole, uniform, dataclasses.replace(
        rotation, springs=np.zeros(0), tau=np.zeros(0)))
    variants["rings 6 + head rotation"] = (rings[6], whole, uniform, rotation)
    variants["rings 6 + head rotation, FEA ram"] = (rings[6], annular, distributed, rotation)
    preload = float(pile_force[0])
    rows = {}
    for name, (groups, ram_ports, ram_force, head) in variants.items():
        start = time.perf_counter()
        tube = head if isinstance(head, Ports) else None
        rotation = head if isinstance(head, HeadRotation) else None
        force = run_variant(anvil, groups, ram_ports, ram_force, cfg.duration, pile, tube,
                            rotation)
        t = np.arange(force.size) * 2 * STEP
        columns = {"time [s]": t, "anvil_pile_force [N]": force + preload}
        run = ModelRun(name, columns, time.perf_counter() - start, {})
        rows[name] = _row(run, fea, fea_columns, t_fea)
        print(f"{name} done ({run.wall_time:.1f} s)", flush=True)
    # the ram in the loop: its own modes, its face in annuli or uniform
    start = time.perf_counter()
    ram = ram_face_ports(cfg, fmax)
    local = wall_local_flexibility(material, r_in, r_out)
    print(f"ram ports: {ram.omega.size} modes to {fmax:g} Hz; the wall's local "
          f"flexibility ({time.perf_counter() - start:.1f} s)", flush=True)
    fea_both = dict(fea_columns, **{"ram_anvil_force [N]": resultant})
    damping = cfg.anvil.ram_contact_damping
    face, face_annuli = [list(range(PATCHES))], [[k] for k in range(PATCHES)]
    closed = {"closed: rings 1 (the ROM's ports)": (rings[1], face, None, None, damping),
              "closed: rings 6 + head rotation": (rings[6], face, rotation, None, damping),
              "closed: + wall's local flexibility": (rings[6], face, rotation, local, damping),
              "closed: + ram face in 6 annuli": (rings[6], face_annuli, rotation, local,
                                                 damping),
              "closed: the same, no ram contact dashpot": (rings[6], face_annuli, rotation,
                                                           local, 0.0)}
    for segment in CLOSED_SEGMENTS:
        for name, (groups, ram_groups, rot, loc, c) in closed.items():
            start = time.perf_counter()
            out, dt = run_closed_loop(anvil, ram, groups, ram_groups, cfg.impact_velocity, c,
                                      cfg.duration, pile, rot, loc, segment,
                                      STEP * segment / SEGMENT, cfg.gravity)
            t = np.arange(out.shape[0]) * dt
            columns = {"time [s]": t, "anvil_pile_force [N]": out[:, 0],
                       "ram_anvil_force [N]": out[:, 1]}
            run = ModelRun(name, columns, time.perf_counter() - start, {})
            rows[f"{name}, {segment:g} m"] = _row(run, fea, fea_columns, t_fea) | {
                "peak_ram_force_error_5kHz [-]": float(
                    band_limited(columns, "ram_anvil_force [N]", t_fea, BAND).max()
                    / band_limited(fea_both, "ram_anvil_force [N]", t_fea, BAND).max() - 1.0)}
            print(f"{name}, {segment:g} m done ({run.wall_time:.1f} s)", flush=True)
    # the FEA's own pile (its mesh, its penalty contacts) as a ring kernel under the ROM
    config = fea_config(cfg)
    wall_elements = config.pile_wall_elements
    start = time.perf_counter()
    kernel = ring_kernel(config.material, r_in, r_out, config.modelled_pile_length, STEP,
                         int(round(cfg.duration / STEP)) + 1, wall_elements,
                         config.pile_axial_size or config.mesh_size)
    groups = rings[wall_elements]
    contact = tube_contact_stiffness(config.material.youngs_modulus, r_out - r_in,
                                     [anvil.areas[g].sum() for g in groups])
    print(f"the FEA's pile as a {wall_elements}-ring kernel ({time.perf_counter() - start:.1f} s)",
          flush=True)
    fe_pile = {f"closed: the FEA's pile ({wall_elements} rings), one ram port": (face, damping),
               f"closed: the FEA's pile ({wall_elements} rings), ram face in 6 annuli": (
                   face_annuli, damping),
               f"closed: the FEA's pile ({wall_elements} rings), ram face in 2 halves": (
                   [[0, 1, 2], [3, 4, 5]], damping),
               f"closed: the FEA's pile ({wall_elements} rings), ram face as disc + rim": (
                   [[0, 1, 2, 3, 4], [5]], damping),
               f"closed: the FEA's pile ({wall_elements} rings), 6 annuli, no dashpot": (
                   face_annuli, 0.0)}
    for name, (ram_groups, c) in fe_pile.items():
        start = time.perf_counter()
        out, dt = run_closed_loop(anvil, ram, groups, ram_groups, cfg.impact_velocity, c,
                                  cfg.duration, pile, gravity=cfg.gravity, kernel=kernel,
                                  contact=contact)
        t = np.arange(out.shape[0]) * dt
        columns = {"time [s]": t, "anvil_pile_force [N]": out[:, 0],
                   "ram_anvil_force [N]": out[:, 1]}
        run = ModelRun(name, columns, time.perf_counter() - start, {})
        rows[name] = _row(run, fea, fea_columns, t_fea) | {
            "peak_ram_force_error_5kHz [-]": float(
                band_limited(columns, "ram_anvil_force [N]", t_fea, BAND).max()
                / band_limited(fea_both, "ram_anvil_force [N]", t_fea, BAND).max() - 1.0)}
        print(f"{name} done ({run.wall_time:.1f} s)", flush=True)
    (out / "study.json").write_text(json.dumps(rows, indent=2) + "\n")
    first = next(iter(rows.values()))
    shown = [i for i, c in enumerate(first["band_centre_frequency [Hz]"]) if 950 < c < 4500]
    print("\nband level deviation from the FEA [dB] (the FEA's ram force drives every variant "
          "but the closed-loop ones)")
    print(f"{'variant':52s} " + " ".join(
        f"{first['band_centre_frequency [Hz]'][i]:6.0f}" for i in shown)
        + f" {'max<=1.26k':>10s} {'max<=4k':>8s} {'peak 5k':>8s}")
    for name, row in rows.items():
        print(f"{name:52s} " + " ".join(
            f"{row['deviation_from_fea [dB]'][i]:+6.1f}" for i in shown)
            + f" {row['max_deviation_to_1259_Hz [dB]']:10.1f} "
              f"{row['max_deviation_to_3981_Hz [dB]']:8.1f} "
              f"{row['peak_pile_force_error_5kHz [-]']:+8.3f}")
    return rows


if __name__ == "__main__":
    main()
