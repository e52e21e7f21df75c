"""Write the SYNTHETIC PDA record of the examples: examples/pda_raw_synthetic.csv (raw
channels: two strains, two accelerations) and examples/pda_record_synthetic.csv (the force and
velocity a PDA would convert them to).

No public measured PDA record of an XL monopile was found, so the examples carry a synthetic
one, made like a field record from a simulation:

1. examples/table1.toml (ROM anvil, illustrative 5500 kJ hammer, 8000 x 140 mm x 80 m pile,
   North Sea sand) is simulated for 100 ms; the gauges are 2 m below the head, 78 m above the
   toe. The record ends at the first zero crossing of the gauge velocity after 75 ms (t1 + 4L/c
   fits: RMX can move t1 over a full round trip): the 80 m pile and the anvil still ring at
   +-0.5 m/s then, and a PDA's drift correction assumes the pile at rest at the record's end.
2. The gauges are zeroed at rest (the anvil and pile weights removed from the force) and a
   2 ms pre-trigger at rest is put before the impact (sample interval 20 us, the simulation's).
3. Noise: white Gaussian, standard deviation 2 % of the signal's peak, on the force and on the
   velocity (seed SEED: the files are reproducible).
4. Unequal gauges: the two strain gauges read the mean strain plus and minus a bending strain
   of 12 % of it (an eccentric blow); the two accelerometers read the axial acceleration (the
   central-difference derivative of the noisy velocity) plus and minus a rocking part of 10 %
   of it.
5. Accelerometer offsets: +12 and -8 m/s^2 from the start, and zero shifts of +3 and -1 m/s^2
   from the impact on (the shock drift of accelerometers).
6. The converted record is the raw record put through the project's conversion
   (pile.pda_records: force = E A x mean strain; velocity = integrated mean acceleration with
   the pre-impact offset and a linear drift from the impact removed), as a PDA would.

Run from the repository root: ``python examples/make_synthetic_pda_record.py`` (about half a
minute: the modal ram and anvil are computed first).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

import anvilwave
from anvilwave.analyses.impact import gauge_steel_area
from anvilwave.analyses.pda import load_record

HERE = Path(__file__).resolve().parent
SYSTEM = HERE / "table1.toml"
RAW = HERE / "pda_raw_synthetic.csv"
RECORD = HERE / "pda_record_synthetic.csv"

SEED = 12
DURATION = 0.1       # [s] simulated
END_AFTER = 0.075    # [s] the record ends at the first zero crossing of the velocity after
PRE_TRIGGER = 0.002  # [s] at rest before the impact
NOISE = 0.02         # [-] of the signal's peak
BENDING = 0.12       # [-] bending strain / mean strain
ROCKING = 0.10       # [-] rocking acceleration / mean acceleration
OFFSETS = (12.0, -8.0)      # [m/s^2]
ZERO_SHIFTS = (3.0, -1.0)   # [m/s^2] from the impact on


def simulate_gauges():
    """Time [s], force [N] (zeroed at rest), velocity [m/s] at the gauges, area [m^2], E [Pa]."""
    cfg = anvilwave.load_system(SYSTEM)
    cfg = dataclasses.replace(cfg, duration=DURATION)
    blow = anvilwave.simulate(cfg, anvil="rom")[0]
    t = blow["time [s]"]
    force = blow["gauge_force [N]"] - blow["gauge_force [N]"][0]
    velocity = blow["gauge_velocity [m/s]"]
    late = np.nonzero((t[1:] > END_AFTER) & (velocity[1:] * velocity[:-1] <= 0.0))[0]
    end = int(late[0]) + 2 if late.size else t.size
    t, force, velocity = t[:end], force[:end], velocity[:end]
    step = float(t[1] - t[0])
    n_pre = int(round(PRE_TRIGGER / step))
    time = np.arange(n_pre + t.size) * step
    force = np.concatenate((np.zeros(n_pre), force))
    velocity = np.concatenate((np.zeros(n_pre), velocity))
    section = cfg.pile_soil.pile.sections[0]
    return time, force, velocity, gauge_steel_area(cfg), section.youngs_modulus, n_pre


def header(kind: str, area: float, modulus: float) -> str:
    lines = [
        f"SYNTHETIC PDA RECORD ({kind}) - NOT A MEASUREMENT.",
        "Made by examples/make_synthetic_pda_record.py from the ROM simulation of",
        "examples/table1.toml (illustrative 5500 kJ hammer, 8 m anvil xl8, 8000 x 140 mm x 80 m",
        "pile, 30 m in sand): gauges 2 m below the head (78 m above the toe), zeroed at rest,",
        "2 ms pre-trigger, ends at the first zero crossing of the velocity after 75 ms;",
        f"white noise 2 % of the peak on force and velocity (seed {SEED});",
        "strain gauges +-12 % bending; accelerometers +-10 % rocking, offsets +12 / -8 m/s^2 and",
        "zero shifts +3 / -1 m/s^2 from the impact.",
        f"Steel area at the gauges {area:.6g} m^2, E {modulus:.4g} Pa, c 5172.2 m/s.",
    ]
    if kind == "raw channels":
        lines.append("Convert: force = E A (strain_1 + strain_2) / 2; velocity = integrated")
        lines.append("mean acceleration, drift-corrected (pile.pda_records).")
    else:
        lines.append("Converted from examples/pda_raw_synthetic.csv by pile.pda_records.")
    return "".join(f"# {line}\n" for line in lines)


def write(path: Path, comment: str, columns: dict[str, np.ndarray], digits: int) -> None:
    names = list(columns)
    rows = np.column_stack([columns[n] for n in names])
    with path.open("w", encoding="utf-8", newline="") as stream:
        stream.write(comment)
        stream.write(",".join(names) + "\n")
        for row in rows:
            stream.write(",".join(f"{x:.{digits}g}" for x in row) + "\n")


def main() -> None:
    time, force, velocity, area, modulus, impact = simulate_gauges()
    rng = np.random.default_rng(SEED)
    force = force + NOISE * np.abs(force).max() * rng.standard_normal(force.size)
    velocity = velocity + NOISE * np.abs(velocity).max() * rng.standard_normal(velocity.size)
    strain = force / (modulus * area)
    acceleration = np.gradient(velocity, time)
    after = (np.arange(time.size) >= impact).astype(float)
    raw = {"time [s]": time,
           "strain_1 [microstrain]": (1.0 + BENDING) * strain * 1e6,
           "strain_2 [microstrain]": (1.0 - BENDING) * strain * 1e6}
    for i, sign in ((0, 1.0), (1, -1.0)):
        raw[f"acceleration_{i + 1} [m/s^2]"] = ((1.0 + sign * ROCKING) * acceleration
                                                + OFFSETS[i] + ZERO_SHIFTS[i] * after)
    write(RAW, header("raw channels", area, modulus), raw, 9)
    record, _, _ = load_record(RAW, area=area, elastic_modulus=modulus)
    write(RECORD, header("force and velocity", area, modulus),
          {"time [s]": record.time, "force [N]": record.force,
           "velocity [m/s]": record.velocity}, 9)
    print(f"wrote {RAW.name} and {RECORD.name}: {time.size} samples, "
          f"peak force {record.force.max() / 1e6:.1f} MN, "
          f"peak velocity {record.velocity.max():.2f} m/s")


if __name__ == "__main__":
    main()
