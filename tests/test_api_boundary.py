"""The Python API enforces what the CLI does, at the boundary of every public function (issue 29,
items 5, 6 and 8), and the limits are declared once (issue 25): a GearPair's material checked
however it was built, another pair's dataset refused, an unknown variant key refused, every list
bounded by count before it is read through, and messages that name the file and the field.
Memory is measured with tracemalloc (numpy reports its buffers to it); no timing."""

from __future__ import annotations

import ast
import dataclasses
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

import gearmesh
from gearmesh.cli import main
from gearmesh.datasets.dynamics import dynamics_dataset
from gearmesh.datasets.geometry import helix_sweep_dataset, low_fluctuation_design_dataset
from gearmesh.datasets.ltca import ltca_dataset, tca_dataset
from gearmesh.datasets.optimise import run_settings
from gearmesh.datasets.stiffness import stiffness_dataset
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import GearPair, Material, pair_geometry
from gearmesh.pairfile import load_pair, pair_from_dict, variant_pair
from gearmesh.stiffness import mesh_stiffness
from pairs import low_fluctuation_pair1
from test_limits import REFUSAL_BYTES, _refused  # one line on the field, bounded memory
PACKAGE = Path(gearmesh.__file__).parent


@pytest.fixture(scope="module")
def pair() -> GearPair:
    return pair_from_dict(low_fluctuation_pair1())


# --- item 5: the material of a GearPair however it was built -----------------------------------


@pytest.mark.parametrize("material, field", [
    (Material(210e9, 0.3, 7850.0), None),
    (dict(youngs_modulus=-210e9, poisson_ratio=0.3, density=7850.0), "material.youngs_modulus_GPa"),
    (dict(youngs_modulus=0.0, poisson_ratio=0.3, density=7850.0), "material.youngs_modulus_GPa"),
    (dict(youngs_modulus=float("nan"), poisson_ratio=0.3, density=7850.0), "material.youngs_modulus_GPa"),
    (dict(youngs_modulus=210e9, poisson_ratio=0.7, density=7850.0), "material.poisson_ratio"),
    (dict(youngs_modulus=210e9, poisson_ratio=-0.1, density=7850.0), "material.poisson_ratio"),
    (dict(youngs_modulus=210e9, poisson_ratio=0.3, density=float("nan")), "material.density_kg_m3"),
    (dict(youngs_modulus=210e9, poisson_ratio=0.3, density=-1.0), "material.density_kg_m3"),
])
def test_a_material_built_in_code_obeys_the_pair_file_rules(pair, material, field):
    """E = -210 GPa gave a negative mesh stiffness, nu = 0.7 and a NaN density were accepted, a NaN
    E gave "Factor is exactly singular": a Material is checked when it is made, so a GearPair
    built in code or by dataclasses.replace carries only a valid one."""
    if field is None:
        assert dataclasses.replace(pair, material=material).material.youngs_modulus == 210e9
        return
    _refused(lambda: dataclasses.replace(pair, material=Material(**material)), field)


def test_a_pair_file_material_is_refused_by_the_same_rule():
    with pytest.raises(GearmeshInputError, match="must lie in"):
        pair_from_dict(low_fluctuation_pair1(material={"youngs_modulus_GPa": 210, "poisson_ratio": 0.5,
                                               "density_kg_m3": 7850}))


# --- item 5: a dataset from another pair -------------------------------------------------------


@pytest.fixture(scope="module")
def other_stiffness():
    other = pair_from_dict(low_fluctuation_pair1(name="other", helix_angle_deg=15))
    return stiffness_dataset(other, slices=20, positions=24, method="traditional")


def test_another_pairs_stiffness_is_refused_by_the_dynamics(pair, other_stiffness):
    """dynamics_dataset gave a dynamic factor of 1.74 instead of 1.08 with another pair's
    stiffness; now refused before any work, naming the argument and the differing key."""
    _refused(lambda: dynamics_dataset(pair, stiffness=other_stiffness, speeds_rpm=[1000.0], slices=20,
                                      positions=24, method="traditional"),
             "stiffness", "helix_angle_deg", "'other'")


