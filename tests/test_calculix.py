"""CalculiX interface: deck writer, ccx run, .frd/.dat readers, and CalculiX modes compared
with anvilwave's own FE modes and with the reference table of free-free cylinders
(shared reference: CalculiX CAX8 40x80 and a 3D Ritz solution, agreeing to 0.01 Hz).

Tests that need the ``ccx`` executable are skipped only when it is not installed (CI installs
the Debian package calculix-ccx, so they run there).
"""

from __future__ import annotations

import shutil

import meshio
import numpy as np
import pytest

from anvilwave.anvil_rom.fem import calculix
from anvilwave.anvil_rom.fem.calculix import (
    CalculixError,
    modes_from_calculix,
    read_dat_frequencies,
    read_frd,
    run_ccx,
    write_ccx_deck,
    write_ccx_deck_from_mesh,
)
from anvilwave.anvil_rom.fem.elasticity import assemble, interface_vectors
from anvilwave.anvil_rom.fem.geometry import STEEL, Interfaces
from anvilwave.anvil_rom.fem.mesh import mesh_outline, split_outline_at_interfaces, to_skfem
from anvilwave.anvil_rom.fem.modes import free_free_modes
from anvilwave.inputs import InputError

needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) not installed")

INTERFACES = Interfaces(ram_contact_radius=0.3, pile_contact_radius=0.35, pile_contact_width=0.1)
CYLINDER = np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]])  # D = 1 m, L/D = 1
# /work/shared/reference/free-free-solid-cylinders.md, L/D = 1, modes 2..12 [Hz]
REFERENCE = np.array([2375.22, 2932.17, 3131.64, 3615.79, 4073.18, 4806.16, 4998.99, 5596.35,
                      5710.26, 6356.56, 6761.17])
N_FLEX = 10  # the issue asks for the first 10 flexible modes


@pytest.fixture(scope="module")
def mesh() -> meshio.Mesh:
    return mesh_outline(split_outline_at_interfaces(CYLINDER, INTERFACES), 0.05)


@pytest.fixture(scope="module")
def ccx_run(mesh, tmp_path_factory):
    """Deck for 13 modes (rigid + 12 flexible: 2 spare above the 11 reference modes), run."""
    work = tmp_path_factory.mktemp("ccx")
    deck = write_ccx_deck_from_mesh(work / "cylinder.inp", mesh, STEEL, 13, "cylinder L/D=1")
    frd, dat = run_ccx(deck)
    return deck, frd, dat


@pytest.fixture(scope="module")
def compared(ccx_run):
    """CalculiX modes on anvilwave's model of the .frd mesh, and anvilwave's modes of it."""
    _, frd, dat = ccx_run
    result = modes_from_calculix(frd, dat, STEEL)
    ours = free_free_modes(result.model, fmax=7000.0)
    return result, ours


# ---------------------------------------------------------------------------- deck
def _deck_elements(text: str) -> tuple[dict[int, tuple[float, float]], list[list[int]]]:
    nodes, elements, section = {}, [], None
    for line in text.splitlines():
        if line.startswith("*"):
            section = line.split(",")[0].upper()
            continue
        fields = [f.strip() for f in line.split(",")]
        if section == "*NODE":
            nodes[int(fields[0])] = (float(fields[1]), float(fields[2]))
        elif section == "*ELEMENT":
            elements.append([int(f) for f in fields[1:]])
    return nodes, elements


def test_deck_orientation_axis_and_no_supports(mesh, tmp_path):
    deck = write_ccx_deck_from_mesh(tmp_path / "d.inp", mesh, STEEL, 5)
    text = deck.read_text()
    nodes, elements = _deck_elements(text)
    xy = np.array([nodes[k] for k in sorted(nodes)])
    # x = r, y = -z
    np.testing.assert_allclose(xy, np.column_stack([mesh.points[:, 0], -mesh.points[:, 1]]),
                               rtol=0, atol=1e-12)
    # ccx needs counter-clockwise corners in (x, y): every element area positive
    corners = np.array(elements)[:, :3] - 1
    x, y = xy[corners, 0], xy[corners, 1]
    area = 0.5 * ((x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0])
                  - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0]))
    assert np.all(area > 0.0)
    assert "TYPE=CAX6" in text
    # the only boundary condition is u_r = 0 of the axis nodes (free-free body)
    assert text.count("*BOUNDARY") == 1 and "NAXIS, 1, 1" in text
    axis_block = text.split("*NSET, NSET=NAXIS\n")[1].split("*")[0]
    axis = sorted(int(v) for v in axis_block.replace("\n", ",").split(",") if v.strip())
    assert axis == sorted(int(i) + 1 for i in np.flatnonzero(mesh.points[:, 0] == 0.0))


