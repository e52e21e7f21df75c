"""Blow-by-blow installation: every blow from the start penetration to the target or refusal.

The tip starts at the self-weight penetration (the first depth where the SRD carries the weight
of pile, ram and anvil) and advances by each blow's permanent set; the pile and soil state
(displacements, velocities, the soil springs' plastic offsets: the residual stresses) carries
over from blow to blow. The SRD follows the tip (friction fatigue): the distribution is rebuilt
when the tip has moved ``srd_update`` (default 0.05 m) since the last rebuild, not more often.
The energy schedule and refusal criterion are those of ``[driveability]``; refusal is more than
``refusal`` blows over the last 0.25 m.

Fatigue: the axial stress history of chosen sections (girth welds at given depths below the
head, or every segment) is streamed blow by blow into a rainflow count over the WHOLE sequence
(cycles that close across blows counted;
:class:`anvilwave.pile.post.fatigue.StreamingMinerDamage`), with
DNV-RP-C203 S-N curves (edition, environment, SCF, the thickness correction at the section's
wall thickness). Memory stays bounded: only the reversal residue is kept between blows.

Noise: the pile-head force of the first blow past each chosen depth is turned into
one-third-octave band energies (IEC 61260-1, base 10; :func:`anvilwave.pile.post.spectra.
third_octave_band_energies`), valid band stated.
"""

from __future__ import annotations

import bisect
import json
import math
import time
from dataclasses import dataclass

import numpy as np

from anvilwave.inputs import InputError, Table

BLOW_COLUMNS = ("blow [-]", "tip_depth [m]", "set [m]", "energy_setting [J]", "enthru [J]",
                "max_compression_stress [Pa]", "max_tension_stress [Pa]",
                "max_pile_head_force [N]", "srd [N]")
FATIGUE_COLUMNS = ("depth_below_head [m]", "sn_curve", "environment", "scf [-]",
                   "thickness [m]", "damage [-]", "closed_cycles [-]")


@dataclass(frozen=True)
class InstallSettings:
    """The ``[installation]`` table.

    start_depth : tip depth of the first blow [m] (None: the self-weight penetration).
    target_depth : final tip depth [m] (None: the last depth of ``[driveability]``).
    max_blows : safety limit on the number of blows [-].
    srd_update : tip movement that triggers a rebuild of the SRD distribution [m].
    weld_depths : sections for fatigue, depth below the pile head [m] (None: every spring).
    sn_curve, environment, edition, scf : DNV-RP-C203 S-N curve of the sections.
    spectra_depths : tip depths whose first blow's head force spectrum is written [m].
    record_interval : sampling of the stress histories and head force [s] (None: every step).
    """

    start_depth: float | None = None
    target_depth: float | None = None
    max_blows: int = 20000
    srd_update: float = 0.05
    weld_depths: tuple | None = None
    sn_curve: str = "D"
    environment: str = "seawater-cp"
    edition: str = "2016"
    scf: float = 1.0
    spectra_depths: tuple = ()
    record_interval: float | None = None


def load_install_settings(table: Table | None) -> InstallSettings:
    """Read and validate ``[installation]`` (absent: the defaults)."""
    from anvilwave.pile.post.fatigue import EDITIONS, ENVIRONMENTS, dnv_rp_c203_curve

    if table is None:
        return InstallSettings()
    welds = table.array("weld_depths", None)
    if welds is not None and np.any(welds < 0.0):
        raise table.error("weld_depths", "depths below the pile head must be >= 0 m")
    edition = table.string("edition", "2016", choices=tuple(EDITIONS))
    curve = table.string("sn_curve", "D")
    try:
        dnv_rp_c203_curve(curve, edition)
    except ValueError as exc:
        raise table.error("sn_curve", str(exc)) from None
    spectra = table.array("spectra_depths", None)
    s = InstallSettings(
        start_depth=table.number("start_depth", None, gt=0.0, unit="m"),
        target_depth=table.number("target_depth", None, gt=0.0, unit="m"),
        max_blows=table.integer("max_blows", 20000, ge=1),
        srd_update=table.number("srd_update", 0.05, gt=0.0, le=1.0, unit="m"),
        weld_depths=tuple(float(w) for w in welds) if welds is not None else None,
        sn_curve=curve,
        environment=table.string("environment", "seawater-cp", choices=ENVIRONMENTS),
        edition=edition,
        scf=table.number("scf", 1.0, ge=1.0, le=10.0),
        spectra_depths=tuple(float(d) for d in spectra) if spectra is not None else (),
        record_interval=table.number("record_interval", None, gt=0.0, le=1e-3, unit="s"),
    )
    if s.max_blows > 200_000:
        raise table.error("max_blows", f"must be at most 200000, got {s.max_blows}")
    table.finish()
    return s


