"""Bad input gets one clear message; files round-trip; the CLI writes complete results."""

from __future__ import annotations

import json
import subprocess
import sys

import meshio
import numpy as np
import pytest

from anvilwave.anvil_rom.fem.geometry import load_anvil
from anvilwave.anvil_rom.fem.modalfile import load_modal_data, save_modal_data
from anvilwave.anvil_rom.fem.pipeline import compute_anvil_modes
from anvilwave.cli import main
from anvilwave.inputs import InputError

from .conftest import EXAMPLES

GOOD = """
[material]
youngs_modulus = 210e9
poisson_ratio = 0.3
density = 7850.0
[geometry]
points = [[0.0, 0.0], [0.5, 0.0], [0.5, 0.4], [0.0, 0.4]]
[interfaces]
ram_contact_radius = 0.2
pile_contact_radius = 0.4
pile_contact_width = 0.05
[mesh]
size = 0.05
"""


def write(tmp_path, text, name="anvil.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize(
    ("change", "key", "rule"),
    [
        (("density = 7850.0", "density = -1.0"), "material.density", "greater than 0"),
        (("poisson_ratio = 0.3", "poisson_ratio = 0.5"), "material.poisson_ratio", "less than"),
        (("size = 0.05", "size = 0.05\ncolour = 1"), "mesh.colour", "unknown key"),
        (("[0.5, 0.4], [0.0, 0.4]", "[0.1, 0.4], [0.5, 0.3]"), "geometry.points", "cross"),
        (("[0.0, 0.0], [0.5, 0.0]", "[-0.1, 0.0], [0.5, 0.0]"), "geometry.points", "r must be"),
        (("ram_contact_radius = 0.2", "ram_contact_radius = 0.7"),
         "interfaces.ram_contact_radius", "must not exceed"),
        (("pile_contact_radius = 0.4", "pile_contact_radius = 0.49"),
         "interfaces.pile_contact_radius", "exceeds the anvil radius"),
        (("youngs_modulus = 210e9", "youngs_modulus = \"steel\""), "material.youngs_modulus",
         "must be a number"),
        (("[mesh]\nsize = 0.05", ""), "mesh", "required"),
    ],
)
def test_bad_anvil_file_names_file_key_and_rule(tmp_path, change, key, rule):
    path = write(tmp_path, GOOD.replace(*change))
    with pytest.raises(InputError) as info:
        load_anvil(path)
    message = str(info.value)
    assert str(path) in message and key in message and rule in message, message
    assert "\n" not in message


def test_toml_syntax_error_is_reported(tmp_path):
    path = write(tmp_path, GOOD + "\n[material\n")
    with pytest.raises(InputError, match="not valid TOML"):
        load_anvil(path)


def test_cli_bad_file_one_line_no_traceback_no_output(tmp_path):
    path = write(tmp_path, GOOD.replace("density = 7850.0", "density = 0"))
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "anvilwave.cli", "modes", str(path), "--out",
                           str(out)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Traceback" not in proc.stderr
    assert proc.stderr.strip().count("\n") == 0 and "material.density" in proc.stderr
    assert not out.exists()
    assert not list(tmp_path.glob(".partial-*"))


def test_cli_modes_writes_complete_results(tmp_path):
    path = write(tmp_path, GOOD)
    out = tmp_path / "res"
    assert main(["modes", str(path), "--fmax", "9000", "--out", str(out)]) == 0
    summary = json.loads((out / "modes.json").read_text())
    for key in ("frequencies [Hz]", "total_mass [kg]", "fmax [Hz]", "n_modes", "n_dof",
                "wall_time [s]"):
        assert key in summary
    assert summary["frequencies [Hz]"][0] == 0.0
    assert summary["n_modes"] == len(summary["frequencies [Hz]"])
    assert summary["total_mass [kg]"] == pytest.approx(7850 * np.pi * 0.25 * 0.4, rel=1e-9)
    assert (out / "modes.png").stat().st_size > 10_000
    data = load_modal_data(out / "modes.npz")
    np.testing.assert_allclose(data.frequencies, summary["frequencies [Hz]"])


def test_cli_help_explains_every_option(capsys):
    with pytest.raises(SystemExit):
        main(["modes", "--help"])
    text = capsys.readouterr().out
    for option in ("--fmax", "--mesh-size", "--export-ccx", "--out", "--from-calculix"):
        assert option in text