def test_deck_rejects_bad_input(tmp_path):
    pts = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]])
    with pytest.raises(ValueError, match="not supported"):
        write_ccx_deck(tmp_path / "a.inp", pts, [[0, 1, 2]], "triangle", STEEL, 3)
    with pytest.raises(ValueError, match=">= 0"):
        write_ccx_deck(tmp_path / "a.inp", pts * [-1.0, 1.0], [[0, 1, 2, 3, 4, 5]], "triangle6",
                       STEEL, 3)


# ---------------------------------------------------------------------------- run + read
@needs_ccx
def test_frd_is_the_2d_mesh_in_our_convention(mesh, ccx_run):
    _, frd, dat = ccx_run
    res = read_frd(frd)
    assert res.cell_type == "triangle6"
    # same nodes in the same order; .frd coordinates have 6 significant digits (E12.5)
    np.testing.assert_allclose(res.points, mesh.points[:, :2], rtol=0, atol=5e-6)
    np.testing.assert_array_equal(np.sort(res.cells, axis=1), np.sort(mesh.cells[0].data, axis=1))
    assert res.displacements.shape == (13, len(mesh.points), 2)
    # mode 1 is the axial rigid-body translation (uniform u_z, no u_r)
    rigid = res.displacements[0]
    assert np.ptp(rigid[:, 1]) < 1e-5 * np.abs(rigid[:, 1]).max()
    assert np.abs(rigid[:, 0]).max() < 1e-5 * np.abs(rigid[:, 1]).max()
    # the axis constraint holds: no radial motion on the axis in any mode
    axis = res.points[:, 0] == 0.0
    assert np.all(res.displacements[:, axis, 0] == 0.0)
    freqs = read_dat_frequencies(dat)
    assert freqs.shape == (13,) and abs(freqs[0]) < 1.0 and np.all(np.diff(freqs) > 0)


@needs_ccx
def test_frequencies_match_builtin_fe_and_reference(compared):
    result, ours = compared
    f_ccx = result.modes.frequencies
    f_ours = ours.frequencies
    assert f_ccx[0] == 0.0 and f_ours[0] == 0.0
    rel = f_ccx[1:N_FLEX + 1] / f_ours[1:N_FLEX + 1] - 1.0
    # (a) the requirement: the external code agrees with the built-in FE within 0.5 %
    assert np.abs(rel).max() < 5e-3, rel
    # Same mesh and the same quadratic element space: only the quadrature (ccx integrates the
    # expanded 15-node wedge, anvilwave uses order-4 triangle rules) and 6-digit .frd rounding
    # differ. Measured 5e-5 at most; 2e-4 leaves a factor 4.
    assert np.abs(rel).max() < 2e-4, rel
    # (b) reference table (converged to 0.01 Hz = 2e-6). What is left is the discretisation
    # error of h = 0.05 m P2 elements, ~(k h)^4 with k the shear wave number: it grows to 2.6e-4
    # at the 11th flexible mode (6.76 kHz, ~10 elements per shear wavelength) and is below
    # 2e-5 up to 4 kHz. 1e-3 leaves a factor 4 and still separates every neighbouring pair of
    # modes (their spacing is >= 2 %), so a missing or swapped mode would fail.
    n = len(REFERENCE)
    for f in (f_ccx, f_ours):
        err = f[1:n + 1] / REFERENCE - 1.0
        assert np.abs(err).max() < 1e-3, err


@needs_ccx
def test_interface_participations_match_builtin_fe(compared):
    result, ours = compared
    model = result.model
    b_ram, b_pile, _, _ = interface_vectors(model, INTERFACES)
    B = np.column_stack([b_ram, b_pile])
    n = N_FLEX + 1
    phi_c, phi_o = result.modes.shapes[:, :n], ours.shapes[:, :n]
    # one sign per mode, from the modal assurance between the two shapes
    cross = np.einsum("ij,ij->j", phi_c, model.mass @ phi_o)
    assert np.all(np.abs(cross) > 0.999)  # same modes in the same order
    p_ccx, p_ours = B.T @ phi_c, B.T @ (phi_o * np.sign(cross))
    # Participations of mass-normalised modes scale with 1/sqrt(m) (the rigid mode's exactly).
    # The codes' shapes differ by the discretisation difference (frequencies ~5e-5, shapes
    # amplified by 1/relative gap to the next mode, >= 2 %), the 6-digit .frd rounding and the
    # 1.5e-4 thickness-average bias of ccx's 2D u_r output. Measured at most 4e-4 / sqrt(m);
    # 2e-3 / sqrt(m) (a factor 5) is still far below what would change the ROM's response.
    scale = 1.0 / np.sqrt(model.total_mass())
    np.testing.assert_allclose(p_ccx[:, 0], scale, rtol=1e-12)
    assert np.abs(p_ccx - p_ours).max() < 2e-3 * scale, (p_ccx - p_ours) / scale


