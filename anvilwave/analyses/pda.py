"""PDA records in the system layer: the Case method (``anvilwave pda``), signal matching
(``anvilwave match``) and the paper's Fig. 4 and 5 (``anvilwave compare-pda``), plus the PDA
quantities of simulated blows (:func:`pda_summary`).

Records are gauge records (``time [s]``, ``force [N]``, ``velocity [m/s]``) or raw channels
(``time [s]``, ``strain_1 [-]``/``[microstrain]``, ``strain_2``, ``acceleration_1 [m/s^2]``/
``[g]``, ``acceleration_2``), told apart by their header (:mod:`anvilwave.pile.pda.records`). Lines
at the
top of the file that start with ``#`` are comments (where the record comes from); they are
carried into the results as ``record_notes``.

Every command writes its folder through :class:`anvilwave.output.writer.ResultWriter` (all files or
none). Bad records and inputs stop with one :class:`anvilwave.InputError`.

References
----------
Rausche, F., Goble, G.G., Likins, G.E. (1985). Dynamic determination of pile capacity. ASCE J.
Geotech. Eng. 111(3), 367-383.
Ligthart, J.A.J., Orlando, M. A novel anvil modelling approach for pile driveability
prediction, validated with PDA measurements (HVR Engineering): Fig. 4 and 5.
"""

from __future__ import annotations

import json
import math
import re
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from anvilwave.analyses.impact import compute_anvil_modes, gauge_section, simulate
from anvilwave.analyses.match import MatchSettings, match_record
from anvilwave.config.system import load_system
from anvilwave.inputs import InputError, read_text
from anvilwave.output.pda_plots import plot_compare_pda, plot_match, plot_pda, plot_static_load_test
from anvilwave.output.tables import write_csv
from anvilwave.output.writer import ResultWriter
from anvilwave.pile.pda.case_method import (
    case_method,
    transferred_energy,
    wave_down,
    wave_up,
)
from anvilwave.pile.pda.records import (
    CLIP_RUN,
    GaugeRecord,
    gauge_record_from_raw,
    read_gauge_record,
)
from anvilwave.pile.pda.signal_matching import IMPOSED
from anvilwave.pile.pile import STEEL_DENSITY, STEEL_YOUNGS_MODULUS

STEEL_WAVE_SPEED = math.sqrt(STEEL_YOUNGS_MODULUS / STEEL_DENSITY)
"""Bar wave speed of the project's steel, sqrt(210 GPa / 7850 kg/m^3) = 5172.2 m/s."""
RAW_MARKER = "strain_1 ["
"""A header with a column starting like this is a raw-channel record."""
ONSET_FRACTION = 0.2
"""compare-pda: a force 'arrives' when it first exceeds this fraction of its peak (as
:data:`anvilwave.analyses.compare.ARRIVAL_FRACTION`)."""
ALIGNMENTS = ("none", "rom", "lumped")
"""compare-pda: put the record's force arrival on that model's, or keep the record's time."""


# ---------------------------------------------------------------------------------- records
def load_record(path: str | Path, *, area: float | None = None,
                elastic_modulus: float = STEEL_YOUNGS_MODULUS,
                strain_calibration: tuple[float, float] = (1.0, 1.0),
                acceleration_calibration: tuple[float, float] = (1.0, 1.0),
                clip_run: int = CLIP_RUN) -> tuple[GaugeRecord, list[str], str]:
    """Read a gauge record or a raw-channel record (module notes).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    area : float or None, default None
        Steel area at the gauges [m^2] (raw channels: force = E A mean strain).
    elastic_modulus : float, default STEEL_YOUNGS_MODULUS
        E [Pa] (raw channels).
    strain_calibration : tuple of float, default (1.0, 1.0)
        Factors on the two raw strain channels [-].
    acceleration_calibration : tuple of float, default (1.0, 1.0)
        Factors on the two raw acceleration channels [-].
    clip_run : int, default CLIP_RUN
        See :mod:`anvilwave.pile.pda.records` [-].

    Returns
    -------
    record : GaugeRecord
        The gauge record.
    comments : list of str
        The comment lines of the file.
    kind : str
        ``"gauge"`` or ``"raw"``.

    Raises
    ------
    InputError
        If a raw-channel record comes without ``area``, or the file breaks a rule of
        :mod:`anvilwave.pile.pda.records`.
    """
    path = Path(path)
    lines = read_text(path).splitlines(keepends=True)
    notes = []
    while lines and lines[0].lstrip().startswith("#"):
        notes.append(lines.pop(0).strip().lstrip("#").strip())
    header = lines[0] if lines else ""
    kind = "raw" if RAW_MARKER in header else "gauge"
    if kind == "raw" and area is None:
        raise InputError(path, "strain_1", "a raw-channel record needs the steel area at the "
                                           "gauges (--area) to convert strain to force")
    with tempfile.TemporaryDirectory(prefix="anvilwave-record-") as tmp:
        source = path
        if notes:  # the readers take the header on the first line: hand them the data
            source = Path(tmp) / path.name
            source.write_text("".join(lines), encoding="utf-8")
        try:
            if kind == "raw":
                record = gauge_record_from_raw(
                    source, area=area, elastic_modulus=elastic_modulus,
                    strain_calibration=strain_calibration,
                    acceleration_calibration=acceleration_calibration, clip_run=clip_run)
            else:
                record = read_gauge_record(source, clip_run)
        except InputError as exc:
            rule = re.sub(r"line (\d+)", lambda m: f"line {int(m.group(1)) + len(notes)}",
                          exc.rule)
            raise InputError(path, exc.key, rule) from None
    return GaugeRecord(record.time, record.force, record.velocity, str(path)), notes, kind


