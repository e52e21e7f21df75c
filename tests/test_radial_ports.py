"""The radial participation of the modes at the ports (the optional radial keys of the modal
file): a uniform radial traction's vector, its static flexibility against the closed-form
uniaxial state of a free cylinder, the participations against an independent dense
eigensolution, the modal sum against the flexibility, and the keys' checks on loading."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import scipy.linalg

from anvilwave.anvil_rom.fem.elasticity import (
    annulus_vectors,
    assemble,
    interface_vectors,
    radial_interface_vectors,
)
from anvilwave.anvil_rom.fem.geometry import STEEL, AnvilSpec, Interfaces
from anvilwave.anvil_rom.fem.mesh import mesh_outline, split_outline_at_interfaces, to_skfem
from anvilwave.anvil_rom.fem.modalfile import load_modal_data, save_modal_data
from anvilwave.anvil_rom.fem.modes import free_free_modes
from anvilwave.anvil_rom.fem.pipeline import modal_data_from_modes
from anvilwave.inputs import InputError

RADIUS, LENGTH = 0.5, 1.0  # a free steel cylinder [m]
# the ram face and the pile ring both cover a whole end face
PORTS = Interfaces(ram_contact_radius=RADIUS, pile_contact_radius=0.5 * RADIUS,
                   pile_contact_width=RADIUS)
FMAX = 6000.0  # [Hz] the first 9 flexible modes of the cylinder (L/D = 1)


@pytest.fixture(scope="module")
def cylinder():
    outline = np.array([[0.0, 0.0], [RADIUS, 0.0], [RADIUS, LENGTH], [0.0, LENGTH]])
    outline = split_outline_at_interfaces(outline, PORTS)
    model = assemble(to_skfem(mesh_outline(outline, 0.125)), STEEL)
    spec = AnvilSpec(name="cylinder", material=STEEL, outline=outline, interfaces=PORTS,
                     mesh_size=0.125)
    modes = free_free_modes(model, FMAX)
    b_ram, b_pile, a_ram, a_pile = interface_vectors(model, PORTS)
    data = modal_data_from_modes(spec, model, modes, b_ram, b_pile, (a_ram, a_pile),
                                 radial=True)
    return model, modes, data


def test_radial_vector_is_the_mean_radial_displacement(cylinder):
    model = cylinder[0]
    c_ram, c_pile = radial_interface_vectors(model, PORTS)
    # u_r = a r: the mean over a disc of radius R is a (2 R / 3) (area weights 2 pi r dr)
    xy = model.node_coordinates
    u = np.zeros(model.basis.N)
    u[model.node_dofs[:, 0]] = 1e-3 * xy[:, 0]
    u = u[model.free_dofs]
    assert c_ram @ u == pytest.approx(1e-3 * 2.0 * RADIUS / 3.0, rel=1e-12)
    assert c_pile @ u == pytest.approx(1e-3 * 2.0 * RADIUS / 3.0, rel=1e-12)
    # radial only: no axial resultant (a self-balanced load)
    assert np.abs(c_ram @ model.axial_free) < 1e-15


def test_radial_annuli_are_the_mean_radial_displacement_of_each_annulus(cylinder):
    """annulus_vectors(radial=True), the seat rings' radial ports of the ROM stack: under
    u_r = a r each annulus reads its own area-weighted mean of a r, (2 / 3) a (r2^3 - r1^3) /
    (r2^2 - r1^2), and their area-weighted sum is the whole face's radial vector."""
    model = cylinder[0]
    C, areas = annulus_vectors(model, 0.0, 0.0, RADIUS, 4, radial=True)
    xy = model.node_coordinates
    u = np.zeros(model.basis.N)
    u[model.node_dofs[:, 0]] = 1e-3 * xy[:, 0]
    u = u[model.free_dofs]
    edges = np.linspace(0.0, RADIUS, 5)
    r1, r2 = edges[:-1], edges[1:]
    mean = 1e-3 * 2.0 / 3.0 * (r2**3 - r1**3) / (r2**2 - r1**2)
    assert C.T @ u == pytest.approx(mean, rel=1e-12)
    assert areas == pytest.approx(np.pi * (r2**2 - r1**2), rel=1e-12)
    whole = radial_interface_vectors(model, PORTS)[0]
    assert np.abs(C @ areas / areas.sum() - whole).max() < 1e-12 * np.abs(whole).max()