@needs_ccx
def test_modeset_usable_like_free_free_modes(compared, ccx_run):
    result, ours = compared
    model, modes = result.model, result.modes
    assert modes.shapes.shape == (model.n_dof, modes.n_modes)
    gram = modes.shapes.T @ (model.mass @ modes.shapes)
    # normalised with our mass matrix: diagonal 1 to round-off; off-diagonal terms only from
    # the codes' different mass quadrature and .frd rounding (measured ~1e-5)
    np.testing.assert_allclose(np.diag(gram), 1.0, rtol=0, atol=1e-12)
    assert np.abs(gram - np.eye(modes.n_modes)).max() < 1e-4
    # the rigid mode is the exact axial translation, as in free_free_modes
    np.testing.assert_allclose(modes.shapes[:, 0], ours.shapes[:, 0], rtol=0, atol=1e-15)
    assert abs(modes.rigid_frequency_computed) < 1.0  # [Hz], ccx's rigid eigenvalue ~ 0
    # with fmax, the same modes as free_free_modes, proven complete by the same Sturm count
    _, frd, dat = ccx_run
    limited = modes_from_calculix(frd, dat, STEEL, fmax=5000.0).modes
    reference = free_free_modes(model, fmax=5000.0)
    assert limited.sturm_count == reference.sturm_count == limited.n_modes
    assert limited.fmax == 5000.0


@needs_ccx
def test_expanded_3d_output_maps_back_to_2d(mesh, ccx_run, tmp_path):
    deck2d, frd2d, _ = ccx_run
    deck = write_ccx_deck_from_mesh(tmp_path / "expanded.inp", mesh, STEEL, 4,
                                    expanded_output=True)
    frd3d, _ = run_ccx(deck)
    two, three = read_frd(frd2d), read_frd(frd3d)
    assert three.cell_type == "triangle6" and len(three.points) == len(two.points)
    # nodes are renumbered in the 3D file: match by position (rounding 5e-6 m)
    order = np.array([np.argmin(np.linalg.norm(three.points - p, axis=1)) for p in two.points])
    np.testing.assert_allclose(three.points[order], two.points, rtol=0, atol=5e-6)
    np.testing.assert_array_equal(np.sort(np.sort(order[two.cells], axis=1), axis=0),
                                  np.sort(np.sort(three.cells, axis=1), axis=0))
    u2, u3 = two.displacements, three.displacements[:4, order]
    peak = np.abs(u2).max()
    # u_z is exact in both outputs (6-digit rounding); the 2D u_r is ccx's thickness average,
    # low by up to 1 - cos(1 deg) = 1.5e-4, so u_r agrees to 2e-4 of the peak
    assert np.abs(u3[..., 1] - u2[:4, :, 1]).max() < 2e-5 * peak
    assert np.abs(u3[..., 0] - u2[:4, :, 0]).max() < 2e-4 * peak


def _quad9_cylinder(nr: int, nz: int) -> meshio.Mesh:
    r, z = np.linspace(0.0, 0.5, 2 * nr + 1), np.linspace(0.0, 1.0, 2 * nz + 1)
    idx = np.arange(len(r) * len(z)).reshape(len(r), len(z))
    points = np.array([[ri, zj] for ri in r for zj in z])
    cells = [[idx[a, b], idx[a + 2, b], idx[a + 2, b + 2], idx[a, b + 2], idx[a + 1, b],
              idx[a + 2, b + 1], idx[a + 1, b + 2], idx[a, b + 1], idx[a + 1, b + 1]]
             for a in range(0, 2 * nr, 2) for b in range(0, 2 * nz, 2)]
    return meshio.Mesh(points, [("quad9", np.array(cells))])


