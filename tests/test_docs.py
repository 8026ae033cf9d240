"""The user-facing documents stay true (issue 18): the README's Python API block runs,
docs/api.md names only functions that exist, CITATION.cff carries the package version,
tests/README.md lists every test file."""

from __future__ import annotations

import importlib
import re

import numpy as np
import pytest
import yaml


def _python_block(text: str, heading: str) -> str:
    """The first ```python block after ``heading``."""
    section = text[text.index(heading):]
    return re.search(r"```python\n(.*?)```", section, flags=re.S).group(1)


def test_readme_python_api_block_runs(root, tmp_path, monkeypatch, capsys):
    code = _python_block((root / "README.md").read_text(encoding="utf-8"), "## Python API")
    assert len(code.strip().splitlines()) <= 12
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md (Python API)", "exec"), {})
    out = capsys.readouterr().out
    assert "eps_alpha 1.452" in out  # 29/71 teeth, m_n 5 mm, 27.5°: εα of the case-study pair
    assert (tmp_path / "te_lte.png").stat().st_size > 10_000


def test_readme_rating_verdict_is_what_its_rating_command_prints(root, capsys, monkeypatch):
    """The verdict line the README quotes is the first line its own ``gearmesh rating`` command
    prints (the command of its command-line block, without ``--json``)."""
    from gearmesh.cli import main

    text = (root / "README.md").read_text(encoding="utf-8")
    command = re.search(r"^gearmesh rating (.*?) --json$", text, flags=re.M).group(1).split()
    quoted = re.search(r"the `rating` command above: `(PASS: .*?)`\)", text, flags=re.S).group(1)
    monkeypatch.chdir(root)
    assert main(["rating", *command]) == 0
    assert capsys.readouterr().out.splitlines()[0] == " ".join(quoted.split())


def test_api_page_names_only_what_exists(root):
    names = set(re.findall(r"`(gearmesh(?:\.\w+)+)\(", (root / "docs/api.md").read_text(encoding="utf-8")))
    assert len(names) >= 30
    for dotted in sorted(names):
        module, _, attr = dotted.rpartition(".")
        assert callable(getattr(importlib.import_module(module), attr)), dotted


def test_citation_carries_the_package_version(root):
    citation = yaml.safe_load((root / "CITATION.cff").read_text(encoding="utf-8"))
    version = re.search(r'^version = "(.+)"', (root / "pyproject.toml").read_text(), flags=re.M).group(1)
    assert citation["version"] == version and citation["license"] == "MIT"
    assert citation["cff-version"] == "1.2.0" and citation["authors"]


@pytest.mark.parametrize("number", ["000", "001", "002", "003", "004"])
def test_references_name_every_source_document_once(root, number):
    text = (root / "docs/references.md").read_text(encoding="utf-8")
    assert len(re.findall(rf"^\| {number} \| ", text, flags=re.M)) == 1


def _markdown_table(text: str, heading: str) -> list[dict[str, str]]:
    """The first Markdown table after ``heading`` as rows of {column: cell}."""
    block = []
    for ln in text[text.index(heading):].splitlines():
        if block and not ln.startswith("|"):
            break  # the table's end: the next table is another's
        if ln.startswith("|"):
            block.append([c.strip() for c in ln.strip("|").split("|")])
    header, rows = block[0], [r for r in block[2:]]
    return [dict(zip(header, r)) for r in rows]


def test_impact_doc_table_is_what_the_impact_stage_computes(root):
    """docs/impact.md's table of the default study's pair (tooth model as its text says) is
    recomputed by the impact stage: a number copied by hand that drifts from the code fails here
    (issue 25). Its columns: F_s closed form and energy balance, v_t, vector v, n, scenario, reduction."""
    from gearmesh.config import load_study
    from gearmesh.datasets.impact import impact_dataset
    from gearmesh.pairfile import example_pair, load_pair, variant_pair

    text = (root / "docs/impact.md").read_text(encoding="utf-8")
    heading = "## Numbers of the default study"
    method = re.search(r"computed\s+with the tooth model `(\w+)`", text[text.index(heading):]).group(1)
    rows = _markdown_table(text, heading)
    study = load_study(root / "config/config.yaml")
    pair = load_pair(example_pair(study["pairs"][0]))
    torques = sorted({float(r["T1 (N·m)"]) for r in rows})
    computed, doubled = {}, {}
    for name in sorted({r["variant"] for r in rows}):
        spec = study["variants"][name]
        ds = impact_dataset(variant_pair(pair, name, spec) if spec else pair, torques_Nm=torques,
                            speeds_rpm=[5000.0, 10000.0], method=method)
        computed[name] = ds.sel(speed=5000.0)
        doubled[name] = ds.impact_force.sel(speed=10000.0) / ds.impact_force.sel(speed=5000.0)
    for row in rows:
        ds = computed[row["variant"]].sel(torque=float(row["T1 (N·m)"]))
        where = f"{row['variant']} at {row['T1 (N·m)']} N·m"
        assert float(row["F_s closed form (N)"]) == pytest.approx(float(ds["impact_force"]), rel=1e-3), where
        assert float(row["F_s energy balance (N)"]) == pytest.approx(float(ds["impact_force_energy_balance"]),
                                                                      rel=1e-3), where
        assert float(row["v_t (m/s)"]) == pytest.approx(float(ds["velocity_transverse"]), abs=1e-3), where
        assert float(row["v, vector form (m/s)"]) == pytest.approx(float(ds["velocity_vector_form"]), abs=1e-3), where
        assert float(row["n"]) == pytest.approx(float(ds["stiffness_exponent"]), abs=0.01), where
        assert row["scenario"] == ("none", "surface", "edge")[int(ds["scenario"])], where
        if row["reduction"] != "—":
            standard = computed["standard"].sel(torque=float(row["T1 (N·m)"]))
            reduction = 100 * (1 - float(ds["impact_force"]) / float(standard["impact_force"]))
            assert float(row["reduction"].rstrip(" %")) == pytest.approx(reduction, abs=1), where
    _impact_doc_prose_is_the_tables_model(text[text.index(heading):], computed, doubled)


def _impact_doc_prose_is_the_tables_model(text: str, computed: dict, doubled: dict) -> None:
    """The numbers of the prose under docs/impact.md's table, each to its printed digits, from the
    same runs as the table: the speed-doubling ratio of F_s and 2^(2n/(n+1)) at 1000 N·m, the relief's
    LTE(φ1A) against TE(φ1A), the standard pair's radius of M and its roll before engagement beside
    the reverse-rotation equation's."""
    from gearmesh.impact import closed_form_force

    def numbers(pattern: str) -> list[float]:
        return [float(v) for v in re.search(pattern, text, flags=re.S).groups()]

    std, rel = computed["standard"], computed["relief"]
    ratio = numbers(r"F_s doubles speed by ([\d.]+) \(standard\) and\s+([\d.]+) \(relief\) against "
                    r"2\^\(2n/\(n\+1\)\) = ([\d.]+) and ([\d.]+)")
    n = [float(computed[v]["stiffness_exponent"].sel(torque=1000.0)) for v in ("standard", "relief")]
    # the closed form at twice the speed over the closed form (F_s ∝ v^(2n/(n+1)): 2^(2n/(n+1)))
    expected = [float(doubled[v].sel(torque=1000.0)) for v in ("standard", "relief")] + [
        float(closed_form_force(1.0, 2.0, 1.0, k) / closed_form_force(1.0, 1.0, 1.0, k)) for k in n]
    np.testing.assert_allclose(ratio, expected, atol=0.005)
    lte = numbers(r"LTE\(φ1A\) ([\d.]+) and ([\d.]+) µm below the entering pair's separation TE\(φ1A\) = ([\d.]+) "
                  r"and\s+([\d.]+) µm \(surface contact\), ([\d.]+) µm above its ([\d.]+) µm")
    um = {k: rel[k].values * 1e6 for k in ("lte_at_engagement", "te_at_engagement")}
    expected = [*um["lte_at_engagement"][:2], *um["te_at_engagement"][:2], um["lte_at_engagement"][2],
                um["te_at_engagement"][2]]
    np.testing.assert_allclose(lte, expected, atol=0.05)
    np.testing.assert_allclose(numbers(r"radius ([\d.]+) →\s+([\d.]+) mm"),
                               std["mesh_in_pinion_radius"].values[[0, -1]] * 1e3, atol=0.005)
    roll = numbers(r"\(([\d.]+), ([\d.]+), ([\d.]+) mm against ([\d.]+), ([\d.]+), ([\d.]+) mm\)")
    np.testing.assert_allclose(roll, np.concatenate([std["roll_before_engagement"].values,
                                                     std["roll_before_engagement_seed_equation"].values]) * 1e3,
                               atol=0.0005)


def test_nothing_shipped_points_into_the_repository(root, capsys):
    """What a pip install carries and shows (the example pair files, the published schemas, every
    command's help) points to the documentation by name or says it in words: no path into a
    checkout (docs/…, tests/…), no source-document or issue number (seed 00x, issue N)."""
    import argparse

    from gearmesh.cli import build_parser

    pointer = re.compile(r"\b(docs|tests)/\S+|\b[Ss]eed 00\d|\b[Ii]ssues? \d+")
    package = root / "src/gearmesh"
    texts = {str(p.relative_to(root)): p.read_text(encoding="utf-8")
             for p in sorted([*package.glob("pairs/*.yaml"), *package.glob("schemas/*")])}
    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    texts["gearmesh --help"] = parser.format_help()
    texts |= {f"gearmesh {name} --help": p.format_help() for name, p in action.choices.items()}
    found = {where: pointer.findall(text) for where, text in texts.items() if pointer.search(text)}
    assert not found, found


def test_source_documents_are_cited_as_papers_everywhere_a_user_reads(root):
    """The README, the docs, the study configs, the workflow and the package's own text (docstrings,
    messages, pair files) name the source documents as papers and the example pairs by what they
    are: no file number of a source document (seed 00x, seed000_case, seed001_pair1, ...)."""
    number = re.compile(r"\b[Ss]eed[ _]?00[0-4]\b|\bseed00\d_\w+")
    files = [root / "README.md", *(root / "docs").rglob("*.md"), *(root / "config").rglob("*.yaml"),
             *(root / "workflow").rglob("*"), *(root / "src/gearmesh").rglob("*.py"),
             *(root / "src/gearmesh").rglob("*.yaml")]
    found = {str(f.relative_to(root)): sorted(set(number.findall(f.read_text(encoding="utf-8"))))
             for f in files if f.is_file() and f.suffix in {".md", ".yaml", ".py", ".smk", ".rst", ""}
             and number.search(f.read_text(encoding="utf-8"))}
    assert not found, found


def test_validation_doc_loaded_contact_rows_are_what_the_ltca_computes(root):
    """docs/validation.md's loaded-contact rows of the default study's pair (standard and relief,
    the study's grid and tooth model) are recomputed here: the LTE mean and peak-to-peak of both tooth
    models (the teeth alone: the study's default body), and the relief's entry (the teeth's LTE at φ1A
    against the entering pair's separation, and the timing the LTCA and lte_table.csv state). A
    number copied by hand that drifts fails."""
    from gearmesh.body import mesh_body_compliance
    from gearmesh.config import load_study
    from gearmesh.datasets.ltca import ltca_dataset
    from gearmesh.gear import pair_geometry
    from gearmesh.pipeline import study_pair

    ours = {q: r["ours"] for q, r in _rows(root, "## TCA / LTCA").items()}
    study = load_study(root / "config/config.yaml")
    grid = {k: study["ltca"][k] for k in ("torques_Nm", "positions", "points")}
    assert grid["torques_Nm"] == [400, 1000, 1600]
    numbers = lambda text: [float(v) for v in re.findall(r"\d+\.\d+", text)]  # noqa: E731
    standard = study_pair(study, study["pairs"][0], "standard")
    assert mesh_body_compliance(pair_geometry(standard)) == 0.0  # "the teeth alone"
    lte = next(text for q, text in ours.items() if q.startswith("LTE mean / p-p, standard"))
    fe, transition = (ltca_dataset(standard, method=method, **grid) for method in ("fe", "transition"))
    printed = numbers(lte)
    for k, ds in enumerate((fe, transition)):
        np.testing.assert_allclose(printed[6 * k:6 * k + 6], np.ravel([ds["lte_mean"].values * 1e6,
                                                                       ds["lte_peak_to_peak"].values * 1e6],
                                                                      order="F"), atol=0.0051)
    assert fe["touches_before_engagement"].values.all()  # "edge contact at every load"
    assert "edge contact at every load" in ours["mesh-in, standard"]
    relief = ltca_dataset(study_pair(study, study["pairs"][0], "relief"), method="fe", **grid)
    text = ours["mesh-in with tip relief"]
    np.testing.assert_allclose(numbers(text)[:3], relief["lte_teeth_at_engagement"].values * 1e6, atol=0.051)
    assert f"separation {float(relief['te_next_pair_at_engagement']) * 1e6:.1f} µm" in text
    entry = ["edge" if early else "surface" for early in relief["touches_before_engagement"].values]
    assert entry == ["surface", "surface", "edge"] and "surface entry at 400 and 1000, edge at 1600" in text


#: Module paths under the package ("/"-joined) whose public functions need no numpydoc sections: the
#: ``python -m gearmesh`` entry point, which only calls the CLI.
NOT_NUMPYDOC = ("__main__",)


def test_every_public_function_has_numpydoc_sections():
    """pvlib's convention for model functions, held for the whole package (physics, stages, workflow,
    command line, figures): a Parameters section (with units) for every public function that takes
    arguments, a Returns section otherwise."""
    import ast
    from pathlib import Path

    import gearmesh

    package = Path(gearmesh.__file__).parent
    missing = []
    for path in sorted(package.rglob("*.py")):
        parts = path.relative_to(package).with_suffix("").parts
        where = "/".join(parts)
        excluded = any(where == n or where.startswith(n + "/") for n in NOT_NUMPYDOC)
        if excluded:
            continue
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.FunctionDef) and not node.name.startswith("_"):
                doc = ast.get_docstring(node) or ""
                takes = node.args.args or node.args.kwonlyargs or node.args.vararg
                if ("Parameters\n" if takes else "Returns\n") not in doc:
                    missing.append(f"{'/'.join(parts)}:{node.name}")
    assert not missing, missing


def test_every_gearmesh_name_in_the_docs_and_docstrings_exists(root):
    """A module, function, class or field the README, docs/ or a docstring names as gearmesh.X.Y
    exists where it is named (code moves; a reference left behind sends the reader nowhere).
    ``gearmesh.module:function`` placeholders (the format of a versioned function) are skipped."""
    import importlib

    import gearmesh

    texts = [root / "README.md", *(root / "docs").glob("*.md"), *(root / "src/gearmesh").rglob("*.py")]
    name = re.compile(r"\bgearmesh\.([a-z_0-9]+(?:\.[A-Za-z_0-9]+)*)(?![:\w])")
    missing = set()
    for path in texts:
        for match in name.finditer(path.read_text(encoding="utf-8")):
            parts = match.group(1).split(".")
            obj, rest = gearmesh, parts
            for i in range(len(parts), 0, -1):
                try:
                    obj, rest = importlib.import_module("gearmesh." + ".".join(parts[:i])), parts[i:]
                    break
                except ImportError:
                    continue
            for attr in rest:
                fields = getattr(obj, "__dataclass_fields__", {})
                if attr in fields:
                    break
                if not hasattr(obj, attr):
                    missing.add(f"{path.relative_to(root)}: gearmesh.{match.group(1)}")
                    break
                obj = getattr(obj, attr)
    assert not missing, sorted(missing)


def test_every_test_file_is_in_the_tests_index_once(root):
    """tests/README.md says where the test for X lives: every test file in it exactly once, and a
    file the index files under "Modules" tests a module that exists (``test_a_b.py`` → ``gearmesh.a.b``)."""
    index = (root / "tests/README.md").read_text(encoding="utf-8")
    listed = re.findall(r"^\| `(test_\w+\.py)` \|", index, flags=re.M)
    files = sorted(p.name for p in (root / "tests").glob("test_*.py"))
    assert sorted(listed) == files, set(listed) ^ set(files)
    modules = index[index.index("## Modules"):index.index("## Contracts")]
    for name, module in re.findall(r"^\| `test_(\w+)\.py` \| `(gearmesh[\w.]*)`", modules, flags=re.M):
        importlib.import_module(module)
        parts = module.split(".")[1:]
        assert name == "_".join(parts), (name, module)


def test_every_gearmesh_name_the_benchmarks_and_scripts_import_exists(root):
    """The benchmarks run only in .ci/run (never imported by pytest), and a name moved in the package
    broke them unseen twice: every ``from gearmesh... import name`` in benchmarks/ and scripts/, at any
    depth (imports inside functions too), names something that exists."""
    import ast
    import importlib.util

    missing = []
    for path in sorted([*(root / "benchmarks").glob("*.py"), *(root / "scripts").glob("**/*.py")]):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").startswith("gearmesh"):
                module = importlib.import_module(node.module)
                missing += [f"{path.name}: {node.module}.{a.name}" for a in node.names
                            if not hasattr(module, a.name) and importlib.util.find_spec(f"{node.module}.{a.name}") is None]
    assert not missing, missing


def _validation(root) -> str:
    return (root / "docs/validation.md").read_text(encoding="utf-8")


def _printed(text: str) -> list[str]:
    """The numbers of a table cell as printed, in order ("−" kept as the sign, "**" ignored)."""
    return [v.replace("−", "-") for v in re.findall(r"−?\d+(?:\.\d+)?", text)]


def _held(printed: str, value: float, where: str) -> None:
    """``value`` is what ``printed`` says, to half a unit of its last printed digit (of its mantissa
    when printed with an exponent: "2.2e-6" to 0.05e-6)."""
    mantissa, _, exponent = printed.lower().partition("e")
    half = 0.5 * 10.0 ** (int(exponent or 0) - len(mantissa.partition(".")[2]))
    assert float(printed) == pytest.approx(float(value), abs=half), (where, printed, float(value))


def _rows(root, heading: str, key: str = "quantity") -> dict[str, dict[str, str]]:
    """docs/validation.md's first table after ``heading``, its rows by their ``key`` column."""
    return {r[key]: r for r in _markdown_table(_validation(root), heading)}


def _study_pairs(study, names) -> dict:
    from gearmesh.pipeline import study_pair

    return {name: study_pair(study, name, None) for name in names}


