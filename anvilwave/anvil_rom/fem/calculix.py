"""CalculiX (``ccx``) as an external FE code for the free-free modes of the anvil.

Write a free-free axisymmetric frequency deck (:func:`write_ccx_deck`), run it
(:func:`run_ccx`), and read the results back (:func:`read_dat_frequencies`, :func:`read_frd`)
into a :class:`~anvilwave.anvil_rom.fem.modes.ModeSet` on anvilwave's own FE model of the same mesh
(:func:`modes_from_calculix`), usable exactly like the output of
:func:`~anvilwave.anvil_rom.fem.modes.free_free_modes`.

CalculiX conventions and how they are mapped (checked with ccx 2.20):

- Axisymmetric elements (CAX6, CAX8) lie in the x-y plane with x = radius and y = the axis of
  revolution. anvilwave's axis z points down, so the deck uses x = r, y = -z, and displacements
  map back as u_r = u_x, u_z = -u_y.
- ccx needs the element nodes counter-clockwise in (x, y) (otherwise it stops with "nonpositive
  jacobian"). The mirror y = -z turns a counter-clockwise (r, z) element clockwise, so every
  element is re-ordered from the sign of its corner area in (x, y).
- ccx expands each axisymmetric element into a 2-degree sector of 3D elements (CAX6 -> 15-node
  wedge, CAX8 -> 20-node brick) and does not by itself keep u_r = 0 on the axis: in free-free
  runs of a cylinder the axis nodes moved radially by up to 0.35 % of the largest radial
  displacement (the frequencies by < 3e-7, as the hoop strain u_r / r penalises it). The deck
  therefore fixes u_x of the nodes on the axis (``*BOUNDARY``), the axisymmetry condition that
  anvilwave's FE applies too. It is not a support: the axial rigid-body mode stays at 0 Hz.
- The eigenvectors are normalised to the mass of the 2-degree sector (1/180 of the body), so
  :func:`modes_from_calculix` re-normalises them with anvilwave's consistent mass matrix.
- For 2D elements ccx writes the ``.frd`` on the 2D mesh by default (``*NODE FILE,
  OUTPUT=2D``). Those values are averages over the sector thickness of the Cartesian u_x of the
  expanded nodes, so u_r comes out low by 1 - cos(1 deg) = 1.5e-4 (relative) at midside nodes
  and by a third of that at corner nodes (measured; u_z is exact). With ``OUTPUT=3D``
  (``write_ccx_deck(..., expanded_output=True)``) ccx writes the expanded sector instead, which
  :func:`read_frd` maps back onto the 2D mesh without that bias (each face node's displacement
  is projected on its own radial direction), at the price of a 2-3 times larger file and
  nodes numbered anew.
- ``.frd`` numbers have 6 significant digits (format E12.5): coordinates and mode shapes read
  back carry a relative rounding error up to 5e-6. The ``.dat`` eigenvalue table has 7.
"""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path
from typing import NamedTuple

import meshio
import numpy as np
from scipy.spatial import cKDTree

from anvilwave.anvil_rom.fem.elasticity import AxisymmetricModel, assemble
from anvilwave.anvil_rom.fem.geometry import Material
from anvilwave.anvil_rom.fem.mesh import to_skfem
from anvilwave.anvil_rom.fem.modes import ModeSet, ModeSolveError, sturm_count
from anvilwave.inputs import InputError, read_text

CCX_ELEMENTS = {"triangle6": "CAX6", "quad8": "CAX8", "quad9": "CAX8"}
"""meshio cell type -> CalculiX axisymmetric element (quad9 loses its centre node)."""

_NODES = {"triangle6": 6, "quad8": 8, "quad9": 9}
_CORNERS = {"triangle6": 3, "quad8": 4}
# orientation reversal keeping meshio's order (corners, then the midside of edge 01, 12, ...)
_REVERSE = {"triangle6": [0, 2, 1, 5, 4, 3], "quad8": [0, 3, 2, 1, 7, 6, 5, 4]}

# .frd element type codes (CalculiX GraphiX numbering) and their node counts
_FRD_NODES = {1: 8, 2: 6, 3: 4, 4: 20, 5: 15, 6: 10, 7: 3, 8: 6, 9: 4, 10: 8, 11: 2, 12: 3}
_FRD_2D = {7: "triangle", 8: "triangle6", 9: "quad", 10: "quad8"}
# expanded CAX6 (15-node wedge) / CAX8 (20-node brick) in .frd node order: the nodes of one
# face (corners, then midsides), the mid-plane corner nodes, and the midsides of the other face
_FRD_SECTOR = {
    5: ("triangle6", {"face_a": [0, 1, 2], "face_a_mid": [6, 7, 8], "mid": [9, 10, 11],
                      "face_b_mid": [12, 13, 14]}),
    4: ("quad8", {"face_a": [0, 1, 2, 3], "face_a_mid": [8, 9, 10, 11],
                  "mid": [12, 13, 14, 15], "face_b_mid": [16, 17, 18, 19]}),
}