def test_a_pairs_own_dataset_is_accepted_and_a_variant_keeps_its_pair_stage_files(pair):
    """A stage of the pair (stiffness) is made without the modification: a variant of the pair
    may use it; a stage of the variant (TCA) is made with it: another variant may not."""
    from gearmesh.upstream import check_dataset_pair

    own = stiffness_dataset(pair, slices=20, positions=24, method="traditional")
    relief = variant_pair(pair, "relief", {"modification": {"pinion": {"tip_relief_um": 10,
                                                                        "tip_relief_length_mm": 1}}})
    check_dataset_pair("stiffness", own, pair)
    check_dataset_pair("stiffness", own, relief)
    tca = tca_dataset(pair, positions=8, points=5)
    check_dataset_pair("tca", tca, pair)
    _refused(lambda: check_dataset_pair("tca", tca, relief), "tca", "modification")


# --- item 5: unknown keys ----------------------------------------------------------------------


def test_a_misspelt_variant_key_is_refused(pair):
    """variant_pair ignored a misspelt key (the unmodified pair came back)."""
    _refused(lambda: variant_pair(pair, "relief", {"modifcation": {"pinion": {"tip_relief_um": 10}}}),
             "variants.relief.modifcation", "unknown key")
    _refused(lambda: variant_pair(pair, "v", {"from": "optimise.x", "modification": {"pinion": {"crowning_um": 1}}}), "variants.v.from",
             "exclusive")


# --- item 6: limits by count, O(1) in the length ------------------------------------------------


def test_ltca_torques_have_a_maximum_count(pair):
    """15 003 torques passed gearmesh validate; 3000 through the API peaked at 4.7 GB."""
    _refused(lambda: ltca_dataset(pair, torques_Nm=[100.0] * 3000), "torques_Nm", "at most 100 items")


def test_ten_million_torques_are_refused_by_their_count(pair):
    """10⁷ torques spent 254 s validating, then tried to allocate 969 GiB: the length is read first."""
    torques = np.full(10**7, 100.0)
    _refused(lambda: ltca_dataset(pair, torques_Nm=torques), "torques_Nm", "10000000 items")


def test_a_million_speeds_are_refused_by_their_count(pair):
    """10⁶ speeds took 10.6 s to refuse (each one read before the count)."""
    speeds = list(np.linspace(100.0, 1000.0, 10**6))
    _refused(lambda: dynamics_dataset(pair, speeds_rpm=speeds), "speeds_rpm", "1000000 items", "at most")


def test_a_helix_sweep_is_sized_before_its_grid(pair):
    """helix_sweep_dataset(step_deg=1e-9) tried 335 GiB."""
    _refused(lambda: helix_sweep_dataset({"p": pair}, pairs=["p"], start_deg=0.0, stop_deg=30.0, step_deg=1e-9),
             "step_deg", "helix angles")
    _refused(lambda: helix_sweep_dataset({"p": pair}, pairs=["p"], start_deg=20.0, stop_deg=10.0, step_deg=1.0),
             "stop_deg", "start_deg")


@pytest.mark.parametrize("function, section, field", [
    (helix_sweep_dataset, {"start_deg": 60}, "start_deg"),
    (helix_sweep_dataset, {"step_deg": None}, "step_deg"),
    (helix_sweep_dataset, {"positions": 4}, "positions"),
    (helix_sweep_dataset, {"angles_deg": [10]}, "angles_deg"),  # an unknown key
    (helix_sweep_dataset, {"pairs": ["q"]}, "pairs"),  # a pair not given
    (low_fluctuation_design_dataset, {"pairs": ["a b"]}, "pairs[0]"),
    (low_fluctuation_design_dataset, {"pairs": ["q"]}, "pairs"),
    (low_fluctuation_design_dataset, {"routes": ["helix_angle_forward"]}, "routes"),  # an unknown key
])
def test_the_geometry_study_tables_refuse_a_bad_setting_by_its_key(pair, function, section, field):
    """The helix sweep and the low-fluctuation designs parse their section once
    (gearmesh.schema.settings_object): a value outside its declaration, a required key left out, an
    unknown key and a pair the caller did not give are refused by their key."""
    given = {"pairs": ["p"]} | ({"start_deg": 10, "stop_deg": 20, "step_deg": 5}
                                if function is helix_sweep_dataset else {})
    _refused(lambda: function({"p": pair}, **{k: v for k, v in (given | section).items() if v is not None}), field)