@pytest.fixture(scope="module")
def small_modal_data():
    from anvilwave.config.cache import cached_modal_data  # the session's cache

    return cached_modal_data(load_anvil(EXAMPLES / "anvils" / "s2.toml"), 20000.0)


def test_modal_file_round_trip(tmp_path, small_modal_data):
    path = save_modal_data(small_modal_data, tmp_path / "m.npz")
    back = load_modal_data(path)
    np.testing.assert_array_equal(back.frequencies, small_modal_data.frequencies)
    np.testing.assert_array_equal(back.elastic_flexibility, small_modal_data.elastic_flexibility)
    assert back.geometry_hash == small_modal_data.geometry_hash
    assert back.total_mass == small_modal_data.total_mass


def test_modal_file_corrupt_or_foreign_is_refused(tmp_path, small_modal_data):
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"not a zip file")
    with pytest.raises(InputError, match="not a readable"):
        load_modal_data(bad)
    path = save_modal_data(small_modal_data, tmp_path / "m.npz")
    with np.load(path) as npz:
        content = dict(npz)
    content["version"] = np.array(99)
    np.savez(tmp_path / "v99.npz", **content)
    with pytest.raises(InputError, match="version 99"):
        load_modal_data(tmp_path / "v99.npz")
    content["version"] = np.array(1)
    content["frequencies"] = content["frequencies"][::-1].copy()
    np.savez(tmp_path / "desc.npz", **content)
    with pytest.raises(InputError, match="frequencies"):
        load_modal_data(tmp_path / "desc.npz")
    del content["total_mass"]
    np.savez(tmp_path / "missing.npz", **content)
    with pytest.raises(InputError, match="total_mass"):
        load_modal_data(tmp_path / "missing.npz")
    with pytest.raises(InputError, match="not found"):
        load_modal_data(tmp_path / "nope.npz")


@pytest.mark.parametrize(("suffix", "kind"), [(".msh", "gmsh22"), (".inp", "abaqus"),
                                              (".vtu", "vtu")])
def test_external_mesh_gives_same_modes(tmp_path, suffix, kind):
    """A mesh read with meshio gives the frequencies of the same mesh made in-process."""
    from anvilwave.anvil_rom.fem.mesh import mesh_outline, split_outline_at_interfaces

    spec = load_anvil(write(tmp_path, GOOD))
    mesh = mesh_outline(split_outline_at_interfaces(spec.outline, spec.interfaces), 0.05)
    points3 = np.column_stack([mesh.points, np.zeros(len(mesh.points))])
    mesh_path = tmp_path / f"anvil{suffix}"
    meshio.write(mesh_path, meshio.Mesh(points3, [("triangle6", mesh.cells[0].data)]),
                 file_format=kind)
    interfaces = "[interfaces]" + GOOD.split("[interfaces]")[1].split("[mesh]")[0]
    text = f'mesh = "{mesh_path.name}"\n' + GOOD.split("[geometry]")[0] + interfaces
    external = load_anvil(write(tmp_path, text, "external.toml"))
    a = compute_anvil_modes(spec, fmax=9000.0)
    b = compute_anvil_modes(external, fmax=9000.0)
    np.testing.assert_allclose(b.modes.frequencies, a.modes.frequencies, rtol=1e-10)
    assert b.modal_data.participation_ram[1:] ** 2 == pytest.approx(
        a.modal_data.participation_ram[1:] ** 2, rel=1e-8)


def test_linear_triangle_mesh_is_lifted_to_quadratic(tmp_path):
    """A 3-node triangle mesh is used with quadratic elements on its straight edges."""
    from anvilwave.anvil_rom.fem.mesh import mesh_outline

    mesh = mesh_outline(np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [0.0, 1.0]]), 0.05)
    tri3 = mesh.cells[0].data[:, :3]
    used, inv = np.unique(tri3, return_inverse=True)
    pts = np.column_stack([mesh.points[used], np.zeros(len(used))])
    meshio.write(tmp_path / "lin.msh", meshio.Mesh(pts, [("triangle", inv.reshape(-1, 3))]),
                 file_format="gmsh22")
    text = 'mesh = "lin.msh"\n' + GOOD.split("[geometry]")[0]
    result = compute_anvil_modes(load_anvil(write(tmp_path, text)), fmax=2400.0)
    # the same mesh as the 0.05 m reference test of the solid cylinder: 2375.22 Hz within 0.3 %
    assert result.modes.frequencies[1] == pytest.approx(2375.22, rel=3e-3)
    assert result.modal_data is None