def test_validation_doc_geometry_table_is_what_gearmesh_computes(root, capsys, monkeypatch):
    """docs/validation.md's "Geometry and contact lines" table, our column and the numbers its "why
    different" column argues with, to their printed digits: the contact ratios, masses and inertias
    of the ``gearmesh geometry`` command its "where" names, the integer-overlap designs of the
    low_fluctuation study, the ε_l minima of the contact_lines study's helix sweep (the local minima
    where ε_β is near an integer) and ε_β at the near-1 one, the default pair's standard centre
    distance and base radii, the transition-curve pair's ε_α and the addendum coefficient at which
    its pinion turns pointed (accepted half a printed unit below, refused above)."""
    import json

    from gearmesh.cli import main
    from gearmesh.config import load_study
    from gearmesh.datasets.geometry import helix_sweep_dataset, low_fluctuation_design_dataset
    from gearmesh.errors import GearmeshInputError
    from gearmesh.gear import pair_geometry
    from gearmesh.pairfile import load_pair, pair_to_dict

    rows = _rows(root, "## Geometry and contact lines")
    monkeypatch.chdir(root)

    def geometry(path: str) -> dict:
        assert main(["geometry", path, "--json"]) == 0
        return json.loads(capsys.readouterr().out)

    def ours(quantity: str) -> list[str]:
        return _printed(rows[quantity]["ours"])

    command = rows["εα, εβ of pair 1"]["where"].strip("`").split()
    assert command[:2] == ["gearmesh", "geometry"] and rows["masses pinion/gear"]["where"] == "same"
    pair1 = geometry(command[2])
    computed = {"εα, εβ of pair 1": [pair1["eps_alpha"], pair1["eps_beta"]],
                "masses pinion/gear": pair1["mass_kg"],
                "inertias pinion/gear": np.multiply(pair1["inertia_kg_m2"], 1e4)}  # printed ×10⁻⁴ kg m²
    for quantity, values in computed.items():
        assert len(ours(quantity)) >= len(values), quantity
        for printed, value in zip(ours(quantity), values):
            _held(printed, value, quantity)
    # the low_fluctuation study's integer-overlap designs (low_fluctuation_design.csv)
    study = load_study(root / "config/studies/low_fluctuation.yaml")
    section = study["low_fluctuation_design"]
    design = low_fluctuation_design_dataset(_study_pairs(study, section["pairs"]), **section)
    beta, width = ours("integer-εβ design, pair 1: β / b")
    _held(beta, design.helix_angle_deg.sel(pair="low_fluctuation_pair1", design="helix_angle_forward"), "β")
    _held(width, design.face_width.sel(pair="low_fluctuation_pair1", design="face_width_forward") * 1e3, "b")
    _held(ours("pair 4 backward design β")[0],
          design.helix_angle_deg.sel(pair="low_fluctuation_pair4", design="helix_angle_backward"), "pair 4 β")
    # the contact_lines study's helix sweep (helix_sweep.nc): input pair, then output pair
    study = load_study(root / "config/studies/contact_lines.yaml")
    section = study["helix_sweep"]
    sweep = helix_sweep_dataset(_study_pairs(study, section["pairs"]), **section)
    minima = []
    for name in section["pairs"]:
        eps_l, eps_beta = (sweep[v].sel(pair=name).values for v in ("length_fluctuation", "eps_beta"))
        minima += [(float(sweep.helix_angle_deg[i]), eps_beta[i]) for i in range(1, eps_l.size - 1)
                   if eps_l[i] <= min(eps_l[i - 1], eps_l[i + 1]) and abs(eps_beta[i] - round(eps_beta[i])) < 0.05]
    printed = ours("ε_l V-curve minima")
    assert len(printed) == len(minima) == 3, minima
    for p, (angle, _) in zip(printed, minima):
        _held(p, angle, "ε_l minimum")
    why = rows["ε_l V-curve minima"]["why different"]
    assert f"{float(printed[1]):g}°" in why  # "15.25° is the minimum on our 0.25° grid near εβ = 1 (0.993)"
    _held(re.search(r"near εβ = 1 \(([\d.]+)\)", why).group(1), minima[1][1], "εβ at the minimum")
    # the default pair: standard centre distance, and the base radii that rule out the paper's 261.0 mm
    row = rows["centre distance, the mesh-in impact paper's pair"]
    default = geometry(re.search(r"`(config/pairs/\S+\.yaml)`", row["where"]).group(1))
    _held(ours("centre distance, the mesh-in impact paper's pair")[0], default["center_distance_mm"], "a")
    _held(re.search(r"base radii alone sum to ([\d.]+) mm", row["why different"]).group(1),
          sum(default["base_radius_mm"]), "r_b1 + r_b2")
    # the transition-curve pair as shipped, and the addendum at which its pinion turns pointed
    quantity = "εα of the transition-curve paper's pair"
    shipped = geometry("config/pairs/transition_curve_z23_62.yaml")
    _held(ours(quantity)[0], shipped["eps_alpha"], quantity)
    printed = re.search(r"pointed at ha ≈ ([\d.]+)", rows[quantity]["why different"]).group(1)
    data = pair_to_dict(load_pair("config/pairs/transition_curve_z23_62.yaml"))
    half = 0.5 * 10.0 ** -len(printed.partition(".")[2])
    pair_geometry(load_pair({**data, "addendum_coefficient": float(printed) - half}))
    with pytest.raises(GearmeshInputError, match="pinion tooth pointed"):
        pair_geometry(load_pair({**data, "addendum_coefficient": float(printed) + half}))


def _stiffness_rows(root) -> dict[str, list[str]]:
    """docs/validation.md's "Mesh stiffness (N/µm)" table: quantity -> the numbers of our column."""
    return {q: _printed(r["ours"]) for q, r in _rows(root, "## Mesh stiffness (N/µm)").items()}


def _stiffness_table(root, name: str):
    """The stiffness_table.nc of study ``name`` (config/studies/NAME.yaml), as its stage computes it."""
    from gearmesh.config import load_study
    from gearmesh.datasets.stiffness import stiffness_table_dataset

    study = load_study(root / f"config/studies/{name}.yaml")
    section = study["stiffness_table"]
    return study, stiffness_table_dataset(_study_pairs(study, section["pairs"]), **section)


def test_validation_doc_printing_train_stiffness_rows_are_what_its_study_computes(root, monkeypatch):
    """docs/validation.md's mesh-stiffness rows of the printing_train study, to their printed digits:
    the 88-tooth pair's mean K by the traditional, improved and transition models and ISO 6336-1's
    (stiffness_table.nc) with the E/E_st it scales by, and the slice convergence of the improved model
    (slice_convergence.nc: whole slices at the fewest, clipped at the most, and the clipped mean's
    relative difference at the N the "why different" column names)."""
    from gearmesh.datasets.stiffness import DEFAULT_RULE, slice_convergence_dataset
    from gearmesh.limits import ISO6336_STEEL_MODULUS

    monkeypatch.chdir(root)
    rows = _stiffness_rows(root)
    study, table = _stiffness_table(root, "printing_train")
    k = table.sel(case="printing_train_z88") * 1e-6
    printed = rows["the improved potential-energy paper gear: traditional < improved < transition?"]
    for p, value in zip(printed, [*k.mean_stiffness.sel(model=["traditional", "improved", "transition"]).values,
                                  k.iso6336_mesh_stiffness.sel(model="improved")]):
        _held(p, value, "printing_train_z88 mean K")
    modulus = _study_pairs(study, ["printing_train_z88"])["printing_train_z88"].material.youngs_modulus
    _held(printed[4], modulus * 1e-9, "E (GPa)")
    _held(printed[5], ISO6336_STEEL_MODULUS * 1e-9, "E_st (GPa)")
    section = study["slice_convergence"]
    ds = slice_convergence_dataset(_study_pairs(study, section["pairs"]), **section).isel(pair=0)
    whole, _, clipped, _ = rows["slice convergence (improved, mean)"]
    _held(whole, ds.mean_stiffness.sel(rule="centre").isel(slices=0) * 1e-6, "whole slices")
    _held(clipped, ds.mean_stiffness.sel(rule=DEFAULT_RULE).isel(slices=-1) * 1e-6, "clipped slices")
    assert rows["slice convergence (improved, mean)"][1::2] == [str(ds.slices.values[0]), str(ds.slices.values[-1])]
    why = _rows(root, "## Mesh stiffness (N/µm)")["slice convergence (improved, mean)"]["why different"]
    difference, n = re.search(r"(\d+e-\d+) at N = (\d+)", why).groups()
    _held(difference, abs(float(ds.mean_relative_difference.sel(rule=DEFAULT_RULE, slices=int(n)))), "slices")