def _finite(value):
    return None if value is None or not math.isfinite(value) else float(value)


# ---------------------------------------------------------------------------------- Case method
@dataclass
class PdaResult:
    """The Case method of one record (``anvilwave pda``).

    Parameters
    ----------
    record : str
        The record file.
    summary : dict
        ``RTL [N]``, ``RSP [N]``, ``RMX [N]``, ``EMX [J]``, ``FMX [N]``, ``CSX [Pa]``,
        ``TSX [Pa]``, ``BTA [-]``.
    content : dict
        ``pda.json``: the summary, ``details`` (t1, 2L/c, the waves at t1 ...), ``inputs``
        and the record's notes.
    columns : dict
        ``pda.csv``: time [s], force [N], Z v [N], wave down and up [N], transferred energy
        [J].
    jc : float
        The Case damping used [-].
    case : object, optional
        The Case method's full result (:func:`anvilwave.pile.pda.case_method.case_method`).
    """

    record: str
    summary: dict
    content: dict
    columns: dict
    jc: float
    case: object = None

    def write(self, out_dir: str | Path, force: bool = False) -> None:
        """Write ``pda.json``, ``pda.csv`` and ``pda.png`` into the result folder ``out_dir``.

        Parameters
        ----------
        out_dir : str or pathlib.Path
            The result folder.
        force : bool, default False
            Replace a folder holding another command's result (``--force``).
        """
        with ResultWriter(out_dir, command="pda", force=force) as out:
            out.part("pda.json").write_text(json.dumps(self.content, indent=2) + "\n")
            write_csv(self.columns, out.part("pda.csv"))
            plot_pda(self.columns, self.case, out.part("pda.png"),
                     title=f"{Path(self.record).name}: Case method (Jc = {self.jc:g})")


