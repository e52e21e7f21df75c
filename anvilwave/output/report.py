"""The client report of a result folder: one self-contained HTML file (``anvilwave report``).

The report formats what the result folder holds and runs nothing: its marker
(:data:`~anvilwave.output.writer.MARKER`) names the command, whose summary (``summary.json``,
``pda.json`` ...) and tables (CSV) are read and shown in practitioner units (MN or kN, MPa,
kJ, blows/0.25 m and blows/m, m, h); the manifest of the inputs
(:data:`~anvilwave.output.writer.INPUTS_MANIFEST`) gives the input files with their SHA-256
hashes, the settings of the command and the text of every TOML input as run; every PNG
figure of the folder is embedded as a base64 data URI. The page uses no external resource
(inline CSS, no fonts, no network) and prints on A4.

The one inline script writes the count of figures the browser decoded into the
``data-figures`` attribute of the page body (``"decoded/total"``) and their places on the page
into ``data-figure-boxes`` (``"left,top,width,height;..."`` [CSS px]); the page reads the same
without it.
"""

from __future__ import annotations

import base64
import csv
import datetime
import html
import json
import math
import os
import tomllib
from pathlib import Path

from anvilwave.inputs import InputError
from anvilwave.output.writer import (
    INPUTS_DIR,
    INPUTS_MANIFEST,
    MARKER,
    STAGING_PREFIX,
    file_sha256,
    result_command,
    software_version,
)

REPORT_NAME = "report.html"
"""The report's file name in the result folder (``--out`` chooses another file)."""

TITLES = {
    "impact": "Impact: one system's blows",
    "drive": "Driveability against the tip depth",
    "install": "Blow-by-blow installation",
    "batch": "Campaign of driveability cases",
    "compare": "ROM anvil, lumped anvil and reference FEA",
    "match": "Signal matching of a gauge record",
    "pda": "Case method of a gauge record",
    "compare-pda": "Gauge record against the ROM and lumped anvils",
    "demo": "The paper's Table 1 case end to end",
    "fea": "Reference FEA of the driving system",
    "modes": "Free-free modes of an anvil",
    "build-fmus": "FMI units of a system",
}
"""Title of the report of each command's result."""

SUMMARY_FILES = ("summary.json", "pda.json", "match.json", "compare_pda.json",
                 "comparison.json", "modes.json")
"""Summary files shown as tables, when the folder holds them."""

MAX_ROWS = 60
"""Rows of a table shown at most (longer tables are thinned evenly; the CSV has them all)."""

# (SI unit, practitioner unit, factor): the value shown is SI value / factor
_UNITS = {
    "N": ("kN", 1e3),
    "Pa": ("MPa", 1e6),
    "J": ("kJ", 1e3),
    "kg": ("t", 1e3),
    "N/m": ("MN/m", 1e6),
    "1/m": ("blows/m", 1.0),
}
_NAMED = {
    "blows_per_0.25m [-]": ("blows_per_0.25m", "blows/0.25 m", 1.0),
    "driving_time [s]": ("driving_time", "h", 3600.0),
    "set [m]": ("set", "mm", 1e-3),
    "permanent_set [m]": ("permanent_set", "mm", 1e-3),
    "grlweap_set [m]": ("grlweap_set", "mm", 1e-3),
    "toe_soil_set [m]": ("toe_soil_set", "mm", 1e-3),
    "wall_time [s]": ("wall_time", "s", 1.0),
}

