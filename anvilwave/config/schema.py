"""Every key of the input files, in one place: unit, default and meaning.

``anvilwave schema`` prints it; ``tests/test_system_layer.py`` checks that every key the
loaders accept in the shipped examples is documented here. The loaders (``load_system`` and
the physics packages' table readers) enforce the rules; a key that is not listed for its table
is rejected with the list of allowed keys.

Each entry: ``"table.key": (unit, default, meaning)``; default ``REQUIRED`` means the key must
be given, ``None`` that it is optional with a computed default described in the meaning.
"""

from __future__ import annotations

from anvilwave.pile.pile import DEFAULT_GAUGE_DEPTH

REQUIRED = "required"

SYSTEM: dict[str, tuple[str, object, str]] = {
    # [simulation]
    "simulation.duration": ("s", REQUIRED, "simulated time of one blow (at most 10 s)"),
    "simulation.time_step": ("s", None, "master step; default automatic (0.4 of the coupled "
                                        "stability limit, 8 steps per period at fmax)"),
    "simulation.output_interval": ("s", None, "spacing of recorded samples; default every "
                                              "step"),
    "simulation.gravity": ("m/s^2", 9.81, "gravitational acceleration"),
    "simulation.blows": ("-", 1, "consecutive blows; the pile keeps its set and soil state"),
    # [hammer]
    "hammer.database": ("-", None, "a hammer of anvilwave/hammer/data (give this or file)"),
    "hammer.file": ("-", None, "a hammer file (TOML, the format of anvilwave/hammer/data)"),
    "hammer.energy": ("J", None, "blow energy; default the rated energy"),
    "hammer.impact_velocity": ("m/s", None, "ram velocity at impact (instead of energy)"),
    "hammer.ram_model": ("-", "rod", "'rod' (Smith chain) or 'modal' (the ram's own modal "
                                     "ROM up to the anvil's fmax)"),
    "hammer.ram_mesh_size": ("m", None, "modal ram only: FE size; default from fmax"),
    # [anvil]
    "anvil.model": ("-", REQUIRED, "'rom', 'lumped', 'classic' or 'none'"),
    "anvil.file": ("-", None, "anvil file (rom, lumped)"),
    "anvil.fmax": ("Hz", None, "frequency content of the ROM; default the anvil file's"),
    "anvil.damping_ratio": ("-", None, "modal damping ratio; default the anvil file's"),
    "anvil.static_correction": ("-", True, "residual flexibility of the truncated modes"),
    "anvil.pile_port_rings": ("-", 1, "the pile port split into rings across the wall (rom; "
                               "anvilwave/anvil_rom/rings.py; the ring's, default 3, in a "
                               "stack)"),
    "anvil.ram_port_annuli": ("-", 1, "the ram port split into equal-width annuli (rom, modal "
                               "ram, pile_port_rings >= 2; anvilwave/anvil_rom/rings.py; "
                               "default 6 in a stack)"),
    "anvil.bodies": ("-", None, "[[anvil.bodies]] instead of file: the driving stack, the "
                                "anvil then the anvil ring (rom, modal ram; one body is file)"),
    "anvil.bodies.file": ("-", REQUIRED, "the body's anvil file (the first: with [interfaces])"),
    "anvil.bodies.seat_friction": ("-", 0.0, "the ring only: Coulomb coefficient of its seat "
                                             "under the anvil (0 to 2)"),
    "anvil.bodies.seat_rings": ("-", 8, "the ring only: the seat in equal-width rings"),
    "anvil.sleeve_clearance": ("m", None, "with [[anvil.bodies]]: a rigid guiding sleeve this "
                                          "far off the bodies' outer faces (0 to 0.1; default "
                                          "none)"),
    "anvil.sleeve_friction": ("-", 0.0, "with a sleeve: Coulomb coefficient against it (0 to "
                                        "2)"),
    "anvil.sleeve_bands": ("-", [8, 8], "with a sleeve: the anvil's and the ring's outer faces "
                                        "in this many equal-height bands"),
    "anvil.pile_head": ("-", "rod", "'rod' (the 1D pile's flat head) or 'tube' (the rings on an "
                                    "FE tube head, anvilwave/pile/head_kernel.py; "
                                    "pile_port_rings >= 2)"),
    "anvil.mass": ("kg", None, "lumped anvil mass; default the FE mass"),
    "anvil.ram_contact_stiffness": ("N/m", None, "default the ram's toe half segment"),
    "anvil.pile_contact_stiffness": ("N/m", None, "default the pile's top half segment"),
    "anvil.ram_contact_damping": ("N s/m", 0.0, "dashpot parallel to the ram contact, or "
                                                "'ram-impedance' (the ram's toe A sqrt(E rho))"),
    "anvil.pile_contact_damping": ("N s/m", 0.0, "dashpot parallel to the pile contact"),
    "anvil.classic": ("-", None, "table of the classic driving system (model 'classic')"),
    "anvil.classic.helmet_mass": ("kg", REQUIRED, "helmet mass"),
    "anvil.classic.assembly_mass": ("kg", 0.0, "hammer assembly (housing) mass"),
    "anvil.classic.assembly_stiffness": ("N/m", None, "assembly spring to the helmet "
                                                      "(required with assembly_mass)"),
    "anvil.classic.assembly_masses": ("kg", None, "assembly chain, top first (GRLWEAP)"),
    "anvil.classic.assembly_stiffnesses": ("N/m", None, "spring below each assembly mass; the "
                                                        "last bears on the helmet"),
    "anvil.classic.assembly_restitution": ("-", 1.0, "CoR of the assembly contact"),
    "anvil.classic.assembly_round_out": ("m", 0.0, "round-out of the assembly contact"),
    "anvil.classic.ram_bottom_stiffness": ("N/m", None, "spring below the ram's lowest "
                                                        "segment, in series with the cushion"),
    "anvil.classic.hammer_damping": ("N s/m", 0.0, "dashpot parallel to the hammer cushion"),
    "anvil.classic.hammer_damping_ratio": ("-", None, "GRLWEAP's rule: c = 2 ratio sqrt(m k) "
                                                      "(0.02 gives 2/50 sqrt(m k))"),
    "anvil.classic.ram_bottom_mass": ("kg", None, "the ram's lowest segment (with "
                                                  "hammer_damping_ratio)"),
    "anvil.classic.pile_contact_restitution": ("-", 1.0, "CoR of the helmet-pile contact"),
    "anvil.classic.pile_contact_round_out": ("m", 0.0, "round-out of the helmet-pile "
                                                       "contact"),
    "anvil.classic.hammer_cushion": ("-", REQUIRED, "cushion table (below)"),
    "anvil.classic.pile_cushion": ("-", None, "cushion table (below)"),
    "anvil.classic.pile_contact_stiffness": ("N/m", REQUIRED, "helmet-pile contact spring"),
    "anvil.classic.*_cushion.stiffness": ("N/m", None, "or area, elastic_modulus, thickness"),
    "anvil.classic.*_cushion.area": ("m^2", None, "cushion area"),
    "anvil.classic.*_cushion.elastic_modulus": ("Pa", None, "cushion modulus"),
    "anvil.classic.*_cushion.thickness": ("m", None, "cushion thickness"),
    "anvil.classic.*_cushion.restitution": ("-", REQUIRED, "coefficient of restitution"),
    "anvil.classic.*_cushion.round_out": ("m", 0.0, "round-out deformation"),
    # [pile]
    "pile.segment_length": ("m", 0.5, "target segment length (upper bound per section)"),
    "pile.gauge_depth": ("m", DEFAULT_GAUGE_DEPTH, "gauge position below the head"),
    "pile.material_damping": ("-", 0.01, "fraction of critical per segment"),
    "pile.material_damping_model": ("-", "segment", "'segment' (2 zeta sqrt(k m) per spring) "
                                                    "or 'uniform' (GRLWEAP: 2 zeta EA/c at "
                                                    "mid-length)"),
    "pile.yield_strength": ("Pa", 355e6, "steel yield strength fy (default S355); the "
                            "driveability plot's allowable driving stress is 0.9 fy "
                            "(API RP 2A-WSD)"),
    "pile.sections": ("-", REQUIRED, "[[pile.sections]], head first"),
    "pile.sections.length": ("m", REQUIRED, "section length"),
    "pile.sections.outer_diameter": ("m", REQUIRED, "outer diameter"),
    "pile.sections.wall_thickness": ("m", REQUIRED, "wall thickness"),
    "pile.sections.youngs_modulus": ("Pa", 210e9, "Young's modulus"),
    "pile.sections.density": ("kg/m^3", 7850.0, "density"),
    # [soil]
    "soil.model": ("-", "smith-viscous", "'smith', 'smith-viscous' or 'lysmer-toe'"),
    "soil.penetration": ("m", REQUIRED, "embedded length (tip depth below the mudline); with "
                                        "[srd]: default the last drive depth"),
    "soil.srd": ("[m, Pa, Pa]", REQUIRED, "rows depth, unit shaft friction, unit toe "
                                          "resistance (optional with [srd])"),
    "soil.quake_shaft": ("m", 0.0025, "shaft quake"),
    "soil.quake_toe": ("m", 0.0025, "toe quake (not lysmer-toe)"),
    "soil.damping_shaft": ("s/m", 0.65, "Smith shaft damping"),
    "soil.damping_toe": ("s/m", 0.5, "Smith toe damping (not lysmer-toe)"),
    "soil.layers": ("[m, m, m, m, s/m, s/m]", None, "per layer: rows top, bottom (below the "
                    "mudline), quake_shaft, quake_toe, damping_shaft, damping_toe; a segment "
                    "takes its embedded middle's layer, the toe the tip's; elsewhere the "
                    "scalars"),
    "soil.friction_perimeter": ("-", "outside+inside", "or 'outside'"),
    "soil.toe_area": ("-", "annulus", "or 'plugged'"),
    "soil.toe_shear_modulus": ("Pa", None, "lysmer-toe: soil shear modulus"),
    "soil.toe_density": ("kg/m^3", None, "lysmer-toe: soil density"),
    "soil.toe_poisson_ratio": ("-", 0.3, "lysmer-toe: Poisson's ratio"),
    # [driveability] (anvilwave drive)
    "driveability.depths": ("m", None, "tip depths below the mudline (or start/stop/step)"),
    "driveability.start": ("m", None, "first tip depth"),
    "driveability.stop": ("m", None, "last tip depth"),
    "driveability.step": ("m", None, "depth step"),
    "driveability.blows_per_depth": ("-", 1, "> 1: residual-stress analysis (each blow from "
                                             "the state the previous one left)"),
    "driveability.refusal": ("blows/0.25m", 250.0, "refusal blow count"),
    "driveability.blow_rate": ("blows/min", 30.0, "for the driving time"),
    "driveability.set_rule": ("-", "permanent", "'permanent' (toe at rest) or 'grlweap' "
                                                "(max toe displacement - toe quake)"),
    "driveability.enthru_location": ("-", "gauge", "'gauge' (PDA) or 'head' (GRLWEAP)"),
    "driveability.energy": ("[m, J]", None, "energy schedule: rows tip depth, blow energy"),
    "driveability.stroke": ("[m, m]", None, "or a stroke schedule: rows tip depth, stroke"),
    "driveability.efficiency": ("[m, -]", None, "efficiency schedule: rows tip depth, "
                                                "efficiency; default the hammer's"),
    "driveability.bound": ("-", "best", "'lower', 'best' or 'upper' SRD"),
    "driveability.lower_multiplier": ("-", 0.8, "SRD factor of the lower bound"),
    "driveability.upper_multiplier": ("-", 1.25, "SRD factor of the upper bound"),
    "driveability.time_series_depths": ("m", None, "depths whose blow time series are written"),
    "driveability.duration": ("s", None, "blow window; default simulation.duration"),
    "driveability.weight_on_soil": ("-", "all", "weight for self-weight penetration and pile "
                                    "runs: 'all' (pile, ram, helmet or anvil, assembly) or "
                                    "'grlweap' (without the ram: GRLWEAP's Total Wt)"),
    "driveability.window": ("-", "fixed", "'fixed' (the whole duration) or 'toe-rebound' (the "
                            "blow ends at the toe's first maximum, Smith's; needs set_rule "
                            "'grlweap', blows_per_depth 1)"),
    # [srd] (the SRD of a drive analysis)
    "srd.method": ("-", REQUIRED, "'table' ([soil] srd), 'tip-table', 'alm-hamre-2001', "
                                  "'stevens-1982'"),
    "srd.pile_mode": ("-", "coring", "'coring' (friction outside and inside, toe on the "
                                     "annulus) or 'plugged' (outside, full toe)"),
    "srd.faces": ("-", None, "'outside' or 'outside+inside' overriding pile_mode's"),
    "srd.cpt": ("-", None, "CPT file (CSV: depth, qc, fs, u2 with units in the header)"),
    "srd.cpt_qc_unit": ("-", None, "'Pa', 'kPa' or 'MPa' when the header has none"),
    "srd.cpt_fs_unit": ("-", None, "as cpt_qc_unit"),
    "srd.cpt_u2_unit": ("-", None, "as cpt_qc_unit"),
    "srd.cpt_depth_reference": ("-", "mudline", "'mudline' or 'sea-level' (needs "
                                                "water_depth)"),
    "srd.water_depth": ("m", None, "water depth"),
    "srd.net_area_ratio": ("-", 0.8, "cone net area ratio for qt = qc + (1 - a) u2"),
    "srd.sand_toe_factor": ("-", 0.15, "Alm & Hamre sand toe factor (0.10: 2018 revision)"),
    "srd.clay_residual_floor": ("-", "zero", "'zero', '0.002qt' or 'clamp'"),
    "srd.stevens_bound": ("-", "lower", "Stevens et al. K: 'lower' 0.5 or 'upper' 0.7"),
    "srd.file": ("-", None, "tip-table: a GRLWEAP input decoded to JSON"),
    "srd.format": ("-", "grlweap-model-json", "tip-table file format"),
    "srd.layer_parameters": ("-", "soil", "quakes and dampings from the [soil] table ('soil'); "
                             "tip-table file: per row of each tip's table ('file', as the "
                             "GRLWEAP model gives them); CPT/layer methods: Smith dampings by "
                             "each layer's soil type ('soil-type': shaft 0.16 sand, 0.65 "
                             "clay, toe 0.5 s/m)"),
    "srd.tip_table_rule": ("-", "interpolate", "tip-table: a tip between table depths blends "
                           "the two tables ('interpolate') or takes the nearest table at or "
                           "below it, the toe above a step at the tip ('grlweap'); on a table "
                           "depth, that table"),
    "srd.tables": ("-", None, "tip-table inline: [[srd.tables]] tip_depth, rows"),
    "srd.tables.tip_depth": ("m", REQUIRED, "tip depth of the table"),
    "srd.tables.rows": ("[m, Pa, Pa]", REQUIRED, "depth, unit shaft, unit toe"),
    "srd.layers": ("-", None, "[[srd.layers]] of the CPT/layer methods"),
    "srd.layers.top": ("m", REQUIRED, "layer top below the mudline"),
    "srd.layers.bottom": ("m", REQUIRED, "layer bottom"),
    "srd.layers.soil": ("-", REQUIRED, "'sand' or 'clay'"),
    "srd.layers.submerged_unit_weight": ("N/m^3", REQUIRED, "submerged unit weight"),
    "srd.layers.interface_friction_angle": ("deg", None, "sand: delta"),
    "srd.layers.friction_angle": ("deg", None, "sand: phi' (delta = phi' - 5)"),
    "srd.layers.undrained_shear_strength": ("Pa", None, "clay: su at the top"),
    "srd.layers.undrained_shear_strength_gradient": ("Pa/m", 0.0, "clay: su increase"),
    "srd.layers.plasticity_index": ("-", None, "clay: PI as a fraction (0.3 = 30 %)"),
    # [installation] (anvilwave install)
    "installation.start_depth": ("m", None, "tip depth of the first blow; default the "
                                            "self-weight penetration"),
    "installation.target_depth": ("m", None, "final tip depth; default the last drive depth"),
    "installation.max_blows": ("-", 20000, "safety limit on the number of blows"),
    "installation.srd_update": ("m", 0.05, "tip movement that rebuilds the SRD"),
    "installation.weld_depths": ("m", None, "fatigue sections below the head; default every "
                                            "spring"),
    "installation.sn_curve": ("-", "D", "DNV-RP-C203 S-N curve (B1 ... W3)"),
    "installation.environment": ("-", "seawater-cp", "'air', 'seawater-cp', "
                                                     "'free-corrosion'"),
    "installation.edition": ("-", "2016", "DNV-RP-C203 edition"),
    "installation.scf": ("-", 1.0, "stress concentration factor"),
    "installation.spectra_depths": ("m", None, "tip depths of the head-force spectra"),
    "installation.record_interval": ("s", None, "sampling of the stress histories"),
    "installation.pauses": ("[m, h]", None, "rows tip depth, pause duration: driving stops "
                            "there; the shaft sets up (restrike blow counts in the summary)"),
    "installation.setup": ("-", "skov-denver-1988", "set-up of the shaft during a pause: "
                           "1 + A log10(t / t0), sand A 0.2, t0 0.5 d; clay A 0.6, t0 1 d"),
    "installation.setup_soil": ("-", None, "'sand' or 'clay' where the SRD has no soil "
                                "layers (default: each segment's layer type)"),
    "installation.setup_a": ("-", None, "set-up A for every soil (site-specific, e.g. from "
                             "restrikes) instead of the soil types'"),
    "installation.setup_t0": ("h", None, "with setup_a: its t0; default 24 h"),
    "installation.remoulding_length": ("m", 0.5, "the blows after a restart remould the gain "
                                       "as exp(-penetration / this length)"),
}