def pda(record_path: str | Path, *, length: float, area: float,
            elastic_modulus: float = STEEL_YOUNGS_MODULUS, wave_speed: float | None = None,
            jc: float, t1_signal: str = "velocity", rmx_window: float | None = None,
            strain_calibration: tuple[float, float] = (1.0, 1.0),
            acceleration_calibration: tuple[float, float] = (1.0, 1.0)) -> PdaResult:
    """The Case method of a record (``anvilwave pda``).

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV.
    length : float
        Pile length below the gauges L [m].
    area : float
        Steel area at the gauges A [m^2].
    elastic_modulus : float, default STEEL_YOUNGS_MODULUS
        E [Pa] (default steel, 210 GPa).
    wave_speed : float or None, default None
        c [m/s] (default sqrt(E / 7850 kg/m^3): 5172.2 m/s for steel).
    jc : float
        Case damping factor Jc [-].
    t1_signal : {"velocity", "force"}
        See :func:`anvilwave.pile.pda.case_method.case_method`.
    rmx_window : float or None, default None
        See :func:`anvilwave.pile.pda.case_method.case_method` [s].
    strain_calibration : tuple of float, default (1.0, 1.0)
        Raw-channel strain factors [-].
    acceleration_calibration : tuple of float, default (1.0, 1.0)
        Raw-channel acceleration factors [-].

    Returns
    -------
    PdaResult
        Its ``summary`` ``{"RTL [N]", "RSP [N]", "RMX [N]", "EMX [J]", "FMX [N]", "CSX [Pa]",
        "TSX [Pa]", "BTA [-]"}``; ``content`` (pda.json) holds it plus ``details`` and ``inputs``.

    Raises
    ------
    InputError
        If ``wave_speed``, ``length`` or ``area`` is not a positive number, ``jc`` is not a
        number >= 0, or the record cannot be analysed.
    """
    for name, value in (("length", length), ("area", area),
                        ("elastic_modulus", elastic_modulus)):
        if not (value is not None and value > 0.0 and math.isfinite(value)):
            raise InputError(record_path, name, f"must be a positive number, got {value!r}")
    c = math.sqrt(elastic_modulus / STEEL_DENSITY) if wave_speed is None else wave_speed
    if not (c > 0.0 and math.isfinite(c)):
        raise InputError(record_path, "wave_speed", f"must be a positive number, got {c!r}")
    if not (jc >= 0.0 and math.isfinite(jc)):
        raise InputError(record_path, "jc", f"must be a number >= 0, got {jc!r}")
    record, notes, kind = load_record(record_path, area=area, elastic_modulus=elastic_modulus,
                                      strain_calibration=strain_calibration,
                                      acceleration_calibration=acceleration_calibration)
    try:
        result = case_method(record.time, record.force, record.velocity, area=area,
                             elastic_modulus=elastic_modulus, wave_speed=c,
                             length_below_gauges=length, case_damping=jc,
                             t1_signal=t1_signal, rmx_window=rmx_window)
    except ValueError as exc:
        raise InputError(record_path, "time [s]", str(exc)) from None
    summary = result.summary()
    z = result.impedance
    columns = {
        "time [s]": record.time, "force [N]": record.force,
        "impedance_times_velocity [N]": z * record.velocity,
        "wave_down [N]": wave_down(record.force, record.velocity, z),
        "wave_up [N]": wave_up(record.force, record.velocity, z),
        "transferred_energy [J]": transferred_energy(record.time, record.force,
                                                     record.velocity),
    }
    content = dict(summary)
    content["details"] = {k: _finite(v) for k, v in result.details().items()}
    content["inputs"] = {"record": Path(record_path).name, "record_kind": kind,
                         "length_below_gauges [m]": length, "area [m^2]": area,
                         "elastic_modulus [Pa]": elastic_modulus, "wave_speed [m/s]": c,
                         "case_damping [-]": jc, "t1_signal": t1_signal}
    content["record_notes"] = notes

    return PdaResult(record=str(record_path), summary=summary, content=content,
                     columns=columns, jc=jc, case=result)


def run_pda(record_path: str | Path, out_dir: str | Path, **options) -> dict:
    """:func:`pda` written to ``out_dir`` (``pda.json``, ``pda.csv``, ``pda.png``).

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV.
    out_dir : str or pathlib.Path
        The result folder.
    **options
        Keyword arguments of :func:`pda`.

    Returns
    -------
    dict
        The summary.
    """
    result = pda(record_path, **options)
    result.write(out_dir)
    return result.summary




# ---------------------------------------------------------------------------------- matching
@dataclass
class MatchResult:
    """Signal matching of one record (``anvilwave match``).

    Parameters
    ----------
    record : str
        The record file.
    content : dict
        ``match.json``: ``rut [N]``, ``rut_shaft [N]``, ``rut_toe [N]``,
        ``match_quality [-]``, the fitted shaft zones, quakes [m] and dampings [s/m].
    match : object
        The match (:func:`anvilwave.analyses.match.match_record`): its ``columns``
        (measured and computed waves [N]) and ``static_load_test`` (load [N], settlement
        [m]).
    config : SystemConfig
        The system matched.
    """

    record: str
    content: dict
    match: object
    config: object

    def write(self, out_dir: str | Path, force: bool = False) -> None:
        """Write the match files into the result folder ``out_dir``.

        ``match.json``, ``match.csv``, ``match.png``, ``static_load_test.csv`` and
        ``static_load_test.png``.

        Parameters
        ----------
        out_dir : str or pathlib.Path
            The result folder.
        force : bool, default False
            Replace a folder holding another command's result (``--force``).
        """
        result = self.match
        with ResultWriter(out_dir, command="match", force=force) as out:
            out.part("match.json").write_text(json.dumps(self.content, indent=2) + "\n")
            write_csv(result.columns, out.part("match.csv"))
            write_csv(result.static_load_test, out.part("static_load_test.csv"))
            plot_match(result.columns, out.part("match.png"),
                       title=f"{Path(self.record).name}: signal matching, MQ = "
                             f"{result.match_quality:.3f}, Rut = {result.soil.rut / 1e6:.2f} MN")
            plot_static_load_test(result, self.config, out.part("static_load_test.png"))


