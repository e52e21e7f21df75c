"""FMI hygiene of the pythonfmu units (Ram.fmu of a database hammer, ~3 s a build).

A GUID derived from the content (identical rebuilds are identical files), version, author and
licence in modelDescription.xml, and fmi2Error with the reason (never fmi2OK, never a crash)
for a wrong GUID, calls out of the FMI 2.0 order and non-finite inputs.
"""

from __future__ import annotations

import pytest

pytest.importorskip("fmpy")
pytest.importorskip("pythonfmu")

from fmpy import extract, read_model_description  # noqa: E402
from fmpy.fmi1 import FMICallException  # noqa: E402
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE  # noqa: E402

from anvilwave.fmu.fmi_build import build_ram_fmu  # noqa: E402


@pytest.fixture(scope="module")
def ram_fmus(tmp_path_factory):
    return [build_ram_fmu(tmp_path_factory.mktemp(f"ram{k}"), "illustrative_s2")
            for k in range(2)]


class Instance:
    """One instance with its log (messages with status >= fmi2Warning)."""

    def __init__(self, path, guid=None):
        md = read_model_description(str(path))
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.log: list[str] = []
        self.callbacks = fmi2CallbackFunctions()
        self.callbacks.logger = fmi2CallbackLoggerTYPE(self._log)
        from fmpy import calloc, free
        from fmpy.fmi2 import fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE

        self.callbacks.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        self.callbacks.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        self.fmu = FMU2Slave(guid=md.guid if guid is None else guid,
                             unzipDirectory=str(extract(str(path))), instanceName="ram",
                             modelIdentifier=md.coSimulation.modelIdentifier)

    def _log(self, environment, instance, status, category, message):
        if status >= 1:
            self.log.append((message or b"").decode(errors="replace"))


def test_identical_builds_are_identical_files_with_metadata(ram_fmus):
    first, second = (path.read_bytes() for path in ram_fmus)
    assert first == second
    md = read_model_description(str(ram_fmus[0]))
    assert md.guid.startswith("{") and len(md.guid) == 38
    assert md.author == "anvilwave" and md.license == "MIT" and md.version


def test_a_wrong_guid_is_refused_with_the_reason(ram_fmus):
    unit = Instance(ram_fmus[0], guid="{00000000-0000-0000-0000-000000000000}")
    with pytest.raises(Exception, match="instantiate"):
        unit.fmu.instantiate(callbacks=unit.callbacks)
    assert any("wrong GUID" in m for m in unit.log), unit.log


def test_calls_out_of_order_and_non_finite_inputs_give_fmi2error(ram_fmus):
    unit = Instance(ram_fmus[0])
    unit.fmu.instantiate(callbacks=unit.callbacks)
    try:
        for call in (unit.fmu.terminate, lambda: unit.fmu.doStep(0.0, 1e-5),
                     unit.fmu.exitInitializationMode):
            with pytest.raises(FMICallException) as info:
                call()
            assert info.value.status == 3  # fmi2Error
        assert sum("not allowed in the state 'instantiated'" in m for m in unit.log) == 3
        unit.fmu.setupExperiment(startTime=0.0)
        unit.fmu.enterInitializationMode()
        unit.fmu.exitInitializationMode()
        with pytest.raises(FMICallException) as info:
            unit.fmu.setReal([unit.vr["F_toe"]], [float("nan")])
        assert info.value.status == 3
        assert any("'F_toe' is not finite" in m for m in unit.log), unit.log
    finally:
        unit.fmu.freeInstance()