def fatigue_sections(pile_soil, settings: InstallSettings):
    """(spring index, depth below head [m], wall thickness [m]) of the fatigue sections: the
    pile spring nearest each weld depth, or every spring."""
    seg = pile_soil.pile.discretise()
    springs = seg.bottom[:-1]  # spring i joins segment i and i + 1 at this depth
    if settings.weld_depths is None:
        index = np.arange(springs.size)
    else:
        index = np.array([int(np.argmin(np.abs(springs - d))) for d in settings.weld_depths])
    thickness = np.minimum(seg.wall_thickness[index], seg.wall_thickness[index + 1])
    return index, springs[index], thickness


def self_weight_penetration(cfg, srd, engine, multiplier: float, step: float = 0.1) -> float:
    """First tip depth (on a ``step`` [m] grid) where the SRD carries the driving weight."""
    from anvilwave.analyses.drive import driving_weight, segment_capacities

    weight = driving_weight(cfg, engine.static_head_force)
    length = cfg.pile_soil.pile.length
    depth = step
    while depth < length:
        shaft, toe = segment_capacities(cfg.pile_soil, srd, depth, multiplier)
        if shaft.sum() + toe > weight:
            return depth
        depth += step
    return length


def run_installation(cfg, srd, drive, settings: InstallSettings, engine, *,
                     progress: bool = False) -> dict:
    """Simulate every blow; returns the blow rows, fatigue rows, spectra rows and summary."""
    from anvilwave.analyses.drive import impact_at, pile_soil_at
    from anvilwave.pile.post.fatigue import StreamingMinerDamage, sn_curve
    from anvilwave.pile.post.spectra import third_octave_band_energies

    start_wall = time.perf_counter()
    multiplier = drive.multiplier
    start = settings.start_depth
    if start is None:
        start = self_weight_penetration(cfg, srd, engine, multiplier)
    target = settings.target_depth if settings.target_depth is not None else float(
        drive.depths[-1])
    length = cfg.pile_soil.pile.length
    if target > length:
        raise InputError(cfg.source, "installation.target_depth",
                         f"{target:g} m is beyond the {length:g} m pile")
    index, depth_below_head, thickness = fatigue_sections(cfg.pile_soil, settings)
    functions = [sn_curve(settings.sn_curve, settings.environment, float(t), settings.scf,
                          edition=settings.edition) for t in thickness]
    miner = StreamingMinerDamage(functions)
    stress_factor = cfg.pile_soil.stress_factors()[index]
    pending_spectra = sorted(d for d in settings.spectra_depths if start <= d <= target)

    tip = float(start)
    ps, shaft, toe = pile_soil_at(cfg.pile_soil, srd, tip, multiplier)
    eng = engine.with_pile_soil(ps)
    state = eng.static_state()
    built_at = tip
    rows: list[dict] = []
    spectra_rows: list[dict] = []
    valid_band = None
    tips: list[float] = []  # tip depth after each blow (non-decreasing), for the refusal
    refusal_depth = None
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=round(target - tip, 2), unit="m", desc="installation",
                   bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} m [{elapsed}<{remaining}]")
    try:
        for k in range(1, settings.max_blows + 1):
            if tip - built_at >= settings.srd_update:
                ps, shaft, toe = pile_soil_at(cfg.pile_soil, srd, tip, multiplier)
                eng = engine.with_pile_soil(ps)
                built_at = tip
            energy, velocity = impact_at(drive, tip, cfg)
            spectrum = bool(pending_spectra) and tip >= pending_spectra[0]
            blow = eng.blow(state=state, impact_velocity=velocity, duration=drive.duration,
                            record_interval=settings.record_interval, record=spectrum,
                            energy=False, sections=index)
            miner.add_blow(blow.section_strain * stress_factor)
            state = blow.final_state
            set_m = max(float(blow.permanent_set), 0.0)
            enthru = blow.emx_gauge if drive.enthru_location == "gauge" else blow.emx_head
            rows.append({"blow [-]": k, "tip_depth [m]": tip, "set [m]": set_m,
                         "energy_setting [J]": energy, "enthru [J]": float(enthru),
                         "max_compression_stress [Pa]": float(blow.max_compression_stress),
                         "max_tension_stress [Pa]": float(blow.max_tension_stress),
                         "max_pile_head_force [N]": float(blow.max_pile_head_force),
                         "srd [N]": shaft + toe})
            if spectrum:
                c = blow.columns
                t = c["time [s]"]
                force = c["anvil_pile_force [N]"]
                # the dynamic force: the anvil's static weight on the pile taken off
                bands = third_octave_band_energies(force - force[0], float(t[1] - t[0]))
                valid_band = bands.valid_range
                for f, level, ok in zip(bands.centre_frequency, bands.level, bands.valid,
                                        strict=True):
                    spectra_rows.append({"tip_depth [m]": tip, "band_centre [Hz]": float(f),
                                         "band_energy_level [dB]": float(level),
                                         "valid [-]": int(ok)})
                pending_spectra.pop(0)
            tip += set_m
            if bar is not None:
                bar.update(min(set_m, max(bar.total - bar.n, 0.0)))
            tips.append(tip)
            # refusal: more than `refusal` blows over the last 0.25 m of penetration
            first = bisect.bisect_right(tips, tip - 0.25)
            if len(tips) - first > drive.refusal:
                refusal_depth = tip
                break
            if tip >= target:
                break
    finally:
        if bar is not None:
            bar.close()
    damage = miner.damage()
    fatigue_rows = [{"depth_below_head [m]": float(d), "sn_curve": settings.sn_curve,
                     "environment": settings.environment, "scf [-]": settings.scf,
                     "thickness [m]": float(t), "damage [-]": float(dm),
                     "closed_cycles [-]": float(n)}
                    for d, t, dm, n in zip(depth_below_head, thickness, damage,
                                           miner.closed_cycles, strict=True)]
    total = len(rows)
    summary = {
        "total_blows [-]": total,
        "start_depth [m]": float(start),
        "final_depth [m]": float(tip),
        "target_depth [m]": float(target),
        "refusal_depth [m]": refusal_depth,
        "driving_time [s]": total / drive.blow_rate * 60.0,
        "max_damage [-]": float(np.max(damage)) if damage.size else 0.0,
        "max_damage_depth_below_head [m]": float(depth_below_head[int(np.argmax(damage))])
        if damage.size else None,
        "max_compression_stress [Pa]": max((r["max_compression_stress [Pa]"] for r in rows),
                                           default=0.0),
        "max_tension_stress [Pa]": min((r["max_tension_stress [Pa]"] for r in rows),
                                       default=0.0),
        "spectra_valid_band [Hz]": list(valid_band) if valid_band is not None else None,
        "sn_curve": settings.sn_curve, "environment": settings.environment,
        "edition": settings.edition, "scf [-]": settings.scf,
        "anvil_model": cfg.anvil.model,
        "stopped_by": ("refusal" if refusal_depth is not None else
                       "target depth" if tip >= target else "max_blows"),
        "wall_time [s]": time.perf_counter() - start_wall,
    }
    summary["seconds_per_blow [s]"] = summary["wall_time [s]"] / max(total, 1)
    return {"blows": rows, "fatigue": fatigue_rows, "spectra": spectra_rows,
            "summary": summary}


