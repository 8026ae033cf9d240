"""Results follow the code: which rule functions a module change reaches."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from gearmesh.codeversion import PACKAGE_ROOT, function_digest, module_closure, versioned
from gearmesh.pipeline import resolve

SPECS = {
    "geometry": "gearmesh.datasets.geometry:geometry_dataset",
    "stiffness": "gearmesh.datasets.stiffness:stiffness_dataset",
    "ltca": "gearmesh.datasets.ltca:ltca_dataset",
    "dynamics": "gearmesh.datasets.dynamics:dynamics_dataset",
    "plot_ltca": "gearmesh.plots.ltca:ltca_figures",
    "plot_pair": "gearmesh.plots.geometry:geometry_figures",
}


def test_closure_follows_relative_and_nested_imports():
    closure = module_closure("gearmesh.datasets.dynamics")
    assert {"gearmesh.dynamics", "gearmesh.dynamics.integrate", "gearmesh.stiffness", "gearmesh.gear",
            "gearmesh.io"} <= set(closure)
    # the contact excitation drives the dynamics with the LTCA's contact model: a change to it reruns the dynamics
    assert {"gearmesh.meshforce", "gearmesh.ltca"} <= set(closure) and "gearmesh.plots.ltca" not in closure
    # every job applies its variant's micro-geometry with pairfile.variant_pair: the glue imports it
    assert "gearmesh.pairfile" in module_closure("gearmesh.pipeline", shallow=("gearmesh.pipeline",))


def test_versioned_spec_resolves_to_the_same_function():
    spec = versioned(SPECS["ltca"])
    assert spec.startswith(SPECS["ltca"] + "@") and len(spec.partition("@")[2]) == 16
    assert resolve(spec) is resolve(SPECS["ltca"])
    with pytest.raises(ValueError):
        function_digest("gearmesh.no_such_module:f")


@pytest.mark.parametrize("module, changed", [
    ("stiffness.py", {"stiffness", "dynamics", "ltca"}),   # ltca builds on the slice tables
    ("ltca.py", {"dynamics", "ltca", "stiffness"}),         # the contact table is the LTCA's contact model;
    #                                                         the stiffness stage's contact term its tangent (issue 28)
    ("plots/ltca.py", {"plot_ltca"}),
    ("dynamics/integrate.py", {"dynamics"}),
    ("pipeline.py", set(SPECS)),                            # the glue every job runs
])
def test_a_module_change_reaches_exactly_its_importers(tmp_path: Path, module: str, changed: set[str]):
    copy = tmp_path / "gearmesh"
    shutil.copytree(PACKAGE_ROOT, copy, ignore=shutil.ignore_patterns("__pycache__"))
    before = {k: function_digest(s, copy) for k, s in SPECS.items()}
    (copy / module).write_text((copy / module).read_text() + "\n# changed\n")
    after = {k: function_digest(s, copy) for k, s in SPECS.items()}
    assert {k for k in SPECS if before[k] != after[k]} == changed


@pytest.mark.parametrize("nested", [True, False])
def test_import_statements_found_are_every_one_a_full_tree_walk_finds(nested):
    """The statement walk finds exactly the import statements that ast.walk over the whole tree
    finds (all of them, or with ``nested`` False those outside the module's own functions and
    classes), over every module of the package and a file with every statement container."""
    import ast

    from gearmesh.codeversion import _import_nodes

    def reference(tree):
        nodes = ast.walk(tree) if nested else (n for stmt in tree.body if not isinstance(
            stmt, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) for n in ast.walk(stmt))
        return {id(n) for n in nodes if isinstance(n, (ast.Import, ast.ImportFrom))}

    every = ("import a\nif x:\n    import b\nelse:\n    import c\nfor i in y:\n    import d\nelse:\n    import e\n"
             "while z:\n    import f\ntry:\n    import g\nexcept E:\n    import h\nelse:\n    import i\nfinally:\n"
             "    import j\nwith w:\n    import k\nmatch v:\n    case 1:\n        import l\n"
             "def fn():\n    import m\n    class Inner:\n        import n\n"
             "class C:\n    import o\n    def method(self):\n        import p\n"
             "async def co():\n    async with u:\n        import q\n    async for t in s:\n        import r\n"
             "if q:\n    def nested():\n        import s\n")
    sources = [p.read_text(encoding="utf-8") for p in PACKAGE_ROOT.rglob("*.py")] + [every]
    for source in sources:
        tree = ast.parse(source)
        found = {id(n) for n in _import_nodes(tree, nested) if isinstance(n, (ast.Import, ast.ImportFrom))}
        assert found == reference(tree)
    assert len(reference(ast.parse(every))) == (19 if nested else 13)
