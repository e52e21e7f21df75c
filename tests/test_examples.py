"""Every shipped system file loads, and its anvil's ram face fits its ram (each example also runs a
short case against its stored number: tests/test_example_numbers.py)."""

from __future__ import annotations

import pytest

from anvilwave.config.system import load_system

from .conftest import EXAMPLES, example_systems

SYSTEMS = example_systems()


@pytest.mark.parametrize("name", SYSTEMS)
def test_example_system_loads_and_its_ram_fits_the_anvil_face(name):
    """The ROM's ram face and the FEA's ram both take the ram's radius: the anvil file's
    ram_contact_radius must be the ram's toe radius (to 1 mm, the files' rounding)."""
    cfg = load_system(EXAMPLES / name)
    spec = cfg.anvil.spec
    if spec is None:
        pytest.skip("no anvil geometry")
    assert spec.interfaces.ram_contact_radius == pytest.approx(
        0.5 * cfg.hammer.ram.toe_diameter, abs=1e-3)
