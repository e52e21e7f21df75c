"""The ``[installation]`` table of a system file: start and target depth, the SRD update
step, the fatigue sections and their S-N curve, the spectra depths, the pauses and the set-up
of the shaft during them (:mod:`anvilwave.pile.soil.setup`)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from anvilwave.inputs import Table
from anvilwave.pile.post.fatigue import EDITIONS, ENVIRONMENTS, dnv_rp_c203_curve
from anvilwave.pile.soil.setup import (
    DEFAULT_REMOULDING_LENGTH,
    SKOV_DENVER_1988,
    remoulded_setup,
    skov_denver_1988_for,
    skov_denver_1988_setup,
)

SETUP_METHODS = ("skov-denver-1988",)


@dataclass(frozen=True)
class InstallSettings:
    """The ``[installation]`` table.

    Parameters
    ----------
    start_depth : float or None, default None
        Tip depth of the first blow [m] (None: the self-weight penetration).
    target_depth : float or None, default None
        Final tip depth [m] (None: the last depth of ``[driveability]``).
    max_blows : int, default 20000
        Safety limit on the number of blows [-].
    srd_update : float, default 0.05
        Tip movement that triggers a rebuild of the SRD distribution [m].
    weld_depths : tuple or None, default None
        Sections for fatigue, depth below the pile head [m] (None: every spring).
    sn_curve : str, default "D"
        DNV-RP-C203 S-N curve of the sections.
    environment : str, default "seawater-cp"
        Environment of the S-N curve (:data:`anvilwave.pile.post.fatigue.ENVIRONMENTS`).
    edition : str, default "2016"
        Edition of DNV-RP-C203.
    scf : float, default 1.0
        Stress concentration factor of the sections [-].
    spectra_depths : tuple, default ()
        Tip depths whose first blow's head force spectrum is written [m].
    record_interval : float or None, default None
        Sampling of the stress histories and head force [s] (None: every step).
    pauses : tuple, default ()
        ((tip depth [m], duration [s]), ...): driving stops when the tip reaches each depth
        and restarts after the duration; sorted by depth.
    setup : str, default "skov-denver-1988"
        The set-up method of the shaft during a pause.
    setup_soil : {"sand", "clay"} or None, default None
        Soil type of the set-up where the SRD has no soil layers (None: the layers' types;
        required without layers when pauses are given).
    remoulding_length : float, default DEFAULT_REMOULDING_LENGTH
        E-folding penetration of the set-up gain after a restart [m].
    setup_a : float or None, default None
        A [-] of the set-up for every soil, overriding the soil types' values
        (site-specific, e.g. from restrike records); None: by soil type.
    setup_t0 : float or None, default None
        t0 [s] of the set-up for every soil, overriding the soil types' values; None: by
        soil type.
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
    pauses: tuple = ()
    setup: str = "skov-denver-1988"
    setup_soil: str | None = None
    remoulding_length: float = DEFAULT_REMOULDING_LENGTH
    setup_a: float | None = None
    setup_t0: float | None = None


def shaft_setup_factors(settings: InstallSettings, duration: float, middle_depths,
                        pause_depth: float, penetration: float, soil_types=None) -> np.ndarray:
    """Set-up factor [-] of each shaft segment after a pause.

    Remoulded by the penetration since the restart
    (:func:`anvilwave.pile.soil.setup.remoulded_setup`).

    Parameters
    ----------
    settings : InstallSettings
        The ``[installation]`` settings (method, soil type, remoulding length).
    duration : float
        The pause [s].
    middle_depths : array_like
        (N,) depth of each segment's embedded middle below the mudline [m] (negative or NaN
        above it).
    pause_depth : float
        Tip depth at the pause [m]: segments embedded above it gain, deeper not.
    penetration : float
        The penetration since the restart [m].
    soil_types : sequence of str or None, default None
        (N,) soil type of each segment (None: ``settings.setup_soil``).

    Returns
    -------
    numpy.ndarray
        (N,) set-up factor of each segment [-].
    """
    z = np.asarray(middle_depths, dtype=float)
    out = np.ones(z.shape)
    for k, depth in enumerate(z):
        if not (0.0 <= depth <= pause_depth):
            continue
        if settings.setup_a is not None:
            a = settings.setup_a
            t0 = settings.setup_t0 if settings.setup_t0 is not None else SKOV_DENVER_1988[
                "clay"][1]
            factor = skov_denver_1988_setup(duration, a, t0)
        else:
            kind = soil_types[k] if soil_types is not None else settings.setup_soil
            factor = skov_denver_1988_for(kind, duration)
        out[k] = remoulded_setup(factor, penetration, settings.remoulding_length)
    return out