CSS = """
body { font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; font-size: 10.5pt;
       color: #111; margin: 24px auto; max-width: 1100px; line-height: 1.35; }
h1 { font-size: 18pt; margin: 0 0 4px 0; }
h2 { font-size: 13pt; border-bottom: 1px solid #999; margin-top: 22px; padding-bottom: 2px; }
h3 { font-size: 11pt; margin: 14px 0 4px 0; }
table { border-collapse: collapse; margin: 6px 0 10px 0; font-size: 9.5pt; }
th, td { border: 1px solid #bbb; padding: 2px 6px; text-align: left; vertical-align: top; }
th { background: #eee; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
.meta td:first-child { font-weight: bold; background: #f6f6f6; }
.hash { font-family: "DejaVu Sans Mono", monospace; font-size: 8.5pt; word-break: break-all; }
pre { font-family: "DejaVu Sans Mono", monospace; font-size: 8.5pt; background: #f6f6f6;
      border: 1px solid #ddd; padding: 6px; white-space: pre-wrap; word-break: break-word; }
figure { margin: 10px 0 16px 0; page-break-inside: avoid; break-inside: avoid; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 9pt; color: #444; }
.note { color: #444; font-size: 9.5pt; }
.wide { overflow-x: auto; }
@media print {
  @page { size: A4; margin: 14mm; }
  body { margin: 0; max-width: none; font-size: 9.5pt; }
  h2 { page-break-after: avoid; break-after: avoid; }
  table, pre { page-break-inside: auto; }
  tr, figure { page-break-inside: avoid; break-inside: avoid; }
  .wide { overflow: visible; }
  .wide table { font-size: 7.5pt; }
}
"""

SCRIPT = """
window.addEventListener("load", function () {
  var images = document.images, decoded = 0, boxes = [];
  for (var i = 0; i < images.length; i++) {
    if (images[i].complete && images[i].naturalWidth > 0) { decoded++; }
    var r = images[i].getBoundingClientRect();
    boxes.push([r.left, r.top + window.scrollY, r.width, r.height].map(Math.round).join(","));
  }
  document.body.setAttribute("data-figures", decoded + "/" + images.length);
  document.body.setAttribute("data-figure-boxes", boxes.join(";"));
});
"""


# ----------------------------------------------------------------------------- values
def practitioner(name: str) -> tuple[str, str, float]:
    """The practitioner unit of a result named ``name [unit]``.

    Parameters
    ----------
    name : str
        A summary key or CSV column, e.g. ``"peak_anvil_pile_force [N]"``.

    Returns
    -------
    label : str
        The name without its unit.
    unit : str
        The unit shown (e.g. ``"kN"``; ``""`` for none).
    factor : float
        The SI value divided by it gives the value shown [-].
    """
    if name in _NAMED:
        return _NAMED[name]
    label, unit = name, ""
    if name.endswith("]") and " [" in name:
        label, unit = name[:-1].rsplit(" [", 1)
    if unit in _UNITS:
        shown, factor = _UNITS[unit]
        if unit == "N" and ("force" in label or label in ("RTL", "RSP", "RMX", "FMX")
                            or label.startswith(("srd", "rut", "driving_weight"))):
            shown, factor = "MN", 1e6
        return label, shown, factor
    return label, "" if unit == "-" else unit, 1.0


def number(value: float) -> str:
    """A number as a report shows it (4 significant digits, no exponent in common ranges).

    Parameters
    ----------
    value : float
        The value.

    Returns
    -------
    str
        Its text; ``"-"`` for NaN.
    """
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return f"{value:d}"
    if not math.isfinite(value):
        return "-" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if value == 0.0:
        return "0"
    if 1e-3 <= abs(value) < 1e6:
        digits = max(0, 3 - int(math.floor(math.log10(abs(value)))))
        return f"{value:.{digits}f}"
    return f"{value:.4g}"


def _text(value) -> str:
    """A summary value as text in its own (already converted) unit."""
    if value is None:
        return "none"
    if isinstance(value, bool | int | float):
        return number(value)
    if isinstance(value, list | tuple):
        if not value:
            return "none"
        if all(isinstance(v, bool | int | float) or v is None for v in value):
            shown = ", ".join(_text(v) for v in value[:8])
            return shown + (f" ... ({len(value)} values)" if len(value) > 8 else "")
        return f"{len(value)} entries"
    return str(value)


def _scaled(value, factor: float):
    if factor == 1.0:
        return value
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, int | float):
        return value / factor
    if isinstance(value, list | tuple):
        return [_scaled(v, factor) for v in value]
    return value


