"""anvilwave on the GRLWEAP S-4000 benchmark input, for the docs: docs/data/grlweap_s4000.json.

Run: python benchmarks/doc_grlweap.py (a few seconds; needs ../shared/reference/grlweap-s4000)

``anvilwave drive`` on anvilwave/examples/grlweap_s4000.toml (GRLWEAP's conventions, its 50 SRD
tables read from the shared folder where they lie) and once more with anvilwave's own defaults
for the three conventions that set the blow count most (the whole blow window, every weight on
the soil, the tables blended between tip depths): the rows of docs/drive.md's table (tip depths
of :data:`TABLE_DEPTHS`), the total blows and the pile runs. Only anvilwave's numbers: GRLWEAP's
own results are not in the shared folder (its input is), so none is shown; the one reference
value quoted is the input's static weight on the soil (model.json). tests/test_doc_tables.py
reruns both drives and checks the file.
"""

from __future__ import annotations

import json
import os
import re
import tempfile
from pathlib import Path

from doc_data import system_inputs, write_doc_data

import anvilwave

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"
SYSTEM = EXAMPLES / "grlweap_s4000.toml"
MODEL = ROOT.parent / "shared" / "reference" / "grlweap-s4000" / "model.json"
TABLE_DEPTHS = (10.0, 20.0, 30.0, 50.0)
"""[m] the tip depths of the docs' table."""
OWN_DEFAULTS = ("window", "weight_on_soil", "tip_table_rule")
"""The keys that the second run leaves at anvilwave's defaults."""
WEIGHT_KEY = "static_weight_on_soil [kN] (pile + helmet + assembly; GRLWEAP 'Total Wt')"

COLUMNS = {
    "tip depth": ("m0", "depth [m]"),
    "SRD": ("MN", "srd [N]"),
    "blow count": ("per_m1", "blow_count [1/m]"),
    "max compression": ("MPa0", "max_compression_stress [Pa]"),
    "max tension": ("MPa0", "max_tension_stress [Pa]"),
    "ENTHRU (head)": ("MJ2", "enthru [J]"),
}
"""The columns of docs/drive.md's table: (format, driveability.csv column)."""


def system_text(own_defaults: bool) -> str:
    """grlweap_s4000.toml with its files as absolute paths and, with ``own_defaults``, the keys
    of :data:`OWN_DEFAULTS` removed."""
    text = SYSTEM.read_text()
    text = re.sub(r'^(\s*file\s*=\s*")([^"]+)"',
                  lambda m: f'{m[1]}{os.path.abspath(EXAMPLES / m[2])}"', text, flags=re.M)
    if own_defaults:
        for key in OWN_DEFAULTS:
            text, n = re.subn(rf"^{key}\s*=.*$\n", "", text, flags=re.M)
            assert n == 1, key
    return text


def run(own_defaults: bool) -> anvilwave.DriveResult:
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / SYSTEM.name
        path.write_text(system_text(own_defaults))
        return anvilwave.drive(path, workers=1)


def row_at(result, depth: float) -> dict:
    return next(r for r in result.rows if r["depth [m]"] == depth)


def depths_text(depths: list[float]) -> str:
    """``5 m``, ``4-6 m`` (consecutive metres), ``1 and 5 m``."""
    depths = [round(d) for d in depths]
    if not depths:
        return "none"
    if len(depths) > 1 and depths == list(range(depths[0], depths[-1] + 1)):
        return f"{depths[0]}-{depths[-1]} m"
    return " and ".join(str(d) for d in depths) + " m"


def reference_weight() -> float:
    """[N] the input's static weight on the soil, pile + helmet + assembly (model.json)."""
    return json.loads(MODEL.read_text())["numerics"][WEIGHT_KEY] * 1e3


def refusal_text(depth: float | None) -> str:
    return "no refusal" if depth is None else f"refusal at {depth:.1f} m"


def main() -> None:
    grlweap, own = run(False), run(True)
    table = {"columns": list(COLUMNS), "formats": [f for f, _ in COLUMNS.values()],
             "rows": [[row_at(grlweap, d)[k] for _, k in COLUMNS.values()]
                      for d in TABLE_DEPTHS]}
    runs = grlweap.summary["pile_run_depths [m]"]
    last = max(r["depth [m]"] for r in grlweap.rows)
    reference = reference_weight()
    subs = {
        "total_blows": [grlweap.summary["total_blows [-]"], "int"],
        "last_depth": [last, "m0"],
        "refusal": [refusal_text(grlweap.summary["refusal_depth [m]"]), None],
        "pile_runs": [depths_text(runs), None],
        "pile_run_srd": [row_at(grlweap, runs[0])["srd [N]"] if runs else None, "MN2"],
        "reference_weight": [reference, "MN2"],
        "reference_weight_kn": [reference, "kN1"],
        "own_defaults_total_blows": [own.summary["total_blows [-]"], "int"],
        "own_defaults_pile_runs": [depths_text(own.summary["pile_run_depths [m]"]), None],
    }
    keep = ("total_blows [-]", "refusal_depth [m]", "pile_run_depths [m]",
            "self_weight_penetration [m]")
    write_doc_data(
        "grlweap_s4000", about="anvilwave's driveability on the GRLWEAP S-4000 benchmark input "
        "(docs/drive.md, \"The GRLWEAP benchmark\"); GRLWEAP's own results are not shown.",
        inputs=system_inputs(SYSTEM), tables={"depths": table}, substitutions=subs,
        values={"grlweap_conventions": {"rows": [row_at(grlweap, d) for d in TABLE_DEPTHS],
                                        **{k: grlweap.summary[k] for k in keep}},
                "own_defaults": {k: own.summary[k] for k in keep},
                "reference_weight [N]": reference})


if __name__ == "__main__":
    main()
