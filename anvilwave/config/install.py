"""The ``[installation]`` table of a system file: start and target depth, the SRD update
step, the fatigue sections and their S-N curve, the spectra depths."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from anvilwave.inputs import Table
from anvilwave.pile.post.fatigue import EDITIONS, ENVIRONMENTS, dnv_rp_c203_curve


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
