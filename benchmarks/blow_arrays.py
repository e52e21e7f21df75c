"""Every array the in-process engine's blows record, saved to compare two revisions to the bit.

Run: python benchmarks/blow_arrays.py OUT.npz [--quick]
     python benchmarks/blow_arrays.py --compare A.npz B.npz

The first form runs, with the anvilwave on ``sys.path`` (``PYTHONPATH`` pointing at a checkout
runs that revision), blows that take every path of the compiled loop
(:func:`anvilwave.engine.direct.run_blow`) and saves to OUT.npz, per blow, every recorded column,
every energy series, the final pile state (u, v, soil offsets, energies and works), the section
strains and the summary's numbers. The configurations: Table 1 (anvilwave/examples/table1.toml)
with each ram model (the modal ram unit, its chain, the hammer's Smith rod, a rigid ram) and each
anvil model (rom, lumped, classic, none), the last two rams also with the contact dashpots off
and on the pile side; the pile port in three rings (``pile_port_rings``) on the 1D head, undamped,
and on the tube head (``pile_head = "tube"``); table1_interfaces.toml (six ram annuli on the
rings, rom and lumped); the XL monopile's driveability blows at three tip depths (soil, static
state, consecutive blows) for rom, lumped and classic. Each configuration runs its blow recorded
with and without the energy bookkeeping, summary only with and without it, the energy at every
step, a record interval of three steps, and (rom, rings, interfaces) chosen pile sections; then
consecutive blows. ``--quick`` runs the recorded blow with the energy bookkeeping only.

The second form compares two such files: the same names, and each array the same dtype, shape
and bytes (NaN equal to NaN). It prints the count and exits with status 1 if any differs.

The wall times are not stored (they differ from run to run).
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

import anvilwave
from anvilwave.config.cache import cached_chain
from anvilwave.config.drive import load_srd_source, pile_soil_at
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.hammer.database import load_hammer
from anvilwave.hammer.modal_ram import modal_ram_chain
from anvilwave.hammer.ram import RamRod

EXAMPLES = Path(anvilwave.__file__).resolve().parent / "examples"
SUMMARY = ("max_compression_stress", "max_tension_stress", "emx_gauge", "emx_head",
           "max_pile_head_force", "max_toe_displacement", "permanent_set", "toe_velocity_end",
           "input_energy", "time_step", "n_steps")
FINAL = ("u", "v", "soil_offset", "energy")


def blow_arrays(name: str, result) -> dict[str, np.ndarray]:
    """The arrays of one blow's result, named ``name|...``."""
    arrays = {f"{name}|col|{k}": np.asarray(v) for k, v in result.columns.items()}
    arrays.update({f"{name}|en|{k}": np.asarray(v) for k, v in result.energies.items()})
    arrays.update({f"{name}|final|{k}": np.asarray(getattr(result.final_state, k))
                   for k in FINAL})
    arrays[f"{name}|summary"] = np.array([getattr(result, k) for k in SUMMARY], dtype=float)
    if result.section_strain is not None:
        arrays[f"{name}|sections"] = np.asarray(result.section_strain)
    return arrays


def with_anvil(cfg, **changes):
    return dataclasses.replace(cfg, anvil=dataclasses.replace(cfg.anvil, **changes))


def table1_configurations():
    """(name, configuration, sections) of Table 1: ram models x anvil models, then the pile port
    in rings and the interfaces' example."""
    cfg = load_system(EXAMPLES / "table1.toml")
    ram = cfg.hammer.ram
    rams = {
        "unit": cfg,
        "chain": dataclasses.replace(cfg, hammer=dataclasses.replace(
            cfg.hammer, ram=modal_ram_chain(ram, ram.modes, cached_chain))),
        "rod": dataclasses.replace(cfg, hammer=load_hammer("illustrative_5500kj")),
        "rigid": with_anvil(dataclasses.replace(cfg, hammer=dataclasses.replace(
            cfg.hammer, ram=RamRod.rigid(275e3, 1.8))), ram_contact_stiffness=2.0e11),
        "undamped": with_anvil(cfg, ram_contact_damping=0.0),
        "piledamped": with_anvil(cfg, pile_contact_damping=3.0e7),
    }
    for ram_name, base in rams.items():
        for model in ("rom", "lumped", "classic", "none"):
            yield f"{ram_name}|{model}", base.with_anvil_model(model), model == "rom"
    spec = cfg.anvil.spec
    rings = with_anvil(cfg, spec=dataclasses.replace(
        spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=3)))
    yield "rings", rings, True
    yield "rings-undamped", with_anvil(rings, ram_contact_damping=0.0), False
    yield "rings-tube", with_anvil(rings, pile_head="tube"), True
    faces = load_system(EXAMPLES / "table1_interfaces.toml")
    yield "interfaces", faces, True
    yield "interfaces-lumped", faces.with_anvil_model("lumped"), False