def flatten(content: dict, prefix: str = "") -> list[tuple[str, object]]:
    """The entries of a summary, nested tables flattened to ``outer / inner`` names.

    Lists of tables (per-blow summaries) and tracebacks are left out.

    Parameters
    ----------
    content : dict
        A summary as read from its JSON file.
    prefix : str, default ""
        Prefix of the names (the outer tables').

    Returns
    -------
    list of tuple
        ``(name [unit], value)`` pairs in the file's order.
    """
    rows = []
    for key, value in content.items():
        if key == "traceback":
            continue
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            inner_unit = ""
            if key.endswith("]") and " [" in key:  # a table of one unit: "x [Hz]": {...}
                inner_unit = " [" + key[:-1].rsplit(" [", 1)[1] + "]"
                name = key[:-1].rsplit(" [", 1)[0]
            for k, v in flatten(value, f"{name} / "):
                rows.append((k + (inner_unit if inner_unit and not k.endswith("]") else ""),
                             v))
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            continue
        else:
            rows.append((name, value))
    return rows


# ----------------------------------------------------------------------------- html parts
def _esc(value) -> str:
    return html.escape(str(value), quote=True)


def _words(label: str) -> str:
    """A result name as words (``max_tension_stress`` -> ``max tension stress``): the table
    headers wrap."""
    return label.replace("_", " ")


def _kv_table(entries: list[tuple[str, object]], heading: str = "") -> str:
    """A table of (name [unit], value) rows in practitioner units."""
    if not entries:
        return ""
    rows = []
    for name, value in entries:
        label, unit, factor = practitioner(name)
        shown = _text(_scaled(value, factor))
        cls = ' class="num"' if isinstance(value, int | float) and not isinstance(value, bool) \
            else ""
        rows.append(f"<tr><td>{_esc(_words(label))}</td><td{cls}>{_esc(shown)}</td>"
                    f"<td>{_esc(unit)}</td></tr>")
    head = f"<h3>{_esc(heading)}</h3>\n" if heading else ""
    return (f'{head}<table class="kv"><tr><th>quantity</th><th>value</th><th>unit</th></tr>\n'
            + "\n".join(rows) + "\n</table>\n")


def _column_unit(name: str, values: list) -> tuple[str, str, float]:
    """Practitioner unit of a column; a force column in kN unless it reaches 10 MN."""
    label, unit, factor = practitioner(name)
    if unit == "MN":
        finite = [abs(v) for v in values if isinstance(v, float) and math.isfinite(v)]
        if finite and max(finite) < 1e7:
            unit, factor = "kN", 1e3
    return label, unit, factor


def _rows_table(header: list[str], rows: list[list], heading: str = "",
                note: str = "") -> str:
    """A table of CSV rows (numbers converted to practitioner units, column by column);
    columns without a finite value are left out; more than :data:`MAX_ROWS` rows thinned."""
    if not rows:
        return (f"<h3>{_esc(heading)}</h3>\n" if heading else "") + \
            '<p class="note">(no rows)</p>\n'
    keep = [j for j, _ in enumerate(header)
            if any(not (isinstance(r[j], float) and math.isnan(r[j])) and r[j] != ""
                   for r in rows)]
    shown_rows = rows
    thinned = ""
    if len(rows) > MAX_ROWS:
        step = math.ceil(len(rows) / MAX_ROWS)
        index = sorted(set(range(0, len(rows), step)) | {len(rows) - 1})
        shown_rows = [rows[i] for i in index]
        thinned = (f"{len(shown_rows)} of {len(rows)} rows shown (every {step}th and the "
                   "last); the CSV file holds them all.")
    units = {j: _column_unit(header[j], [r[j] for r in rows]) for j in keep}
    cells = []
    for j in keep:
        label, unit, _ = units[j]
        shown = f"<br>[{_esc(unit)}]" if unit else ""
        cells.append(f"<th>{_esc(_words(label))}{shown}</th>")
    body = []
    for r in shown_rows:
        tds = []
        for j in keep:
            v = r[j]
            if isinstance(v, float):
                tds.append(f'<td class="num">{_esc(number(v / units[j][2]))}</td>')
            else:
                tds.append(f"<td>{_esc(v)}</td>")
        body.append("<tr>" + "".join(tds) + "</tr>")
    head = f"<h3>{_esc(heading)}</h3>\n" if heading else ""
    notes = "".join(f'<p class="note">{_esc(n)}</p>\n' for n in (note, thinned) if n)
    return (f'{head}<div class="wide"><table><tr>{"".join(cells)}</tr>\n' + "\n".join(body)
            + "\n</table></div>\n" + notes)


