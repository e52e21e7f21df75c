"""The ``anvilwave`` command line."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from anvil_rom.inputs import InputError
from anvil_rom.modes import ModeSolveError

from .output import ResultWriter


def _modes(args: argparse.Namespace) -> int:
    from anvil_rom.geometry import load_anvil
    from anvil_rom.modalfile import save_modal_data
    from anvil_rom.pipeline import anvil_modes_from_calculix, compute_anvil_modes

    from .plots import plot_modes

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
    with ResultWriter(args.out) as out:
        summary = {
            "anvil": str(args.anvil),
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
            from anvil_rom.calculix import write_ccx_deck_from_mesh

            write_ccx_deck_from_mesh(args.export_ccx, result.mesh, spec.material,
                                     result.modes.n_modes, title=spec.name)
    print(f"{spec.name}: {result.modes.n_modes} modes up to {result.modes.fmax:g} Hz, "
          f"{result.model.n_dof} DOF, {result.wall_time:.1f} s -> {args.out}")
    return 0


def _impact(args: argparse.Namespace) -> int:
    from .engine import build_engine
    from .plots import plot_impact_blows
    from .report import summarise, write_csv
    from .system import load_system

    cfg = load_system(args.system)
    if args.anvil is not None:
        cfg = cfg.with_anvil_model(args.anvil)
    model = cfg.anvil.model
    if args.engine == "fmi":
        from .fmi_engine import run_fmi

        blows = run_fmi(cfg, args.out / "fmus", anvil_model=model, progress=True)
    else:
        engine = build_engine(cfg)
        blows = engine.run(progress=True)
    gauge_area = _gauge_area(cfg)
    with ResultWriter(args.out) as out:
        summaries = []
        for i, blow in enumerate(blows):
            name = "impact.csv" if len(blows) == 1 else f"impact_blow{i + 1}.csv"
            write_csv(blow.columns, out.part(name))
            summaries.append(summarise(blow, cfg, args.engine, model, gauge_area))
        summary = dict(summaries[0])
        summary["system"] = str(args.system)
        if len(blows) > 1:
            summary["blows"] = summaries
        out.part("summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        plot_impact_blows(blows, out.part("impact.png"),
                          title=f"{Path(args.system).name}: {model} anvil, {args.engine} engine")
    s = summaries[0]
    print(f"{Path(args.system).name} [{model}, {args.engine}]: peak ram-anvil "
          f"{s['peak_ram_anvil_force [N]'] / 1e6:.1f} MN, anvil-pile "
          f"{s['peak_anvil_pile_force [N]'] / 1e6:.1f} MN; "
          f"{s['simulated_time [s]'] * 1e3:.1f} ms in {s['wall_time [s]']:.4f} s "
          f"({s['realtime_factor [-]']:.0f}x real time) -> {args.out}")
    return 0


def _gauge_area(cfg) -> float:
    """Steel area of the pile section at the gauge depth [m^2]."""
    depth = 0.0
    for section in cfg.pile_soil.pile.sections:
        depth += section.length
        if cfg.pile_soil.pile.gauge_depth <= depth:
            return section.area
    return cfg.pile_soil.pile.sections[-1].area


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="anvilwave",
        description="Impact pile driving with a Mode Displacement Method anvil.",
    )
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
                        "(pythonfmu) co-simulated by the fmpy master")
    p.add_argument("--anvil", choices=("rom", "lumped", "classic", "none"), default=None,
                   help="anvil model, overriding [anvil] model of the system file: rom (Mode "
                        "Displacement Method), lumped (rigid FE mass), classic (cushion-helmet "
                        "system), none (ram directly on the pile)")
    p.add_argument("--out", type=Path, required=True, metavar="DIR", help="output folder")
    p.set_defaults(func=_impact)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (InputError, ModeSolveError) as exc:
        print(f"anvilwave: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("anvilwave: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