def match(record_path: str | Path, system_path: str | Path, *,
              shaft_zones: int = 3, imposed: str = "velocity",
              segment_length: float | None = None, fit_quakes: bool = True,
          fit_dampings: bool = True, preload: float | None = None) -> MatchResult:
    """Signal matching of a record with the pile and soil of a system file.

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV (raw: converted with the area and modulus of the
        system's pile at the gauges).
    system_path : str or pathlib.Path
        System file (pile, gauge depth, soil model and starting SRD, gravity, and the hammer
        and anvil resting on the pile).
    shaft_zones : int, default 3
        Number of shaft resistance zones [-].
    imposed : {"velocity", "wave_down"}
        The measured signal imposed at the gauges.
    segment_length : float or None, default None
        Segment length of the matching model [m] (default: the system's).
    fit_quakes : bool, default True
        Fit the quakes, or keep the system's.
    fit_dampings : bool, default True
        Fit the dampings, or keep the system's.
    preload : float or None, default None
        Force on the gauges at rest [N] (default from the system file).

    Returns
    -------
    MatchResult
        Its ``content`` is match.json (``rut [N]``, ``rut_shaft [N]``, ``rut_toe [N]``,
        ``match_quality [-]``, the fitted parameters ...).

    Raises
    ------
    InputError
        If ``imposed`` is unknown, ``shaft_zones`` is not an integer >= 1, or the record
        cannot be matched.
    """

    if imposed not in IMPOSED:
        raise InputError(system_path, "imposed", f"must be one of {', '.join(IMPOSED)}, got "
                                                 f"{imposed!r}")
    if not (isinstance(shaft_zones, int) and shaft_zones >= 1):
        raise InputError(system_path, "shaft_zones", f"must be an integer >= 1, got "
                                                     f"{shaft_zones!r}")
    cfg = load_system(system_path)
    section = gauge_section(cfg)
    record, notes, kind = load_record(record_path, area=section.area,
                                      elastic_modulus=section.youngs_modulus)
    settings = MatchSettings(shaft_zones=shaft_zones, imposed=imposed,
                             segment_length=segment_length, fit_quakes=fit_quakes,
                             fit_dampings=fit_dampings, preload=preload)
    try:
        result = match_record(record, cfg, settings)
    except ValueError as exc:  # a record the match cannot use (no rising wave down ...)
        raise InputError(record_path, "", str(exc)) from None
    content = result.summary()
    content["record"] = Path(record_path).name
    content["record_kind"] = kind
    content["system"] = Path(system_path).name
    content["record_notes"] = notes
    return MatchResult(record=str(record_path), content=content, match=result, config=cfg)


def run_match(record_path: str | Path, system_path: str | Path, out_dir: str | Path,
              **options) -> dict:
    """:func:`match` written to ``out_dir``.

    ``match.json``, ``match.csv``, ``match.png``, ``static_load_test.csv``,
    ``static_load_test.png``.

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV.
    system_path : str or pathlib.Path
        The system file.
    out_dir : str or pathlib.Path
        The result folder.
    **options
        Keyword arguments of :func:`match`.

    Returns
    -------
    dict
        The match.json content.
    """
    result = match(record_path, system_path, **options)
    result.write(out_dir)
    return result.content


# ---------------------------------------------------------------------------------- Fig. 4, 5
def onset_time(time, force) -> float:
    """First time a force exceeds ONSET_FRACTION of its peak [s] (NaN if never).

    Parameters
    ----------
    time : array_like
        t [s].
    force : array_like
        F [N].

    Returns
    -------
    float
        The onset time [s], NaN if the force never exceeds the fraction.
    """
    f = np.asarray(force, dtype=float)
    above = np.flatnonzero(f > ONSET_FRACTION * float(np.max(f)))
    return float(np.asarray(time)[above[0]]) if above.size else math.nan