def test_mesh_stiffness_grid_is_sized_before_allocation(pair):
    """stiffness.mesh_stiffness with large grids tried 10.8 GiB."""
    geom = pair_geometry(pair)
    _refused(lambda: mesh_stiffness(geom, n_positions=100000, n_slices=20000), "n_slices", "slice-positions")
    _refused(lambda: mesh_stiffness(geom, n_positions=24, n_slices=2.5), "n_slices", "integer")


def test_every_list_setting_declares_a_maximum_length():
    from gearmesh.pair_keys import pair_schema
    from gearmesh.registry import study_schema

    def arrays(schema, path=""):
        if isinstance(schema, dict):
            kind = schema.get("type")
            if kind == "array" or (isinstance(kind, list) and "array" in kind):
                yield path, schema
            if kind == "object" and "additionalProperties" in schema and schema["additionalProperties"] is not False:
                assert "maxProperties" in schema, path
            for key, sub in schema.items():
                yield from arrays(sub, f"{path}/{key}")
        elif isinstance(schema, list):
            for k, sub in enumerate(schema):
                yield from arrays(sub, f"{path}[{k}]")

    found = list(arrays(study_schema())) + list(arrays(pair_schema()))
    assert len(found) > 20
    for path, schema in found:
        assert "maxItems" in schema, path


def test_validate_refuses_a_long_list_by_its_count(tmp_path, capsys):
    """The study config's lists too (gearmesh validate; the workflow uses the same schema)."""
    config = tmp_path / "c.yaml"
    config.write_text("study: s\npairs: [low_fluctuation_pair1]\nltca:\n  torques_Nm: [" + ", ".join(["100"] * 15003) + "]\n")
    assert main(["validate", str(config)]) == 2
    err = capsys.readouterr().err
    assert "ltca.torques_Nm" in err and "at most 100 items" in err


# --- item 8: messages that name the file, the field and what to do ------------------------------


def test_an_empty_pair_file_is_named(tmp_path):
    empty = tmp_path / "empty.yaml"
    empty.write_text("")
    message = _refused(lambda: load_pair(empty), "pair file", "empty.yaml", "is empty", "gearmesh example")
    assert "None" not in message


def test_a_bad_key_of_a_pair_file_names_the_file(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("teeth: [29, 49]\nnormal_module_mm: 1.75\nnormal_pressure_angle_deg: 20\nhelix_angle_deg: 10\n"
                   "face_width_mm: -20\n")
    _refused(lambda: load_pair(bad), "face_width_mm", "must be positive", "bad.yaml")


def test_a_negative_speed_start_names_the_start(pair):
    """It said "must be a mapping or a list"."""
    _refused(lambda: dynamics_dataset(pair, speeds_rpm={"start": -1, "stop": 100, "step": 10}),
             "speeds_rpm.start", "must be positive")


def test_an_absurd_optimisation_torque_is_named_as_a_load(pair):
    """optimise torque_Nm = 1e12 blamed load_window_step_Nm."""
    _refused(lambda: run_settings(pair, torque_Nm=1e12), "torque_Nm", "contact stress")


# --- issue 25: each limit declared once ---------------------------------------------------------


def test_the_population_cap_is_the_declared_one(pair):
    """settings.Optimise capped the population at 10 000, optimise.check_settings at 100 000."""
    nominal = {"objective": "force", "tolerance_statistic": None, "torque_Nm": 100}
    assert run_settings(pair, population=10000, keep_elitism=2, **nominal)[1].population == 10000
    _refused(lambda: run_settings(pair, population=50000, **nominal), "population", "10000")
    _refused(lambda: run_settings(pair, generations=50000, **nominal), "generations", "10000")


def _module_level_assignments(path: Path) -> list[str]:
    tree = ast.parse(path.read_text())
    return [t.id for node in tree.body if isinstance(node, (ast.Assign, ast.AnnAssign))
            for t in (node.targets if isinstance(node, ast.Assign) else [node.target]) if isinstance(t, ast.Name)]


def test_every_max_limit_lives_in_limits():
    """MAX_* limits lived in six modules. (errors.MAX_EXCERPT, the length of a message excerpt,
    is how an error is printed, not a limit of the input.)"""
    elsewhere = {f"{p.relative_to(PACKAGE)}:{name}" for p in PACKAGE.rglob("*.py") if p.name != "limits.py"
                 for name in _module_level_assignments(p) if name.startswith("MAX_")}
    assert elsewhere == {"errors.py:MAX_EXCERPT"}


def test_one_speed_check():
    """impact.check_speeds and limits.check_speeds had the same name and different rules."""
    import gearmesh.impact
    import gearmesh.limits

    assert not hasattr(gearmesh.impact, "check_speeds") or gearmesh.impact.check_speeds is gearmesh.limits.check_speeds
    defined = [p.name for p in PACKAGE.rglob("*.py")
               if any(isinstance(n, ast.FunctionDef) and n.name == "check_speeds" for n in ast.parse(p.read_text()).body)]
    assert defined == ["limits.py"]


def _imports(path: Path, module: str) -> set[str]:
    """The gearmesh modules ``module`` (at ``path``) imports anywhere (functions included), but
    not under ``if TYPE_CHECKING``."""
    tree = ast.parse(path.read_text())
    skip = {id(n) for node in ast.walk(tree) if isinstance(node, ast.If) and getattr(node.test, "id", "") == "TYPE_CHECKING"
            for n in ast.walk(node)}
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(tree):
        if id(node) in skip or not isinstance(node, ast.ImportFrom) or not node.level:
            continue
        base = package.split(".")[:len(package.split(".")) - (node.level - 1)]
        target = ".".join(base + ([node.module] if node.module else []))
        out |= {target} | {f"{target}.{a.name}" for a in node.names}
    return out


def test_no_import_circle():
    """jobserver <-> pipeline was the one remaining circle (imports inside functions count)."""
    modules = {}
    for p in PACKAGE.rglob("*.py"):
        parts = p.relative_to(PACKAGE.parent).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = p
    graph = {m: _imports(p, m) & set(modules) - {m} for m, p in modules.items()}
    state: dict[str, int] = {}

    def visit(m: str, path: list[str]) -> None:
        state[m] = 1
        path.append(m)
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                raise AssertionError("import circle: " + " -> ".join(path[path.index(n):] + [n]))
            if n not in state:
                visit(n, path)
        path.pop()
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [])