class CalculixError(RuntimeError):
    """CalculiX is missing or a ccx run failed."""


class FrdResult(NamedTuple):
    """Mesh and mode shapes read from a CalculiX ``.frd`` file (anvilwave conventions).

    Parameters
    ----------
    points : numpy.ndarray
        Node coordinates (r, z), shape (n, 2) [m], z down.
    cells : numpy.ndarray
        Connectivity in meshio node order, counter-clockwise in (r, z), shape (n_cells, k).
    cell_type : str
        meshio cell type ("triangle6", "quad8", ...).
    displacements : numpy.ndarray
        Nodal (u_r, u_z) of each mode, shape (n_modes, n, 2) [-] (ccx normalisation).
    """

    points: np.ndarray
    cells: np.ndarray
    cell_type: str
    displacements: np.ndarray


class CalculixModes(NamedTuple):
    """Result of :func:`modes_from_calculix`.

    Parameters
    ----------
    mesh : meshio.Mesh
        The 2D mesh the model is built on, (r, z) [m].
    model : AxisymmetricModel
        anvilwave's assembled FE model of that mesh.
    modes : ModeSet
        CalculiX frequencies [Hz] with shapes mass-normalised by ``model.mass``.
    """

    mesh: meshio.Mesh
    model: AxisymmetricModel
    modes: ModeSet


# ---------------------------------------------------------------------------------- deck
def write_ccx_deck(path: str | Path, points: np.ndarray, cells: np.ndarray, cell_type: str,
                   material: Material, n_modes: int, title: str = "", *,
                   expanded_output: bool = False) -> Path:
    """Write a CalculiX deck for the free-free axisymmetric modes of a 2D (r, z) mesh.

    Node i of ``points`` becomes CalculiX node i + 1 and cell j element j + 1. Only nodes used
    by the elements are written. Nodes on the axis get u_r = 0 (see the module docstring); no
    other boundary condition is applied.

    Parameters
    ----------
    path : str or Path
        Output ``.inp`` file.
    points : numpy.ndarray
        Node coordinates (r, z), shape (n, 2) [m], z down, r >= 0.
    cells : numpy.ndarray
        Connectivity in meshio node order (0-based), shape (n_cells, k).
    cell_type : {"triangle6", "quad8", "quad9"}
        "triangle6" (-> CAX6), "quad8" or "quad9" (-> CAX8, centre node dropped).
    material : Material
        Linear elastic material (E [Pa], nu [-], rho [kg/m^3]).
    n_modes : int
        Number of eigenmodes to extract, the axial rigid-body mode included [-].
    title : str, default ""
        One-line heading written into the deck.
    expanded_output : bool, default False
        Write the results on the expanded 3D sector (``OUTPUT=3D``) instead of the 2D mesh;
        see the module docstring.

    Returns
    -------
    Path
        The written deck.

    Raises
    ------
    ValueError
        If the cell type is not supported, or the points, cells, radii or ``n_modes``
        are invalid.
    """
    if cell_type not in CCX_ELEMENTS:
        raise ValueError(f"cell type {cell_type!r} not supported; use one of "
                         f"{', '.join(CCX_ELEMENTS)}")
    points = np.asarray(points, dtype=float)
    cells = np.asarray(cells, dtype=np.int64)
    if points.ndim != 2 or points.shape[1] < 2:
        raise ValueError("points must be an (n, 2) array of (r, z)")
    if cells.ndim != 2 or cells.shape[1] != _NODES[cell_type]:
        raise ValueError(f"{cell_type} cells need {_NODES[cell_type]} nodes each")
    if cells.size == 0 or cells.min() < 0 or cells.max() >= len(points):
        raise ValueError("cells refer to nodes that do not exist")
    if int(n_modes) < 1:
        raise ValueError("n_modes must be at least 1")
    kind = "quad8" if cell_type == "quad9" else cell_type
    conn = cells[:, :_NODES[kind]]
    # CalculiX plane: x = r, y = -z
    xy = np.column_stack([points[:, 0], -points[:, 1]]) + 0.0  # + 0.0: no "-0" in the deck
    conn = _counter_clockwise(xy, conn, kind)
    used = np.unique(conn)
    scale = max(float(np.abs(points[used, :2]).max()), 1e-300)
    if np.any(points[used, 0] < -1e-9 * scale):
        raise ValueError("all radii r must be >= 0")
    axis = used[np.abs(points[used, 0]) <= 1e-9 * scale]

    # ccx reads at most 20 characters per number: 13 significant digits fit
    heading = " ".join(str(title).encode("ascii", "replace").decode().split()).lstrip("*")
    lines = ["*HEADING", heading or "anvilwave free-free axisymmetric modes"]
    lines.append("*NODE, NSET=NALL")
    lines += [f"{i + 1}, {xy[i, 0]:.12e}, {xy[i, 1]:.12e}" for i in used]
    lines.append(f"*ELEMENT, TYPE={CCX_ELEMENTS[cell_type]}, ELSET=EALL")
    lines += [f"{j + 1}, " + ", ".join(str(n + 1) for n in row) for j, row in enumerate(conn)]
    if len(axis):
        lines.append("*NSET, NSET=NAXIS")
        lines += [", ".join(str(n + 1) for n in axis[k:k + 8]) for k in range(0, len(axis), 8)]
        lines += ["*BOUNDARY", "NAXIS, 1, 1"]
    lines += [
        "*MATERIAL, NAME=ANVIL",
        "*ELASTIC",
        f"{material.youngs_modulus:.12e}, {material.poisson_ratio:.12e}",
        "*DENSITY",
        f"{material.density:.12e}",
        "*SOLID SECTION, ELSET=EALL, MATERIAL=ANVIL",
        "*STEP",
        "*FREQUENCY",
        f"{int(n_modes)}",
        f"*NODE FILE, OUTPUT={'3D' if expanded_output else '2D'}",
        "U",
        "*END STEP",
    ]
    path = Path(path)
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path