@dataclass
class ComparePdaResult:
    """The paper's Fig. 4 and 5 for one record (``anvilwave compare-pda``).

    Parameters
    ----------
    record : str
        The record file.
    content : dict
        ``compare_pda.json``: the measured and each model's peak force [N], peak velocity
        [m/s], their errors [-], normalised RMS errors [-], arrival times [s], the alignment
        and the record's time shift [s].
    columns : dict
        ``compare_pda.csv``: time [s], measured and each model's force [N] and velocity
        [m/s] on the record's samples.
    """

    record: str
    content: dict
    columns: dict

    def write(self, out_dir: str | Path, force: bool = False) -> None:
        """Write the json, csv and the two figures into the result folder ``out_dir``.

        Parameters
        ----------
        out_dir : str or pathlib.Path
            The result folder.
        force : bool, default False
            Replace a folder holding another command's result (``--force``).
        """
        name = Path(self.record).name
        with ResultWriter(out_dir, command="compare-pda", force=force) as out:
            out.part("compare_pda.json").write_text(json.dumps(self.content, indent=2) + "\n")
            write_csv(self.columns, out.part("compare_pda.csv"))
            plot_compare_pda(self.columns, "force [N]", out.part("fig4_pile_top_force.png"),
                             f"Fig. 4: pile-top force at the gauges, {name}")
            plot_compare_pda(self.columns, "velocity [m/s]",
                             out.part("fig5_pile_top_velocity.png"),
                             f"Fig. 5: pile-top velocity at the gauges, {name}")