def test_validation_doc_transition_curve_stiffness_rows_are_what_its_study_computes(root, monkeypatch):
    """docs/validation.md's mesh-stiffness rows of the transition_curve study (stiffness_table.nc), to
    their printed digits: the pair as given by the three cantilevers and ISO 6336-1, the transition
    model's mean K at each pressure angle, and its LSTE peak-to-peak at the contact ratios the row
    names, the first the worst of the contact-ratio variants."""
    monkeypatch.chdir(root)
    rows = _stiffness_rows(root)
    _, table = _stiffness_table(root, "transition_curve")
    k = table[["mean_stiffness", "iso6336_mesh_stiffness"]] * 1e-6
    given = k.sel(case="transition_curve_z23_62-as_given")
    for p, value in zip(rows["the transition-curve paper as given (transition)"],
                        [*given.mean_stiffness.sel(model=["transition", "traditional", "improved"]).values,
                         given.iso6336_mesh_stiffness.sel(model="transition")]):
        _held(p, value, "as given")
    quantity = next(q for q in rows if q.startswith("pressure angle "))
    for angle, p in zip(re.findall(r"\d+", quantity), rows[quantity]):
        _held(p, k.mean_stiffness.sel(case=f"transition_curve_z23_62-alpha_{angle}", model="transition"), quantity)
    p2p = table.lste_peak_to_peak.sel(model="transition") * 1e6
    printed = rows["TE p-p at half-integer εγ"]  # (εα,εβ) value, twice
    for eps_alpha, eps_beta, value in zip(printed[0::3], printed[1::3], printed[2::3]):
        _held(value, p2p.sel(case=f"transition_curve_z23_62-ratios_{eps_alpha}_{eps_beta}"), "TE p-p")
    ratios = p2p.sel(case=[c for c in p2p.case.values if "-ratios_" in c])
    assert str(ratios.idxmax().values).endswith(f"ratios_{printed[0]}_{printed[1]}")  # "worst"


def test_validation_doc_low_fluctuation_stiffness_rows_are_what_its_study_computes(root, monkeypatch):
    """docs/validation.md's mesh-stiffness rows of the low_fluctuation study, to their printed digits:
    pairs 1–4's mean K and ε_k and the LSTE F/K (mean, and peak-to-peak of pair 1) of stiffness_table.nc,
    the study's linear TVMS with its Hertz term; beside them the LTCA's LTE mean (and pair 1's
    peak-to-peak) at the study's LTCA torque."""
    from gearmesh.datasets.ltca import ltca_dataset

    monkeypatch.chdir(root)
    rows = _stiffness_rows(root)
    study, table = _stiffness_table(root, "low_fluctuation")
    names = list(table.case.values)
    assert names == [f"low_fluctuation_pair{i}" for i in (1, 2, 3, 4)]
    t = table.sel(model="transition")
    for quantity, values in (("the low-fluctuation paper's pairs 1–4, mean K", t.mean_stiffness * 1e-6),
                             ("ε_k pairs 1–4", t.fluctuation * 100)):
        assert len(rows[quantity]) == 4, quantity
        for p, value in zip(rows[quantity], values.values):
            _held(p, value, quantity)
    pairs = _study_pairs(study, names)
    lte = {n: ltca_dataset(pairs[n], **study["ltca"]).isel(torque=0) for n in names}
    f_over_k, p2p, mean, ltca_p2p = rows["LSTE pair 1 at 200 N·m (mean / p-p µm)"]
    first = names[0]
    for p, value in ((f_over_k, t.lste_mean.sel(case=first) * 1e6), (p2p, t.lste_peak_to_peak.sel(case=first) * 1e6),
                     (mean, lte[first].lte_mean * 1e6), (ltca_p2p, lte[first].lte_peak_to_peak * 1e6)):
        _held(p, value, first)
    printed = rows["LSTE pairs 2–4, F/K vs LTCA (mean µm)"]
    assert len(printed) == 6
    for name, p, q in zip(names[1:], printed[0::2], printed[1::2]):
        _held(p, t.lste_mean.sel(case=name) * 1e6, name)
        _held(q, lte[name].lte_mean * 1e6, name)


#: docs/validation.md's FE-tooth row: the name of each pair it quotes, as its cell names it.
_TOOTH_MODEL_PAIRS = {"the mesh-in impact paper": "helical_z29_71_m5",
                      "the low-fluctuation paper's pair 1": "low_fluctuation_pair1",
                      "the transition-curve paper": "transition_curve_z23_62",
                      "the improved potential-energy paper": "printing_train_z88"}


@pytest.mark.slow
@pytest.mark.parametrize("name", _TOOTH_MODEL_PAIRS.values())
def test_validation_doc_tooth_model_row_is_what_stiffness_methods_computes(root, monkeypatch, name):
    """docs/validation.md's "FE tooth" row, to its printed digits: the mean mesh stiffness of the
    four tooth models (traditional / improved / transition / fe) of each pair it quotes, as the
    stiffness_methods study's stiffness_table computes them (its grid, the pair as shipped: the teeth
    alone), and for the default pair also with solid-disc bodies described (hub = bore, as
    tests/test_body.py's ``_solid_discs``), their compliance in series at every position. One pair
    per test: the FE tooth tables take 1–2 s a pair."""
    from test_body import _solid_discs

    from gearmesh.config import load_study
    from gearmesh.datasets.stiffness import stiffness_table_dataset
    from gearmesh.gear import pair_geometry
    from gearmesh.stiffness import mesh_stiffness

    monkeypatch.chdir(root)
    text = next(r["ours"] for q, r in _rows(root, "## Mesh stiffness (N/µm)").items()
                if q.startswith("FE tooth (our own check of the PEMs)"))
    cells = {}
    for part in re.split(r"; (?=the )", text):  # one part per pair, each opening with its name
        label = next(lab for lab in sorted(_TOOTH_MODEL_PAIRS, key=len, reverse=True) if part.startswith(lab))
        cells[_TOOTH_MODEL_PAIRS[label]] = _printed(part[len(label):])
    assert list(cells) == list(_TOOTH_MODEL_PAIRS.values())
    study = load_study(root / "config/studies/stiffness_methods.yaml")
    section = {**study["stiffness_table"], "pairs": [name]}
    methods = section["methods"]
    assert methods == ["traditional", "improved", "transition", "fe"]
    table = stiffness_table_dataset(_study_pairs(study, [name]), **section)
    printed = cells[name]
    assert len(printed) == (8 if name == "helical_z29_71_m5" else 4), printed
    for p, value in zip(printed[:4], table.mean_stiffness.sel(case=name, model=methods).values * 1e-6):
        _held(p, value, name)
    if len(printed) == 8:  # "with its default solid-disc bodies in series"
        geom = pair_geometry(_solid_discs(name))
        for p, method in zip(printed[4:], methods):
            k = mesh_stiffness(geom, n_positions=section["positions"], n_slices=section["slices"], method=method,
                               components=False)
            _held(p, k.mean * 1e-6, f"{name} with solid discs, {method}")