ANVIL: dict[str, tuple[str, object, str]] = {
    "material.youngs_modulus": ("Pa", REQUIRED, "Young's modulus"),
    "material.poisson_ratio": ("-", REQUIRED, "Poisson's ratio, in [0, 0.5)"),
    "material.density": ("kg/m^3", REQUIRED, "density"),
    "geometry.points": ("[m, m]", REQUIRED, "closed (r, z) polygon of the half-section, z down"),
    "mesh": ("-", None, "instead of [geometry]/[mesh]: a 2D mesh file read with meshio"),
    "mesh.size": ("m", REQUIRED, "target element size (quadratic triangles)"),
    "interfaces.ram_contact_radius": ("m", REQUIRED, "radius of the top face under the ram"),
    "interfaces.pile_contact_radius": ("m", REQUIRED, "mid-radius of the pile wall"),
    "interfaces.pile_contact_width": ("m", REQUIRED, "width of the pile contact ring"),
    "modes.fmax": ("Hz", 5000.0, "frequency content of the ROM"),
    "modes.damping_ratio": ("-", 0.0, "modal damping ratio"),
}

FILES = {"system": SYSTEM, "anvil": ANVIL}


def documented(kind: str, dotted_key: str) -> bool:
    """Whether a key of a file of ``kind`` is documented (a ``*`` matches one part).

    Parameters
    ----------
    kind : {"system", "anvil"}
        The file kind.
    dotted_key : str
        The key, array indices dropped, e.g. ``pile.sections.length``.

    Returns
    -------
    bool
        True if the key is documented or is a table holding documented keys.
    """
    parts = dotted_key.split(".")
    for key in FILES[kind]:
        if key.startswith(dotted_key + "."):  # a table
            return True
        pattern = key.split(".")
        if len(pattern) == len(parts) and all(p in ("*", q) or (p.startswith("*") and
                                                               q.endswith(p[1:]))
                                              for p, q in zip(pattern, parts, strict=True)):
            return True
    return False


def describe(kind: str = "system") -> str:
    """The keys of a file kind as a plain-text table.

    Parameters
    ----------
    kind : str, default "system"
        The file kind (a key of :data:`FILES`).

    Returns
    -------
    str
        One row per key: key, unit, default and meaning.
    """
    rows = [f"{'key':44s} {'unit':12s} {'default':16s} meaning"]
    for key, (unit, default, meaning) in FILES[kind].items():
        rows.append(f"{key:44s} {unit:12s} {str(default):16s} {meaning}")
    return "\n".join(rows)
