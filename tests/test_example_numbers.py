"""Every example file runs a short case and gives its stored number (tests/example_numbers.py
lists the cases; tests/data/example_numbers.json holds the numbers).

After a change that moves a number on purpose, regenerate the file:
``python -m tests.regenerate_example_numbers`` (or ``--only CASE``), and commit the reviewed
diff with the change.

Tolerance: relative 1e-6. The runs are deterministic (fixed inputs, no random numbers except
the seeded noise of the synthetic record, serial time stepping), so on one machine type they
repeat to the last bit; the margin leaves room for a different BLAS / CPU's summation order in
the modal analysis (eigenvectors agree to ~1e-10 there, the peaks to ~1e-9) while any model or
input change worth a test moves these numbers by far more than 1e-6.
"""

from __future__ import annotations

import pytest

from .conftest import NEEDS_SHARED
from .example_numbers import SCRIPT_API_FIRST_PEAK, cases, check_soil_script, compute, load_numbers

RTOL = 1e-6  # module docstring
NUMBERS = load_numbers()
CASES = [name for name in cases() if name != SCRIPT_API_FIRST_PEAK]  # test_system_layer.py


def _needs_shared(case: str) -> bool:
    return case.split("/", 1)[1] in NEEDS_SHARED


def test_every_case_has_a_stored_number_and_no_stale_ones():
    """The data file and the case list agree (regenerate after adding or removing an example).
    The cases of the examples that read the shared reference folder exist only where it is
    present (see test_example_gives_its_stored_number)."""
    stored = set(NUMBERS)
    known = set(cases())
    missing = {n for n in known - stored if not _needs_shared(n)}
    assert not missing, f"no stored number: {sorted(missing)} (regenerate)"
    stale = {n for n in stored - known if not _needs_shared(n)}
    assert not stale, f"stale stored numbers: {sorted(stale)}"


@pytest.mark.parametrize("case", CASES)
def test_example_gives_its_stored_number(case):
    if case not in NUMBERS and _needs_shared(case):
        pytest.skip(f"{case}: no stored number yet; it reads the shared reference folder, so "
                    "store it where that folder is present: python -m "
                    f"tests.regenerate_example_numbers --only {case}")
    assert case in NUMBERS, "regenerate: python -m tests.regenerate_example_numbers"
    assert compute(case) == pytest.approx(NUMBERS[case], rel=RTOL)


def test_synthetic_campaign_cpt_script_reproduces_the_shipped_soil_files(tmp_path):
    """examples/make_synthetic_campaign_cpts.py run on a copy rewrites examples/soil's campaign
    files byte for byte (the files are deterministic, the script under a second)."""
    assert check_soil_script(tmp_path) == []