def test_static_radial_displacement_under_a_self_balanced_load(cylinder):
    """Unit forces pressing the two end faces together: uniaxial stress 1 / A, so
    u_r = nu r / (E A) and the mean over an end face 2 nu R / (3 E A), exactly representable
    by the quadratic elements (measured to 2e-14)."""
    G = cylinder[2].radial_flexibility
    area = np.pi * RADIUS**2
    exact = 2.0 * STEEL.poisson_ratio * RADIUS / (3.0 * STEEL.youngs_modulus * area)
    for radial in (2, 3):  # ram face, pile ring
        assert G[radial, 0] - G[radial, 1] == pytest.approx(exact, rel=1e-8)
    # and the axial block is the file's axial flexibility
    assert np.array_equal(G[:2, :2], cylinder[2].elastic_flexibility)


def test_participations_and_modal_sum_against_a_dense_eigensolution(cylinder):
    """scipy's dense generalised eigensolver on the same K, M: the stored radial
    participations are the projections of its modes (to sign), and its complete modal sum
    sum (c^T phi)(f^T phi) / omega^2 is the stored flexibility (the modes + static correction
    of a truncated ROM give the full static response; measured to 5e-14). The 9 flexible
    modes up to fmax alone overshoot the static radial displacement by 0.18 %, the part the
    static correction supplies."""
    model, modes, data = cylinder
    lam, phi = scipy.linalg.eigh(model.stiffness.toarray(), model.mass.toarray())
    c_ram, c_pile = radial_interface_vectors(model, PORTS)
    b_ram, b_pile = interface_vectors(model, PORTS)[:2]
    ports = np.column_stack([b_ram, b_pile, c_ram, c_pile])
    P = ports.T @ phi[:, 1:]  # the flexible modes (lam[0]: the rigid mode, ~0)
    full = (P / lam[1:]) @ P.T
    G = data.radial_flexibility
    assert np.abs(full - G).max() < 1e-6 * np.abs(G).max()
    n = data.n_modes
    stored = np.vstack([data.participation_ram_radial, data.participation_pile_radial])
    assert np.allclose(np.abs(stored[:, 1:]), np.abs(P[2:, :n - 1]),
                       rtol=1e-6, atol=1e-9 * np.abs(P[2:]).max())
    assert np.all(stored[:, 0] == 0.0)  # the axial rigid mode has no radial motion
    retained = (P[:, :n - 1] / lam[1:n]) @ P[:, :n - 1].T
    f = np.array([1.0, -1.0])  # the self-balanced pair of the previous test
    static = (G[2:, :2] @ f)
    truncated = (retained[2:, :2] @ f)
    assert np.all(np.abs(truncated - static) > 5e-4 * np.abs(static))


def test_radial_keys_round_trip_and_are_checked(cylinder, tmp_path):
    data = cylinder[2]
    path = save_modal_data(data, tmp_path / "modes.npz")
    back = load_modal_data(path)
    assert np.array_equal(back.radial_flexibility, data.radial_flexibility)
    assert np.array_equal(back.participation_pile_radial, data.participation_pile_radial)
    with pytest.raises(InputError, match="radial_flexibility"):
        dataclasses.replace(data, radial_flexibility=None)
    bad = data.radial_flexibility.copy()
    bad[0, 0] *= 1.01
    with pytest.raises(InputError, match="axial block"):
        dataclasses.replace(data, radial_flexibility=bad)
    rigid = data.participation_ram_radial.copy()
    rigid[0] = 1e-3
    with pytest.raises(InputError, match="rigid-body"):
        dataclasses.replace(data, participation_ram_radial=rigid)
    # a file without the radial keys still loads (they are optional)
    plain = dataclasses.replace(data, participation_ram_radial=None,
                                participation_pile_radial=None, radial_flexibility=None)
    assert load_modal_data(save_modal_data(plain, tmp_path / "plain.npz")).radial_flexibility \
        is None
