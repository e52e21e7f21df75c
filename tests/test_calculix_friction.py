"""Coulomb friction in the reference FEA (anvilwave.fea) against CalculiX on a small
axisymmetric contact case: a soft cylinder (E 70 GPa, nu 0.35) pressed onto a steel one of
the same radius (E 210 GPa, nu 0.3) by equal and opposite pressures on their free ends. Free
of friction each is in uniaxial stress, u_r = nu p r / E (the soft one expands 3.5 x more);
friction on the interface holds the two back towards each other, with a stick zone about the
axis and slip towards the rim.

CalculiX (ccx 2.20): CAX8 elements, *CONTACT PAIR surface to surface, linear
pressure-overclosure penalty and *FRICTION with the same penalty as stick slope, *STATIC. The
FEA: the same vertex grid of 9-node quadrilaterals, node-to-node pairs with
:func:`anvilwave.anvil_rom.contact.coulomb_friction`, brought to rest by the explicit
integrator with a mass-proportional damping c = 2 m / h (each step then moves u by
h^2 / (2 m) times the residual: a monotone relaxation to the static state under the constant
load, so the slip never reverses on the way). Skipped without ``ccx`` (CI installs it).
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from anvilwave.anvil_rom.fem.calculix import read_frd, run_ccx
from anvilwave.anvil_rom.fem.geometry import Material
from anvilwave.fea.bodies import contact_between, face, tensor_body
from anvilwave.fea.impact import _global, _place
from anvilwave.fea.solver import (
    CONTACT_PHASE_LIMIT,
    ExplicitSystem,
    contact_pair_frequency,
    integrate,
    stable_time_step,
)

needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not installed")

RADIUS = HEIGHT = 0.1  # each cylinder [m]
ELEMENTS = 8  # across the radius and along each height
SOFT = Material(70e9, 0.35, 2700.0)
STEEL = Material(210e9, 0.3, 7850.0)
PRESSURE = 50e6  # [Pa]
MU = 0.2
PENALTY = STEEL.youngs_modulus / (HEIGHT / ELEMENTS)  # alpha E / h, alpha = 1 [N/m^3]


def _ccx_cylinder(z0: float, first_node: int, first_element: int):
    """CAX8 grid of one cylinder: {(i, j): node id} on the 9-node lattice without centres,
    nodes (id, r, z) and elements (id, j, 8 node ids counter-clockwise in x = r, y = -z)."""
    r = np.linspace(0.0, RADIUS, 2 * ELEMENTS + 1)
    z = np.linspace(z0, z0 + HEIGHT, 2 * ELEMENTS + 1)
    ids, nodes = {}, []
    for j, zz in enumerate(z):
        for i, rr in enumerate(r):
            if i % 2 and j % 2:
                continue
            ids[(i, j)] = first_node + len(nodes) + 1
            nodes.append((ids[(i, j)], rr, zz))
    elements = []
    for j in range(ELEMENTS):
        for i in range(ELEMENTS):
            a, b = 2 * i, 2 * j
            corners = [ids[(a, b + 2)], ids[(a + 2, b + 2)], ids[(a + 2, b)], ids[(a, b)],
                       ids[(a + 1, b + 2)], ids[(a + 2, b + 1)], ids[(a + 1, b)],
                       ids[(a, b + 1)]]
            elements.append((first_element + len(elements) + 1, j, corners))
    return ids, nodes, elements


def _ccx_deck(path, friction: float):
    """The two cylinders as a CalculiX deck; returns the node ids of the interface nodes of
    the soft and of the steel cylinder, sorted by radius, and all nodes (id, r, z)."""
    up_ids, up_nodes, up_el = _ccx_cylinder(0.0, 0, 0)
    lo_ids, lo_nodes, lo_el = _ccx_cylinder(HEIGHT, len(up_nodes), len(up_el))
    nodes = up_nodes + lo_nodes
    axis = [n for n, r, _ in nodes if r == 0.0]
    lines = ["*HEADING", "anvilwave friction cross-check", "*NODE, NSET=NALL"]
    lines += [f"{n}, {r:.12e}, {-z + 0.0:.12e}" for n, r, z in nodes]
    for name, elements in (("ESOFT", up_el), ("ESTEEL", lo_el)):
        lines.append(f"*ELEMENT, TYPE=CAX8, ELSET={name}")
        lines += [f"{e}, " + ", ".join(map(str, c)) for e, _, c in elements]
    lines.append("*NSET, NSET=NAXIS")
    lines += [", ".join(map(str, axis[k:k + 8])) for k in range(0, len(axis), 8)]
    # the loads balance: one axial support on the axis at the steel's far end fixes the
    # rigid motion
    lines += ["*BOUNDARY", "NAXIS, 1, 1", f"{lo_ids[(0, 2 * ELEMENTS)]}, 2, 2"]
    # face S1 of these elements is their z-max edge, S3 their z-min edge
    lines.append("*SURFACE, NAME=SSOFT, TYPE=ELEMENT")
    lines += [f"{e}, S1" for e, j, _ in up_el if j == ELEMENTS - 1]
    lines.append("*SURFACE, NAME=SSTEEL, TYPE=ELEMENT")
    lines += [f"{e}, S3" for e, j, _ in lo_el if j == 0]
    for name, mat in (("SOFT", SOFT), ("STEEL", STEEL)):
        lines += [f"*MATERIAL, NAME={name}", "*ELASTIC",
                  f"{mat.youngs_modulus:.6e}, {mat.poisson_ratio}", "*DENSITY",
                  f"{mat.density}"]
    lines += ["*SOLID SECTION, ELSET=ESOFT, MATERIAL=SOFT",
              "*SOLID SECTION, ELSET=ESTEEL, MATERIAL=STEEL",
              "*SURFACE INTERACTION, NAME=SEAT",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{PENALTY:.6e}"]
    if friction > 0.0:  # ccx refuses a zero coefficient: no card is no friction
        lines += ["*FRICTION", f"{friction}, {PENALTY:.6e}"]
    lines += ["*CONTACT PAIR, INTERACTION=SEAT, TYPE=SURFACE TO SURFACE", "SSTEEL, SSOFT",
              "*STEP, INC=200", "*STATIC", "0.05, 1.0, 1e-6, 0.05", "*DLOAD"]
    lines += [f"{e}, P3, {PRESSURE:.6e}" for e, j, _ in up_el if j == 0]
    lines += [f"{e}, P1, {PRESSURE:.6e}" for e, j, _ in lo_el if j == ELEMENTS - 1]
    lines += ["*NODE FILE", "U", "*END STEP"]
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    interface = [[ids[(i, j)] for i in range(2 * ELEMENTS + 1)]
                 for ids, j in ((up_ids, 2 * ELEMENTS), (lo_ids, 0))]
    return interface, nodes


def _ccx_interface(tmp_path, friction):
    """Radial displacement of the soft and the steel interface nodes by CalculiX [m]."""
    (soft, steel), nodes = _ccx_deck(tmp_path / "seat.inp", friction)
    frd, _ = run_ccx(tmp_path / "seat.inp")
    result = read_frd(frd)
    coords = np.array([(r, z) for _, r, z in nodes])
    assert np.allclose(result.points, coords)  # .frd nodes in id order
    u = result.displacements[-1]
    return u[np.array(soft) - 1, 0], u[np.array(steel) - 1, 0]


def _fea_interface(friction, steps=40000):
    """Radial displacement of the two interface faces' nodes at rest by the FEA [m], and the
    node radii [m]."""
    grid = np.linspace(0.0, RADIUS, ELEMENTS + 1)
    soft = tensor_body("soft", grid, np.linspace(0.0, HEIGHT, ELEMENTS + 1), SOFT)
    steel = tensor_body("steel", grid, np.linspace(HEIGHT, 2 * HEIGHT, ELEMENTS + 1), STEEL)
    n = _place([soft, steel])
    K, M = _global([soft, steel])
    top, seat_soft = face(soft, 0.0), face(soft, HEIGHT)
    seat_steel, bottom = face(steel, HEIGHT), face(steel, 2 * HEIGHT)
    contact = contact_between("seat", seat_soft, seat_steel, PENALTY,
                              friction_coefficient=friction)
    f = np.zeros(n)
    f[top.axial_dofs] += PRESSURE * top.weights
    f[bottom.axial_dofs] -= PRESSURE * bottom.weights
    probes = {}
    for name, side in (("soft", seat_soft), ("steel", seat_steel)):
        for k, dof in enumerate(side.radial_dofs):
            if dof >= 0:
                probes[f"{name}{k}"] = np.eye(1, n, dof).ravel()
    zero = np.zeros(n)
    system = ExplicitSystem(K, M, zero, f, [contact], zero, zero, force_probes=probes)
    h = min(0.9 * stable_time_step(system)[0], CONTACT_PHASE_LIMIT / contact_pair_frequency(
        system))
    system.damping = 2.0 / h * M
    out = integrate(system, steps * h, steps * h / 4, time_step=h).probes
    radii = seat_soft.radii
    result = [np.array([out[f"{name}{k}"][-1] if f"{name}{k}" in out else 0.0
                        for k in range(len(radii))]) for name in ("soft", "steel")]
    change = max(abs(out[f"{name}{len(radii) - 1}"][-1] - out[f"{name}{len(radii) - 1}"][-2])
                 for name in ("soft", "steel"))
    return radii, result[0], result[1], change


def test_fea_relaxation_without_friction_is_the_uniaxial_state():
    """The relaxation itself is exact: friction off, each cylinder takes u_r = nu p r / E
    at its interface (measured within 2e-6)."""
    radii, soft, steel, _ = _fea_interface(0.0)
    for u, mat in ((soft, SOFT), (steel, STEEL)):
        exact = mat.poisson_ratio * PRESSURE * radii / mat.youngs_modulus
        assert np.abs(u - exact).max() < 1e-5 * exact.max()


@needs_ccx
def test_friction_against_calculix(tmp_path):
    radii, soft, steel, change = _fea_interface(MU)
    ccx_soft, ccx_steel = _ccx_interface(tmp_path, MU)
    free_soft = SOFT.poisson_ratio * PRESSURE * RADIUS / SOFT.youngs_modulus
    free_steel = STEEL.poisson_ratio * PRESSURE * RADIUS / STEEL.youngs_modulus
    assert change < 1e-3 * soft[-1]  # the relaxation has come to rest
    # friction holds both rims far from their free expansion, in both codes (0.54 x and
    # 1.75 x free, measured)
    for u_soft, u_steel in ((soft, steel), (ccx_soft, ccx_steel)):
        assert u_soft[-1] < 0.6 * free_soft and u_steel[-1] > 1.6 * free_steel
    # the rims agree within 1 % (measured 0.2 % soft, 0.5 % steel); the whole interface
    # profile within 7 % of the rim value (measured 5.5 %, near the axis): CalculiX's
    # surface-to-surface contact is itself off the exact frictionless state by up to 1.1 %
    # of the rim value there (4.5 % locally at r = 0.025 m), and the two discretise the stick
    # zone differently (mortar faces against node pairs). On a 16 x 16 grid per cylinder the
    # profile differences halve (2.7 % soft, 2.1 % steel): they are discretisation.
    assert soft[-1] == pytest.approx(ccx_soft[-1], rel=0.01)
    assert steel[-1] == pytest.approx(ccx_steel[-1], rel=0.01)
    assert np.abs(soft - ccx_soft).max() < 0.07 * soft[-1]
    assert np.abs(steel - ccx_steel).max() < 0.07 * soft[-1]
    # the rim slip, a small difference of the two (7 % of the soft rim's u_r), outward in
    # both and within 15 % (measured 9.7 %)
    slip, ccx_slip = soft[-1] - steel[-1], ccx_soft[-1] - ccx_steel[-1]
    assert slip > 0.0 and ccx_slip > 0.0
    assert slip == pytest.approx(ccx_slip, rel=0.15)
