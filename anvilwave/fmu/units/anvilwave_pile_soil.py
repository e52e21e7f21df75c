"""Slave script of ``PileSoil.fmu``: the pile with its soil (embedded pile/soil TOML file).

The module name is unique to this FMU type (pythonfmu runs the first loaded module of a name for
every FMU in a process); everything build-specific (pile/soil file, parameter defaults) lives in
the FMU's resources, so every PileSoil.fmu runs this same code. See
:mod:`anvilwave.fmu.units.pile_soil`.
"""

from anvilwave.fmu.units.base import pin_namespace
from anvilwave.fmu.units.pile_soil import PileSoilSlave

pin_namespace(globals())  # pythonfmu 0.7.0 loader work-around (see pin_namespace)


class PileSoil(PileSoilSlave):
    """The ``PileSoil.fmu`` slave: the pile with its soil.

    Input F_head [N]; outputs u_head [m], v_head [m/s], F_gauge [N], v_gauge [m/s],
    u_head_total [m], u_pile_toe [m], max_compression_stress [Pa], max_tension_stress [Pa].

    Parameters
    ----------
    **kwargs
        pythonfmu's ``Fmi2Slave`` arguments (``instance_name``, ``resources``, ...), passed on
        unchanged.
    """
