"""`anvilwave impact --engine fmi|direct` write the same outputs with the same numbers."""

from __future__ import annotations

import json

import numpy as np
import pytest

from anvilwave.cli import main
from anvilwave.output.tables import read_csv

from .conftest import EXAMPLES


@pytest.mark.parametrize("anvil", ["rom", "lumped"])
def test_fmi_and_direct_outputs_agree(tmp_path, anvil, monkeypatch):
    """--engine fmi runs the native anvil FMU (its shipped binary: no C compiler needed) and
    writes the direct engine's numbers (1e-9 of each value)."""
    import anvilwave.engine.fmus as fmus
    import anvilwave.fmu.native_build as native_build

    built = []
    build = native_build.build_native_anvil_fmu
    monkeypatch.setattr(fmus, "build_native_anvil_fmu",
                        lambda *args, **kwargs: built.append(kwargs.get("lumped", False))
                        or build(*args, **kwargs))
    out = {}
    for engine in ("direct", "fmi"):
        out[engine] = tmp_path / engine
        assert main(["impact", str(EXAMPLES / "table1.toml"), "--engine", engine, "--anvil",
                     anvil, "--out", str(out[engine])]) == 0
    assert built == [False, True]  # the native Anvil and AnvilLumped were built and run
    a = json.loads((out["direct"] / "summary.json").read_text())
    b = json.loads((out["fmi"] / "summary.json").read_text())
    # the same kernels in the same order: only round-off differs (measured <= 1e-12)
    for key in ("peak_ram_anvil_force [N]", "peak_anvil_pile_force [N]", "peak_gauge_force [N]",
                "peak_pile_compression_stress [Pa]", "peak_pile_tension_stress [Pa]",
                "transferred_energy_unzeroed [J]", "permanent_set [m]", "simulated_time [s]"):
        assert b[key] == pytest.approx(a[key], rel=1e-9), key
    ca, cb = read_csv(out["direct"] / "impact.csv"), read_csv(out["fmi"] / "impact.csv")
    assert list(ca) == list(cb)
    for name in ("ram_anvil_force [N]", "anvil_pile_force [N]", "gauge_force [N]"):
        peak = np.abs(ca[name]).max()
        # the CSV carries 9 significant digits
        np.testing.assert_allclose(cb[name], ca[name], atol=1e-8 * peak)
