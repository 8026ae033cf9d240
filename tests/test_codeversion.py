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
    # every job applies its variant's micro-geometry with gear.variant_pair: the glue imports it
    assert "gearmesh.gear" in module_closure("gearmesh.pipeline", shallow=("gearmesh.pipeline",))


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