def read_rows(path: Path) -> tuple[list[str], list[list]]:
    """The header and rows of a CSV result table (numbers as float, the rest as text).

    Parameters
    ----------
    path : Path
        The CSV file.

    Returns
    -------
    header : list of str
        The column names.
    rows : list of list
        The rows; an empty field is NaN in a numeric column.
    """
    with open(path, newline="", encoding="utf-8") as fh:
        table = [row for row in csv.reader(fh) if row and not row[0].startswith("#")]
    if not table:
        return [], []
    header, rows = table[0], []
    for row in table[1:]:
        values = []
        for cell in row:
            try:
                values.append(float(cell) if cell.strip() else math.nan)
            except ValueError:
                values.append(cell)
        rows.append(values + [math.nan] * (len(header) - len(values)))
    return header, rows


def _csv_section(folder: Path, name: str, heading: str, columns: tuple[str, ...] = (),
                 note: str = "") -> str:
    path = folder / name
    if not path.is_file():
        return ""
    header, rows = read_rows(path)
    if columns:
        pick = [header.index(c) for c in columns if c in header]
        header = [header[j] for j in pick]
        rows = [[r[j] for j in pick] for r in rows]
    return _rows_table(header, rows, heading, note)


def _json(path: Path) -> dict | None:
    try:
        content = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return content if isinstance(content, dict) else None


# ----------------------------------------------------------------------------- sections
DRIVE_COLUMNS = ("depth [m]", "srd [N]", "srd_shaft [N]", "srd_toe [N]",
                 "blows_per_0.25m [-]", "blow_count [1/m]", "set [m]", "energy_setting [J]",
                 "enthru [J]", "max_compression_stress [Pa]", "max_tension_stress [Pa]",
                 "max_pile_head_force [N]", "restrike_blow_count [1/m]")
"""Columns of driveability.csv shown in a report."""

BLOW_COLUMNS = ("blow [-]", "tip_depth [m]", "set [m]", "energy_setting [J]", "enthru [J]",
                "max_compression_stress [Pa]", "max_tension_stress [Pa]",
                "max_pile_head_force [N]", "srd [N]")
"""Columns of blows.csv shown in a report."""


def _summaries(folder: Path) -> str:
    parts = []
    for name in SUMMARY_FILES:
        content = _json(folder / name)
        if content is None:
            continue
        if name == "comparison.json":
            parts.append(_comparison(content))
            continue
        parts.append(_kv_table(flatten(content), f"{name}"))
        blows = content.get("blows")
        if isinstance(blows, list) and blows and all(isinstance(b, dict) for b in blows):
            keys = [k for k, v in blows[0].items() if isinstance(v, int | float)
                    and not isinstance(v, bool)]
            parts.append(_rows_table(["blow [-]", *keys],
                                     [[float(i + 1), *[float(b.get(k, math.nan))
                                                       for k in keys]]
                                      for i, b in enumerate(blows)], "Every blow"))
    return "".join(parts)


def _comparison(content: dict) -> str:
    """comparison.json: one column per model (fea, rom, lumped), then the rest."""
    models = [m for m in ("fea", "rom", "lumped") if isinstance(content.get(m), dict)]
    parts = []
    if models:
        names = []
        for m in models:
            for k, v in content[m].items():
                if k not in names and isinstance(v, int | float) and not isinstance(v, bool):
                    names.append(k)
        rows = []
        for k in names:
            label, unit, factor = practitioner(k)
            cells = "".join(
                f'<td class="num">{_esc(_text(_scaled(content[m].get(k), factor)))}</td>'
                for m in models)
            rows.append(f"<tr><td>{_esc(_words(label))}</td><td>{_esc(unit)}</td>{cells}</tr>")
        head = "".join(f"<th>{_esc(m)}</th>" for m in models)
        parts.append("<h3>comparison.json: the models</h3>\n<table><tr><th>quantity</th>"
                     f"<th>unit</th>{head}</tr>\n" + "\n".join(rows) + "\n</table>\n")
    rest = {k: v for k, v in content.items() if k not in models
            and k != "pile_head_force_spectra"}
    parts.append(_kv_table(flatten(rest), "comparison.json: settings"))
    return "".join(parts)


def _drive(folder: Path) -> str:
    parts = [_csv_section(folder, "driveability.csv", "Driveability (driveability.csv)",
                          DRIVE_COLUMNS)]
    for graph in sorted(folder.glob("bearing_graph_*.csv")):
        parts.append(_csv_section(folder, graph.name, f"Bearing graph ({graph.name})"))
    comparison = _json(folder / "anvil_comparison.json")
    if comparison:
        models = list(comparison)
        names = []
        for m in models:
            for k, v in comparison[m].items():
                if k not in names and (isinstance(v, int | float | str) or v is None) \
                        and k != "system":
                    names.append(k)
        rows = []
        for k in names:
            label, unit, factor = practitioner(k)
            cells = "".join(f"<td>{_esc(_text(_scaled(comparison[m].get(k), factor)))}</td>"
                            for m in models)
            rows.append(f"<tr><td>{_esc(_words(label))}</td><td>{_esc(unit)}</td>{cells}</tr>")
        head = "".join(f"<th>{_esc(m)}</th>" for m in models)
        parts.append("<h3>The anvil models (anvil_comparison.json)</h3>\n<table><tr>"
                     f"<th>quantity</th><th>unit</th>{head}</tr>\n" + "\n".join(rows)
                     + "\n</table>\n")
        for m in models[1:]:
            parts.append(_csv_section(folder / m, "driveability.csv",
                                      f"Driveability, {m} anvil ({m}/driveability.csv)",
                                      DRIVE_COLUMNS))
    return "".join(parts)


def _install(folder: Path) -> str:
    return (_csv_section(folder, "fatigue.csv", "Fatigue damage by section (fatigue.csv)")
            + _csv_section(folder, "blows.csv", "Blows (blows.csv)", BLOW_COLUMNS))


def _batch(folder: Path) -> str:
    path = folder / "campaign.csv"
    if not path.is_file():
        return '<p class="note">No campaign.csv in the folder.</p>\n'
    header, rows = read_rows(path)
    status = [r[header.index("status")] for r in rows] if "status" in header else []
    counts = ", ".join(f"{status.count(s)} {s}" for s in ("ok", "error", "pending")
                       if status.count(s))
    note = f"{len(rows)} cases: {counts}." if status else ""
    return _rows_table(header, rows, "Cases (campaign.csv)", note)


SECTIONS = {"drive": _drive, "install": _install, "batch": _batch}
"""Tables of a command's result beyond its summary files."""


def _settings(folder: Path, manifest: dict | None) -> list[tuple[str, object]]:
    """The key settings: the command's options and what the system file and summary say."""
    entries: list[tuple[str, object]] = []
    if manifest:
        for k, v in (manifest.get("arguments") or {}).items():
            if v is not None and v is not False:
                entries.append((f"option --{k.replace('_', '-')}", v))
    system = _system_table(folder, manifest)
    summary = next((c for n in SUMMARY_FILES if (c := _json(folder / n)) is not None), {})
    anvil = system.get("anvil", {})
    hammer = system.get("hammer", {})
    soil = system.get("soil", {})
    simulation = system.get("simulation", {})
    srd = system.get("srd", {})
    pick = [
        ("hammer", hammer.get("database") or hammer.get("file") or hammer.get("name")),
        ("hammer energy [J]", hammer.get("energy")),
        ("ram model", hammer.get("ram_model")),
        ("anvil model", summary.get("anvil_model") or anvil.get("model")),
        ("anvil file", anvil.get("file")),
        ("fmax [Hz]", anvil.get("fmax") or summary.get("fmax [Hz]")),
        ("engine", summary.get("engine")),
        ("time step [s]", simulation.get("time_step") or summary.get("time_step [s]")),
        ("blow window [s]", simulation.get("duration")),
        ("soil model", soil.get("model")),
        ("shaft damping [s/m]", soil.get("damping_shaft")),
        ("toe damping [s/m]", soil.get("damping_toe")),
        ("shaft quake [m]", soil.get("quake_shaft")),
        ("toe quake [m]", soil.get("quake_toe")),
        ("SRD method", srd.get("method")),
        ("SRD bound", summary.get("bound")),
        ("refusal [blows/0.25m]", summary.get("refusal_criterion [blows/0.25m]")),
    ]
    entries += [(k, v) for k, v in pick if v is not None]
    return entries