def segment_middles(pile, tip: float) -> np.ndarray:
    """Depth below the mudline of each segment's embedded middle for the tip at ``tip``.

    Parameters
    ----------
    pile : PileSpec
        The pile.
    tip : float
        Tip depth below the mudline [m].

    Returns
    -------
    numpy.ndarray
        (N,) depths [m], NaN for a segment above the mudline.
    """
    seg = pile.discretise()
    mudline = pile.length - tip
    low = np.clip(seg.top - mudline, 0.0, tip)
    high = np.clip(seg.bottom - mudline, 0.0, tip)
    return np.where(high > low, 0.5 * (low + high), np.nan)


def segment_soil_types(srd, middles: np.ndarray):
    """The soil type at each depth from the SRD's soil layers.

    Below the layers, the deepest layer's type.

    Parameters
    ----------
    srd : SrdSource
        The SRD source.
    middles : numpy.ndarray
        Depths below the mudline [m] (:func:`segment_middles`).

    Returns
    -------
    list of str or None
        The soil type at each depth, or None where the SRD has no layers.
    """
    layers = getattr(getattr(srd, "profile", None), "layers", None)
    if not layers:
        return None
    kinds = []
    for z in middles:
        kind = layers[-1].soil_type
        for layer in layers:
            if z == z and layer.top <= z < layer.bottom:
                kind = layer.soil_type
                break
        kinds.append(kind)
    return kinds


def setup_pile_soil(ps, srd, tip: float, settings: InstallSettings, duration: float,
                    pause_depth: float, penetration: float):
    """The pile and soil with the shaft set up by a pause.

    ``ps`` (embedded to ``tip``, its capacities set) with the shaft set up by a pause of
    ``duration`` at ``pause_depth`` and remoulded by ``penetration`` since the restart
    (:func:`shaft_setup_factors`, the soil types of the SRD's layers or
    ``settings.setup_soil``).

    Parameters
    ----------
    ps : PileSoil
        The pile and soil, embedded to ``tip`` with its capacities set.
    srd : SrdSource
        The SRD source (its soil layers).
    tip : float
        Tip depth below the mudline [m].
    settings : InstallSettings
        The ``[installation]`` settings.
    duration : float
        The pause [s].
    pause_depth : float
        Tip depth at the pause [m].
    penetration : float
        The penetration since the restart [m].

    Returns
    -------
    pile_soil : PileSoil
        The pile and soil with the shaft set up.
    shaft : float
        Total shaft resistance [N].
    factor : float
        Largest set-up factor [-].
    """
    middles = segment_middles(ps.pile, tip)
    factors = shaft_setup_factors(settings, duration, middles, pause_depth, penetration,
                                  segment_soil_types(srd, middles))
    shaft, toe = ps.soil.capacities
    scaled = np.asarray(shaft, dtype=float) * factors
    return (replace(ps, soil=replace(ps.soil, capacities=(scaled, toe))), float(scaled.sum()),
            float(np.max(factors)))


def load_install_settings(table: Table | None) -> InstallSettings:
    """Read and validate ``[installation]`` (absent: the defaults).

    Parameters
    ----------
    table : Table or None
        The ``[installation]`` table.

    Returns
    -------
    InstallSettings
        The settings.

    Raises
    ------
    InputError
        If a key breaks its rule.
    """

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
        pauses=_pauses(table),
        setup=table.string("setup", "skov-denver-1988", choices=SETUP_METHODS),
        setup_soil=table.string("setup_soil", None, choices=tuple(SKOV_DENVER_1988)),
        remoulding_length=table.number("remoulding_length", DEFAULT_REMOULDING_LENGTH,
                                       gt=0.0, le=50.0, unit="m"),
        setup_a=table.number("setup_a", None, ge=0.0, le=20.0),
        setup_t0=_hours(table.number("setup_t0", None, gt=0.0, le=8760.0, unit="h")),
    )
    if s.setup_t0 is not None and s.setup_a is None:
        raise table.error("setup_t0", "give setup_a with it (A and t0 of one law)")
    if s.max_blows > 200_000:
        raise table.error("max_blows", f"must be at most 200000, got {s.max_blows}")
    table.finish()
    return s


def _hours(value: float | None) -> float | None:
    """Hours [h] to seconds [s] (None stays None)."""
    return None if value is None else 3600.0 * value


def _pauses(table: Table) -> tuple:
    """The ``pauses`` rows [tip depth [m], duration [h]] as ((depth [m], duration [s]), ...)."""
    rows = table.array("pauses", None, columns=2)
    if rows is None:
        return ()
    if np.any(rows[:, 0] <= 0.0) or np.any(np.diff(rows[:, 0]) <= 0.0):
        raise table.error("pauses", "rows [tip depth [m], duration [h]] need positive, "
                                    "strictly increasing depths")
    if np.any(rows[:, 1] <= 0.0) or np.any(rows[:, 1] > 24.0 * 365.0):
        raise table.error("pauses", "durations must be in (0, 8760] h")
    return tuple((float(d), 3600.0 * float(h)) for d, h in rows)
