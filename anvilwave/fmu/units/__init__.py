"""The FMU slaves (pythonfmu): thin classes mapping FMI variables onto component objects.

Each FMU type has its own slave script whose module name is unique to that type
(``anvilwave_anvil_rom.py`` -> ``Anvil.fmu``, ``anvilwave_anvil_lumped.py`` ->
``AnvilLumped.fmu``, ``anvilwave_anvil_stack.py`` -> ``AnvilStack.fmu``, ``anvilwave_ram.py`` ->
``Ram.fmu``, ``anvilwave_pile_soil.py`` -> ``PileSoil.fmu``): pythonfmu imports the script by
module name, and a process runs the first module of a given name for every FMU that names it.
The scripts only subclass the slave classes of this package (:mod:`anvilwave.fmu.units.anvil`,
:mod:`anvilwave.fmu.units.ram`, :mod:`anvilwave.fmu.units.pile_soil`, built on
:mod:`anvilwave.fmu.units.base`); the build copies those classes with what they import into each
FMU (:mod:`anvilwave.fmu.vendoring`, :mod:`anvilwave.fmu.units.vendor_init`), so the FMUs need a
Python with numpy, scipy and numba, not anvilwave. Build them with
:func:`anvilwave.fmu.fmi_build.build_fmu` (or the helpers there, or
:func:`anvilwave.engine.fmus.build_system_fmus` for a whole system file).
"""
