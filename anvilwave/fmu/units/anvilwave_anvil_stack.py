"""Slave script of ``AnvilStack.fmu``: the driving stack, the anvil and the anvil ring.

The module name is unique to this FMU type (pythonfmu runs the first loaded module of a name for
every FMU in a process); the stack data file and the parameter defaults live in the FMU's
resources. See :mod:`anvilwave.fmu.units.anvil`.
"""

from anvilwave.fmu.units.anvil import AnvilStackSlave
from anvilwave.fmu.units.base import pin_namespace

pin_namespace(globals())  # pythonfmu 0.7.0 loader work-around (see pin_namespace)


class AnvilStack(AnvilStackSlave):
    """The ``AnvilStack.fmu`` slave: the anvil and the anvil ring.

    Inputs u_ram [m], v_ram [m/s], u_pile [m], v_pile [m/s]; outputs F_ram [N], F_pile [N],
    u_top [m], u_bottom [m].

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """
