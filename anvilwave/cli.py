"""The ``anvilwave`` command line."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from anvilwave import api
from anvilwave.analyses.compare import (
    ModelRun,
    band_levels,
    compare,
    comparison_bandwidth,
    fea_config,
    metrics,
    plot_comparison,
    plot_spectra,
    run_models,
    without_soil,
)
from anvilwave.analyses.drive import (
    available_anvil_models,
    drive_bearing_graph,
    write_anvil_comparison,
)
from anvilwave.analyses.impact import write_blows
from anvilwave.anvil_rom.fem.calculix import write_ccx_deck_from_mesh
from anvilwave.anvil_rom.fem.geometry import load_anvil
from anvilwave.anvil_rom.fem.modalfile import save_modal_data
from anvilwave.anvil_rom.fem.modes import ModeSolveError
from anvilwave.anvil_rom.fem.pipeline import anvil_modes_from_calculix, compute_anvil_modes
from anvilwave.config.cache import cache_info, clear_cache
from anvilwave.config.schema import describe
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.engine.fmus import build_system_fmus
from anvilwave.fea.impact import run_impact_fea
from anvilwave.fmu.native_build import NativeBuildError
from anvilwave.inputs import InputError, record_inputs
from anvilwave.output.examples import EXAMPLES_DIR, copy_examples
from anvilwave.output.plots import plot_columns, plot_modes
from anvilwave.output.progress import Step
from anvilwave.output.report import REPORT_NAME
from anvilwave.output.tables import write_csv
from anvilwave.output.writer import ResultWriter, check_output


def _modes(args: argparse.Namespace) -> int:
    check_output(args.out, "modes", args.force)

    spec = load_anvil(args.anvil)
    if args.mesh_size is not None:
        if args.mesh_size <= 0:
            raise InputError("--mesh-size", "", f"must be positive, got {args.mesh_size:g} m")
        if spec.outline is None:
            raise InputError("--mesh-size", "", "only applies to anvils given as [geometry] "
                                                "points (this one reads a mesh file)")
        spec = type(spec)(**{**spec.__dict__, "mesh_size": args.mesh_size})
    if args.fmax is not None and args.fmax <= 0:
        raise InputError("--fmax", "", f"must be positive, got {args.fmax:g} Hz")
    if args.from_calculix is not None:
        result = anvil_modes_from_calculix(spec, args.from_calculix, fmax=args.fmax)
    else:
        result = compute_anvil_modes(spec, fmax=args.fmax)
    with ResultWriter(args.out, command="modes", force=args.force) as out:
        summary = {
            "anvil": Path(args.anvil).name,
            "frequencies [Hz]": [float(f) for f in result.modes.frequencies],
            "total_mass [kg]": result.model.total_mass(),
            "fmax [Hz]": result.modes.fmax,
            "n_modes": result.modes.n_modes,
            "n_dof": result.model.n_dof,
            "sturm_count": result.modes.sturm_count,
            "rigid_mode_computed [Hz]": result.modes.rigid_frequency_computed,
            "mesh_elements": int(result.model.mesh.t.shape[1]),
            "wall_time [s]": result.wall_time,
        }
        if result.modal_data is not None:
            save_modal_data(result.modal_data, out.part("modes.npz"))
        else:
            summary["note"] = "no [interfaces] in the anvil file: modes.npz (the ROM) not written"
        out.part("modes.json").write_text(json.dumps(summary, indent=2) + "\n")
        plot_modes(result, out.part("modes.png"))
        if args.export_ccx is not None:

            write_ccx_deck_from_mesh(args.export_ccx, result.mesh, spec.material,
                                     result.modes.n_modes, title=spec.name)
    print(f"{spec.name}: {result.modes.n_modes} modes up to {result.modes.fmax:g} Hz, "
          f"{result.model.n_dof} DOF, {result.wall_time:.1f} s -> {args.out}")
    return 0


def _impact(args: argparse.Namespace) -> int:
    check_output(args.out, "impact", args.force)
    cfg = load_system(args.system)
    blows = api.simulate(cfg, engine=args.engine, anvil=args.anvil, progress=True)
    model = blows[0].summary["anvil_model"]
    with ResultWriter(args.out, command="impact", force=args.force) as out:
        write_blows(blows, out, system=str(args.system),
                    title=f"{Path(args.system).name}: {model} anvil, {args.engine} engine")
    s = blows[0].summary
    print(f"{Path(args.system).name} [{model}, {args.engine}]: peak ram-anvil "
          f"{s['peak_ram_anvil_force [N]'] / 1e6:.1f} MN, anvil-pile "
          f"{s['peak_anvil_pile_force [N]'] / 1e6:.1f} MN; "
          f"{s['simulated_time [s]'] * 1e3:.1f} ms in {s['wall_time [s]']:.4f} s "
          f"({s['realtime_factor [-]']:.3g}x real time) -> {args.out}")
    _maybe_report(args)
    return 0


def _maybe_report(args: argparse.Namespace) -> None:
    """The report of the result just written, with ``--report``."""
    if getattr(args, "report", False):
        print(f"report -> {api.report(args.out)}")


def _report(args: argparse.Namespace) -> int:
    target = api.report(args.result_dir, args.out)
    print(f"report -> {target}")
    return 0


def _build_fmus(args: argparse.Namespace) -> int:
    check_output(args.out, "build-fmus", args.force)
    try:
        with ResultWriter(args.out, command="build-fmus", force=args.force) as out:
            built = api.build_fmus(args.system, out.staging, anvil=args.anvil,
                                   native_anvil=not args.python_anvil,
                                   native_units=False if args.python_units else None,
                                   fmi_version=args.fmi_version)
    except NativeBuildError as exc:
        raise InputError(str(args.system), "", f"the native anvil FMU cannot be built "
                                               f"({_one_line(exc)}); --python-anvil builds "
                                               "the Python one") from None
    names = ", ".join(Path(built[k]).name for k in ("Ram", "Anvil", "AnvilLumped", "AnvilStack",
                                                    "PileSoil", "ssp") if k in built)
    print(f"{names} -> {args.out} (anvils: {built['anvil_implementation']}, ram: "
          f"{built['ram_implementation']}, pile/soil: {built['pile_soil_implementation']}; "
          f"system.ssp uses "
          f"{built['anvil']} with input extrapolation, step {built['ssp_step'] * 1e6:.3g} us "
          f"= engine step {built['time_step'] * 1e6:.3g} us / "
          f"{built['time_step'] / built['ssp_step']:.0f})")
    return 0


def _fea(args: argparse.Namespace) -> int:
    check_output(args.out, "fea", args.force)

    cfg = without_soil(load_system(args.system))
    config = fea_config(cfg, mesh_size=args.mesh_size, truncate_length=args.truncate)
    with _progress("FEA") as progress:
        result = run_impact_fea(config, progress=progress)
    columns = result.to_columns()
    summary = {
        "system": Path(args.system).name,
        "model": "axisymmetric explicit FEA (ram + anvil + pile top)",
        "peak_ram_anvil_force [N]": float(result.ram_anvil_force.max()),
        "peak_anvil_pile_force [N]": float(result.anvil_pile_force.max()),
        "peak_gauge_force [N]": float(result.gauge_force.max()),
        "n_dof": result.n_dof, "n_steps": result.n_steps, "time_step [s]": result.time_step,
        "simulated_time [s]": float(result.time[-1] - result.time[0]),
        "wall_time [s]": result.wall_time, "setup_time [s]": result.setup_time,
        "pile_model": ("full length" if config.truncate_length is None else
                       f"{config.truncate_length:g} m with an absorbing cut"),
    }
    with ResultWriter(args.out, command="fea", force=args.force) as out:
        write_csv(columns, out.part("impact.csv"))
        out.part("summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        plot_columns(columns, out.part("impact.png"), title=f"{Path(args.system).name}: FEA")
    print(f"FEA {Path(args.system).name}: {result.n_dof} DOF, {result.n_steps} steps in "
          f"{result.wall_time:.1f} s; peak ram-anvil "
          f"{summary['peak_ram_anvil_force [N]'] / 1e6:.1f} MN, anvil-pile "
          f"{summary['peak_anvil_pile_force [N]'] / 1e6:.1f} MN -> {args.out}")
    return 0


def _compare(args: argparse.Namespace) -> int:
    check_output(args.out, "compare", args.force)

    cfg = load_system(args.system)
    with ResultWriter(args.out, command="compare", force=args.force) as out:
        comparison, _ = _run_comparison(cfg, out, args.rom_engine, args.fea_mesh_size)
    _print_comparison(comparison, args.out)
    _maybe_report(args)
    return 0


def _run_comparison(cfg, out, rom_engine: str, fea_mesh_size) -> tuple[dict, dict]:
    """The comparison output of ``cfg`` into ``out``; returns (comparison, the runs)."""

    with _progress("FEA") as progress:
        runs = run_models(cfg, out.staging, rom_engine=rom_engine, fea_mesh_size=fea_mesh_size,
                          progress=progress)
    # the static anvil weight on the pile at t = 0 (the arrival threshold sits above it)
    preload = float(runs["lumped"].columns["anvil_pile_force [N]"][0])
    band = comparison_bandwidth(cfg)
    comparison = compare(runs, preload=preload, bandwidth=band)
    comparison["system"] = Path(cfg.source).name
    for name, run in runs.items():
        write_csv(run.columns, out.part(f"{name}.csv"))
    out.part("comparison.json").write_text(json.dumps(comparison, indent=2) + "\n")
    plot_comparison(runs, "ram_anvil_force [N]", out.part("fig2_ram_force.png"),
                    "Ram impact force (ram-anvil contact): FEA vs simulation", band)
    plot_comparison(runs, "anvil_pile_force [N]", out.part("fig3_pile_force.png"),
                    "Pile-top impact force (anvil-pile contact): FEA vs simulation", band)
    if "pile_head_force_spectra" in comparison:
        plot_spectra(comparison["pile_head_force_spectra"], out.part("fig_spectra.png"))
    return comparison, runs


INTERFACES = "table1_interfaces.toml"
"""Table 1 with the anvil's interfaces resolved (the demo's fourth step)."""


def _interfaces_comparison(system: Path, runs: dict, out, bandwidth: float) -> dict:
    """The ROM of ``system`` (Table 1 with its interfaces resolved: pile rings on the tube
    head, ram annuli; the in-process engine) against the FEA and the lumped anvil of ``runs``
    (the same free pile): ``interfaces/`` with its series, comparison and band-level figure;
    returns its figures against the FEA for the summary."""

    cfg = without_soil(load_system(system))
    with Step("    running the ROM with the interfaces resolved (tube head kernel and ram annuli; "
              "computed once, then cached)..."):
        blow = build_engine(cfg).run()[0]
    rom = ModelRun("rom", blow.columns, blow.wall_time, {"engine": "direct"})
    preload = float(runs["lumped"].columns["anvil_pile_force [N]"][0])
    spectra = band_levels({"rom": rom, "lumped": runs["lumped"], "fea": runs["fea"]}, bandwidth)
    result = {"system": Path(system).name, **metrics(rom, runs["fea"], preload, bandwidth),
              "pile_head_force_spectra": spectra}
    write_csv(rom.columns, out.part("interfaces/rom.csv"))
    out.part("interfaces/comparison.json").write_text(json.dumps(result, indent=2) + "\n")
    plot_spectra(spectra, out.part("interfaces/fig_spectra.png"),
                 title="Pile-head force, one-third-octave bands: Table 1, interfaces resolved")
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool) & (centre <= 4000.0)
    deviation = np.array([np.nan if d is None else d
                          for d in spectra["deviation_from_fea [dB]"]["rom"]])
    worst = int(np.nanargmax(np.where(valid, np.abs(deviation), np.nan)))
    summary = {k: v for k, v in result.items() if k.endswith("[-]")}
    summary["max_abs_band_deviation_to_4_kHz [dB]"] = float(abs(deviation[worst]))
    summary["at_band [Hz]"] = float(centre[worst])
    print(f"    every band from {centre[valid].min():.0f} Hz to 4 kHz within "
          f"{abs(deviation[worst]):.2f} dB of the FEA ({centre[worst]:.0f} Hz); peaks "
          f"{summary['peak_ram_anvil_force_error [-]'] * 100:+.1f} % ram, "
          f"{summary['peak_anvil_pile_force_error [-]'] * 100:+.1f} % pile")
    return summary


def _print_comparison(comparison: dict, out) -> None:
    print(f"{'model':7s} {'ram peak':>9s} {'pile peak':>9s} {'arrival':>8s} {'RMS ram':>8s} "
          f"{'RMS pile':>8s} {'wall':>8s}")
    for name in ("fea", "rom", "lumped"):
        if name not in comparison:
            continue
        m = comparison[name]
        print(f"{name:7s} {m['peak_ram_anvil_force [N]'] / 1e6:8.1f}M "
              f"{m['peak_anvil_pile_force [N]'] / 1e6:8.1f}M "
              f"{m['pile_force_arrival_time [s]'] * 1e3:6.2f}ms "
              f"{m.get('ram_anvil_force_normalised_rms_error [-]', 0.0):8.3f} "
              f"{m.get('anvil_pile_force_normalised_rms_error [-]', 0.0):8.3f} "
              f"{m['wall_time [s]']:7.2f}s")
    print(f"-> {out}")


class _progress:
    """A tqdm bar driven by a fraction callback (the FEA reports its progress that way)."""

    def __init__(self, label: str):
        self.label = label

    def __enter__(self):
        from tqdm import tqdm

        self.bar = None
        self._last = 0

        def update(fraction: float) -> None:
            if self.bar is None:  # started with the stepping: its rate and estimate are true
                self.bar = tqdm(total=100, desc=self.label, unit="%", leave=False)
            now = int(round(100 * fraction))
            if now > self._last:
                self.bar.update(now - self._last)
                self._last = now

        return update

    def __exit__(self, *exc):
        if self.bar is not None:
            self.bar.close()
        return False


def _demo(args: argparse.Namespace) -> int:
    check_output(args.out, "demo", args.force)
    """The Table 1 comparison end to end (the README's main job)."""
    import time


    start = time.perf_counter()
    system = EXAMPLES_DIR / "table1.toml"
    if args.system is not None:
        system = args.system
    cfg = load_system(system)  # a modal ram's modes are computed here
    ram = cfg.hammer.ram
    ram_model = "modal" if ram.is_modal else "rod"
    steps = ["modes of the anvil and the ram", "FMUs", "ROM (FMI co-simulation), lumped anvil, FEA",
             "figures and summary"]
    interfaces = system.parent / INTERFACES if args.system is None else None
    if interfaces is not None:
        steps.insert(3, f"ROM with the interfaces resolved ({INTERFACES}, in-process engine)")
    print(f"anvilwave demo: {system.name} -> {args.out}")
    with ResultWriter(args.out, command="demo", force=args.force) as out:
        _say(1, steps)
        with Step("    meshing the anvil and solving its free-free modes..."):
            modes = compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax)
        save_modal_data(modes.modal_data, out.part("modes/modes.npz"))
        plot_modes(modes, out.part("modes/modes.png"))
        print(f"    {modes.modes.n_modes} modes up to {modes.modes.fmax:g} Hz, "
              f"{modes.model.n_dof} DOF, {modes.wall_time:.1f} s")
        if ram.is_modal_unit:
            print(f"    ram: modal ROM up to {ram.fmax:g} Hz, {ram.modes.n_modes} modes (modal "
                  "unit)")
        elif ram_model == "modal":
            print(f"    ram: modal ROM up to {ram.fmax:g} Hz, realised as a {ram.n_masses}-mass "
                  "chain")
        else:
            print(f"    ram: Smith rod of {ram.n_masses} masses")
        _say(2, steps)

        with Step("    building the FMUs (compiling the native anvils' C sources)..."):
            fmus = build_system_fmus(cfg, out.staging / "fmus")
        print("    " + ", ".join(Path(fmus[k]).name
                                 for k in ("Ram", "Anvil", "AnvilLumped", "PileSoil", "ssp")))
        _say(3, steps)
        comparison, runs = _run_comparison(cfg, out, "fmi", None)
        resolved = None
        if interfaces is not None:
            _say(4, steps)
            resolved = _interfaces_comparison(interfaces, runs, out,
                                              comparison["comparison_bandwidth [Hz]"])
        _say(len(steps), steps)
        rom, lumped, fea = comparison["rom"], comparison["lumped"], comparison["fea"]
        summary = {
            "system": Path(system).name,
            "anvil_modes": modes.modes.n_modes, "anvil_fmax [Hz]": modes.modes.fmax,
            "anvil_fe_dof": modes.model.n_dof,
            "ram_model": ram_model,
            "ram_modes" if ram.is_modal_unit else "ram_masses":
                ram.modes.n_modes if ram.is_modal_unit else ram.n_masses,
            "comparison_bandwidth [Hz]": comparison["comparison_bandwidth [Hz]"],
            "rom_vs_fea": {k: v for k, v in rom.items() if k.endswith("[-]") or
                           k.endswith("error [s]")},
            "lumped_vs_fea": {k: v for k, v in lumped.items() if k.endswith("[-]") or
                              k.endswith("error [s]")},
            "fea_lift_off_intervals [s]": fea["anvil_lift_off_intervals [s]"],
            "rom_lift_off_intervals [s]": rom["anvil_lift_off_intervals [s]"],
            "wall_time_fea [s]": fea["wall_time [s]"], "wall_time_rom [s]": rom["wall_time [s]"],
        }
        if resolved is not None:
            summary["interfaces_rom_vs_fea"] = resolved
        summary["total_time [s]"] = time.perf_counter() - start
        out.part("summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    _print_comparison(comparison, args.out)
    print(f"demo finished in {time.perf_counter() - start:.0f} s")
    return 0


def _say(i: int, steps: list[str]) -> None:
    print(f"[{i}/{len(steps)}] {steps[i - 1]}", flush=True)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``anvilwave`` command and its sub-commands.

    Returns
    -------
    argparse.ArgumentParser
        The parser; each sub-command sets ``func``, the function that runs it.
    """
    parser = argparse.ArgumentParser(
        prog="anvilwave",
        description="Impact pile driving with a Mode Displacement Method anvil.",
    )
    parser.add_argument("--version", action="version",
                        version=f"anvilwave {_version()}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "modes", help="free-free modes of an anvil and its modal ROM",
        description="Mesh the anvil (gmsh), assemble the axisymmetric FE model (scikit-fem), "
                    "solve ALL free-free modes up to fmax (shift-invert Lanczos, completeness "
                    "proved by a Sturm count) and write the modal ROM.",
    )
    p.add_argument("anvil", type=Path, help="anvil file (TOML): [material], [geometry] or mesh, "
                                            "[interfaces], [mesh]")
    p.add_argument("--fmax", type=float, default=None, metavar="HZ",
                   help="frequency content of the ROM [Hz]: every mode up to it is kept "
                        "(default: [modes] fmax of the file, else 5000)")
    p.add_argument("--mesh-size", type=float, default=None, metavar="M",
                   help="target element size [m] (default: [mesh] size of the file)")
    p.add_argument("--export-ccx", type=Path, default=None, metavar="FILE",
                   help="also write the meshed anvil as a CalculiX deck (CAX6, *FREQUENCY) to "
                        "check the modes in CalculiX")
    p.add_argument("--from-calculix", type=Path, default=None, metavar="JOB",
                   help="build the ROM from CalculiX results JOB.frd (mesh and mode shapes) and "
                        "JOB.dat (frequencies) instead of the built-in FE solution")
    p.add_argument("--out", type=Path, required=True, metavar="DIR",
                   help="output folder: modes.npz (ROM), modes.json (summary), modes.png")
    p.set_defaults(func=_modes)

    p = sub.add_parser(
        "impact", help="simulate blows of a hammer on a pile (in-process engine or FMUs)",
        description="Simulate the impact of the ram on the anvil and the pile (system file, see "
                    "README) and write DIR/impact.csv (time series), DIR/summary.json (peak "
                    "forces and stresses, transferred energy, permanent set, energy balance, "
                    "simulated and wall time) and DIR/impact.png.",
    )
    p.add_argument("system", type=Path, help="system file (TOML): [simulation], [hammer], "
                                             "[anvil], [pile], [soil]")
    p.add_argument("--engine", choices=("direct", "fmi"), default="direct",
                   help="direct: the in-process numba engine (default); fmi: the FMUs "
                        "(native anvil, pythonfmu ram and pile) co-simulated by the fmpy "
                        "master")
    p.add_argument("--anvil", choices=("rom", "lumped", "classic", "none"), default=None,
                   help="anvil model, overriding [anvil] model of the system file: rom (Mode "
                        "Displacement Method), lumped (rigid FE mass), classic (cushion-helmet "
                        "system), none (ram directly on the pile)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_impact)

    p = sub.add_parser(
        "build-fmus", help="write the Ram, Anvil, AnvilLumped and PileSoil FMUs and system.ssp",
        description="Build the FMI 2.0 (or 3.0) co-simulation units of a system (native C "
                    "anvils with the modal data embedded, ram and pile/soil, all from shipped "
                    "Linux x86-64 and Windows x64 binaries: no compiler needed) "
                    "and an SSP 1.0 file connecting ram, anvil and pile/soil with the "
                    "system's parameter values, for Jacobi-type masters such as libcosim.",
    )
    p.add_argument("system", type=Path, help="system file (TOML)")
    p.add_argument("--anvil", choices=("rom", "lumped"), default=None,
                   help="anvil unit of system.ssp (default: [anvil] model of the file)")
    p.add_argument("--python-anvil", action="store_true",
                   help="build Anvil.fmu and AnvilLumped.fmu with pythonfmu instead of the "
                        "native C units (they run in the Python that built them)")
    p.add_argument("--fmi-version", type=int, choices=(2, 3), default=2,
                   help="FMI version of the native units (3: FMI 3.0 co-simulation for the "
                        "anvils, Ram.fmu and PileSoil.fmu, the same numbers; not with "
                        "--python-anvil or --python-units)")
    p.add_argument("--python-units", action="store_true",
                   help="build Ram.fmu and PileSoil.fmu with pythonfmu instead of the native "
                        "units (they run in the Python that built them; the pile and soil "
                        "settings stay parameters)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=_build_fmus)

    p = sub.add_parser(
        "fea", help="the reference axisymmetric impact FEA (ram + anvil + pile top)",
        description="Explicit transient axisymmetric FE of ram, anvil and pile top with "
                    "compression-only contacts (lift-off and re-impact), gravity preload, the "
                    "whole pile or a length of it with an absorbing cut; writes DIR/impact.csv, "
                    "DIR/summary.json (with wall_time [s] of the stepping) and DIR/impact.png. "
                    "The soil is left out.",
    )
    p.add_argument("system", type=Path, help="system file (TOML)")
    p.add_argument("--mesh-size", type=float, default=None, metavar="M",
                   help="element size in the ram and the anvil [m] (default 0.1)")
    p.add_argument("--truncate", type=float, default=None, metavar="M",
                   help="model only this length of pile, with an absorbing cut [m] (default: "
                        "the whole pile, exact until its toe reflection returns)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=_fea)

    p = sub.add_parser(
        "compare", help="ROM anvil (FMUs) vs lumped-mass anvil vs FEA: the paper's Fig. 2 and 3",
        description="Run the ROM anvil (through the FMUs), the rigid lumped-mass anvil and the "
                    "reference FEA on the same configuration (free pile, see the README) and "
                    "write DIR/comparison.json (peak forces, pile-force arrival time, "
                    "normalised RMS errors against the FEA, wall times), DIR/fig2_ram_force.png, "
                    "DIR/fig3_pile_force.png and the three time series.",
    )
    p.add_argument("system", type=Path, help="system file (TOML)")
    p.add_argument("--rom-engine", choices=("fmi", "direct"), default="fmi",
                   help="run the ROM through the FMUs (default) or the in-process engine")
    p.add_argument("--fea-mesh-size", type=float, default=None, metavar="M",
                   help="FEA element size in the ram and the anvil [m]")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_compare)

    p = sub.add_parser(
        "demo", help="the paper's Table 1 comparison end to end (modes, FMUs, co-simulation, "
                     "lumped anvil, FEA, Fig. 2 and 3, summary)",
        description="Run the Table 1 case end to end: anvil modes, the four FMUs and system.ssp, "
                    "the ROM through the FMI co-simulation, the lumped-mass anvil, the reference "
                    "FEA, Fig. 2 and Fig. 3 and DIR/summary.json.",
    )
    p.add_argument("--system", type=Path, default=None,
                   help="system file (default: the shipped Table 1 example, table1.toml)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=_demo)

    p = sub.add_parser(
        "drive", help="driveability: blow count, stresses and ENTHRU against the tip depth",
        description="For every tip depth of [driveability]: the pile embedded to that depth "
                    "with its SRD ([srd]: CPT/layer methods with friction fatigue, tables per "
                    "tip depth, or [soil] srd), the hammer at the energy of the schedule, one "
                    "or more blows; writes DIR/driveability.csv, DIR/summary.json and "
                    "DIR/driveability.png.")
    p.add_argument("system", type=Path, help="system file (TOML) with a [driveability] table")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--anvil", choices=("rom", "lumped", "classic", "none"), default=None,
                   help="anvil model (default: the system file's)")
    p.add_argument("--bound", choices=("lower", "best", "upper"), default=None,
                   help="SRD bound (default: the file's, else best)")
    p.add_argument("--compare-anvils", action="store_true",
                   help="run every anvil model the file supports (rom, lumped, classic) and "
                        "plot them together")
    p.add_argument("--bearing-graph", type=float, default=None, metavar="DEPTH",
                   help="blow count against Rut at this tip depth [m] instead")
    p.add_argument("--restrike", type=float, default=None, metavar="DURATION",
                   help="also the restrike blow count at every depth after a pause of DURATION "
                        "[h] (shaft set-up of Skov & Denver 1988; [installation] setup_soil)")
    p.add_argument("--workers", type=int, default=None,
                   help="processes over the depths (default: all cores)")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_drive)

    p = sub.add_parser(
        "install", help="blow-by-blow installation with fatigue damage and force spectra",
        description="Every blow from the self-weight penetration to the target depth or "
                    "refusal, the pile and soil state carried from blow to blow; writes "
                    "DIR/blows.csv, DIR/fatigue.csv, DIR/spectra.csv, DIR/summary.json and "
                    "DIR/installation.png.")
    p.add_argument("system", type=Path, help="system file (TOML) with [driveability] and "
                                             "optionally [installation]")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--anvil", choices=("rom", "lumped", "classic", "none"), default=None,
                   help="anvil model (default: the system file's)")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_install)

    p = sub.add_parser(
        "batch", help="a wind-farm campaign of driveability cases on dask.distributed",
        description="Every case of a campaign file (positions x SRD bounds x hammers x anvil "
                    "models x energy schedules), each one driveability, on a LocalCluster of "
                    "processes or an existing dask scheduler; results per case in "
                    "DIR/cases/<case>/ as each finishes, indexed by DIR/campaign.csv; a rerun "
                    "skips finished cases.")
    p.add_argument("campaign", type=Path, help="campaign file (TOML)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="campaign folder")
    p.add_argument("--workers", type=int, default=None,
                   help="worker processes of the local cluster (default: all cores)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="address of an existing dask scheduler (e.g. tcp://host:8786, one "
                        "started by dask-jobqueue on Slurm or PBS)")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_batch)

    p = sub.add_parser(
        "pda", help="Case method of a gauge record (RTL, RSP, RMX, EMX, FMX, CSX, TSX, BTA)",
        description="Read a gauge record (time [s], force [N], velocity [m/s]; or raw "
                    "strains and accelerations) and write DIR/pda.json and DIR/pda.png.")
    p.add_argument("record", type=Path, help="gauge record (CSV)")
    p.add_argument("--length", type=float, required=True, help="pile length below the gauges "
                                                               "[m]")
    p.add_argument("--area", type=float, required=True, help="steel area at the gauges [m^2]")
    p.add_argument("--elastic-modulus", type=float, default=210e9, help="[Pa] (steel)")
    p.add_argument("--wave-speed", type=float, default=None,
                   help="[m/s] (default sqrt(E / 7850))")
    p.add_argument("--jc", type=float, required=True, help="Case damping factor [-]")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_pda)

    p = sub.add_parser(
        "match", help="signal matching: fit the soil of a system file to a gauge record",
        description="Impose the measured velocity (or wave down) at the gauges on the pile "
                    "and soil of the system file, fit shaft zones, toe, quakes and dampings by "
                    "least squares; writes DIR/match.json, the match plots and the simulated "
                    "static load test.")
    p.add_argument("record", type=Path, help="gauge record (CSV)")
    p.add_argument("system", type=Path, help="system file (TOML): pile and starting soil")
    p.add_argument("--zones", type=int, default=3, help="shaft resistance zones")
    p.add_argument("--imposed", choices=("velocity", "wave_down"), default="velocity")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_match)

    p = sub.add_parser(
        "compare-pda", help="the paper's Fig. 4 and 5: a record against the ROM and lumped "
                            "anvils",
        description="Measured pile-top force and velocity against the ROM anvil and the "
                    "lumped anvil of the system file (gravity preload removed as gauges "
                    "zeroed at rest do).")
    p.add_argument("record", type=Path, help="gauge record (CSV)")
    p.add_argument("system", type=Path, help="system file (TOML)")
    p.add_argument("--align", choices=("rom", "lumped"), default=None,
                   help="shift the record so that its force arrival coincides with this "
                        "model's (default: keep the record's time; the shift is reported "
                        "and that model's arrival error is then 0 by construction)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.add_argument("--report", action="store_true",
                   help=f"also write the client report, DIR/{REPORT_NAME} (see 'anvilwave "
                        "report')")
    p.set_defaults(func=_compare_pda)

    p = sub.add_parser(
        "report", help="a result folder as one self-contained HTML file for a client",
        description="Read a result folder written by impact, drive, install, batch, compare, "
                    "match, pda or compare-pda (its summaries, tables, recorded inputs and "
                    "figures; nothing is run) and write one HTML file with no external "
                    "resources: version, date, the input files with their SHA-256 hashes and "
                    "their text, the key settings, the tables in practitioner units and every "
                    "figure embedded; printable on A4.")
    p.add_argument("result_dir", type=Path, metavar="RESULT_DIR", help="a result folder")
    p.add_argument("--out", type=Path, default=None, metavar="FILE",
                   help=f"the HTML file (default: RESULT_DIR/{REPORT_NAME})")
    p.set_defaults(func=_report)

    p = sub.add_parser(
        "cache", help="the modal-data cache: where it is and what it holds, or empty it",
        description="The modes of every anvil (and modal ram) are computed once and kept in a "
                    "user cache directory ($ANVILWAVE_CACHE_DIR, else $XDG_CACHE_HOME/anvilwave "
                    "or ~/.cache/anvilwave), keyed by geometry, material, mesh, fmax, damping "
                    "and the code version. 'info' lists it, 'clear' deletes its entries.")
    p.add_argument("action", choices=("info", "clear"))
    p.set_defaults(func=_cache)

    p = sub.add_parser("schema", help="list every key of the input files (unit, default, "
                                      "meaning)")
    p.add_argument("kind", nargs="?", choices=("system", "anvil"), default="system")
    p.set_defaults(func=_schema)

    p = sub.add_parser("examples", help="copy the shipped example files (system files, anvils, "
                                        "soil, PDA records, scripts) into DIR",
                       description="Copy the example files that ship with anvilwave into DIR "
                                   "(created; a file already there is never overwritten). "
                                   "Then e.g. anvilwave impact DIR/table1.toml --out res.")
    p.add_argument("dir", type=Path, metavar="DIR", help="destination folder")
    p.set_defaults(func=_examples)
    for name, p in sub.choices.items():  # every command that writes a result folder
        if name != "report" and any("--out" in a.option_strings for a in p._actions):
            p.add_argument("--force", action="store_true",
                           help="replace an output folder that holds another command's result "
                                "(refused without it; a result is always replaced whole)")
    return parser


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("anvilwave")
    except PackageNotFoundError:  # run from a checkout that is not installed
        return "unknown (not installed)"


def _examples(args: argparse.Namespace) -> int:

    try:
        copied = copy_examples(args.dir)
    except FileExistsError as exc:
        print(f"anvilwave: error: {exc}", file=sys.stderr)
        return 2
    print(f"anvilwave examples: {len(copied)} files -> {args.dir}")
    return 0


def _drive(args: argparse.Namespace) -> int:
    check_output(args.out, "drive", args.force)
    if args.workers is not None and args.workers < 1:
        raise InputError("--workers", "", f"must be at least 1, got {args.workers}")
    cfg = load_system(args.system)
    name = Path(args.system).name
    if args.bearing_graph is not None:
        models = list(available_anvil_models(cfg)) if args.compare_anvils else [args.anvil]
        with ResultWriter(args.out, command="drive", force=args.force) as out:
            for model in models:
                graph = drive_bearing_graph(cfg, args.bearing_graph, anvil=model,
                                            bound=args.bound)
                write_csv(graph.columns(), out.part(f"bearing_graph_{graph.model}.csv"))
                for r in graph.rows:
                    print(f"{graph.model:7s} Rut {r['srd [N]'] / 1e6:8.2f} MN: "
                          f"{r['blows_per_0.25m [-]']:8.1f} blows/0.25 m")
        print(f"-> {args.out}")
        _maybe_report(args)
        return 0
    if args.compare_anvils:
        results = api.compare_anvils(cfg, bound=args.bound, workers=args.workers,
                                     progress=True)
    else:
        result = api.drive(cfg, anvil=args.anvil, bound=args.bound, workers=args.workers,
                           progress=True, restrike=args.restrike)
        results = {result.model: result}
    with ResultWriter(args.out, command="drive", force=args.force) as out, \
            Step("writing driveability.csv, summary.json and the figures..."):
        write_anvil_comparison(results, out, title=name)
    for model, result in results.items():
        for depth, blow in result.time_series.items():
            if blow is None:
                print(f"{model:7s} no blow at {depth:g} m (the pile runs under its own weight "
                      "there): no time series")
        s = result.summary
        refusal = s["refusal_depth [m]"]
        print(f"{model:7s} total blows {s['total_blows [-]']:8.0f}, driving time "
              f"{s['driving_time [s]'] / 3600:6.2f} h, refusal "
              f"{'none' if refusal is None else f'{refusal:g} m'}, max compression "
              f"{s['max_compression_stress [Pa]'] / 1e6:6.1f} MPa, max tension "
              f"{s['max_tension_stress [Pa]'] / 1e6:6.1f} MPa; {s['depths_analysed [-]']} "
              f"depths in {s['wall_time [s]']:.1f} s")
    print(f"-> {args.out}")
    _maybe_report(args)
    return 0


def _install(args: argparse.Namespace) -> int:
    check_output(args.out, "install", args.force)
    result = api.install(args.system, anvil=args.anvil, progress=True)
    model = result.summary["anvil_model"]
    with ResultWriter(args.out, command="install", force=args.force) as out, \
            Step("writing blows.csv, fatigue.csv, spectra.csv, summary.json and the figure..."):
        result.write(out, title=f"{Path(args.system).name}: installation, {model} anvil")
    s = result.summary
    print(f"{Path(args.system).name} [{model}]: {s['total_blows [-]']} blows from "
          f"{s['start_depth [m]']:.1f} to {s['final_depth [m]']:.2f} m ({s['stopped_by']}), "
          f"driving time {s['driving_time [s]'] / 3600:.2f} h, max damage "
          f"{s['max_damage [-]']:.3g} at {s['max_damage_depth_below_head [m]']:.1f} m below "
          f"the head; {s['wall_time [s]']:.1f} s ({s['seconds_per_blow [s]'] * 1e3:.1f} ms "
          f"per blow) -> {args.out}")
    _maybe_report(args)
    return 0


def _batch(args: argparse.Namespace) -> int:
    if args.workers is not None and args.scheduler is not None:
        raise InputError("--workers", "", "give --workers (a local cluster) or --scheduler (a "
                                          "running one), not both")
    if args.workers is not None and args.workers < 1:
        raise InputError("--workers", "", f"must be at least 1, got {args.workers}")
    check_output(args.out, "batch", args.force)
    r = api.batch(args.campaign, args.out, workers=args.workers, scheduler=args.scheduler,
                  progress=True, force=args.force)
    print(f"{r.cases} cases: {r.ok} ok, {r.error} failed, {r.pending} pending ({r.ran} run, "
          f"{r.skipped} finished before) on {r.workers} workers in {r.wall_time:.1f} s -> "
          f"{r.campaign_csv}")
    _maybe_report(args)
    return 0 if r.error == 0 and r.pending == 0 else 1


def _pda(args: argparse.Namespace) -> int:
    check_output(args.out, "pda", args.force)
    result = api.pda(args.record, length=args.length, area=args.area,
                     elastic_modulus=args.elastic_modulus, wave_speed=args.wave_speed,
                     jc=args.jc)
    result.write(args.out, force=args.force)
    print("  ".join(f"{k} {_si(v)}" for k, v in result.summary.items()
                    if isinstance(v, float | int)))
    print(f"-> {args.out}")
    _maybe_report(args)
    return 0


def _match(args: argparse.Namespace) -> int:
    check_output(args.out, "match", args.force)
    result = api.match(args.record, args.system, shaft_zones=args.zones, imposed=args.imposed)
    result.write(args.out, force=args.force)
    s = result.content
    print(f"Rut {s['rut [N]'] / 1e6:.2f} MN (shaft {s['rut_shaft [N]'] / 1e6:.2f} MN, toe "
          f"{s['rut_toe [N]'] / 1e6:.2f} MN), match quality {s['match_quality [-]']:.3f} "
          f"-> {args.out}")
    _maybe_report(args)
    return 0


def _compare_pda(args: argparse.Namespace) -> int:
    check_output(args.out, "compare-pda", args.force)
    result = api.compare_pda(args.record, args.system, align=args.align or "none")
    result.write(args.out, force=args.force)
    c = result.content
    if args.align:
        print(f"record shifted by {c['record_time_shift [s]'] * 1e3:+.3f} ms onto the "
              f"{args.align} anvil's force arrival (its arrival error is 0 by construction)")
    else:
        print("record time kept (t = 0 the ram impact; --align rom|lumped shifts it)")
    for model in ("rom", "lumped"):
        m = c[model]
        print(f"{model:7s} peak force {m['peak_force_error [-]'] * 100:+6.1f} %, force RMS "
              f"{m['force_normalised_rms_error [-]'] * 100:5.1f} %, arrival error "
              f"{m['force_arrival_error [s]'] * 1e3:+.3f} ms")
    print(f"Fig. 4 and Fig. 5 -> {args.out}")
    _maybe_report(args)
    return 0


def _si(value) -> str:
    return f"{value:.4g}"


def _cache(args: argparse.Namespace) -> int:

    if args.action == "clear":
        count, size = clear_cache()
        info = cache_info()
        print(f"removed {_entries(count)} ({size / 2**20:.1f} MiB) from {info['directory']}")
        return 0
    info = cache_info()
    print(f"{info['directory']}: {_entries(info['entries'])}, {info['bytes'] / 2**20:.1f} MiB")
    for row in info["files"]:
        name, size = row["name"][:16], f"{row['bytes'] / 1024:.0f} KiB"
        if row.get("unreadable"):
            print(f"  {name}  unreadable, {size}")
        elif "chain_masses" in row:
            print(f"  {name}  modal ram chain of {row['chain_masses']} masses, "
                  f"{row['total_mass [kg]'] / 1e3:.1f} t, {size}")
        elif "head_kernel_steps" in row:
            print(f"  {name}  tube head kernel, {row['rings']} rings, "
                  f"{row['head_kernel_steps']} steps, {size}")
        else:
            print(f"  {name}  {row['modes']:4d} modes to {row['fmax [Hz]']:g} Hz, "
                  f"{row['n_dof']} DOF, {row['total_mass [kg]'] / 1e3:.1f} t, {size}")
    return 0


def _entries(count: int) -> str:
    return f"{count} entr{'y' if count == 1 else 'ies'}"


def _schema(args: argparse.Namespace) -> int:

    print(describe(args.kind))
    return 0


def _user_error(exc: Exception) -> bool:
    """An input error, a modal analysis that cannot be solved, or a native build that
    fails (the compiler's own message)."""
    return isinstance(exc, InputError | ModeSolveError | NativeBuildError)


def main(argv: list[str] | None = None) -> int:
    """Run the ``anvilwave`` command line.

    Every command runs inside :func:`anvilwave.inputs.record_inputs`, so that its result
    folder records the input files it read. A user error (an input error, a modal analysis
    that cannot be solved, or a native build that fails) prints one line
    ``anvilwave: error: ...`` to stderr instead of a traceback; any other exception
    propagates.

    Parameters
    ----------
    argv : list of str or None, default None
        The arguments (None: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit status: the sub-command's, 0 on a broken pipe, 130 on Ctrl-C, 2 on a user
        error.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        with record_inputs(command=args.command, arguments=_arguments(args)):
            return args.func(args)
    except BrokenPipeError:  # output piped into head, less ...
        return 0
    except KeyboardInterrupt:
        print("anvilwave: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:
        if not _user_error(exc):
            raise
        print(f"anvilwave: error: {_one_line(exc)}", file=sys.stderr)
        return 2


def _arguments(args: argparse.Namespace) -> dict:
    """The options of a command as its result records them (the files it reads are recorded
    with their hashes instead; the output folder is where the record lies)."""
    return {k: v for k, v in vars(args).items()
            if k not in ("func", "command", "report") and not isinstance(v, Path)}


def _one_line(exc: Exception) -> str:
    """The message of ``exc`` on one line (a compiler's output has several)."""
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    return "; ".join(lines[:3]) + (" ..." if len(lines) > 3 else "")


if __name__ == "__main__":
    sys.exit(main())
