"""numpydoc docstrings (issue 25): every public function, class, method and property of the
modules converted so far passes numpydoc's validator on the error codes that make an API
reference complete and correct (parameters, returns, sections, summary).

A module joins ``MODULES`` once all its public objects have numpydoc sections. Public means
defined at module level (or in a public class of the module) with a name that does not start
with ``_``; the objects are found from the module's source, so a new function cannot slip
past the check by being left out of a list.
"""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import numpydoc.validate as numpydoc_validate
import pytest
from numpydoc.docscrape import get_doc_object

MODULES_PHYSICS_AND_OUTPUT = (
    "anvilwave.analyses.compare",
    "anvilwave.analyses.stack_blow",
    "anvilwave.analyses.match",
    "anvilwave.anvil_rom.arrays",
    "anvilwave.anvil_rom.chain",
    "anvilwave.anvil_rom.contact",
    "anvilwave.anvil_rom.fem.calculix",
    "anvilwave.anvil_rom.fem.elasticity",
    "anvilwave.anvil_rom.fem.geometry",
    "anvilwave.anvil_rom.fem.mesh",
    "anvilwave.anvil_rom.fem.modalfile",
    "anvilwave.anvil_rom.fem.modes",
    "anvilwave.anvil_rom.fem.pipeline",
    "anvilwave.fea.bodies",
    "anvilwave.fea.cache",
    "anvilwave.fea.impact",
    "anvilwave.fea.solver",
    "anvilwave.hammer.cushion",
    "anvilwave.hammer.database",
    "anvilwave.hammer.impact",
    "anvilwave.inputs",
    "anvilwave.output.campaign_plots",
    "anvilwave.output.pda_plots",
    "anvilwave.output.plots",
    "anvilwave.output.report",
    "anvilwave.output.tables",
    "anvilwave.output.writer",
    "anvilwave.pile.head_kernel",
    "anvilwave.pile.pda.records",
    "anvilwave.pile.pda.signal_matching",
    "anvilwave.pile.pile",
    "anvilwave.pile.post.fatigue",
    "anvilwave.pile.post.spectra",
    "anvilwave.pile.soil.cpt_classification",
    "anvilwave.pile.soil.srd",
    "anvilwave.pile.static",
)
MODULES_SYSTEM = (
    "anvilwave.analyses.batch",
    "anvilwave.analyses.drive",
    "anvilwave.analyses.impact",
    "anvilwave.analyses.install",
    "anvilwave.analyses.pda",
    "anvilwave.api",
    "anvilwave.cli",
    "anvilwave.config.budget",
    "anvilwave.config.cache",
    "anvilwave.config.drive",
    "anvilwave.config.install",
    "anvilwave.config.schema",
    "anvilwave.config.system",
    "anvilwave.engine.anvils",
    "anvilwave.engine.compilation",
    "anvilwave.engine.fmi",
    "anvilwave.engine.fmus",
    "anvilwave.output.examples",
    "anvilwave.output.figure_style",
    "anvilwave.output.progress",
    "anvilwave.pile.model",
    "anvilwave.pile.pda.case_method",
    "anvilwave.pile.soil.cpt",
    "anvilwave.pile.soil.models",
    "anvilwave.pile.soil.profile",
    "anvilwave.pile.soil.setup",
    "anvilwave.pile.soil.srd_methods",
)
"""The system layer (config, engine, analyses, api, cli) and the soil and PDA modules."""
MODULES_FMU = (
    "anvilwave.fmu.coupling",
    "anvilwave.fmu.fmi_build",
    "anvilwave.fmu.fmi_master",
    "anvilwave.fmu.native_build",
    "anvilwave.fmu.native_units",
    "anvilwave.fmu.ssp",
    "anvilwave.fmu.units.anvil",
    "anvilwave.fmu.units.anvilwave_anvil_lumped",
    "anvilwave.fmu.units.anvilwave_anvil_rom",
    "anvilwave.fmu.units.anvilwave_anvil_stack",
    "anvilwave.fmu.units.anvilwave_pile_soil",
    "anvilwave.fmu.units.anvilwave_ram",
    "anvilwave.fmu.units.base",
    "anvilwave.fmu.units.pile_soil",
    "anvilwave.fmu.units.ram",
    "anvilwave.fmu.units.vendor_init",
    "anvilwave.fmu.vendoring",
)
"""The FMI package."""
MODULES_KERNELS = (
    "anvilwave.engine.direct",
    "anvilwave.anvil_rom.rings",
    "anvilwave.anvil_rom.stack",
    "anvilwave.anvil_rom.unit",
    "anvilwave.anvil_rom.rom",
    "anvilwave.pile.kernels",
    "anvilwave.hammer.ram",
    "anvilwave.hammer.modal_ram",
    "anvilwave.hammer.ram_table",
    "anvilwave.hammer.driving_system",
)
"""The compiled kernels and the units they step (engine.direct, anvil_rom, hammer, pile)."""
MODULES = MODULES_PHYSICS_AND_OUTPUT + MODULES_SYSTEM + MODULES_FMU + MODULES_KERNELS

