"""Results of an impact run: CSV time series, JSON summary, PNG figure (no computations of
physics here beyond the bookkeeping of recorded series)."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np


def write_csv(columns: dict[str, np.ndarray], path: str | Path) -> Path:
    """Write time series with a ``name [unit]`` header (DESIGN.md)."""
    names = list(columns)
    data = np.column_stack([columns[n] for n in names])
    with open(path, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(names)
        for row in data:
            writer.writerow([f"{x:.9g}" for x in row])
    return Path(path)


def read_csv(path: str | Path) -> dict[str, np.ndarray]:
    """Read a CSV written by :func:`write_csv`."""
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        names = next(reader)
        rows = np.array([[float(x) for x in row] for row in reader])
    return {n: rows[:, i] for i, n in enumerate(names)}


def transferred_energy(force: np.ndarray, velocity: np.ndarray, time: np.ndarray) -> float:
    """EMX: the largest value of the integral of F v dt [J] (Case method / PDA)."""
    power = force * velocity
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(time))])
    return float(work.max())


def energy_balance(result) -> dict[str, float]:
    """Where the ram's energy went at the end of the blow [J], and the closing residual.

    Every term is the change from the start of the blow; gravity's work on ram, anvil and pile
    enters as the change of their potential energy. residual = final - initial total; relative
    to the ram's impact energy.
    """
    E = result.energies

    def change(name):
        return float(E[name][-1] - E[name][0])

    terms = {
        "ram_impact_energy [J]": result.input_energy,
        "ram_kinetic_and_strain [J]": change("ram_kinetic [J]") + change("ram_strain [J]"),
        "anvil_kinetic [J]": change("anvil_kinetic [J]"),
        "anvil_strain_contact_and_gravity [J]": change("anvil_potential [J]"),
        "pile_kinetic [J]": change("pile_kinetic [J]"),
        "pile_strain [J]": change("pile_strain [J]"),
        "soil_static_work [J]": change("soil_static_work [J]"),
        "soil_damping_work [J]": change("soil_damping_work [J]"),
        "pile_damping_work [J]": change("pile_damping_work [J]"),
        "contact_damping_work [J]": (change("contact_damping_work [J]")
                                     if "contact_damping_work [J]" in E else 0.0),
        "gravity_work_ram_and_pile [J]": (-change("ram_gravity_potential [J]")
                                          + change("pile_gravity_work [J]")),
    }
    total = total_energy(E)
    terms["residual [J]"] = float(total[-1] - total[0])
    terms["residual_relative [-]"] = terms["residual [J]"] / result.input_energy
    terms["max_deviation_relative [-]"] = float(np.abs(total - total[0]).max()
                                                / result.input_energy)
    return terms


def total_energy(E: dict[str, np.ndarray]) -> np.ndarray:
    """Total mechanical energy plus the work dissipated or stored in the soil [J] over time."""
    return (E["ram_kinetic [J]"] + E["ram_strain [J]"] + E["ram_gravity_potential [J]"]
            + E["anvil_kinetic [J]"] + E["anvil_potential [J]"]
            + E["pile_kinetic [J]"] + E["pile_strain [J]"] - E["pile_gravity_work [J]"]
            + E["soil_static_work [J]"] + E["soil_damping_work [J]"]
            + E["pile_damping_work [J]"] + E.get("contact_damping_work [J]", 0.0))


def gauge_steel_area(config) -> float:
    """Steel area of the pile section at the gauge depth [m^2] of a system configuration."""
    depth = 0.0
    for section in config.pile_soil.pile.sections:
        depth += section.length
        if config.pile_soil.pile.gauge_depth <= depth:
            return section.area
    return config.pile_soil.pile.sections[-1].area


def summarise(result, config, engine: str, anvil_model: str, pile_area_at_gauge: float
              ) -> dict:
    """The summary.json content of one blow."""
    c = result.columns
    t = c["time [s]"]
    summary = {
        "engine": engine,
        "anvil_model": anvil_model,
        "impact_velocity [m/s]": config.impact_velocity,
        "peak_ram_anvil_force [N]": float(c["ram_anvil_force [N]"].max()),
        "peak_anvil_pile_force [N]": float(c["anvil_pile_force [N]"].max()),
        "peak_gauge_force [N]": float(c["gauge_force [N]"].max()),
        "peak_gauge_stress [Pa]": float(c["gauge_force [N]"].max() / pile_area_at_gauge),
        "peak_pile_compression_stress [Pa]": getattr(result, "pile_max_compression_stress",
                                                     None),
        "peak_pile_tension_stress [Pa]": getattr(result, "pile_max_tension_stress", None),
        "transferred_energy_gauge [J]": transferred_energy(c["gauge_force [N]"],
                                                          c["gauge_velocity [m/s]"], t),
        "simulated_time [s]": float(t[-1] - t[0]),
        "time_step [s]": result.time_step,
        "n_steps": result.n_steps,
        "wall_time [s]": result.wall_time,
        "realtime_factor [-]": float((t[-1] - t[0]) / max(result.wall_time, 1e-12)),
    }
    # the toe's displacement over the window: the blow's permanent set once the pile has come
    # to rest (a window of some tens of ms); the same in both engines
    toe = c["pile_toe_displacement [m]"]
    summary["permanent_set [m]"] = float(toe[-1] - toe[0])
    final = getattr(result, "final_state", {})
    if "soil_offset" in final:
        # the toe soil's plastic offset gained in the blow (the set as the soil sees it)
        summary["toe_soil_set [m]"] = float(final["soil_offset"][-1]
                                            - final["soil_offset_start"][-1])
    # the Case method on the simulated gauge signals, as a PDA reports a blow
    from anvilwave.analyses.pda import pda_summary

    try:
        summary.update(pda_summary(c, config))
    except (ValueError, KeyError):  # a record too short or without a velocity peak
        pass
    if getattr(result, "energies", None):
        summary["energy_balance"] = energy_balance(result)
    else:
        summary["note"] = ("the energy balance is computed by the in-process engine only (the "
                           "FMU interface exposes forces, motions and stress extremes)")
    return summary
