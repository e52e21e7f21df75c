"""The XL monopile's driveability with three anvil models, for the docs: docs/data/xl_drive.json.

Run: python benchmarks/doc_xl_drive.py (a few seconds)

``anvilwave drive anvilwave/examples/xl_monopile_drive.toml --compare-anvils``: the ROM, the
rigid lumped anvil and the classic helmet-and-cushion model, each over the file's 39 tip
depths; per model the total blows, the largest blow count, compression and tension stress along
the pile, and ENTHRU at the last depth (docs/drive.md's table, differences against the ROM).
tests/test_doc_tables.py reruns the three drives and checks the file.
"""

from __future__ import annotations

from pathlib import Path

from doc_data import system_inputs, write_doc_data

import anvilwave

ROOT = Path(__file__).resolve().parents[1]
SYSTEM = ROOT / "anvilwave" / "examples" / "xl_monopile_drive.toml"
MODELS = {"rom": "ROM (Mode Displacement Method)", "lumped": "lumped (rigid FE mass)",
          "classic": "classic (helmet and cushion)"}


def figures(result) -> dict:
    """The table's figures of one drive."""
    last = max(result.rows, key=lambda r: r["depth [m]"])
    hardest = max(result.rows, key=lambda r: r["blow_count [1/m]"])
    return {
        "total_blows [-]": result.summary["total_blows [-]"],
        "max_blow_count [1/m]": hardest["blow_count [1/m]"],
        "max_blow_count_depth [m]": hardest["depth [m]"],
        "max_compression_stress [Pa]": result.summary["max_compression_stress [Pa]"],
        "max_tension_stress [Pa]": result.summary["max_tension_stress [Pa]"],
        "last_depth [m]": last["depth [m]"],
        "enthru_last_depth [J]": last["enthru [J]"],
        "refusal_depth [m]": result.summary["refusal_depth [m]"],
    }


def compute() -> dict[str, dict]:
    return {model: figures(anvilwave.drive(SYSTEM, anvil=model, workers=1)) for model in MODELS}


def _with_difference(value: float, rom: float, text: str) -> str:
    """``text``, and the difference against the ROM's value in % unless it is the ROM's."""
    if value != rom:
        text = f"{text} ({100.0 * (value / rom - 1.0):+.0f} %)"
    return text.replace("-", "\u2212")


def main() -> None:
    values = compute()
    rom = values["rom"]
    last = rom["last_depth [m]"]
    rows = []
    for model, label in MODELS.items():
        v = values[model]
        rows.append([
            label,
            _with_difference(v["total_blows [-]"], rom["total_blows [-]"],
                             f"{v['total_blows [-]']:d}"),
            v["max_blow_count [1/m]"],
            _with_difference(v["max_compression_stress [Pa]"], rom["max_compression_stress [Pa]"],
                             f"{v['max_compression_stress [Pa]'] / 1e6:.0f} MPa"),
            _with_difference(v["max_tension_stress [Pa]"], rom["max_tension_stress [Pa]"],
                             f"{v['max_tension_stress [Pa]'] / 1e6:.0f} MPa"),
            v["enthru_last_depth [J]"]])
    table = {"columns": ["anvil model", "total blows", "max blow count", "max compression",
                         "max tension", f"ENTHRU at {last:.0f} m"],
             "formats": [None, None, "per_m0", None, None, "MJ2"], "rows": rows}
    lumped = values["lumped"]
    subs = {
        "lumped_compression_low": [
            1.0 - lumped["max_compression_stress [Pa]"] / rom["max_compression_stress [Pa]"],
            "pct"],
        "lumped_tension_low": [
            1.0 - lumped["max_tension_stress [Pa]"] / rom["max_tension_stress [Pa]"], "pct"],
        "rom_more_blows": [rom["total_blows [-]"] / lumped["total_blows [-]"] - 1.0, "pct"],
    }
    write_doc_data(
        "xl_drive", about="The XL monopile driven with three anvil models (docs/drive.md, \"The "
        "paper's open question\").", inputs=system_inputs(SYSTEM), tables={"anvils": table},
        substitutions=subs, values=values)


if __name__ == "__main__":
    main()
