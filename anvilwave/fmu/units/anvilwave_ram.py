"""Slave script of ``Ram.fmu``: the ram as a lumped rod (hammer database or embedded file).

The module name is unique to this FMU type (pythonfmu runs the first loaded module of a name for
every FMU in a process); everything build-specific (hammer file, parameter defaults) lives in
the FMU's resources, so every Ram.fmu runs this same code. See :mod:`anvilwave.fmu.units.ram`.
"""

from anvilwave.fmu.units.base import pin_namespace
from anvilwave.fmu.units.ram import RamSlave

pin_namespace(globals())  # pythonfmu 0.7.0 loader work-around (see pin_namespace)


class Ram(RamSlave):
    """Ram: input F_toe [N]; outputs u_toe [m], v_toe [m/s].

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """
