"""Slave script of ``Anvil.fmu``: the Mode Displacement Method anvil (modal ROM).

The module name is unique to this FMU type (pythonfmu runs the first loaded module of a name for
every FMU in a process); everything build-specific (modal-data file, parameter defaults) lives in
the FMU's resources, so every Anvil.fmu runs this same code. See :mod:`anvilwave.fmu.units.anvil`.
"""

from anvilwave.fmu.units.anvil import AnvilROMSlave
from anvilwave.fmu.units.base import pin_namespace

pin_namespace(globals())  # pythonfmu 0.7.0 loader work-around (see pin_namespace)


class Anvil(AnvilROMSlave):
    """The ``Anvil.fmu`` slave: the Mode Displacement Method anvil (ROM).

    Inputs u_ram [m], v_ram [m/s], u_pile [m], v_pile [m/s]; outputs F_ram [N], F_pile [N],
    u_top [m], u_bottom [m].

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """
