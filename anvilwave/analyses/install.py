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

Pauses and set-up (``[installation] pauses``, rows tip depth [m], duration [h]): when the tip
reaches a pause depth, driving stops for the duration; the shaft resistance of the segments in
the ground gains the set-up of Skov & Denver (1988) for the soil type of each segment (the
SRD's soil layers, or ``setup_soil``), and the blows after the restart remould the gain
exponentially over ``remoulding_length`` of penetration (:mod:`anvilwave.pile.soil.setup`);
the SRD is rebuilt at every blow while the gain lasts. The first blow after a restart is the
restrike: its blow count (1 / set), the one of the last blow before the pause and the set-up
factor are listed in the summary's ``"restrikes"``; ``blows.csv`` carries the shaft set-up
factor of every blow (the largest over the segments).

Noise: the pile-head force of the first blow past each chosen depth is turned into
one-third-octave band energies (IEC 61260-1, base 10; :func:`anvilwave.pile.post.spectra.
third_octave_band_energies`), valid band stated.
"""

from __future__ import annotations

import bisect
import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from anvilwave.analyses.drive import driving_weight
from anvilwave.analyses.impact import energy_balance
from anvilwave.config.drive import impact_at, load_srd_source, pile_soil_at, segment_capacities
from anvilwave.config.install import InstallSettings, segment_soil_types, setup_pile_soil
from anvilwave.engine.direct import build_engine
from anvilwave.inputs import InputError
from anvilwave.output.plots import plot_installation
from anvilwave.output.progress import Step
from anvilwave.output.progress import bar as progress_bar
from anvilwave.output.tables import write_csv, write_dict_rows
from anvilwave.pile.post.fatigue import StreamingMinerDamage, sn_curve
from anvilwave.pile.post.spectra import third_octave_band_energies

BLOW_COLUMNS = ("blow [-]", "tip_depth [m]", "set [m]", "energy_setting [J]", "enthru [J]",
                "max_compression_stress [Pa]", "max_tension_stress [Pa]",
                "max_pile_head_force [N]", "srd [N]", "shaft_setup_factor [-]",
                "energy_residual_relative [-]")
FATIGUE_COLUMNS = ("depth_below_head [m]", "sn_curve", "environment", "scf [-]",
                   "thickness [m]", "damage [-]", "closed_cycles [-]")
"""Columns of ``fatigue.csv``."""
SPECTRA_COLUMNS = ("tip_depth [m]", "band_centre [Hz]", "band_energy_level [dB]", "valid [-]")
"""Columns of ``spectra.csv``."""


@dataclass
class InstallResult:
    """A blow-by-blow installation (``anvilwave install``).

    Parameters
    ----------
    source : str
        The system file.
    blows : list of dict
        One row per blow, keyed by :data:`BLOW_COLUMNS` (the columns of ``blows.csv``).
    fatigue : list of dict
        One row per fatigue section, keyed by :data:`FATIGUE_COLUMNS` (``fatigue.csv``):
        Miner's damage [-] and the closed cycles [-] over the whole installation.
    spectra : list of dict
        The pile-head force band levels of the first blow past each spectra depth
        (``spectra.csv``: tip depth [m], band centre [Hz], band energy level [dB], valid).
    summary : dict
        The entries of ``summary.json``: ``"total_blows [-]"``, ``"start_depth [m]"``,
        ``"final_depth [m]"``, ``"refusal_depth [m]"``, ``"driving_time [s]"``,
        ``"max_damage [-]"``, ``"stopped_by"``, ``"wall_time [s]"`` ...
    """

    source: str
    blows: list[dict]
    fatigue: list[dict]
    spectra: list[dict]
    summary: dict

    def write(self, out, title: str = "", driveability: dict | None = None) -> None:
        """Write the results into a ResultWriter ``out``.

        blows.csv, fatigue.csv, spectra.csv, summary.json and installation.png.

        Parameters
        ----------
        out : ResultWriter
            The writer (:mod:`anvilwave.output.writer`).
        title : str, default ""
            Title of the plot.
        driveability : dict or None, default None
            Driveability CSV columns overlaid on the blow count (one blow per depth).
        """
        write_csv({c: np.array([r[c] for r in self.blows], dtype=float) for c in BLOW_COLUMNS},
                  out.part("blows.csv"))
        write_dict_rows(self.fatigue, FATIGUE_COLUMNS, out.part("fatigue.csv"))
        write_dict_rows(self.spectra, SPECTRA_COLUMNS, out.part("spectra.csv"))
        summary = dict(self.summary)
        summary["system"] = Path(self.source).name
        out.part("summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        plot_installation({"blows": self.blows, "fatigue": self.fatigue,
                           "spectra": self.spectra, "summary": summary},
                          out.part("installation.png"), title=title, driveability=driveability)


def install(cfg, *, anvil: str | None = None, progress: bool = False) -> InstallResult:
    """Drive the pile blow by blow from the self-weight penetration to the target or refusal.

    With the residual stresses, fatigue and spectra of ``[installation]``.

    Parameters
    ----------
    cfg : SystemConfig
        A system with a ``[driveability]`` table (energy schedule, refusal) and optionally
        ``[installation]`` (defaults: :class:`~anvilwave.config.install.InstallSettings`).
    anvil : str, optional
        Install with this anvil model instead of the system's.
    progress : bool, default False
        A progress bar over the penetration.

    Returns
    -------
    InstallResult
        The blow rows, fatigue rows, spectra rows and summary.

    Raises
    ------
    InputError
        If the system has no ``[driveability]`` table, or the target depth or the pauses break
        a rule (:func:`run_installation`).
    """
    if anvil is not None:
        cfg = cfg.with_anvil_model(anvil)
    if cfg.drive is None:
        raise InputError(str(cfg.source), "driveability", "the installation takes its energy "
                                                          "schedule and refusal from a "
                                                          "[driveability] table")
    srd = cfg.srd if cfg.srd is not None else load_srd_source(None, cfg.source, cfg.pile_soil)
    settings = cfg.install if cfg.install is not None else InstallSettings()
    with Step(f"{cfg.anvil.model} anvil: building the engine (the modes of the anvil and the "
              "ram)...", enabled=progress):
        engine = build_engine(cfg)
    return run_installation(cfg, srd, cfg.drive, settings, engine, progress=progress)


def fatigue_sections(pile_soil, settings: InstallSettings):
    """The fatigue sections: the pile spring nearest each weld depth, or every spring.

    Parameters
    ----------
    pile_soil : PileSoil
        The pile and its soil.
    settings : InstallSettings
        The ``[installation]`` settings (weld depths).

    Returns
    -------
    index : numpy.ndarray
        Spring index of each section.
    depth : numpy.ndarray
        Depth below the pile head [m].
    thickness : numpy.ndarray
        Wall thickness [m].
    """
    seg = pile_soil.pile.discretise()
    springs = seg.bottom[:-1]  # spring i joins segment i and i + 1 at this depth
    if settings.weld_depths is None:
        index = np.arange(springs.size)
    else:
        index = np.array([int(np.argmin(np.abs(springs - d))) for d in settings.weld_depths])
    thickness = np.minimum(seg.wall_thickness[index], seg.wall_thickness[index + 1])
    return index, springs[index], thickness


def self_weight_penetration(cfg, srd, engine, multiplier: float, step: float = 0.1) -> float:
    """First tip depth (on a ``step`` grid) where the SRD carries the driving weight.

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    srd : SrdSource
        The SRD source.
    engine : Engine
        The built engine (its static head force).
    multiplier : float
        SRD factor of the bound [-].
    step : float, default 0.1
        Spacing of the depth grid [m].

    Returns
    -------
    float
        The self-weight penetration [m].
    """

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
                     progress: bool = False, energy_check: bool = False) -> InstallResult:
    """Simulate every blow of an installation.

    Parameters
    ----------
    cfg : SystemConfig
        The system.
    srd : SrdSource
        The SRD source.
    drive : DriveSettings
        The ``[driveability]`` settings (energy schedule, refusal).
    settings : InstallSettings
        The ``[installation]`` settings.
    engine : Engine
        The built engine for ``cfg``.
    progress : bool, default False
        A progress bar over the penetration.
    energy_check : bool, default False
        Book every blow's energies and give its relative energy residual
        (``energy_residual_relative [-]``; NaN without).

    Returns
    -------
    InstallResult
        The blow rows, fatigue rows, spectra rows and summary.

    Raises
    ------
    InputError
        If the target depth lies beyond the pile, or pauses need a soil type the SRD lacks.
    """

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
    pending_pauses = [p for p in settings.pauses if p[0] >= start]
    if pending_pauses and settings.setup_soil is None and settings.setup_a is None \
            and segment_soil_types(
            srd, np.array([0.0])) is None:
        raise InputError(cfg.source, "installation.setup_soil",
                         "the pauses' set-up needs the soil type ('sand' or 'clay') where the "
                         "SRD has no soil layers")
    pause = None  # the active pause: depth, duration, restart tip, factor and counts
    restrikes: list[dict] = []
    factor_now = 1.0

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
    warming = Step(f"first blow at {tip:.2f} m (compiling the kernels on a first run, about "
                 "30 s)...", enabled=progress).__enter__()
    try:
        for k in range(1, settings.max_blows + 1):
            restart = bool(pending_pauses) and tip >= pending_pauses[0][0]
            if restart:
                _, duration = pending_pauses.pop(0)
                before = 1.0 / rows[-1]["set [m]"] if rows and rows[-1]["set [m]"] > 0 \
                    else None
                pause = {"depth": tip, "duration": duration, "restart": tip}
                restrikes.append({"depth [m]": tip, "pause [h]": duration / 3600.0,
                                  "blow_count_before [1/m]": before})
            if pause is not None or restart or tip - built_at >= settings.srd_update:
                ps, shaft, toe = pile_soil_at(cfg.pile_soil, srd, tip, multiplier)
                factor_now = 1.0
                if pause is not None:
                    ps, shaft, factor_now = setup_pile_soil(
                        ps, srd, tip, settings, pause["duration"], pause["depth"],
                        tip - pause["restart"])
                eng = engine.with_pile_soil(ps)
                built_at = tip
                if pause is not None and factor_now - 1.0 < 1e-4:
                    pause = None  # remoulded: the next rebuilds follow srd_update again
            energy, velocity = impact_at(drive, tip, cfg)
            spectrum = bool(pending_spectra) and tip >= pending_spectra[0]
            blow = eng.blow(state=state, impact_velocity=velocity, duration=drive.duration,
                            record_interval=settings.record_interval,
                            record=spectrum or energy_check, energy=energy_check,
                            sections=index)
            miner.add_blow(blow.section_strain * stress_factor)
            state = blow.final_state
            set_m = max(float(blow.permanent_set), 0.0)
            enthru = blow.emx_gauge if drive.enthru_location == "gauge" else blow.emx_head
            rows.append({"blow [-]": k, "tip_depth [m]": tip, "set [m]": set_m,
                         "energy_setting [J]": energy, "enthru [J]": float(enthru),
                         "max_compression_stress [Pa]": float(blow.max_compression_stress),
                         "max_tension_stress [Pa]": float(blow.max_tension_stress),
                         "max_pile_head_force [N]": float(blow.max_pile_head_force),
                         "srd [N]": shaft + toe, "shaft_setup_factor [-]": factor_now,
                         "energy_residual_relative [-]":
                             energy_balance(blow)["residual_relative [-]"] if energy_check
                             else float("nan")})
            if restart:
                restrikes[-1].update({"shaft_setup_factor [-]": factor_now,
                                      "restrike_blow_count [1/m]": 1.0 / set_m if set_m > 0
                                      else None})
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
            if k == 1:  # compiled: the bar starts now, its rate and estimate are true
                warming.__exit__(None, None, None)
                bar = progress_bar(round(target - tip, 2), enabled=progress, warm=0,
                                   unit="m", desc="installation",
                                   bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} m "
                                              "[{elapsed}<{remaining}]")
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
        warming.__exit__(None, None, None)
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
        "restrikes": restrikes,
        "stopped_by": ("refusal" if refusal_depth is not None else
                       "target depth" if tip >= target else "max_blows"),
        "wall_time [s]": time.perf_counter() - start_wall,
    }
    summary["seconds_per_blow [s]"] = summary["wall_time [s]"] / max(total, 1)
    return InstallResult(source=str(cfg.source), blows=rows, fatigue=fatigue_rows,
                         spectra=spectra_rows, summary=summary)