#: docs/validation.md's body-compliance table: row label -> the pairs its " / "-separated cells are of.
_BODY_ROWS = {"helical_z29_71_m5 (default)": ["helical_z29_71_m5"],
              "printing_train_z88": ["printing_train_z88"],
              "low_fluctuation_pair1 / 2 / 3 / 4": [f"low_fluctuation_pair{i}" for i in (1, 2, 3, 4)],
              "contact_lines_input_z29_36 / output": ["contact_lines_input_z29_36", "contact_lines_output_z15_65"],
              "transition_curve_z23_62": ["transition_curve_z23_62"]}


def test_validation_doc_body_compliance_table_is_what_gearmesh_body_computes(root):
    """docs/validation.md's gear-body table, to its printed digits: the plate compliance c_body of
    both gears as solid discs held at the bore (``gearmesh.body.mesh_body_compliance`` of
    tests/test_body.py's ``_solid_discs``), and the columns it makes with the 3-D reference's
    stiffnesses, which are taken from the "Verdict" table (the 3-D reference under the transverse
    and the flank-normal load, minutes of FE each, not recomputed here): the 3-D normal − transverse
    compliance, plate / 3-D, the 3-D transverse stiffness with the plate in series and its excess over
    the 3-D normal-load stiffness."""
    from test_body import _solid_discs

    from gearmesh.body import mesh_body_compliance
    from gearmesh.gear import pair_geometry

    text = _validation(root)
    verdict = {r["pair"]: r for r in _markdown_table(text, "### Verdict")}
    rows = _markdown_table(text, "| pair | c_body plate (µm/kN) |")
    assert [r["pair"] for r in rows] == list(_BODY_ROWS)

    def cells(row, column):
        return row[column].split(" / ")

    for row in rows:
        names = _BODY_ROWS[row["pair"]]
        c_body = [mesh_body_compliance(pair_geometry(_solid_discs(n))) * 1e9 for n in names]  # µm/kN
        k_3d = [float(verdict[n]["3-D reference"].strip("*")) for n in names]  # N/µm
        k_normal = [float(verdict[n]["3-D, normal load"]) for n in names]
        difference = [1e3 * (1 / kn - 1 / k) for kn, k in zip(k_normal, k_3d)]  # µm/kN
        series = [1 / (1 / k + 1e-3 * c) for k, c in zip(k_3d, c_body)]
        for column, values in (("c_body plate (µm/kN)", c_body), ("3-D normal − transverse (µm/kN)", difference),
                               ("3-D transverse + plate body (N/µm)", series)):
            assert len(cells(row, column)) == len(names), (row["pair"], column)
            for p, value in zip(cells(row, column), values):
                _held(p, value, f"{row['pair']}: {column}")
        ratio = [c / d for c, d in zip(c_body, difference)]
        printed = _printed(row["plate / 3-D"])
        if "–" in row["plate / 3-D"]:  # a range over the row's pairs
            ratio = [min(ratio), max(ratio)]
        for p, value in zip(printed, ratio, strict=True):
            _held(p, value, f"{row['pair']}: plate / 3-D")
        normal = row["3-D normal load (N/µm)"]
        assert _printed(normal.split(" (")[0]) == [f"{k:g}" for k in k_normal], row["pair"]
        if "%" in normal:
            excess = re.search(r"\(([+−]?[\d.]+) %\)", normal).group(1).replace("−", "-")
            _held(excess, 100 * (series[0] / k_normal[0] - 1), f"{row['pair']}: excess")


@pytest.mark.slow
def test_validation_doc_dynamics_rows_are_what_the_studies_compute(root, monkeypatch):
    """docs/validation.md's "## Dynamics" rows of the low_fluctuation and printing_train studies, to
    their printed digits: the largest relative difference of the mean mesh force from the static one
    over every pair and speed of the low_fluctuation sweep (dynamics.nc, the LTCA-excited pair with the
    stiffness stage beside it, as the workflow passes them); pairs 2 and 3 against pair 1
    (dynamics_comparison.nc: the mean change of the mesh-deflection std, and the range of the mean
    change of the gears' vibration velocity RMS); the printing train's mean mesh force in both meshes,
    its range over the mesh cycle, the mesh force's amplitudes at mesh orders 1–3 and its idle blanket
    (train.nc)."""
    from gearmesh.config import load_study
    from gearmesh.datasets.dynamics import dynamics_comparison_dataset, dynamics_dataset, train_dataset
    from gearmesh.datasets.ltca import ltca_dataset
    from gearmesh.datasets.stiffness import stiffness_dataset

    monkeypatch.chdir(root)
    rows = {q: r["ours"] for q, r in _rows(root, "## Dynamics\n").items()}
    study = load_study(root / "config/studies/low_fluctuation.yaml")
    dynamics = []
    for name, pair in _study_pairs(study, study["pairs"]).items():
        ds = dynamics_dataset(pair, stiffness=stiffness_dataset(pair, **study["stiffness"]),
                              ltca=ltca_dataset(pair, **study["ltca"]), **study["dynamics"])
        dynamics.append(ds.assign_attrs(pair_name=name))
    residual = max(float(np.abs(d.mesh_force_mean / d.static_mesh_force - 1).max()) for d in dynamics)
    printed = re.fullmatch(r"equal to (\d\.\de-\d+) at every speed", rows["mean mesh force"]).group(1)
    _held(printed, residual, "mean mesh force against the static one")
    comparison = dynamics_comparison_dataset(dynamics, **study["dynamics_comparison"])
    against_1 = [c for c in comparison.couple.values if c.split(" vs ")[0][-1] in "23" and c.endswith("pair1")]
    assert len(against_1) == 2
    dte, fast, slow = _printed(rows["pairs 2, 3 vs 1: DTE std"])
    for c in against_1:
        _held(dte, 100 * comparison.mesh_deflection_std_change_mean.sel(couple=c), c)
    velocity = 100 * comparison.velocity_change_mean.sel(couple=against_1)
    _held(fast, velocity.max(), "smallest vibration reduction")
    _held(slow, velocity.min(), "largest vibration reduction")
    # the printing train
    study = load_study(root / "config/studies/printing_train.yaml")
    pair = _study_pairs(study, study["pairs"])[study["pairs"][0]]
    train = train_dataset(pair, stiffness=stiffness_dataset(pair, **study["stiffness"]),
                          **study["train_dynamics"]).isel(speed=0)
    printed = rows["the improved potential-energy paper train: mean mesh forces"]
    assert "both meshes" in printed
    mean, low, high = _printed(printed)
    for value in train.mesh_force_mean.values:
        _held(mean, value, "train mean mesh force")
    for p, values in ((low, train.mesh_force_min), (high, train.mesh_force_max)):
        for value in values.values:
            _held(p, value, "train mesh force range")
    orders = _printed(rows["the improved potential-energy paper: 249.4 Hz dominates"].split(":", 1)[1])
    spectrum = train.mesh_force_spectrum.isel(sample_speed=0)
    assert len(orders) == 3
    for order, p in zip((1.0, 2.0, 3.0), orders):
        for value in spectrum.sel(order=order).values:
            _held(p, value, f"train mesh force at order {order:g}")
    assert "blanket motionless" in rows["the improved potential-energy paper: blanket has the largest axial vibration"]
    rms = train.displacement_rms
    assert float(rms.sel(gear="blanket").max()) < 1e-9 * float(rms.sel(gear="plate").max())



