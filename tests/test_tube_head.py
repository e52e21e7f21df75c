"""The anvil's rings on a tube head (``[anvil] pile_head = "tube"``,
anvilwave/pile/head_kernel.py): the
1D head's response the correction removes is the engine's own, the engine's blow is the study's
closed loop on the FEA's pile, its band levels against the reference FEA, its energy balance and
the refusals."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from anvilwave.analyses.compare import ModelRun, band_levels, fea_config, without_soil
from anvilwave.analyses.impact import total_energy
from anvilwave.config.system import load_system
from anvilwave.engine.direct import build_engine
from anvilwave.inputs import InputError
from anvilwave.pile.head_kernel import rod_head_response
from anvilwave.pile.kernels import HEAD_EXTRAPOLATION, stable_time_step
from anvilwave.pile.model import substeps

from .study_loop import loop_on_feas_pile

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "anvilwave" / "examples"


def on_rings(cfg, head: str, rings: int = 3):
    spec = cfg.anvil.spec
    return dataclasses.replace(cfg, anvil=dataclasses.replace(
        cfg.anvil, pile_head=head, spec=dataclasses.replace(
            spec, interfaces=dataclasses.replace(spec.interfaces, pile_rings=rings))))


@pytest.fixture(scope="module")
def table1():
    return without_soil(load_system(EXAMPLES / "table1.toml"))


@pytest.fixture(scope="module")
def blows(table1):
    """Table 1's blow with three rings on the 1D head and on the tube head."""
    return {head: build_engine(on_rings(table1, head)).blow(energy_interval=2e-5)
            for head in ("rod", "tube")}


def test_rod_response_is_the_engines_rod(table1, blows):
    """The 1D head's response the correction takes out (:func:`rod_head_response`, the pile's
    top section continued, a unit force held over one step) convolved with the engine's pile
    force (its changes from the anvil's weight) is the engine's pile-head displacement in the
    Table 1 blow to 1e-9 of its peak (measured 4e-15: the pile is linear, the response the
    same kernels'); if it were the face's instead of the top mass's it would be off by 0.4 %."""
    cfg = on_rings(table1, "rod")
    blow = blows["rod"]
    arrays = cfg.pile_soil.arrays()
    h = 2e-5
    force = blow.columns["anvil_pile_force [N]"]
    n_sub = substeps(h, float(stable_time_step(arrays.pile, arrays.soil)))
    rod = rod_head_response(cfg.pile_soil.pile, h, force.size, n_sub,
                            float(arrays.probes[HEAD_EXTRAPOLATION]))
    change = force - build_engine(cfg).anvil.unit.anvil.total_mass * cfg.gravity
    u = np.array([rod[1:s + 1] @ change[s - 1::-1][:s] for s in range(force.size)])
    head = blow.columns["pile_head_displacement [m]"]
    engine = head - head[0]
    assert np.abs(u - engine).max() <= 1e-9 * np.abs(engine).max()


def test_engine_is_the_study_loop_on_the_feas_pile(table1, blows):
    """The engine's blow on the tube head against the pile-port study's closed loop on the
    FEA's own pile (benchmarks/study_pile_port.py: other code, the anvil and the ram meshed
    afresh with six patches on their faces, the tube's kernel as the whole pile instead of the
    1D pile plus its correction): pile force within 0.5 % of the peak RMS (measured 0.1 %)."""
    out, dt = loop_on_feas_pile(table1, None)
    t = np.arange(out.shape[0]) * dt
    columns = blows["tube"].columns
    engine = np.interp(t, columns["time [s]"], columns["anvil_pile_force [N]"])
    assert np.sqrt(np.mean((engine - out[:, 0]) ** 2)) <= 0.005 * out[:, 0].max()


def test_tube_head_band_levels_against_the_fea(table1, blows):
    """Table 1 against the reference FEA, one-third-octave bands of the pile-head force: on the
    tube head every band from 1 to 4 kHz is within 1 dB (measured +0.1 to +0.7 dB), every valid
    band to 4 kHz within 1.5 dB (measured 1.25 dB, the 398 Hz band: the uniform ram port); on
    the 1D head the 2.5 kHz band is more than 2 dB high (measured +3.3 dB), so the test tells
    the two heads apart."""
    from anvilwave.fea.cache import cached_impact_fea

    fea = cached_impact_fea(fea_config(table1))
    runs = {"fea": ModelRun("fea", fea.to_columns(), fea.wall_time, {})}
    for head, blow in blows.items():
        runs[head] = ModelRun(head, blow.columns, 0.0, {})
    spectra = band_levels(runs, 5000.0)
    centre = np.array(spectra["band_centre_frequency [Hz]"])
    valid = np.array(spectra["valid [-]"], bool) & (centre <= 4000.0)

    def deviation(head):
        return np.array([np.nan if d is None else d
                         for d in spectra["deviation_from_fea [dB]"][head]])

    tube = deviation("tube")
    upper = valid & (centre >= 990.0)
    assert np.abs(tube[upper]).max() <= 1.0
    assert np.abs(tube[valid]).max() <= 1.5
    rod = deviation("rod")
    assert rod[np.argmin(np.abs(centre - 2512.0))] > 2.0


def test_tube_head_energy_balance(blows):
    """The blow's total energy on the tube head, the work the rings hand to the tube beyond the
    1D head included, stays within 0.5 % of the impact energy (measured -0.19 % to +0.25 %,
    -0.05 % at the end), the bound of the rings' balance on the 1D head."""
    blow = blows["tube"]
    total = total_energy(blow.energies)
    drift = (total - total[0]) / blow.input_energy
    assert np.abs(drift).max() <= 5e-3


def test_tube_head_refusals(table1, tmp_path):
    text = (EXAMPLES / "table1.toml").read_text().replace(
        'file = "anvils/xl8.toml"',
        f'file = "{(EXAMPLES / "anvils" / "xl8.toml").as_posix()}"\npile_head = "tube"')
    one = tmp_path / "one.toml"
    one.write_text(text)
    with pytest.raises(InputError, match="pile_head.*needs pile_port_rings >= 2"):
        load_system(one)
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(text.replace('pile_head = "tube"', 'pile_head = "shell"'))
    with pytest.raises(InputError, match="pile_head"):
        load_system(wrong)
    from anvilwave.engine.fmus import build_system_fmus

    with pytest.raises(InputError, match="pile_head.*in-process engine only"):
        build_system_fmus(on_rings(table1, "tube"), tmp_path / "fmus")
    with pytest.raises(ValueError, match="longer than the tube head's kernel"):
        build_engine(on_rings(table1, "tube")).blow(duration=2 * table1.duration)
    pile = table1.pile_soil.pile
    thinner = dataclasses.replace(table1, pile_soil=dataclasses.replace(
        table1.pile_soil, pile=dataclasses.replace(pile, sections=(dataclasses.replace(
            pile.sections[0], wall_thickness=0.1),) + pile.sections[1:])))
    with pytest.raises(InputError, match="pile_head.*must be the same ring"):
        build_engine(on_rings(thinner, "tube"))
