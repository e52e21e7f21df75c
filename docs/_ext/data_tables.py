"""The docs' measured numbers, rendered at build time from docs/data/*.json.

A page never types a measured number: a study or benchmark script writes its results to
``docs/data/NAME.json`` (benchmarks/doc_data.py describes the file) and the page shows them with

* a table: a fenced block ``{data-table} NAME TABLE`` (no content), rendered as a markdown table
  with a line naming the data file and the command that wrote it;
* an inline number: ``{{ NAME_KEY }}``, a MyST substitution set from the file's
  ``substitutions`` (:func:`substitutions`, called by docs/conf.py).

Numbers are formatted here, by the formats of :data:`FORMATS`, never in the data files: the
files keep the raw results that the tests compare.
"""

from __future__ import annotations

import json
import math
from functools import cache
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.util.docutils import SphinxDirective

DATA = Path(__file__).resolve().parents[1] / "data"
MINUS = "\u2212"


def _signed(text: str, value: float, sign: bool) -> str:
    if text.startswith("-"):
        return MINUS + text[1:]
    return ("+" + text) if sign else text


def _decimals_below_ten(value: float) -> int:
    """One decimal below 10, none from 10 on: two significant digits for 1 <= |x| < 100."""
    return 1 if abs(value) < 9.95 else 0


def _sig2(value: float) -> str:
    """Two significant digits, no exponent (38, 9.8, 0.72)."""
    if value == 0:
        return "0"
    digits = max(0, 1 - math.floor(math.log10(abs(value))))
    text = f"{round(value, digits):.{digits}f}"
    return text


def percent(value: float, sign: bool = False) -> str:
    """A fraction as a percentage: ``+14 %``, ``−4.4 %``."""
    x = 100.0 * value
    return _signed(f"{x:.{_decimals_below_ten(x)}f}", x, sign) + " %"


def milliseconds(value: float, sign: bool = True) -> str:
    """A time [s] in ms: two decimals below 1 ms, one above (``+0.04 ms``, ``−2.9 ms``)."""
    x = 1e3 * value
    return _signed(f"{x:.{2 if abs(x) < 0.995 else 1}f}", x, sign) + " ms"


FORMATS = {
    "int": lambda v: _signed(f"{round(v):d}", v, False),
    "int+": lambda v: _signed(f"{round(v):d}", v, True),
    "sig2": lambda v: _signed(_sig2(v), v, False),
    "f1": lambda v: _signed(f"{v:.1f}", v, False),
    "f2": lambda v: _signed(f"{v:.2f}", v, False),
    "f3": lambda v: _signed(f"{v:.3f}", v, False),
    "f1+": lambda v: _signed(f"{v:.1f}", v, True),
    "f2+": lambda v: _signed(f"{v:.2f}", v, True),
    "pct": lambda v: percent(v),
    "pct+": lambda v: percent(v, sign=True),
    "pct+sig2": lambda v: _signed(_sig2(100.0 * v), v, True) + " %",
    "pct+2": lambda v: _signed(f"{100.0 * v:.2f}", v, True) + " %",
    "pct+3": lambda v: _signed(f"{100.0 * v:.3f}", v, True) + " %",
    "pctsig2": lambda v: _signed(_sig2(100.0 * v), v, False) + " %",
    "pct1": lambda v: _signed(f"{100.0 * v:.1f}", v, False) + " %",
    "ms+": lambda v: milliseconds(v),
    "ms": lambda v: milliseconds(v, sign=False),
    "ms2": lambda v: _signed(f"{v * 1e3:.2f}", v, False) + " ms",
    "dB": lambda v: _signed(f"{v:.1f}", v, False) + " dB",
    "dB2": lambda v: _signed(f"{v:.2f}", v, False) + " dB",
    "dB+": lambda v: _signed(f"{v:.1f}", v, True),
    "MN": lambda v: _signed(f"{v / 1e6:.1f}", v, False) + " MN",
    "MN2": lambda v: _signed(f"{v / 1e6:.2f}", v, False) + " MN",
    "MN0": lambda v: _signed(f"{v / 1e6:.0f}", v, False) + " MN",
    "MPa0": lambda v: _signed(f"{v / 1e6:.0f}", v, False) + " MPa",
    "kJ0": lambda v: _signed(f"{v / 1e3:.0f}", v, False) + " kJ",
    "MJ2": lambda v: _signed(f"{v / 1e6:.2f}", v, False) + " MJ",
    "kN1": lambda v: _signed(f"{v / 1e3:.1f}", v, False) + " kN",
    "per_m0": lambda v: _signed(f"{v:.0f}", v, False) + " /m",
    "per_m1": lambda v: _signed(f"{v:.1f}", v, False) + " /m",
    "m0": lambda v: _signed(f"{v:.0f}", v, False) + " m",
    "us1": lambda v: _signed(f"{v * 1e6:.1f}", v, False) + " µs",
    "t1": lambda v: _signed(f"{v / 1e3:.1f}", v, False) + " t",
}
"""Format name -> function of the raw value (SI units as the data file stores them)."""


def render(value, fmt: str | None) -> str:
    """The text of one cell or substitution."""
    if value is None:
        return ""
    if isinstance(value, str):
        return value
    if fmt is None:
        raise ValueError(f"number {value!r} without a format")
    return FORMATS[fmt](value)


@cache
def load(name: str) -> dict:
    """The data file ``docs/data/NAME.json``."""
    return json.loads((DATA / f"{name}.json").read_text(encoding="utf-8"))


def table_lines(name: str, table: str) -> list[str]:
    """The markdown lines of one table of a data file, and the line naming its source."""
    data = load(name)
    spec = data["tables"][table]
    formats = spec["formats"]
    lines = ["| " + " | ".join(spec["columns"]) + " |",
             "|" + "---|" * len(spec["columns"])]
    for row in spec["rows"]:
        bold = isinstance(row, dict) and row.get("bold", False)
        cells = row["cells"] if isinstance(row, dict) else row
        if len(cells) != len(formats):
            raise ValueError(f"{name}.json, table {table}: a row of {len(cells)} cells, "
                             f"{len(formats)} columns")
        texts = [render(c, f) for c, f in zip(cells, formats, strict=True)]
        if bold:
            texts = [f"**{t}**" if t else t for t in texts]
        lines.append("| " + " | ".join(texts) + " |")
    lines += ["", f"*Computed by `{data['command']}` (anvilwave {data['anvilwave_version']}); "
                  f"data: `docs/data/{name}.json`.*"]
    return lines


def substitutions() -> dict[str, str]:
    """``NAME_KEY`` -> text of every data file's substitutions (docs/conf.py sets them as
    ``myst_substitutions``)."""
    out = {}
    for path in sorted(DATA.glob("*.json")):
        for key, (value, fmt) in load(path.stem)["substitutions"].items():
            out[f"{path.stem}_{key}"] = render(value, fmt)
    return out


class DataTable(SphinxDirective):
    """``{data-table} NAME TABLE``: the table TABLE of docs/data/NAME.json."""

    required_arguments = 2
    has_content = False

    def run(self):
        name, table = self.arguments
        self.env.note_dependency(str(DATA / f"{name}.json"))
        try:
            lines = table_lines(name, table)
        except (OSError, KeyError, ValueError) as exc:
            raise self.error(f"data-table {name} {table}: {exc!r}") from None
        container = nodes.container(classes=["data-table"])
        self.state.nested_parse(StringList(lines, source=f"docs/data/{name}.json"),
                                self.content_offset, container)
        return [container]


def setup(app):
    app.add_directive("data-table", DataTable)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