@pytest.mark.slow
def test_validation_doc_dynamics_command_row_is_what_it_prints(root, capsys, monkeypatch):
    """docs/validation.md's command row under "## Dynamics": its ``gearmesh dynamics`` command, run as
    printed, gives the dynamic TE mean the row states at each of its speeds, and ``gearmesh ltca`` of the
    same pair, torque and gear (the command without its dynamics options) the LTE mean the row sets it
    against, to their printed digits; both with the tooth model the row names."""
    import json
    import shlex

    from gearmesh.cli import main

    monkeypatch.chdir(root)
    row = next(r for q, r in _rows(root, "## Dynamics\n").items() if q.startswith("`gearmesh dynamics"))
    command = shlex.split(re.match(r"`gearmesh (.*?)`", row["quantity"]).group(1))
    assert main([*command, "--json"]) == 0
    dynamics = json.loads(capsys.readouterr().out)
    ltca_command = [c for k, c in enumerate(command) if c not in ("--excitation", "--speeds")
                    and (k == 0 or command[k - 1] not in ("--excitation", "--speeds"))]
    ltca_command[0] = "ltca"
    assert main([*ltca_command, "--json"]) == 0
    ltca = json.loads(capsys.readouterr().out)
    model = re.search(r"tooth model `(\w+)`", row["source"]).group(1)
    assert ltca["tooth_model"] == dynamics["tooth_model"] == model
    _held(_printed(row["source"].split("lte_mean_um")[1])[0], ltca["lte_mean_um"], "ltca lte_mean_um")
    mean, *speeds = _printed(row["ours"])
    assert [float(s) for s in speeds] == [s["speed_rpm"] for s in dynamics["speeds"]]
    for s in dynamics["speeds"]:
        _held(mean, s["dynamic_te_mean_um"], f"dynamic TE mean at {s['speed_rpm']:g} rpm")

#: docs/validation.md's K_v table, row label -> (output of scripts/dynamics_iso.py: default or
#: solid-disc bodies, its model key).
_KV_ROWS = {"model, rigid supports, `contact`": ("", "rigid / contact"),
            "model, rigid supports, `tvms`": ("", "rigid / tvms"),
            "model, the pair file's supports, `contact`": ("", "pair file / contact"),
            "model, the pair file's supports, `tvms`": ("", "pair file / tvms"),
            "model, the low-fluctuation paper's bearings, `contact`": ("", "the low-fluctuation paper / contact"),
            "solid-disc bodies, rigid supports, `contact`": ("_web42.0", "rigid / contact"),
            "solid-disc bodies, the pair file's supports, `contact`": ("_web42.0", "pair file / contact"),
            "solid-disc bodies, the pair file's supports, `tvms`": ("_web42.0", "pair file / tvms")}


@pytest.fixture(scope="module")
def dynamics_iso(tmp_path_factory) -> dict:
    """scripts/dynamics_iso.py's two outputs, by file suffix: "" the teeth alone, "_web42.0" with
    solid-disc bodies (``--web-thickness-mm 42``); run once for the tests of the tables it makes,
    without the tip-relief cases (``--relief-um 0``), which no table holds."""
    import json
    import subprocess
    import sys
    from pathlib import Path

    root, out = Path(__file__).resolve().parents[1], tmp_path_factory.mktemp("dynamics_iso")
    for extra in ([], ["--web-thickness-mm", "42"]):
        subprocess.run([sys.executable, str(root / "scripts/dynamics_iso.py"), "--out", str(out), "--relief-um", "0",
                        *extra],
                       cwd=root, check=True, capture_output=True, timeout=600)
    return {suffix: json.loads((out / f"helical_z29_71_m5{suffix}.json").read_text())
            for suffix in ("", "_web42.0")}