# --- item 7: configs that only Snakemake's loader would see ---------------------------------------


def test_validate_names_the_template_engine(tmp_path, capsys):
    """A config with __use_yte__: true runs Python when Snakemake loads it."""
    config = tmp_path / "yte.yaml"
    config.write_text("study: s\npairs: [low_fluctuation_pair1]\n__use_yte__: true\n")
    assert main(["validate", str(config)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearmesh: error: __use_yte__ = True:") and "runs Python" in err


@pytest.mark.parametrize("content, words", [
    (None, "not a regular file"),  # a FIFO: Snakemake's loader blocked on it forever
    ("study: s\npairs: [low_fluctuation_pair1]\nx: " + "[" * 100 + "]" * 100 + "\n", "nests deeper"),
    ("study: s\npairs: [low_fluctuation_pair1]\n" + "# padding\n" * 40000, "larger than"),
    ("study: s\npairs: [low_fluctuation_pair1]\n__use_yte__: true\n", "__use_yte__"),
])
def test_gearmesh_run_reads_configs_bounded_before_snakemake(tmp_path, monkeypatch, capsys, content, words):
    """A 200 MB config parsed for minutes at 6.5 GB, a deep one printed a 2985-line RecursionError:
    'gearmesh run' refuses each before Snakemake starts (its entry point is never reached)."""
    import os

    path = tmp_path / "c.yaml"
    if content is None:
        os.mkfifo(path)
    else:
        path.write_text(content)
    monkeypatch.setattr("snakemake.cli.main", lambda *a: pytest.fail("snakemake was started"))
    tracemalloc.start()
    try:
        assert main(["run", "-n", "--cores", "1", "--configfile", str(path)]) == 2
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and words in err, err
    assert peak < REFUSAL_BYTES


def test_gearmesh_run_finds_every_config_file(tmp_path, monkeypatch):
    from gearmesh.launch import snakemake_inputs

    monkeypatch.chdir(tmp_path)  # no Snakefile, no profiles/default
    monkeypatch.delenv("SNAKEMAKE_PROFILE", raising=False)
    assert snakemake_inputs(["--cores", "2"]).configfiles == ["config/config.yaml"]
    assert snakemake_inputs(["-n", "--configfile", "a.yaml", "b.yaml", "--cores", "2"]).configfiles == ["a.yaml", "b.yaml"]
    # as Snakemake's parser reads them: a second --configfile replaces the first
    assert snakemake_inputs(["-n", "--configfile", "a.yaml", "--configfile=c.yaml"]).configfiles == ["c.yaml"]
    assert snakemake_inputs(["-n", "--configfiles", "a.yaml"]).configfiles == ["a.yaml"]


YTE_STUDY = "study: s\npairs: [low_fluctuation_pair1]\n__use_yte__: true\n"


def _profile(folder, text: str):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "config.yaml").write_text(text)
    return folder


@pytest.mark.parametrize("how", ["--profile", "SNAKEMAKE_PROFILE", "profiles/default", "--workflow-profile",
                                 "profile.yaml", "configfiles list"])
def test_gearmesh_run_refuses_a_template_a_profile_names(tmp_path, monkeypatch, capsys, how):
    """'gearmesh run -n --profile P' (P's config.yaml: configfile: yte.yaml), or SNAKEMAKE_PROFILE=P,
    executed the template's Python: every profile Snakemake reads is followed to its config files."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv("SNAKEMAKE_PROFILE", raising=False)
    (tmp_path / "yte.yaml").write_text(YTE_STUDY)
    (tmp_path / "Snakefile").write_text("rule all:\n    input: []\n")
    monkeypatch.setattr("snakemake.cli.main", lambda *a: pytest.fail("snakemake was started"))
    argv = ["run", "-n"]
    if how == "--profile":
        argv += ["--profile", str(_profile(tmp_path / "P", "configfile: yte.yaml\ncores: 1\n"))]
    elif how == "SNAKEMAKE_PROFILE":
        monkeypatch.setenv("SNAKEMAKE_PROFILE", str(_profile(tmp_path / "P", "configfile: yte.yaml\n")))
    elif how == "profiles/default":  # the workflow profile, applied without a flag
        _profile(tmp_path / "profiles" / "default", "configfile: yte.yaml\n")
    elif how == "--workflow-profile":
        argv += ["--workflow-profile", str(_profile(tmp_path / "W", "configfile: ../yte.yaml\n"))]
    elif how == "profile.yaml":  # the profile itself a template
        argv += ["--profile", str(_profile(tmp_path / "P", "__use_yte__: true\ncores: 1\n"))]
    else:
        argv += ["--profile", str(_profile(tmp_path / "P", "configfiles: [yte.yaml]\n"))]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and err.startswith("gearmesh: error: __use_yte__ = True"), err


def test_gearmesh_run_refuses_what_snakemake_would(tmp_path, monkeypatch, capsys):
    """An abbreviated --configfile is still a config file to Snakemake; arguments it refuses are refused here."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr("snakemake.cli.main", lambda *a: pytest.fail("snakemake was started"))
    (tmp_path / "yte.yaml").write_text(YTE_STUDY)
    assert main(["run", "-n", "--configfile", "yte.yaml"]) == 2
    assert "in config file yte.yaml" in capsys.readouterr().err
    assert main(["run", "-n", "--no-such-option"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearmesh: error: snakemake arguments = ") and "--no-such-option" in err
    assert main(["run", "-n", "--profile", str(tmp_path / "nowhere")]) == 2
    assert "profile" in capsys.readouterr().err


#: Functions allowed over the length limit, each with its reason: numba compiles them whole (a
#: compiled kernel cannot call back into helpers without paying for it on every step).
COMPILED_KERNELS = {"dynamics/integrate.py:_sweep": "the RK4 sweep with its shooting, compiled by numba"}


def test_modules_and_functions_stay_short_enough_to_read():
    """Modules by topic (no module of the package over 800 lines) and functions that do one thing
    (none over 80 lines but the compiled kernels above)."""
    package = Path(gearmesh.__file__).parent
    long_modules, long_functions = {}, {}
    for path in sorted(package.rglob("*.py")):
        text = path.read_text(encoding="utf-8")
        where = path.relative_to(package).as_posix()
        if len(text.splitlines()) > 800:
            long_modules[where] = len(text.splitlines())
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = node.end_lineno - node.lineno + 1
                if length > 80 and f"{where}:{node.name}" not in COMPILED_KERNELS:
                    long_functions[f"{where}:{node.name}"] = length
    assert not long_modules, long_modules
    assert not long_functions, long_functions