def compare_pda(record_path: str | Path, system_path: str | Path, *,
                align: str | bool = "none", modal_data=None) -> ComparePdaResult:
    """The paper's Fig. 4 (pile-top force) and Fig. 5 (pile-top velocity) for a record.

    The system is simulated with the ROM anvil and with the lumped (rigid) anvil of its anvil
    file, over its ``[simulation] duration``; the gauge signals are compared with the record.
    The simulated force has its value at rest (the weights of the anvil and the pile above
    the gauges) removed, as gauges zeroed at rest do.

    By default the record keeps its own time (t = 0 is the ram impact in the simulations), and
    each model's ``force_arrival_error [s]`` (its force arrival, :func:`onset_time`, minus the
    record's) is a result. With ``align`` the record is shifted onto one model's arrival
    first (the shift is ``record_time_shift [s]``): that model's arrival error is then zero by
    construction (``arrival_aligned_on``), and only the other's difference to it, the anvil's
    wave travel the lumped model lacks, says something.

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV.
    system_path : str or pathlib.Path
        The system file.
    align : {"none", "rom", "lumped"} or bool, default "none"
        Keep the record's time (``"none"`` or False: a record whose t = 0 is the ram impact),
        or shift it so that its force arrival (:func:`onset_time`) coincides with the
        ``"rom"`` (or True) or ``"lumped"`` model's.
    modal_data : ModalData or path, optional
        Precomputed modal data of the anvil (default: from the cache or computed).

    Returns
    -------
    ComparePdaResult
        ``content`` (compare_pda.json) and ``columns`` (compare_pda.csv: record and models on
        the record's samples within the simulated window).

    Raises
    ------
    InputError
        If ``align`` is unknown, the system has no anvil file, the record is shorter than 2L/c
        or its time does not overlap the simulated window.
    """

    if align is True or align is False:
        align = "rom" if align else "none"
    if align not in ALIGNMENTS:
        raise InputError(system_path, "align", f"must be one of {', '.join(ALIGNMENTS)}, got "
                                               f"{align!r}")
    cfg = load_system(system_path)
    if cfg.anvil.spec is None:
        raise InputError(system_path, "anvil.file", "compare-pda runs the ROM and the lumped "
                                                    "anvil: the system needs an anvil file")
    section = gauge_section(cfg)
    record, notes, kind = load_record(record_path, area=section.area,
                                      elastic_modulus=section.youngs_modulus)
    pile = cfg.pile_soil.pile
    seg = pile.discretise()
    below = np.asarray(seg.top) >= pile.gauge_depth - 1e-9
    round_trip = 2.0 * float(np.sum(seg.length[below] / seg.wave_speed[below]))
    span = float(record.time[-1] - record.time[0])
    if span < round_trip:
        raise InputError(record_path, "time [s]",
                         f"the record spans {span:g} s, shorter than 2L/c = {round_trip:g} s "
                         "of the pile below the gauges")
    if modal_data is None:
        modal_data = compute_anvil_modes(cfg.anvil.spec, fmax=cfg.anvil.fmax).modal_data
    runs = {}
    for model in ("rom", "lumped"):
        blow = simulate(cfg.with_anvil_model(model), modal_data=modal_data)[0]
        c = blow.columns
        runs[model] = {"time": c["time [s]"],
                       "force": c["gauge_force [N]"] - c["gauge_force [N]"][0],
                       "velocity": c["gauge_velocity [m/s]"],
                       "rest_force": float(c["gauge_force [N]"][0])}
    measured_onset = onset_time(record.time, record.force)
    shift = 0.0
    if align != "none":
        shift = onset_time(runs[align]["time"], runs[align]["force"]) - measured_onset
    t_rec = record.time + shift
    start, end = runs["rom"]["time"][0], runs["rom"]["time"][-1]
    inside = (t_rec >= start) & (t_rec <= end)
    if np.count_nonzero(inside) < 3:
        raise InputError(record_path, "time [s]", f"the record (shifted by {shift:g} s) does "
                                                  "not overlap the simulated window "
                                                  f"[{start:g}, {end:g}] s")
    grid = t_rec[inside]
    columns = {"time [s]": grid, "measured_force [N]": record.force[inside],
               "measured_velocity [m/s]": record.velocity[inside]}
    for model, run in runs.items():
        columns[f"{model}_force [N]"] = np.interp(grid, run["time"], run["force"])
        columns[f"{model}_velocity [m/s]"] = np.interp(grid, run["time"], run["velocity"])
    f_m, v_m = columns["measured_force [N]"], columns["measured_velocity [m/s]"]
    content = {"measured": {"peak_force [N]": float(f_m.max()),
                            "peak_velocity [m/s]": float(v_m.max()),
                            "force_arrival_time [s]": onset_time(grid, f_m)},
               "alignment": align, "record_time_shift [s]": shift,
               "arrival_aligned_on": None if align == "none" else align}
    for model in runs:
        f, v = columns[f"{model}_force [N]"], columns[f"{model}_velocity [m/s]"]
        content[model] = {
            "peak_force [N]": float(f.max()), "peak_velocity [m/s]": float(v.max()),
            "peak_force_error [-]": float(f.max() / f_m.max() - 1.0),
            "peak_velocity_error [-]": float(v.max() / v_m.max() - 1.0),
            "force_normalised_rms_error [-]": float(np.sqrt(np.mean((f - f_m) ** 2))
                                                    / np.abs(f_m).max()),
            "velocity_normalised_rms_error [-]": float(np.sqrt(np.mean((v - v_m) ** 2))
                                                       / np.abs(v_m).max()),
            "force_arrival_time [s]": onset_time(runs[model]["time"], runs[model]["force"]),
            "removed_rest_force [N]": runs[model]["rest_force"],
        }
        # zero by construction for the model the record was aligned on
        content[model]["force_arrival_error [s]"] = (
            content[model]["force_arrival_time [s]"]
            - content["measured"]["force_arrival_time [s]"])
    content["rom_minus_lumped_arrival [s]"] = (content["rom"]["force_arrival_time [s]"]
                                               - content["lumped"]["force_arrival_time [s]"])
    content.update({"record": Path(record_path).name, "record_kind": kind,
                    "system": Path(system_path).name, "record_notes": notes})
    return ComparePdaResult(record=str(record_path), content=content, columns=columns)


def run_compare_pda(record_path: str | Path, system_path: str | Path, out_dir: str | Path,
                    **options) -> dict:
    """:func:`compare_pda` written to ``out_dir``.

    ``fig4_pile_top_force.png``, ``fig5_pile_top_velocity.png``, ``compare_pda.json``,
    ``compare_pda.csv``.

    Parameters
    ----------
    record_path : str or pathlib.Path
        Gauge record or raw channels CSV.
    system_path : str or pathlib.Path
        The system file.
    out_dir : str or pathlib.Path
        The result folder.
    **options
        Keyword arguments of :func:`compare_pda`.

    Returns
    -------
    dict
        The compare_pda.json content.
    """
    result = compare_pda(record_path, system_path, **options)
    result.write(out_dir)
    return result.content


__all__ = ["ALIGNMENTS", "STEEL_WAVE_SPEED", "ComparePdaResult", "MatchResult", "PdaResult",
           "compare_pda", "load_record", "match", "onset_time", "pda", "run_compare_pda",
           "run_match", "run_pda"]
