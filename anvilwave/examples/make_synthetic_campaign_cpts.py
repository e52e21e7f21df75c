"""Write the SYNTHETIC soil data of the campaign examples: one CPT per foundation position,
examples/soil/campaign_<position>_cpt.csv, and its [srd] table (Alm & Hamre 2001 on that CPT
with its layers), examples/soil/campaign_<position>_srd.toml.

These are ILLUSTRATIVE North Sea type profiles made up for the examples (not measurements):
each layer's cone resistance qc runs linearly from its top to its bottom value with a small
undulation (a few per cent, a different phase per position), the sleeve friction is a friction
ratio times qc (about 0.8 % in sand, 3.5 % in clay) and the pore pressure u2 is zero in sand
and a fraction of qc in clay. Layer tops, soil types and unit weights are those of the [srd]
layers, so the two files of a position agree.

Positions A01 and B07 are the two of examples/campaign_small.toml (inline there, the same
layers as their _srd.toml files); C03, D11, E05 and F09 complete the six of
examples/campaign_farm.toml.

Run from the repository root: ``python anvilwave/examples/make_synthetic_campaign_cpts.py``
(well under a second; the files are deterministic).
"""

from __future__ import annotations

import math
from pathlib import Path

HERE = Path(__file__).resolve().parent
SOIL = HERE / "soil"
STEP = 0.2            # [m] reading interval
BOTTOM = 45.0         # [m] every CPT reaches 45 m below the mudline
UNDULATION = 0.04     # [-] relative amplitude of the qc undulation
WAVELENGTH = 3.1      # [m]

# (top [m], bottom [m], soil, qc top [MPa], qc bottom [MPa], submerged unit weight [N/m^3],
#  interface friction angle [deg] (sand) or undrained shear strength [Pa] (clay))
PROFILES: dict[str, dict] = {
    "A01": {"phase": 0.0, "description": "dense sand, a stiff clay band 12-17 m, very dense "
                                         "sand below",
            "layers": [(0.0, 12.0, "sand", 5.0, 24.0, 10.0e3, 29.0),
                       (12.0, 17.0, "clay", 2.2, 2.7, 9.0e3, 140.0e3),
                       (17.0, 45.0, "sand", 26.0, 50.0, 10.5e3, 30.0)]},
    "B07": {"phase": 1.3, "description": "soft clay at the top, medium dense to dense sand, a "
                                         "clay band 20-25 m, very dense sand below",
            "layers": [(0.0, 6.0, "clay", 0.6, 1.2, 8.0e3, 30.0e3),
                       (6.0, 20.0, "sand", 10.0, 30.0, 10.0e3, 28.0),
                       (20.0, 25.0, "clay", 2.8, 3.3, 9.0e3, 170.0e3),
                       (25.0, 45.0, "sand", 32.0, 55.0, 10.5e3, 30.0)]},
    "C03": {"phase": 2.1, "description": "loose to dense sand over very dense sand",
            "layers": [(0.0, 9.0, "sand", 3.0, 18.0, 9.5e3, 27.0),
                       (9.0, 45.0, "sand", 20.0, 48.0, 10.5e3, 30.0)]},
    "D11": {"phase": 3.4, "description": "sand over a thick stiff clay 10-22 m, dense sand "
                                         "below",
            "layers": [(0.0, 10.0, "sand", 6.0, 22.0, 10.0e3, 29.0),
                       (10.0, 22.0, "clay", 2.0, 3.6, 9.0e3, 150.0e3),
                       (22.0, 45.0, "sand", 24.0, 45.0, 10.5e3, 30.0)]},
    "E05": {"phase": 4.0, "description": "dense sand throughout, stiffening with depth",
            "layers": [(0.0, 15.0, "sand", 8.0, 30.0, 10.0e3, 29.0),
                       (15.0, 45.0, "sand", 30.0, 58.0, 10.5e3, 30.0)]},
    "F09": {"phase": 5.2, "description": "soft clay 0-4 m, sand, a clay band 28-32 m, dense "
                                         "sand below",
            "layers": [(0.0, 4.0, "clay", 0.5, 0.9, 8.0e3, 25.0e3),
                       (4.0, 28.0, "sand", 9.0, 34.0, 10.0e3, 29.0),
                       (28.0, 32.0, "clay", 3.0, 3.4, 9.0e3, 180.0e3),
                       (32.0, 45.0, "sand", 36.0, 52.0, 10.5e3, 30.0)]},
}


def layer_at(layers, depth: float):
    """The layer holding ``depth`` [m] (the deeper one on a boundary)."""
    for layer in layers:
        if depth < layer[1]:
            return layer
    return layers[-1]


def reading(layers, depth: float, phase: float) -> tuple[float, float, float]:
    """qc, fs, u2 [MPa] at ``depth`` [m]."""
    top, bottom, soil, qc_top, qc_bottom = layer_at(layers, depth)[:5]
    s = (depth - top) / (bottom - top)
    qc = (qc_top + s * (qc_bottom - qc_top)) * (
        1.0 + UNDULATION * math.sin(2.0 * math.pi * depth / WAVELENGTH + phase))
    if soil == "sand":
        return qc, 0.008 * qc, 0.0
    return qc, 0.035 * qc, 0.15 * qc


def write_cpt(name: str, profile: dict) -> Path:
    path = SOIL / f"campaign_{name.lower()}_cpt.csv"
    lines = [f"# ILLUSTRATIVE synthetic CPT of position {name} for the campaign examples "
             "(anvilwave example",
             "# data, not a measurement; made by examples/make_synthetic_campaign_cpts.py):",
             f"# {profile['description']}.",
             "# Depth below the mudline.",
             "depth [m],qc [MPa],fs [MPa],u2 [MPa]"]
    n = int(round(BOTTOM / STEP))
    for i in range(n + 1):
        z = i * STEP
        qc, fs, u2 = reading(profile["layers"], z, profile["phase"])
        lines.append(f"{z:.1f},{qc:.3f},{fs:.4f},{u2:.3f}")
    path.write_text("\n".join(lines) + "\n")
    return path


def write_srd(name: str, profile: dict) -> Path:
    path = SOIL / f"campaign_{name.lower()}_srd.toml"
    lines = [f"# [srd] of position {name} for the campaign examples: ILLUSTRATIVE, synthetic",
             "# (anvilwave/examples/make_synthetic_campaign_cpts.py), the layers of its CPT file:",
             f"# {profile['description']}.",
             "# Paths are relative to this file.",
             "",
             "[srd]",
             'method = "alm-hamre-2001"',
             f'cpt = "campaign_{name.lower()}_cpt.csv"',
             'pile_mode = "coring"']
    for top, bottom, soil, _, _, gamma, strength in profile["layers"]:
        lines += ["", "[[srd.layers]]", f"top = {top:.1f}", f"bottom = {bottom:.1f}",
                  f'soil = "{soil}"', f"submerged_unit_weight = {gamma:.1f}    # [N/m^3]"]
        if soil == "sand":
            lines.append(f"interface_friction_angle = {strength:.1f}    # [deg]")
        else:
            lines += [f"undrained_shear_strength = {strength:.1f}    # [Pa]",
                      "plasticity_index = 0.3    # [-]"]
    path.write_text("\n".join(lines) + "\n")
    return path


def main() -> None:
    SOIL.mkdir(exist_ok=True)
    for name, profile in PROFILES.items():
        print(write_cpt(name, profile).relative_to(HERE.parent),
              write_srd(name, profile).relative_to(HERE.parent))


if __name__ == "__main__":
    main()