def _system_table(folder: Path, manifest: dict | None) -> dict:
    """The first TOML input with a [pile] (the system file as run), parsed; {} if none."""
    for entry in (manifest or {}).get("files", []):
        copy = entry.get("copy")
        if not copy or not copy.endswith(".toml"):
            continue
        try:
            table = tomllib.loads((folder / copy).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        if "pile" in table or "campaign" in table:
            return table
    return {}


def _inputs(folder: Path, manifest: dict | None) -> str:
    if manifest is None:
        return ('<p class="note">This result folder records no inputs (no inputs.json: it was '
                "written by a script outside anvilwave.inputs.record_inputs, or by an older "
                "anvilwave).</p>\n")
    rows = []
    for e in manifest.get("files", []):
        copy = e.get("copy")
        state = ""
        if copy and (folder / copy).is_file():
            state = "copy matches" if file_sha256(folder / copy) == e.get("sha256") \
                else "COPY CHANGED since the run"
        elif copy is None:
            state = "not copied (large file)"
        rows.append(f'<tr><td>{_esc(e.get("name"))}</td><td class="num">'
                    f'{_esc(number(int(e.get("bytes", 0))))}</td>'
                    f'<td class="hash">{_esc(e.get("sha256"))}</td><td>{_esc(state)}</td></tr>')
    return ("<h3>Input files</h3>\n<table><tr><th>file</th><th>bytes</th><th>SHA-256</th>"
            "<th>copy in inputs/</th></tr>\n" + "\n".join(rows) + "\n</table>\n")


def _input_texts(folder: Path, manifest: dict | None) -> str:
    """The text of every TOML input as run (the appendix)."""
    parts = []
    for e in (manifest or {}).get("files", []):
        copy = e.get("copy")
        if copy and copy.endswith(".toml") and (folder / copy).is_file():
            text = (folder / copy).read_text(encoding="utf-8", errors="replace")
            parts.append(f"<h3>{_esc(e.get('name'))} (as run)</h3>\n<pre>{_esc(text)}</pre>\n")
    if not parts:
        return ""
    return "<h2>Appendix: the input files as run</h2>\n" + "".join(parts)


MAX_CASE_FIGURES = 6
"""A campaign's case figures (``cases/<case>/*.png``) are embedded up to this many cases; a
larger campaign's report shows its campaign plots only."""


def figures(folder: Path) -> list[Path]:
    """The PNG figures of a result folder, in a report's order.

    The top folder's first, then the sub-folders' (sorted); the input copies and staging
    folders are left out, and the case figures of a campaign of more than
    :data:`MAX_CASE_FIGURES` cases.

    Parameters
    ----------
    folder : Path
        The result folder.

    Returns
    -------
    list of Path
        The PNG files.
    """
    found = [p for p in folder.rglob("*.png")
             if not any(part == INPUTS_DIR or part.startswith((STAGING_PREFIX, "."))
                        for part in p.relative_to(folder).parts[:-1])]
    cases = folder / "cases"
    if cases.is_dir() and sum(1 for c in cases.iterdir() if c.is_dir()) > MAX_CASE_FIGURES:
        found = [p for p in found if not p.is_relative_to(cases)]
    return sorted(found, key=lambda p: (len(p.relative_to(folder).parts),
                                        p.relative_to(folder).as_posix()))


def _figures(folder: Path) -> str:
    parts = []
    for k, path in enumerate(figures(folder), start=1):
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        name = path.relative_to(folder).as_posix()
        parts.append(f'<figure><img src="data:image/png;base64,{data}" alt="{_esc(name)}">'
                     f"<figcaption>Figure {k}: {_esc(name)}</figcaption></figure>\n")
    return "".join(parts) or '<p class="note">No figures in the folder.</p>\n'


# ----------------------------------------------------------------------------- report
def check_result_folder(folder: str | Path) -> str:
    """The command whose result a folder holds; refuse anything else.

    Parameters
    ----------
    folder : str or Path
        The result folder.

    Returns
    -------
    str
        The command named by its marker.

    Raises
    ------
    anvilwave.inputs.InputError
        If the folder is missing, not a folder, or holds no anvilwave result.
    """
    folder = Path(folder)
    if not folder.exists():
        raise InputError(folder, "", "no such result folder")
    if not folder.is_dir():
        raise InputError(folder, "", "is a file, not a result folder")
    command = result_command(folder)
    if command is None:
        raise InputError(folder, "", f"is not an anvilwave result folder (no {MARKER} "
                                     "marker; give a folder written by impact, drive, "
                                     "install, batch, compare, match, pda or compare-pda)")
    return command


def build_report(folder: str | Path, generated: datetime.datetime | None = None) -> str:
    """The HTML text of the report of a result folder (module docstring).

    Parameters
    ----------
    folder : str or Path
        The result folder.
    generated : datetime.datetime, optional
        The time of generation shown (default: now, local time).

    Returns
    -------
    str
        One self-contained HTML document.

    Raises
    ------
    anvilwave.inputs.InputError
        If ``folder`` holds no anvilwave result (:func:`check_result_folder`).
    """
    folder = Path(folder)
    command = check_result_folder(folder)
    manifest = _json(folder / INPUTS_MANIFEST)
    when = (generated or datetime.datetime.now().astimezone()).isoformat(timespec="seconds")
    title = f"{TITLES.get(command, command)}: {folder.resolve().name}"
    meta = [("result of", f"anvilwave {command}"), ("result folder", folder.resolve().name),
            ("report generated", when),
            ("report by", f"anvilwave {software_version()}")]
    if manifest:
        meta += [("result written", manifest.get("written", "unknown")),
                 ("result by", f"anvilwave {manifest.get('anvilwave_version', 'unknown')}")]
    meta_rows = "\n".join(f"<tr><td>{_esc(k)}</td><td>{_esc(v)}</td></tr>" for k, v in meta)
    sections = SECTIONS.get(command)
    body = [
        f"<h1>{_esc(title)}</h1>\n",
        f'<table class="meta">\n{meta_rows}\n</table>\n',
        "<h2>Inputs and assumptions</h2>\n",
        _kv_table(_settings(folder, manifest), "Key settings"),
        _inputs(folder, manifest),
        "<h2>Results</h2>\n",
        '<p class="note">SI results in practitioner units: forces in kN or MN, stresses in '
        "MPa, energies in kJ, blow counts in blows/0.25 m and blows/m, sets in mm, depths in "
        "m, driving times in h. Compression is positive, tension negative.</p>\n",
        _summaries(folder),
        sections(folder) if sections else "",
        "<h2>Figures</h2>\n",
        _figures(folder),
        _input_texts(folder, manifest),
        f'<p class="note">Generated by anvilwave {_esc(software_version())} on {_esc(when)} '
        "from the files of the result folder.</p>\n",
    ]
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{_esc(title)}</title>\n<style>{CSS}</style>\n<script>{SCRIPT}</script>\n"
            "</head>\n<body>\n" + "".join(body) + "</body>\n</html>\n")


def write_report(folder: str | Path, out: str | Path | None = None) -> Path:
    """Write the report of a result folder (``anvilwave report``).

    Parameters
    ----------
    folder : str or Path
        The result folder.
    out : str or Path, optional
        The HTML file (default: :data:`REPORT_NAME` in the folder).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    anvilwave.inputs.InputError
        If ``folder`` holds no anvilwave result, or ``out`` cannot be written (naming
        ``--out``).
    """
    folder = Path(folder)
    text = build_report(folder)
    target = Path(out) if out is not None else folder / REPORT_NAME
    if target.is_dir():
        raise InputError("--out", "", f"{target}: is a folder (give the report's file name)")
    tmp = target.with_name(f".{target.name}.{os.getpid()}.part")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, target)
    except OSError as exc:
        try:
            tmp.unlink()
        except OSError:
            pass
        raise InputError("--out", "", f"{target}: cannot be written "
                                      f"({exc.strerror or exc})") from None
    return target