@needs_ccx
def test_cax8_quadrilaterals(tmp_path):
    mesh = _quad9_cylinder(5, 10)
    deck = write_ccx_deck_from_mesh(tmp_path / "quad.inp", mesh, STEEL, 6)
    assert "TYPE=CAX8" in deck.read_text()
    frd, dat = run_ccx(deck, tmp_path / "work")
    assert read_frd(frd).cell_type == "quad8"
    result = modes_from_calculix(frd, dat, STEEL)
    ours = free_free_modes(assemble(to_skfem(mesh), STEEL), fmax=4000.0)
    # 8-node serendipity (ccx) vs 9-node Lagrange (anvilwave) on a coarse 0.1 m mesh: different
    # element spaces, so only the 0.5 % is asked (measured 2.5e-6 for these low modes).
    # modes_from_calculix has already checked the mapped shapes (centre nodes interpolated from
    # the serendipity field) for M-orthonormality (measured 1e-4) and Rayleigh quotients.
    n = ours.n_modes
    assert n >= 5
    np.testing.assert_allclose(result.modes.frequencies[1:n], ours.frequencies[1:n], rtol=5e-3)


# ---------------------------------------------------------------------------- errors
def test_missing_or_foreign_files_give_input_error(tmp_path):
    with pytest.raises(InputError, match="file not found"):
        read_frd(tmp_path / "none.frd")
    with pytest.raises(InputError, match="file not found"):
        read_dat_frequencies(tmp_path / "none.dat")
    junk = tmp_path / "junk.frd"
    junk.write_text("this is not a result file\n")
    with pytest.raises(InputError, match="no node block"):
        read_frd(junk)
    junk_dat = tmp_path / "junk.dat"
    junk_dat.write_text("nothing here\n")
    with pytest.raises(InputError, match="no eigenvalue table"):
        read_dat_frequencies(junk_dat)


@needs_ccx
def test_corrupt_frd_and_dat_give_input_error(ccx_run, tmp_path):
    _, frd, dat = ccx_run
    lines = frd.read_text().splitlines(keepends=True)
    truncated = tmp_path / "truncated.frd"
    truncated.write_text("".join(lines[: len(lines) // 2]))
    with pytest.raises(InputError) as err:
        read_frd(truncated)
    assert str(truncated) in str(err.value)
    # a damaged number inside the node block: the message names the line
    i = next(k for k, ln in enumerate(lines) if ln.startswith(" -1")) + 3
    damaged = tmp_path / "damaged.frd"
    damaged.write_text("".join(lines[:i] + [lines[i][:20] + "x.xxxxxE+00" + lines[i][31:]]
                               + lines[i + 1:]))
    with pytest.raises(InputError, match=f"line {i + 1}"):
        read_frd(damaged)
    bad_dat = tmp_path / "bad.dat"
    bad_dat.write_text(dat.read_text().replace("0.2375", "0.2x75", 1))
    with pytest.raises(InputError, match="corrupt eigenvalue table row"):
        read_dat_frequencies(bad_dat)
    # .dat of another run: frequencies do not match the .frd headers
    other = tmp_path / "other.dat"
    other.write_text(dat.read_text().replace("0.2375", "0.2475", 1))
    with pytest.raises(InputError, match="different runs"):
        modes_from_calculix(frd, other, STEEL)


@needs_ccx
def test_ccx_failure_is_reported(tmp_path):
    deck = tmp_path / "clockwise.inp"
    # one CAX6 element with clockwise nodes: ccx stops with a nonpositive Jacobian
    deck.write_text("*NODE\n1, 0, 0\n2, 0, 1\n3, 1, 0\n4, 0, 0.5\n5, 0.5, 0.5\n6, 0.5, 0\n"
                    "*ELEMENT, TYPE=CAX6, ELSET=E\n1, 1, 2, 3, 4, 5, 6\n"
                    "*MATERIAL, NAME=S\n*ELASTIC\n2e11, 0.3\n*DENSITY\n7850\n"
                    "*SOLID SECTION, ELSET=E, MATERIAL=S\n*STEP\n*FREQUENCY\n2\n"
                    "*NODE FILE\nU\n*END STEP\n")
    with pytest.raises(CalculixError, match="ccx failed"):
        run_ccx(deck)
    with pytest.raises(InputError, match="file not found"):
        run_ccx(tmp_path / "absent.inp")


def test_missing_ccx_is_reported(tmp_path, monkeypatch):
    monkeypatch.setattr(calculix.shutil, "which", lambda name: None)
    with pytest.raises(CalculixError, match="not installed"):
        run_ccx(tmp_path / "any.inp")