@pytest.mark.slow
@pytest.mark.workflow  # the script runs as a Python process of its own
def test_validation_doc_dynamic_factor_table_is_what_its_script_computes(root, dynamics_iso):
    """docs/validation.md's K_v table ("Dynamics against ISO 6336-1") is what the script it names
    prints, to its printed digits: ISO's K_v and the model's dynamic factor at each speed column, the
    peak and its speed, for every row (the teeth alone, and with solid-disc bodies); and so is the
    resonance table above it (mean mesh stiffness, rigid-support mesh mode, ISO's n_E1)."""
    out = dynamics_iso
    text = _validation(root)
    rows = _rows(root, "| r/min | 1000 | 3000 |", key="r/min")
    columns = [c for c in rows["ISO method B, K_v"] if c.isdigit()]
    speeds = out[""]["speeds_rpm"]
    iso = out[""]["iso"]["K_v_perfect"]
    for c in columns:
        assert float(rows["ISO method B, K_v"][c]) == pytest.approx(iso[speeds.index(float(c))], abs=5e-4), c
    assert float(rows["ISO method B, K_v"]["peak (r/min)"].split()[0]) == pytest.approx(max(iso), abs=5e-4)
    for label, (suffix, key) in _KV_ROWS.items():
        row, model = rows[label], out[suffix]["model"][key]
        for c in columns:
            assert float(row[c]) == pytest.approx(model["dynamic_factor_on_grid"][speeds.index(float(c))],
                                                  abs=5e-4), (label, c)
        peak, at = row["peak (r/min)"].replace("(", "").replace(")", "").split()
        assert float(peak) == pytest.approx(model["peak_dynamic_factor"], abs=5e-4), label
        assert float(at) == pytest.approx(model["peak_speed_rpm"], abs=0.5), label
    # the resonance table above it: mean mesh stiffness and rigid-support mesh mode of each excitation
    modes = {r["excitation"]: r for r in _markdown_table(text, "| excitation | mean mesh stiffness (N/µm) |")}
    assert float(modes["ISO 6336-1 c_γα·b"]["rigid-support resonance (r/min)"]) == pytest.approx(
        out[""]["iso"]["n_E1_rpm"], abs=0.5)
    for label, cases in (("`contact` (LTCA tangent at 1000 N·m)", [("", "rigid / contact")]),
                         ("`tvms` (the same law's tangent, and the tips' loaded contact beyond the active zone)",
                          [("", "rigid / tvms")]),
                         ("solid-disc bodies in series: `contact` / `tvms`",
                          [("_web42.0", "rigid / contact"), ("_web42.0", "rigid / tvms")])):
        row = modes[label]
        stiffness = [float(v) for v in row["mean mesh stiffness (N/µm)"].split(" / ")]
        resonance = [float(v) for v in row["rigid-support resonance (r/min)"].split(" / ")]
        for k, (suffix, key) in enumerate(cases):
            model = out[suffix]["model"][key]
            assert stiffness[k] == pytest.approx(model["mesh_stiffness_transverse_N_per_um"], abs=0.05), label
            assert resonance[k] == pytest.approx(model["mesh_mode_rpm"], abs=0.5), label


@pytest.mark.slow
@pytest.mark.workflow  # the script runs as a Python process of its own
def test_validation_doc_before_and_after_table_is_what_its_script_computes(root, monkeypatch, dynamics_iso):
    """docs/validation.md's "Before and after" table, the columns of today's code (the teeth alone, and
    solid-disc bodies described), to its printed digits: the mean mesh stiffness of ``tvms`` and
    ``contact``, the mesh modes with the pair's and rigid supports and how far apart they are, ISO's
    n_E1, the peak dynamic factors and their speeds (scripts/dynamics_iso.py, the script of the tables
    above it), the stiffness stage's linear TVMS of the default study and the loaded tip contact
    ``tvms`` adds to it. The 3-D + Weber row is the "Weber" table's (3-D reference, not recomputed).
    The c61da5b column is history."""
    from gearmesh.config import load_study
    from gearmesh.datasets.stiffness import stiffness_dataset

    text = _validation(root)
    rows = {}
    for row in _markdown_table(text, "| | c61da5b |"):
        label, _, *columns = row.values()  # the c61da5b column is history
        rows[label] = [c.replace("**", "") for c in columns]
    rigid = next(q for q in rows if q.startswith("rigid supports `tvms` / `contact`"))  # "(n_E1 4851)"
    model = {"": dynamics_iso[""]["model"], "_web42.0": dynamics_iso["_web42.0"]["model"]}
    for k, suffix in enumerate(model):  # the teeth alone, solid discs
        m = model[suffix]
        where = suffix or "teeth alone"
        _held(_printed(rows["mean mesh stiffness `tvms` (N/µm)"][k])[0],
              m["rigid / tvms"]["mesh_stiffness_transverse_N_per_um"], where)
        _held(_printed(rows["LTCA tangent = `contact` (N/µm)"][k])[0],
              m["rigid / contact"]["mesh_stiffness_transverse_N_per_um"], where)
        for label, supports in (("mesh mode `tvms` / `contact`, pair's supports (r/min)", "pair file"),
                                (rigid, "rigid")):
            printed = _printed(rows[label][k])
            tvms, contact = (m[f"{supports} / {e}"]["mesh_mode_rpm"] for e in ("tvms", "contact"))
            _held(printed[0], tvms, (label, where))
            _held(printed[1], contact, (label, where))
            if len(printed) == 3:  # how far apart, %
                _held(printed[2], 100 * (tvms / contact - 1), (label, where))
        contact = _printed(rows["peak dynamic factor `contact`, pair's supports"][k])
        _held(contact[0], m["pair file / contact"]["peak_dynamic_factor"], where)
        _held(contact[1], m["pair file / contact"]["peak_speed_rpm"], where)
        tvms = _printed(rows["peak dynamic factor `tvms`, rigid / pair's supports"][k])
        for (factor, speed), supports in zip((tvms[:2], tvms[2:]), ("rigid", "pair file")):
            _held(factor, m[f"{supports} / tvms"]["peak_dynamic_factor"], where)
            _held(speed, m[f"{supports} / tvms"]["peak_speed_rpm"], where)
    n_e1 = re.search(r"n_E1 (\d+)", rigid).group(1)
    _held(n_e1, dynamics_iso[""]["iso"]["n_E1_rpm"], "n_E1")
    # solid discs: the peak is not the mesh mode; the dynamic factor at 7000 r/min beside it
    factor, at = re.search(r"([\d.]+) at (\d+)\)", rows["peak dynamic factor `contact`, pair's supports"][1]).groups()
    speeds = dynamics_iso["_web42.0"]["speeds_rpm"]
    _held(factor, model["_web42.0"]["pair file / contact"]["dynamic_factor_on_grid"][speeds.index(float(at))], "at")
    # the teeth's tvms: the stiffness stage's linear TVMS plus the loaded tip contact
    monkeypatch.chdir(root)
    study = load_study(root / "config/config.yaml")
    pair = _study_pairs(study, study["pairs"][:1])[study["pairs"][0]]
    linear = float(stiffness_dataset(pair, **study["stiffness"]).mesh_stiffness.mean()) * 1e-6
    _, stage, extension = _printed(rows["mean mesh stiffness `tvms` (N/µm)"][0])
    _held(stage, linear, "linear TVMS of the stiffness stage")
    _held(extension, model[""]["rigid / tvms"]["mesh_stiffness_transverse_N_per_um"] - linear, "loaded tip contact")
    # the 3-D reference's row is the Weber table's
    weber = next(r for r in _markdown_table(text, "| pair | Weber / Yang–Sun |") if r["pair"] == "helical_z29_71_m5")
    for cell in rows["3-D + Weber, transverse / normal load (N/µm)"]:
        assert cell == f"{weber['3-D + Weber']} / {weber['3-D normal load + Weber']}"