def write_ccx_deck_from_mesh(path: str | Path, mesh: meshio.Mesh, material: Material,
                             n_modes: int, title: str = "", *,
                             expanded_output: bool = False) -> Path:
    """:func:`write_ccx_deck` for a 2D meshio mesh in (r, z) [m] (its first cell block).

    Parameters
    ----------
    path : str or Path
        Output ``.inp`` file.
    mesh : meshio.Mesh
        The 2D mesh, (r, z) [m].
    material : Material
        Linear elastic material.
    n_modes : int
        Number of eigenmodes to extract, the rigid-body mode included [-].
    title : str, default ""
        One-line heading written into the deck.
    expanded_output : bool, default False
        Write the results on the expanded 3D sector (``OUTPUT=3D``).

    Returns
    -------
    Path
        The written deck.
    """
    block = mesh.cells[0]
    return write_ccx_deck(path, np.asarray(mesh.points)[:, :2], block.data, block.type,
                          material, n_modes, title, expanded_output=expanded_output)


def _signed_areas(xy: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Shoelace area of each element's corner polygon, positive counter-clockwise [m^2]."""
    x, y = xy[corners, 0], xy[corners, 1]
    return 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)


def _counter_clockwise(xy: np.ndarray, conn: np.ndarray, kind: str) -> np.ndarray:
    """Re-order elements so that their corners run counter-clockwise in the xy plane."""
    area = _signed_areas(xy, conn[:, :_CORNERS[kind]])
    scale = np.ptp(xy[np.unique(conn)], axis=0).max() ** 2
    bad = np.flatnonzero(np.abs(area) <= 1e-14 * scale)
    if bad.size:
        raise ValueError(f"element {bad[0]} has zero area")
    out = conn.copy()
    flip = area < 0.0
    out[flip] = conn[flip][:, _REVERSE[kind]]
    return out


# ---------------------------------------------------------------------------------- run
def run_ccx(inp_path: str | Path, workdir: str | Path | None = None,
            timeout: float = 3600.0) -> tuple[Path, Path]:
    """Run CalculiX on a deck and return the paths of its ``.frd`` and ``.dat`` results.

    ccx's screen output is kept in ``<job>.log`` in the work directory. Old ``.frd``/``.dat``
    files of the job are removed first, so stale results are never returned.

    Parameters
    ----------
    inp_path : str or Path
        The ``.inp`` deck; the job name is its stem.
    workdir : str or Path, optional
        Directory to run in (the deck is copied there); default: the deck's directory.
    timeout : float, default 3600.0
        Wall-clock limit [s].

    Returns
    -------
    frd : Path
        The ``.frd`` result file.
    dat : Path
        The ``.dat`` result file.

    Raises
    ------
    CalculixError
        If ccx is missing or the run fails.
    InputError
        If the deck is missing or is not an ``.inp`` file.
    """
    exe = shutil.which("ccx")
    if exe is None:
        raise CalculixError("CalculiX is not installed: no 'ccx' on PATH (Debian/Ubuntu: "
                            "apt-get install calculix-ccx)")
    inp = Path(inp_path)
    if not inp.is_file():
        raise InputError(inp, "", "file not found")
    if inp.suffix != ".inp":
        raise InputError(inp, "", "a CalculiX deck must have the extension .inp")
    work = Path(workdir) if workdir is not None else inp.parent
    work.mkdir(parents=True, exist_ok=True)
    job = inp.stem
    deck = work / inp.name
    if not deck.exists() or deck.resolve() != inp.resolve():
        shutil.copyfile(inp, deck)
    frd, dat = work / f"{job}.frd", work / f"{job}.dat"
    for old in (frd, dat):
        old.unlink(missing_ok=True)
    try:
        proc = subprocess.run([exe, "-i", job], cwd=work, capture_output=True, text=True,
                              timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        raise CalculixError(f"ccx did not finish {inp} within {timeout:g} s") from None
    except OSError as exc:
        raise CalculixError(f"ccx could not be started: {exc}") from None
    output = proc.stdout + proc.stderr
    (work / f"{job}.log").write_text(output, encoding="utf-8", errors="replace")
    errors = [ln.strip() for ln in output.splitlines() if "*ERROR" in ln]
    if proc.returncode != 0 or errors or not frd.is_file() or not dat.is_file():
        detail = "; ".join(errors[:3]) or f"exit code {proc.returncode}"
        raise CalculixError(f"ccx failed on {inp}: {detail} (screen output in "
                            f"{work / (job + '.log')})")
    return frd, dat


# ---------------------------------------------------------------------------------- readers
def _read_lines(path: Path) -> list[str]:
    return read_text(path, encoding="latin-1").splitlines()


def read_dat_frequencies(path: str | Path) -> np.ndarray:
    """Natural frequencies [Hz] from the eigenvalue table of a CalculiX ``.dat`` file.

    The table of a ``*FREQUENCY`` step lists, per mode, the eigenvalue [rad^2/s^2], the real
    part of omega [rad/s] and of f [Hz] (CYCLES/TIME), and the imaginary part of omega; the
    real part of f is returned (0 for the slightly negative eigenvalue of a rigid-body mode).

    Parameters
    ----------
    path : str or Path
        The ``.dat`` file.

    Returns
    -------
    numpy.ndarray
        Frequency of each mode [Hz].
    """
    path = Path(path)
    lines = _read_lines(path)
    starts = [i for i, ln in enumerate(lines) if "E I G E N V A L U E   O U T P U T" in ln]
    if not starts:
        raise InputError(path, "EIGENVALUE OUTPUT", "no eigenvalue table: not the .dat file of a "
                                                    "CalculiX *FREQUENCY step")
    if len(starts) > 1:
        raise InputError(path, "EIGENVALUE OUTPUT", f"{len(starts)} eigenvalue tables (several "
                                                    "*FREQUENCY steps); expected one")
    rows: list[list[float]] = []
    for lineno in range(starts[0] + 1, len(lines)):
        tokens = lines[lineno].split()
        if not tokens:
            if rows:
                break
            continue
        if not tokens[0].isdigit():
            if rows:
                break
            continue  # column headings
        try:
            if len(tokens) != 5 or int(tokens[0]) != len(rows) + 1:
                raise ValueError
            rows.append([float(t) for t in tokens[1:]])
        except ValueError:
            raise InputError(path, f"line {lineno + 1}", "corrupt eigenvalue table row "
                                                         f"{lines[lineno].strip()!r}") from None
    if not rows:
        raise InputError(path, "EIGENVALUE OUTPUT", "the eigenvalue table is empty")
    freq = np.array(rows)[:, 2]
    if not np.all(np.isfinite(freq)):
        raise InputError(path, "EIGENVALUE OUTPUT", "non-finite frequencies")
    return freq


class _Frd(NamedTuple):
    ids: np.ndarray  # node numbers
    xyz: np.ndarray  # (n, 3) coordinates in the CalculiX frame
    etype: int
    conn: np.ndarray  # (n_cells, k) node numbers
    values: list  # per DISP block: (mode value [Hz], {node number: (dx, dy, dz)})


def _parse_frd(path: Path) -> _Frd:
    """Nodes, elements and DISP blocks of an ASCII .frd file."""
    lines = _read_lines(path)

    def error(lineno: int, rule: str) -> InputError:
        return InputError(path, f"line {lineno + 1}", rule)

    def width_of(lineno: int) -> int:
        try:
            fmt = int(lines[lineno].split()[-1])
        except (ValueError, IndexError):
            raise error(lineno, "corrupt block header") from None
        if fmt == 2:
            raise error(lineno, "binary .frd files are not supported: write ASCII output")
        if fmt not in (0, 1):
            raise error(lineno, f"unknown number format {fmt}")
        return 5 if fmt == 0 else 10

    def floats(lineno: int, w: int, count: int) -> tuple[int, list[float]]:
        ln = lines[lineno]
        try:
            number = int(ln[3:3 + w])
            vals = [float(ln[3 + w + 12 * k:3 + w + 12 * (k + 1)]) for k in range(count)]
        except ValueError:
            raise error(lineno, f"corrupt data line {ln.strip()!r}") from None
        if not np.all(np.isfinite(vals)):
            raise error(lineno, "non-finite value")
        return number, vals

    def block_end(lineno: int, what: str) -> None:
        if lineno >= len(lines):
            raise InputError(path, what, "the file ends inside the block (truncated?)")

    ids: list[int] = []
    xyz: list[list[float]] = []
    etypes: set[int] = set()
    conn: list[list[int]] = []
    values: list = []
    i, n, ended = 0, len(lines), False
    while i < n:
        ln = lines[i]
        rec, kind = ln[:5].strip(), ln[5:6]
        if rec == "9999":
            ended = True
            break
        if rec == "2" and kind == "C":  # nodal point coordinate block
            w = width_of(i)
            i += 1
            while i < n and not lines[i].startswith(" -3"):
                if not lines[i].startswith(" -1"):
                    raise error(i, "expected a node line ' -1' in the node block")
                number, vals = floats(i, w, 3)
                ids.append(number)
                xyz.append(vals)
                i += 1
            block_end(i, "nodes")
        elif rec == "3" and kind == "C":  # element definition block
            w = width_of(i)
            i += 1
            while i < n and not lines[i].startswith(" -3"):
                head = lines[i]
                try:
                    if not head.startswith(" -1"):
                        raise ValueError
                    etype = int(head[3 + w:8 + w])
                    need = _FRD_NODES[etype]
                except (ValueError, KeyError):
                    raise error(i, f"corrupt element line {head.strip()!r}") from None
                nodes: list[int] = []
                i += 1
                while len(nodes) < need:
                    if i >= n or not lines[i].startswith(" -2"):
                        raise error(i, f"element needs {need} nodes")
                    body = lines[i][3:].rstrip()
                    try:
                        nodes += [int(body[k:k + w]) for k in range(0, len(body), w)]
                    except ValueError:
                        raise error(i, f"corrupt element node line {lines[i].strip()!r}") from None
                    i += 1
                if len(nodes) != need:
                    raise error(i - 1, f"element has {len(nodes)} nodes, its type needs {need}")
                etypes.add(etype)
                conn.append(nodes)
            block_end(i, "elements")
        elif rec == "100" and kind == "C":  # nodal results block
            w = width_of(i)
            try:
                value = float(ln[12:24])
                name = lines[i + 1].split()[1]
            except (ValueError, IndexError):
                raise error(i, "corrupt result block header") from None
            i += 1
            while i < n and lines[i].startswith((" -4", " -5")):
                i += 1
            data: dict[int, list[float]] = {}
            while i < n and not lines[i].startswith(" -3"):
                if name == "DISP":
                    if not lines[i].startswith(" -1"):
                        raise error(i, "expected a ' -1' line in the DISP block")
                    number, vals = floats(i, w, 3)
                    data[number] = vals
                i += 1
            block_end(i, name)
            if name == "DISP":
                values.append((value, data))
        i += 1
    if not ids:
        raise InputError(path, "nodes", "no node block (2C): not a CalculiX .frd result file")
    if not conn:
        raise InputError(path, "elements", "no element block (3C)")
    if not values:
        raise InputError(path, "DISP", "no displacement results (the deck needs *NODE FILE, U)")
    if not ended:
        raise InputError(path, "", "no end record 9999: the file is truncated")
    if len(etypes) > 1:
        raise InputError(path, "elements", f"mixed element types {sorted(etypes)}; use one")
    ids_arr = np.array(ids, dtype=np.int64)
    if len(np.unique(ids_arr)) != len(ids_arr):
        raise InputError(path, "nodes", "repeated node numbers")
    return _Frd(ids_arr, np.array(xyz), etypes.pop(), np.array(conn, dtype=np.int64), values)


def _index_of(ids: np.ndarray, numbers: np.ndarray, path: Path, key: str) -> np.ndarray:
    order = np.argsort(ids)
    pos = np.clip(np.searchsorted(ids, numbers, sorter=order), 0, len(ids) - 1)
    index = order[pos]
    if np.any(ids[index] != numbers):
        missing = numbers[ids[index] != numbers].ravel()[0]
        raise InputError(path, key, f"node {missing} is not defined")
    return index


def _frd_2d(frd: _Frd, path: Path):
    """2D (x, y) nodes, connectivity and per-mode (u_x, u_y) of a 2D-element .frd."""
    cell_type = _FRD_2D[frd.etype]
    used, inverse = np.unique(frd.conn, return_inverse=True)
    node_index = _index_of(frd.ids, used, path, "elements")
    xyz = frd.xyz[node_index]
    if np.any(np.abs(xyz[:, 2]) > 1e-9 * max(float(np.abs(xyz).max()), 1e-300)):
        raise InputError(path, "nodes", "2D elements with nodes off the x-y plane")
    # keep the file's node order
    keep = np.sort(node_index)
    rank = np.empty(len(frd.ids), dtype=np.int64)
    rank[keep] = np.arange(len(keep))
    cells = rank[node_index][inverse.reshape(frd.conn.shape)]
    numbers = frd.ids[keep]
    disp = []
    for _value, data in frd.values:
        try:
            disp.append(np.array([data[k][:2] for k in numbers]))
        except KeyError as exc:
            raise InputError(path, "DISP", f"no displacement for node {exc.args[0]}") from None
    return frd.xyz[keep, :2], cells, cell_type, np.array(disp)


def _frd_sector(frd: _Frd, path: Path):
    """Map the expanded 2-degree sector (``*NODE FILE, OUTPUT=3D``) back onto the 2D mesh.

    Corner nodes of the 2D elements are the mid-plane nodes of the sector; the 2D midside nodes
    exist only on the two sector faces and are the average of the pair, with the radial
    displacement taken along each face node's radial direction.
    """
    cell_type, local = _FRD_SECTOR[frd.etype]
    index = _index_of(frd.ids, frd.conn, path, "elements")
    xyz = frd.xyz
    scale = max(float(np.abs(xyz).max()), 1e-300)
    mid = index[:, local["mid"]]
    a, b = index[:, local["face_a_mid"]], index[:, local["face_b_mid"]]
    tol = 1e-9 * scale
    face = np.concatenate([a.ravel(), b.ravel()])
    off_axis = np.hypot(xyz[face, 0], xyz[face, 2]) > tol
    if np.any(np.abs(xyz[mid, 2]) > tol) or np.any(np.abs(xyz[face, 2])[off_axis] <= tol):
        raise InputError(path, "elements", "unexpected node layout of the expanded 3D elements")
    # 2D nodes: mid-plane corners (by node index) and face pairs (by sorted index pair)
    pairs = np.sort(np.stack([a.ravel(), b.ravel()], axis=1), axis=1)
    corner_nodes, corner_inv = np.unique(mid.ravel(), return_inverse=True)
    pair_nodes, pair_inv = np.unique(pairs, axis=0, return_inverse=True)
    pair_inv = pair_inv.ravel()
    nc = len(corner_nodes)
    cells = np.hstack([corner_inv.reshape(mid.shape), nc + pair_inv.reshape(a.shape)])

    def radial(p, u):
        """Displacement of sector-face nodes along their own radial direction."""
        r = np.hypot(p[:, 0], p[:, 2])
        safe = np.where(r > 0.0, r, 1.0)
        return np.where(r > 0.0, (u[:, 0] * p[:, 0] + u[:, 2] * p[:, 2]) / safe, u[:, 0])

    pa, pb = xyz[pair_nodes[:, 0]], xyz[pair_nodes[:, 1]]
    r_mid = 0.5 * (np.hypot(pa[:, 0], pa[:, 2]) + np.hypot(pb[:, 0], pb[:, 2]))
    y_mid = 0.5 * (pa[:, 1] + pb[:, 1])
    points = np.vstack([xyz[corner_nodes, :2], np.column_stack([r_mid, y_mid])])
    disp = []
    for _value, data in frd.values:
        try:
            u = np.array([data[k] for k in frd.ids])
        except KeyError as exc:
            raise InputError(path, "DISP", f"no displacement for node {exc.args[0]}") from None
        ua, ub = u[pair_nodes[:, 0]], u[pair_nodes[:, 1]]
        ura, urb = radial(pa, ua), radial(pb, ub)
        disp.append(np.vstack([u[corner_nodes, :2],
                               np.column_stack([0.5 * (ura + urb), 0.5 * (ua[:, 1] + ub[:, 1])])]))
    return points, cells, cell_type, np.array(disp)


def _read_frd(path: str | Path) -> tuple[FrdResult, np.ndarray]:
    path = Path(path)
    frd = _parse_frd(path)
    if frd.etype in _FRD_2D:
        xy, cells, cell_type, disp = _frd_2d(frd, path)
    elif frd.etype in _FRD_SECTOR:
        xy, cells, cell_type, disp = _frd_sector(frd, path)
    else:
        raise InputError(path, "elements", f"element type {frd.etype} is not an axisymmetric "
                                           "(CAX) element or its expansion")
    # CalculiX (x, y) -> anvilwave (r, z) with z = -y, and u_z = -u_y
    points = np.column_stack([xy[:, 0], -xy[:, 1]])
    disp = disp * np.array([1.0, -1.0])
    kind = {"triangle": "triangle6", "quad": "quad8"}.get(cell_type, cell_type)
    ncorner = _CORNERS[kind]
    area = _signed_areas(points, cells[:, :ncorner])
    flip = area < 0.0
    if flip.any():
        if cell_type in _REVERSE:
            cells[flip] = cells[flip][:, _REVERSE[cell_type]]
        else:  # linear elements: reverse the corners
            cells[flip] = cells[flip][:, ::-1]
    freqs = np.array([v for v, _ in frd.values])
    return FrdResult(points, cells, cell_type, disp), freqs


def read_frd(path: str | Path) -> FrdResult:
    """Mesh and mode shapes from a CalculiX ``.frd`` result file, in anvilwave conventions.

    Only nodes used by the elements are returned, in the file's order.

    Parameters
    ----------
    path : str or Path
        ASCII ``.frd`` file of a run with axisymmetric elements and ``*NODE FILE`` U output,
        on the 2D mesh (ccx default) or the expanded 3D sector (``OUTPUT=3D``, mapped back).

    Returns
    -------
    FrdResult
        points (n, 2) as (r, z) [m] with z down; cells (counter-clockwise in (r, z));
        cell_type; displacements (n_modes, n, 2) as (u_r, u_z), one entry per DISP block.

    Raises
    ------
    InputError
        If the file is missing, truncated or not a CalculiX result file.
    """
    return _read_frd(path)[0]


# ---------------------------------------------------------------------------------- modes
def _serendipity_to_quad9(points: np.ndarray, cells: np.ndarray, disp: np.ndarray):
    """Add the centre node of 8-node quads: the serendipity field's value at the centre.

    At the centre the serendipity shape functions are -1/4 (corners) and 1/2 (midsides); the
    9-node Lagrange element represents the 8-node field exactly.
    """
    weights = np.array([-0.25] * 4 + [0.5] * 4)
    centre = np.einsum("k,ekd->ed", weights, points[cells])
    centre_disp = np.einsum("k,mekd->med", weights, disp[:, cells])
    n = len(points)
    cells9 = np.hstack([cells, (n + np.arange(len(cells)))[:, None]])
    return np.vstack([points, centre]), cells9, np.concatenate([disp, centre_disp], axis=1)


def modes_from_calculix(frd_path: str | Path, dat_path: str | Path, material: Material,
                        fmax: float | None = None) -> CalculixModes:
    """CalculiX modes as a :class:`ModeSet` on anvilwave's FE model of the same mesh.

    The model is built on the mesh of the ``.frd`` (8-node quads become 9-node quads whose
    centre carries the interpolated serendipity field). Shapes are mapped node by node onto the
    free DOFs (CalculiX's u_r on the axis is dropped; it is fixed to 0 in decks from
    :func:`write_ccx_deck`), normalised with anvilwave's consistent mass matrix, the first mode
    is replaced by the exact axial translation and the others made M-orthogonal to it, as in
    :func:`~anvilwave.anvil_rom.fem.modes.free_free_modes`. Frequencies are CalculiX's (rigid
    mode: exactly 0).

    Parameters
    ----------
    frd_path : str or Path
        ``.frd`` of a free-free axisymmetric ``*FREQUENCY`` run (mesh and shapes).
    dat_path : str or Path
        ``.dat`` of the same run (frequencies).
    material : Material
        The material of the run (E [Pa], nu [-], rho [kg/m^3]).
    fmax : float, optional
        Keep the modes with f <= fmax [Hz] and prove with a Sturm count of anvilwave's model
        that CalculiX found all of them; None keeps every mode of the run (``sturm_count`` is
        then just their number, not a proof).

    Returns
    -------
    CalculixModes
        The mesh, anvilwave's model of it and the modes.

    Raises
    ------
    InputError
        Unreadable or mismatched files.
    ModeSolveError
        The modes do not fit the model (wrong material or mesh, no rigid mode, not
        M-orthogonal, a mode below fmax missing).
    """
    frd_path, dat_path = Path(frd_path), Path(dat_path)
    result, frd_freqs = _read_frd(frd_path)
    freqs = read_dat_frequencies(dat_path)
    points, cells, cell_type, disp = result
    if len(freqs) != len(disp):
        raise InputError(dat_path, "EIGENVALUE OUTPUT",
                         f"{len(freqs)} frequencies but {frd_path} holds {len(disp)} mode shapes")
    # the .frd result headers carry the frequency too: both files must come from one run
    if np.any(np.abs(frd_freqs - freqs) > 1e-5 * max(freqs.max(), 1.0)):
        raise InputError(dat_path, "EIGENVALUE OUTPUT",
                         f"frequencies differ from those in {frd_path}: different runs?")
    if cell_type not in ("triangle6", "quad8"):
        raise InputError(frd_path, "elements", f"{cell_type} elements: use quadratic CAX6 or "
                                               "CAX8 elements")
    if cell_type == "quad8":
        points, cells, disp = _serendipity_to_quad9(points, cells, disp)
        cell_type = "quad9"
    mesh = meshio.Mesh(points, [(cell_type, cells)])
    model = assemble(to_skfem(mesh), material)

    # node-by-node map from the .frd nodes to the model's DOFs
    node_dofs = model.node_dofs
    locations = model.node_coordinates
    scale = max(float(np.ptp(points, axis=0).max()), 1e-300)
    dist, which = cKDTree(points).query(locations)
    if (len(locations) != len(points) or np.any(dist > 1e-9 * scale)
            or len(np.unique(which)) != len(points)):
        raise ModeSolveError("the FE model's nodes do not coincide with the .frd nodes")
    full = np.zeros((model.basis.N, len(disp)))
    full[node_dofs[:, 0]] = disp[:, which, 0].T
    full[node_dofs[:, 1]] = disp[:, which, 1].T
    shapes = full[model.free_dofs]

    K, M = model.stiffness, model.mass
    e = model.axial_free
    total = float(e @ (M @ e))
    norms = np.sqrt(np.einsum("ij,ij->j", shapes, M @ shapes))
    if np.any(norms <= 0.0):
        raise ModeSolveError(f"{frd_path}: a mode shape is zero")
    shapes = shapes / norms
    # the first mode must be the axial rigid-body translation
    rigid_mac = float((e @ (M @ shapes[:, 0])) ** 2 / total)
    if len(freqs) < 1 or rigid_mac < 0.999 or (len(freqs) > 1 and freqs[0] > 1e-3 * freqs[1]):
        raise ModeSolveError(f"{frd_path}: CalculiX's first mode is not the axial rigid-body "
                             "mode (is the model free-free and axisymmetric?)")
    shapes[:, 0] = e / np.sqrt(total)
    Me = M @ shapes[:, 0]
    shapes[:, 1:] -= np.outer(shapes[:, 0], Me @ shapes[:, 1:])
    shapes /= np.sqrt(np.einsum("ij,ij->j", shapes, M @ shapes))
    # 1e-3: the two codes' mass matrices differ only by quadrature and the 6-digit .frd
    # rounding (measured ~1e-5); anything larger means the shapes belong to another mesh
    gram = shapes.T @ (M @ shapes)
    if np.abs(gram - np.eye(len(freqs))).max() > 1e-3:
        raise ModeSolveError(f"{frd_path}: the CalculiX modes are not orthonormal in the FE "
                             "model's mass matrix")
    # Rayleigh quotients: 1 % catches a wrong material (the codes agree to ~1e-4)
    rayleigh = np.einsum("ij,ij->j", shapes, K @ shapes)[1:]
    omega2 = (2.0 * np.pi * freqs[1:]) ** 2
    if np.any(np.abs(rayleigh - omega2) > 1e-2 * omega2):
        raise ModeSolveError(f"{frd_path}: CalculiX frequencies do not fit the FE model's "
                             "stiffness: is the material the one of the run?")

    rigid_computed = float(freqs[0])
    freqs = freqs.copy()
    freqs[0] = 0.0
    if fmax is None:
        fmax_used, count = float(freqs.max()), len(freqs)
    else:
        fmax_used = float(fmax)
        keep = freqs <= fmax_used
        count = sturm_count(K, M, (2.0 * np.pi * fmax_used) ** 2)
        if count != int(keep.sum()):
            raise ModeSolveError(f"the FE model has {count} modes below {fmax_used:g} Hz but "
                                 f"CalculiX gives {int(keep.sum())}: ask ccx for more modes")
        freqs, shapes = freqs[keep], shapes[:, keep]
    modes = ModeSet(freqs, np.ascontiguousarray(shapes), fmax_used, count, rigid_computed)
    return CalculixModes(mesh, model, modes)