# Checked: what an API reference needs to be complete and to parse.
#   GL01-GL03, GL05-GL07, GL10: docstring layout, tabs, unknown or misordered sections (an
#     unknown section header swallows the parameters that follow it);
#   GL08: a docstring exists;
#   SS01, SS03, SS04, SS06: a one-line summary ending with a period;
#   PR01-PR07, PR09, PR10: every parameter documented, in order, with a type and a
#     description, none unknown (PR02 catches a prose paragraph indented under Parameters);
#   RT01-RT03, RT05, YD01: a Returns (Yields) section whenever something is returned, with
#     types and descriptions;
#   SA02-SA04: See Also entries, when present, are well formed.
# Not checked, on purpose:
#   SS02, PR08, RT04 (start with a capital letter): summaries and descriptions here often
#     start with a symbol or a formula whose case carries meaning (``n = 0.381 Ic ...``,
#     ``t_eff``, ``log10 a1``, ``|F(f)|``, ``k_h``);
#   SS05 (summary starts with an infinitive verb): the summaries name what a function
#     returns, after pvlib ("Lumped segment masses ...", "Miner's sum ..."), a style choice;
#   ES01, EX01, SA01 (extended summary, Examples, See Also present): optional content, not
#     needed for a complete parameter reference.
CODES = frozenset({
    "GL01", "GL02", "GL03", "GL05", "GL06", "GL07", "GL08", "GL10",
    "SS01", "SS03", "SS04", "SS06",
    "PR01", "PR02", "PR03", "PR04", "PR05", "PR06", "PR07", "PR09", "PR10",
    "RT01", "RT02", "RT03", "RT05", "YD01",
    "SA02", "SA03", "SA04",
})


def public_names(module) -> list[str]:
    """Dotted names (inside ``module``) of its public functions, classes, methods and
    properties, read from its source."""
    tree = ast.parse(Path(module.__file__).read_text(encoding="utf-8"))
    names: list[str] = []

    def walk(body, prefix):
        for node in body:
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                if node.name.startswith("_"):
                    continue
                names.append(prefix + node.name)
                if isinstance(node, ast.ClassDef):
                    walk(node.body, f"{prefix}{node.name}.")

    walk(tree.body, "")
    return names


def _objects():
    for module_name in MODULES:
        module = importlib.import_module(module_name)
        for name in public_names(module):
            yield f"{module_name}.{name}"


def _doc_object(qualified_name: str):
    """numpydoc's view of an object; a numba dispatcher is validated as its Python function,
    so that the checks on returns (RT01) apply to compiled kernels too."""
    obj = numpydoc_validate.Validator._load_obj(qualified_name)
    return get_doc_object(getattr(obj, "py_func", obj))


@pytest.mark.parametrize("qualified_name", list(_objects()))
def test_numpydoc(qualified_name):
    result = numpydoc_validate.validate(_doc_object(qualified_name))
    errors = [f"{code} {message}" for code, message in result["errors"] if code in CODES]
    assert not errors, f"{qualified_name}:\n  " + "\n  ".join(errors)


def test_every_module_listed_exists():
    for module_name in MODULES:
        assert public_names(importlib.import_module(module_name)), module_name


def test_every_module_with_public_objects_is_listed():
    """Every module of the package that defines a public function or class is checked: the
    API reference has no module without its parameters. The example scripts are not modules
    of the API (they are run, not imported)."""
    root = Path(importlib.import_module("anvilwave").__file__).parent
    missing = []
    for path in sorted(root.rglob("*.py")):
        parts = path.relative_to(root.parent).with_suffix("").parts
        if "examples" in parts:
            continue
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if any(isinstance(n, ast.FunctionDef | ast.ClassDef) and not n.name.startswith("_")
               for n in tree.body) and name not in MODULES:
            missing.append(name)
    assert not missing, missing
