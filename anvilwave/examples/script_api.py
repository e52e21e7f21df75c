"""A parameter study in a few lines of Python: the Table 1 blow at three energy settings with
the ROM anvil and the rigid lumped-mass anvil (the anvil's modes are computed once and reused).
EMX is the PDA's transferred energy: the largest integral of F v dt at the gauges, the gauges
zeroed at rest (``summary["EMX [J]"]``).

Run: ``python anvilwave/examples/script_api.py`` (about 10 s).
"""

from pathlib import Path

import anvilwave

system = anvilwave.load_system(Path(__file__).parent / "table1.toml")
modes = anvilwave.compute_anvil_modes(system.anvil.spec, fmax=system.anvil.fmax)

print(f"{'energy [kJ]':>11s} {'anvil':>6s} {'pile peak [MN]':>14s} {'EMX [kJ]':>9s} "
      f"{'set [mm]':>8s} {'x real time':>11s}")
for energy in (3.5e6, 4.5e6, 5.5e6):
    for anvil in ("rom", "lumped"):
        blow = anvilwave.simulate(system.with_energy(energy), anvil=anvil,
                                  modal_data=modes.modal_data)[0]
        s = blow.summary
        print(f"{energy / 1e3:11.0f} {anvil:>6s} {s['peak_anvil_pile_force [N]'] / 1e6:14.1f} "
              f"{s['EMX [J]'] / 1e3:9.0f} "
              f"{s['permanent_set [m]'] * 1e3:8.2f} {s['realtime_factor [-]']:11.1f}")
