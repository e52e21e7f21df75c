"""Reading CPT (cone penetration test) data from CSV files.

The file is a CSV table with a header row; lines starting with ``#`` before or after the header
are comments. The columns needed are the depth, the cone resistance qc and the sleeve friction
fs; the pore pressure u2 is optional (zeros, so qt = qc, when the file has none). Columns are
found by name, ignoring case and a trailing unit in brackets: ``depth`` (or ``z``), ``qc``,
``fs``, ``u2``; other names can be mapped with ``columns``, and other columns are ignored.

Units are stated in the header, ``depth [m]``, ``qc [MPa]``, ``fs [kPa]``, ``u2 [kPa]``, or
given as arguments (``qc_unit="MPa"`` ...); when both are there they must agree. Without
either, depth is taken in m and qc in MPa (the universal CPT practice), while fs and u2 - often
given in kPa as well as in MPa - must be stated. Pressures: Pa, kPa, MPa (also kN/m2, MN/m2);
depth: m, cm.

Depth and water: anvilwave measures depth down from the mudline (seabed). A seabed CPT is
logged that way (``depth_reference="mudline"``, the default). A log referenced to sea level
(``depth_reference="sea-level"``) needs the ``water_depth`` [m]: depth below the mudline =
depth below sea level - water depth; a reading above the mudline is an error. The pressures are
taken as logged by a cone zeroed at the seabed (qc and u2 without the ambient water pressure).

Every problem stops with one :class:`anvilwave.inputs.InputError` naming the file, the column
and the rule: file not found, missing column, unknown unit, a missing or non-numeric value
(unless ``missing`` says how to treat it), depths not increasing (repeats allowed with
``duplicate_depths="average"``), negative qc or fs, qc values that cannot be in the declared
unit (median above 200 MPa or below 10 kPa once converted; e.g. kPa declared as MPa).

Cleaning options for real logs (e.g. the ISFOG 2020 full-resolution CPTs):
``push_column`` and ``skip_push_start`` drop the first metres of every push (the cone is still
loading there); ``missing="interpolate"`` fills a missing fs or u2 (or qc) linearly in depth
from its neighbours, ``"drop"`` removes the row; ``duplicate_depths="average"`` averages
readings logged at the same depth; ``negative_fs="zero"`` sets a slightly negative sleeve
friction (zero drift) to 0; ``rows_where`` keeps the rows whose named columns hold the
given text (one location of a multi-location file).
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import numpy as np

from anvilwave.inputs import InputError, read_text
from anvilwave.pile.soil.profile import Cpt

PRESSURE_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "kn/m2": 1e3, "mn/m2": 1e6,
                  "kn/m^2": 1e3, "mn/m^2": 1e6}
"""Pressure units accepted, to Pa."""
DEPTH_UNITS = {"m": 1.0, "cm": 0.01}
"""Depth units accepted, to m."""
ROLES = ("depth", "qc", "fs", "u2")
"""Columns the reader looks for."""
ALIASES = {"depth": ("depth", "z"), "qc": ("qc",), "fs": ("fs",), "u2": ("u2",)}
"""Column names recognised for each role (case-insensitive, unit ignored)."""
DEPTH_REFERENCES = ("mudline", "sea-level")
MISSING_RULES = ("error", "interpolate", "drop")
DUPLICATE_RULES = ("error", "average")
NEGATIVE_FS_RULES = ("error", "zero")
QC_MEDIAN_MAX = 200e6
"""A median qc above this [Pa] cannot be real (kPa declared as MPa, ...)."""
QC_MEDIAN_MIN = 10e3
"""A median qc below this [Pa] cannot be real (MPa declared as kPa, ...)."""
FS_MEDIAN_MAX = 5e6
"""A median fs above this [Pa] cannot be real."""

_HEADER = re.compile(r"^\s*(.*?)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")


def _split_header(text: str) -> tuple[str, str | None]:
    name, unit = _HEADER.match(text).groups()
    return name.strip().lower(), (unit if unit else None)


def read_cpt_csv(path, *, qc_unit: str | None = None, fs_unit: str | None = None,
                 u2_unit: str | None = None, depth_unit: str | None = None,
                 columns: dict[str, str] | None = None, depth_reference: str = "mudline",
                 water_depth: float | None = None, missing: str = "error",
                 duplicate_depths: str = "error", push_column: str | None = None,
                 skip_push_start: float = 0.0, negative_fs: str = "error",
                 rows_where: dict[str, str] | None = None) -> Cpt:
    """Read a CPT from a CSV file (module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    qc_unit : {"Pa", "kPa", "MPa"} or None, default None
        Pressure unit of the qc column when the header does not state it (or to confirm it).
    fs_unit : {"Pa", "kPa", "MPa"} or None, default None
        Pressure unit of the fs column, as ``qc_unit``.
    u2_unit : {"Pa", "kPa", "MPa"} or None, default None
        Pressure unit of the u2 column, as ``qc_unit``.
    depth_unit : {"m", "cm"} or None, default None
        Unit of the depth column.
    columns : dict or None, default None
        Header names (without unit) for roles whose name is not recognised, e.g.
        ``{"depth": "penetration"}``.
    depth_reference : {"mudline", "sea-level"}
        "mudline" (depth below the seabed) or "sea-level".
    water_depth : float or None, default None
        Water depth [m], required with ``depth_reference="sea-level"``.
    missing : {"error", "interpolate", "drop"}
        What to do with empty / NaN values of qc, fs and u2.
    duplicate_depths : {"error", "average"}
        What to do with readings at the same depth.
    push_column : str or None, default None
        Name of a column numbering the pushes of the cone.
    skip_push_start : float, default 0.0
        Readings within this distance below the start of their push are dropped [m] (needs
        ``push_column``).
    negative_fs : {"error", "zero"}
        "zero" sets small negative sleeve friction (from the zero drift of the sensor) to 0.
    rows_where : dict or None, default None
        {column name: text}; only rows whose columns hold that text are read.

    Returns
    -------
    Cpt
        The CPT (:class:`anvilwave.pile.soil.profile.Cpt`), depths below the mudline [m],
        pressures [Pa].

    Raises
    ------
    InputError
        If an option or the file breaks a rule (the message names the file and the column
        or option).
    """
    path = Path(path)
    source = str(path)
    _check_choice(source, "depth_reference", depth_reference, DEPTH_REFERENCES)
    _check_choice(source, "missing", missing, MISSING_RULES)
    _check_choice(source, "duplicate_depths", duplicate_depths, DUPLICATE_RULES)
    _check_choice(source, "negative_fs", negative_fs, NEGATIVE_FS_RULES)
    if depth_reference == "sea-level" and (water_depth is None or not water_depth > 0.0):
        raise InputError(source, "water_depth",
                         "a positive water depth [m] is required with depth_reference "
                         "'sea-level'")
    if skip_push_start < 0.0 or (skip_push_start > 0.0 and push_column is None):
        raise InputError(source, "skip_push_start", "must be >= 0 m and needs push_column")

    header, rows = _read_rows(path)
    names = [_split_header(h) for h in header]
    index = _locate_columns(source, header, names, columns or {})
    for key in (push_column, *(rows_where or {})):
        if key is not None and _find(names, key.lower()) is None:
            raise InputError(source, key, f"column is missing (header: {', '.join(header)})")
    if rows_where:
        keep = [all(_cell(row, _find(names, k.lower())).strip() == str(v)
                    for k, v in rows_where.items()) for row, _ in rows]
        rows = [r for r, k in zip(rows, keep, strict=True) if k]
        if not rows:
            raise InputError(source, next(iter(rows_where)),
                             f"no row matches {rows_where}")
    if not rows:
        raise InputError(source, "", "has no data rows")

    scales = {}
    given = {"depth": depth_unit, "qc": qc_unit, "fs": fs_unit, "u2": u2_unit}
    for role, col in index.items():
        scales[role] = _scale(source, header[col], role, names[col][1], given[role])

    lines = np.array([line for _, line in rows], dtype=int)
    data = {role: _numbers(source, header[col], rows, col, lines, allow_missing=role != "depth")
            for role, col in index.items()}
    if "u2" not in data:
        data["u2"] = np.zeros(len(rows))

    if push_column is not None:
        push_col = _find(names, push_column.lower())
        push = np.array([_cell(row, push_col).strip() for row, _ in rows])
        keep = np.ones(push.size, dtype=bool)
        if skip_push_start > 0.0:
            depth = data["depth"] * scales["depth"]
            for label in np.unique(push):
                sel = push == label
                keep &= ~sel | (depth - depth[sel].min() >= skip_push_start - 1e-12)
        data = {role: values[keep] for role, values in data.items()}
        lines = lines[keep]

    for role in ("qc", "fs", "u2"):
        data[role] = data[role] * scales.get(role, 1.0)
    depth = data["depth"] * scales["depth"]
    if depth_reference == "sea-level":
        depth = depth - water_depth

    depth, data, lines = _duplicates(source, header[index["depth"]], depth, data, lines,
                                     duplicate_depths)
    depth, data, lines = _missing(source, header, index, depth, data, lines, missing)

    label = {role: header[col] for role, col in index.items()}
    label.setdefault("u2", "u2")
    if depth.size < 2:
        raise InputError(source, label["depth"], "needs at least two readings")
    if depth[0] < 0.0:
        where = ("above the mudline (depth below sea level smaller than the water depth)"
                 if depth_reference == "sea-level" else "negative")
        raise InputError(source, label["depth"],
                         f"line {lines[0]}: depth {depth[0]:g} m is {where}")
    if negative_fs == "zero":
        data["fs"] = np.maximum(data["fs"], 0.0)
    for role in ("qc", "fs"):
        bad = np.flatnonzero(data[role] < 0.0)
        if bad.size:
            k = bad[0]
            raise InputError(source, label[role],
                             f"must not be negative: line {lines[k]} (depth {depth[k]:g} m) has "
                             f"{data[role][k] / scales[role]:g}")
    _plausible(source, label, scales, data)
    return Cpt(depth, data["qc"], data["fs"], data["u2"], source=source)


# ---------------------------------------------------------------------------- helpers
def _check_choice(source: str, key: str, value: str, choices) -> None:
    if value not in choices:
        raise InputError(source, key, f"must be one of {', '.join(map(repr, choices))}, "
                                      f"got {value!r}")


def _read_rows(path: Path):
    """(header cells, [(row cells, line number)]) without comment and blank lines."""
    text = read_text(path, encoding="utf-8-sig")
    header = None
    rows = []
    reader = csv.reader(text.splitlines())
    number = 0
    while True:
        try:
            cells = next(reader)
        except StopIteration:
            break
        except csv.Error as exc:
            raise InputError(path, "", f"line {reader.line_num}: is not a CSV row ({exc})") \
                from None
        number = reader.line_num
        if not cells or all(not c.strip() for c in cells) or cells[0].lstrip().startswith("#"):
            continue
        if header is None:
            header = [c.strip() for c in cells]
        else:
            rows.append((cells, number))
    if header is None:
        raise InputError(path, "", "is empty (no header row)")
    return header, rows


def _find(names, wanted: str) -> int | None:
    for i, (name, _) in enumerate(names):
        if name == wanted:
            return i
    return None


def _locate_columns(source, header, names, columns) -> dict[str, int]:
    unknown = set(columns) - set(ROLES)
    if unknown:
        raise InputError(source, "columns", f"unknown role {sorted(unknown)[0]!r}; roles are "
                                            f"{', '.join(ROLES)}")
    index = {}
    for role in ROLES:
        candidates = (columns[role].lower(),) if role in columns else ALIASES[role]
        found = [i for c in candidates if (i := _find(names, c)) is not None]
        if found:
            index[role] = found[0]
        elif role != "u2" or role in columns:
            wanted = " or ".join(repr(c) for c in candidates)
            raise InputError(source, role, f"column {wanted} is missing (header: "
                                           f"{', '.join(header)})")
    return index


def _scale(source, column, role, header_unit, given_unit) -> float:
    table = DEPTH_UNITS if role == "depth" else PRESSURE_UNITS
    default = {"depth": "m", "qc": "MPa"}.get(role)
    units = [u for u in (header_unit, given_unit) if u is not None]
    if len(units) == 2 and units[0].lower() != units[1].lower():
        raise InputError(source, column, f"the header states {header_unit!r} but "
                                         f"{role}_unit={given_unit!r} was given")
    unit = units[0] if units else default
    if unit is None:
        raise InputError(source, column, "unit not stated: write it in the header "
                                         f"('{role} [kPa]') or pass {role}_unit=")
    if unit.lower() not in table:
        raise InputError(source, column, f"unknown unit {unit!r}; use one of "
                                         f"{', '.join(sorted(table))}")
    return table[unit.lower()]


def _cell(row, col) -> str:
    return row[col] if col < len(row) else ""


def _numbers(source, column, rows, col, lines, allow_missing: bool) -> np.ndarray:
    values = np.empty(len(rows))
    for k, (row, _) in enumerate(rows):
        text = _cell(row, col).strip()
        if not text:
            value = math.nan
        else:
            try:
                value = float(text)
            except ValueError:
                raise InputError(source, column,
                                 f"line {lines[k]}: {text!r} is not a number") from None
        if math.isinf(value) or (math.isnan(value) and not allow_missing):
            raise InputError(source, column, f"line {lines[k]}: missing or non-finite value")
        values[k] = value
    return values


def _missing(source, header, index, depth, data, lines, rule):
    nan = {role: np.isnan(values) for role, values in data.items() if role != "depth"}
    anywhere = np.any(np.column_stack(list(nan.values())), axis=1)
    if not anywhere.any():
        return depth, data, lines
    if rule == "error":
        role = next(r for r in ("qc", "fs", "u2") if nan[r].any())
        k = int(np.flatnonzero(nan[role])[0])
        raise InputError(source, header[index[role]],
                         f"line {lines[k]} (depth {depth[k]:g} m): missing or NaN value "
                         "(missing='interpolate' or 'drop' to accept gaps)")
    if rule == "drop":
        keep = ~anywhere
        return depth[keep], {r: v[keep] for r, v in data.items()}, lines[keep]
    filled = dict(data)
    for role, mask in nan.items():
        if mask.all():
            raise InputError(source, header[index[role]], "has no value at all")
        if mask.any():
            filled[role] = data[role].copy()
            filled[role][mask] = np.interp(depth[mask], depth[~mask], data[role][~mask])
    return depth, filled, lines


def _duplicates(source, column, depth, data, lines, rule):
    steps = np.diff(depth)
    back = np.flatnonzero(steps < 0.0)
    if back.size:
        k = back[0]
        raise InputError(source, column,
                         f"depths must increase: line {lines[k + 1]} ({depth[k + 1]:g} m) "
                         f"follows line {lines[k]} ({depth[k]:g} m)")
    same = np.flatnonzero(steps == 0.0)
    if not same.size:
        return depth, data, lines
    if rule == "error":
        k = same[0]
        raise InputError(source, column,
                         f"depths must increase: line {lines[k + 1]} repeats depth "
                         f"{depth[k]:g} m (duplicate_depths='average' to merge repeats)")
    unique, start = np.unique(depth, return_index=True)
    group = np.searchsorted(unique, depth)
    merged = {}
    for role, values in data.items():  # mean of the values present (NaN if none)
        present = ~np.isnan(values)
        counts = np.bincount(group[present], minlength=unique.size)
        sums = np.bincount(group[present], weights=values[present], minlength=unique.size)
        with np.errstate(invalid="ignore", divide="ignore"):
            merged[role] = np.where(counts > 0, sums / np.maximum(counts, 1), np.nan)
    return unique, merged, lines[start]


def _plausible(source, label, scales, data) -> None:
    median_qc = float(np.median(data["qc"]))
    unit_qc = 1.0 / scales["qc"]
    if median_qc > QC_MEDIAN_MAX:
        raise InputError(source, label["qc"],
                         f"median qc is {median_qc / 1e6:g} MPa once read in the declared unit "
                         f"({median_qc * unit_qc:g} as given): the values look like kPa "
                         "(or Pa); check the unit")
    if median_qc < QC_MEDIAN_MIN:
        raise InputError(source, label["qc"],
                         f"median qc is {median_qc / 1e3:g} kPa once read in the declared unit"
                         f" ({median_qc * unit_qc:g} as given): the values look like MPa; "
                         "check the unit")
    median_fs = float(np.median(data["fs"]))
    if median_fs > FS_MEDIAN_MAX:
        raise InputError(source, label["fs"],
                         f"median fs is {median_fs / 1e6:g} MPa once read in the declared unit:"
                         " the values look like kPa (or Pa); check the unit")
