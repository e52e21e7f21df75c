"""The pile-port study's closed loop on the FEA's own pile (benchmarks/study_pile_port.py), as
the engine's tube head and ram annuli are checked against it: other code, the anvil and the
ram meshed afresh with six patches on their faces, the ram's whole modal state, the tube's
kernel as the whole pile."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np

from anvilwave.analyses.compare import fea_config

ROOT = Path(__file__).resolve().parents[1]


def loop_on_feas_pile(table1, ram_groups, step: float = 2e-5):
    """(pile-head force, ram force) [N] every 10 us and that interval [s] of the study's closed
    loop for Table 1 (``table1``, no soil) with three rings on the FEA's tube (the kernel the
    engine's tube head filled the cache with) and the ram face's six patches in
    ``ram_groups``."""
    spec = importlib.util.spec_from_file_location("study_pile_port",
                                                  ROOT / "benchmarks" / "study_pile_port.py")
    study = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = study
    try:
        spec.loader.exec_module(study)
        from anvilwave.anvil_rom.fem.geometry import STEEL, Material
        from anvilwave.config.cache import cached_ring_kernel
        from anvilwave.pile.head_kernel import echo_free_length, tube_contact_stiffness

        config = fea_config(table1)
        r_in, r_out = config.pile_ring
        anvil = study.anvil_ports(table1, r_in, r_out, 0.5 * table1.hammer.ram.toe_diameter)
        ram = study.ram_face_ports(table1)
        area = np.pi * (r_out**2 - r_in**2)
        pile = (STEEL.youngs_modulus, STEEL.density, area, r_out - r_in, 80.0)
        rings = [[0, 1], [2, 3], [4, 5]]
        contact = tube_contact_stiffness(config.material.youngs_modulus, r_out - r_in,
                                         [anvil.areas[g].sum() for g in rings])
        length = echo_free_length(np.sqrt(STEEL.youngs_modulus / STEEL.density),
                                  table1.duration)
        kernel = cached_ring_kernel(Material(STEEL.youngs_modulus, STEEL.poisson_ratio,
                                             STEEL.density), r_in, r_out, length, step,
                                    int(round(table1.duration / step)) + 1, 3)
        groups = [list(range(study.PATCHES))] if ram_groups is None else ram_groups
        return study.run_closed_loop(anvil, ram, rings, groups, table1.impact_velocity,
                                     table1.anvil.ram_contact_damping, table1.duration, pile,
                                     gravity=table1.gravity, kernel=kernel, contact=contact,
                                     step=step)
    finally:
        del sys.modules[spec.name]