def run(quick: bool) -> dict[str, np.ndarray]:
    """Every configuration's blows (module docstring)."""
    arrays: dict[str, np.ndarray] = {}
    for name, cfg, sections in table1_configurations():
        engine = build_engine(cfg)  # the anvil's modes from the modal-data cache
        print(name, file=sys.stderr, flush=True)
        arrays.update(blow_arrays(f"{name}|rec+energy", engine.blow()))
        if quick:
            continue
        h = engine.time_step
        arrays.update(blow_arrays(f"{name}|rec", engine.blow(energy=False)))
        arrays.update(blow_arrays(f"{name}|summary", engine.blow(record=False)))
        arrays.update(blow_arrays(f"{name}|summary+energy",
                                  engine.blow(record=False, energy=True)))
        arrays.update(blow_arrays(f"{name}|energy-every-step", engine.blow(energy_interval=h)))
        arrays.update(blow_arrays(f"{name}|interval", engine.blow(record_interval=3 * h)))
        if sections:
            arrays.update(blow_arrays(f"{name}|sections", engine.blow(sections=[0, 5, 40])))
            arrays.update(blow_arrays(f"{name}|sections-summary",
                                      engine.blow(record=False, sections=[1, 7])))
        for i, result in enumerate(engine.run(blows=2)):
            arrays.update(blow_arrays(f"{name}|run2|{i}", result))
    xl = load_system(EXAMPLES / "xl_monopile_drive.toml")
    srd = xl.srd if xl.srd is not None else load_srd_source(None, xl.source, xl.pile_soil)
    for model in ("rom", "lumped", "classic"):
        print(f"xl {model}", file=sys.stderr, flush=True)
        engine = build_engine(xl.with_anvil_model(model))
        arrays.update(blow_arrays(f"xl|{model}|default", engine.blow()))
        for depth in ((25.0,) if quick else (8.0, 25.0, 40.0)):
            pile_soil, _, _ = pile_soil_at(xl.pile_soil, srd, depth, 1.0)
            at_depth = engine.with_pile_soil(pile_soil)
            state = at_depth.static_state()
            name = f"xl|{model}|{depth:g}"
            arrays.update(blow_arrays(f"{name}|summary+energy",
                                      at_depth.blow(state, record=False, energy=True)))
            if quick:
                continue
            arrays.update(blow_arrays(f"{name}|summary", at_depth.blow(state, record=False)))
            for i, result in enumerate(at_depth.run(blows=2)):
                arrays.update(blow_arrays(f"{name}|run2|{i}", result))
    return arrays


def compare(first: Path, second: Path) -> int:
    """Print how many arrays of the two files differ; 1 if any does or the names differ."""
    a, b = np.load(first), np.load(second)
    names_a, names_b = set(a.files), set(b.files)
    if names_a != names_b:
        print(f"names differ: only in {first}: {sorted(names_a - names_b)[:5]}, only in "
              f"{second}: {sorted(names_b - names_a)[:5]}")
        return 1
    differ = [k for k in sorted(names_a)
              if a[k].dtype != b[k].dtype or a[k].shape != b[k].shape
              or a[k].tobytes() != b[k].tobytes()]
    values = sum(a[k].size for k in names_a)
    print(f"{len(names_a)} arrays ({values} values) compared, {len(differ)} differ")
    for k in differ[:20]:
        print(f"  {k}: largest difference {np.nanmax(np.abs(a[k] - b[k])):.3e}")
    return 1 if differ else 0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", type=Path, help="the .npz to write")
    parser.add_argument("--quick", action="store_true",
                        help="one recorded blow with the energy per configuration")
    parser.add_argument("--compare", nargs=2, type=Path, metavar=("A", "B"),
                        help="compare two files written by this script")
    args = parser.parse_args()
    if args.compare:
        sys.exit(compare(*args.compare))
    if args.out is None:
        parser.error("give OUT.npz or --compare A B")
    print("anvilwave from", anvilwave.__file__, file=sys.stderr)
    arrays = run(args.quick)
    np.savez(args.out, **arrays)
    print(f"{len(arrays)} arrays saved to {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
