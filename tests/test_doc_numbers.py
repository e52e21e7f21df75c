"""Numbers the docs and the example files quote, computed: the ram contact dashpot of Table 1
and the lowest valid one-third-octave band of a 25 ms blow (what the demo prints)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from anvilwave.pile.post.spectra import third_octave_band_energies

from .conftest import EXAMPLES

ROOT = Path(__file__).resolve().parents[1]


def test_table1_ram_dashpot_is_quoted_as_computed():
    """ram_contact_damping = "ram-impedance": A sqrt(E rho) of the 1.8 m steel ram toe,
    1.033e8 N s/m, quoted as 1.03e8 in table1.toml, table1_interfaces.toml and theory.md."""
    area = np.pi * 0.9**2
    impedance = area * np.sqrt(210e9 * 7850.0)
    assert f"{impedance:.2e}" == "1.03e+08"
    for path in (EXAMPLES / "table1.toml", EXAMPLES / "table1_interfaces.toml",
                 ROOT / "docs" / "theory.md"):
        quoted = set(re.findall(r"(\d\.\d\de8) N s/m", path.read_text()))
        assert quoted == {"1.03e8"}, (path.name, quoted)


def test_lowest_valid_band_of_a_25_ms_blow_is_50_hz():
    """The valid band starts at 1/T = 40 Hz; the lowest band wholly inside it is centred at
    50 Hz, the first band the demo and the docs name (never "from 40 Hz")."""
    step = 2e-5
    t = np.arange(0.0, 0.025, step)
    bands = third_octave_band_energies(np.sin(2e3 * t), step)
    assert bands.valid_range[0] == 40.0
    assert round(float(bands.centre_frequency[bands.valid][0])) == 50
    for path in (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))):
        assert "band from 40 Hz" not in re.sub(r"\s+", " ", path.read_text()), path.name