def blow_count_profile(rows: list[dict], bin_size: float = 0.25) -> tuple[np.ndarray, ...]:
    """(depth at the bin's bottom [m], blows in the bin [-]) of the blows per ``bin_size``."""
    tip = np.array([r["tip_depth [m]"] for r in rows])
    if tip.size == 0:
        return np.zeros(0), np.zeros(0)
    edges = np.arange(math.floor(tip[0] / bin_size) * bin_size, tip[-1] + bin_size, bin_size)
    counts, _ = np.histogram(tip, bins=edges)
    return edges[1:], counts.astype(float)


def write_results(result: dict, out, title: str = "") -> None:
    """blows.csv, fatigue.csv, spectra.csv, summary.json and the figures into a ResultWriter."""
    import csv

    from anvilwave.output.plots import plot_installation
    from anvilwave.output.tables import write_csv

    blows = result["blows"]
    write_csv({c: np.array([r[c] for r in blows], dtype=float) for c in BLOW_COLUMNS},
              out.part("blows.csv"))
    with open(out.part("fatigue.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FATIGUE_COLUMNS)
        w.writeheader()
        w.writerows(result["fatigue"])
    with open(out.part("spectra.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=("tip_depth [m]", "band_centre [Hz]",
                                          "band_energy_level [dB]", "valid [-]"))
        w.writeheader()
        w.writerows(result["spectra"])
    out.part("summary.json").write_text(json.dumps(result["summary"], indent=2) + "\n")
    plot_installation(result, out.part("installation.png"), title=title)
