"""The workflow's rules are generated from the stage declarations (gearmesh.plan, issue 37 item 2):
the plan of every shipped study (and tests/plans/*.yaml) is job for job the one recorded from the
hand-written rules (tests/workflow_plan.py says how, and which deliberate changes it carries);
a stage's needs and its reads of sections a study leaves out (issue 37: ``Read.when`` looked at the
raw config)."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
import yaml

from gearmesh import plan
from gearmesh.config import check_study, load_study, validate_study
from gearmesh.errors import GearmeshInputError

sys.path.insert(0, str(Path(__file__).resolve().parent))
import workflow_plan  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
#: The default study without its ltca and signoff sections: the rating still reads the LTCA.
RATING_WITHOUT_LTCA = {k: v for k, v in yaml.safe_load((ROOT / "config/config.yaml").read_text()).items()
                       if k not in ("ltca", "signoff")}


@pytest.mark.workflow
@pytest.mark.parametrize("study", sorted(workflow_plan.studies()))
def test_the_generated_rules_plan_each_study_as_recorded(study):
    pytest.importorskip("snakemake")
    recorded = (workflow_plan.PLANS / f"{study}.json").read_text()
    assert workflow_plan.dumps(workflow_plan.plan(workflow_plan.studies()[study])) == recorded, (
        "the study's jobs differ from tests/plans: if the change is meant, python tests/workflow_plan.py --write")


def test_a_study_that_rates_without_an_ltca_section_is_refused_naming_what_it_needs(root):
    with pytest.raises(GearmeshInputError) as err:
        check_study(validate_study(RATING_WITHOUT_LTCA), root)
    assert err.value.field == "rating"
    assert err.value.rule == "needs a ltca section in the study: the rating stage reads its results"


def test_gearmesh_validate_refuses_it_in_one_line_with_exit_2(root, tmp_path, capsys):
    from gearmesh.cli import main

    path = tmp_path / "rating.yaml"
    path.write_text(yaml.safe_dump({**RATING_WITHOUT_LTCA, "pairs_dir": str(root / "config/pairs")}))
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("gearmesh: error: rating = {") and "needs a ltca section" in err[0]


@pytest.mark.workflow
def test_the_workflow_refuses_it_before_any_job(root, tmp_path, capsys):
    """The Snakefile's own check (check_study): exit 2 with the one line, while Snakemake reads the
    workflow, so no job is planned, let alone run."""
    pytest.importorskip("snakemake")
    path = tmp_path / "rating.yaml"
    path.write_text(yaml.safe_dump({**RATING_WITHOUT_LTCA, "study": "rating_without_ltca"}))
    with pytest.raises(SystemExit) as exit_:
        workflow_plan.plan([str(path)])
    assert exit_.value.code == 2
    assert "gearmesh: error: rating = {" in capsys.readouterr().err
    assert not (root / "results/rating_without_ltca").exists()


def _rule(config, name):
    return next(r for r in plan.rules(config) if r.name == name)


def test_a_section_left_out_is_read_as_its_defaults_and_its_fe_tables_are_made(root):
    """An optimisation without an impact section takes the declared impact model (the FE tooth):
    its job reads the pair's FE tables, and the study makes them, as it does when the impact section
    says method fe. With the slice-model tooth it reads none."""
    base = {"study": "s", "pairs": ["low_fluctuation_pair1"], "stiffness": {"method": "transition"},
            "optimise": {"run": {"population": 4, "generations": 1, "tolerance_statistic": None, "objective": "force",
                                 "torque_Nm": 100}}}
    config = validate_study(base)
    check_study(config, root)
    wildcards = SimpleNamespace(study="s", pair="low_fluctuation_pair1", run="run",
                                items=lambda: {"study": "s", "pair": "low_fluctuation_pair1", "run": "run"}.items())
    inputs = _rule(config, "optimise").input(wildcards)
    assert inputs["fe_compliance"] == "results/s/low_fluctuation_pair1/fe_compliance.nc"
    assert "fe_compliance" in {r.name for r in plan.rules(config)}
    slice_model = validate_study({**base, "impact": {"method": "transition"}})
    assert "fe_compliance" not in _rule(slice_model, "optimise").input(wildcards)
    assert "fe_compliance" not in {r.name for r in plan.rules(slice_model)}


def test_the_targets_are_the_wanted_stages_results_and_tables(root):
    config = load_study(root / "config/config.yaml")
    targets = plan.targets(config)
    assert len(targets) == len(set(targets))
    base = "results/impact_case/helical_z29_71_m5"
    for path in ("geometry.nc", "fe_compliance.nc", "optimised/ltca.nc", "optimise/optimised/ga.nc",
                 "optimise/optimised/plots/pareto.png", "lte_table.nc", "signoff_table.nc", "signoff_verdict.nc",
                 "engagement_table.nc"):
        assert f"{base}/{path}" in targets, path
    assert f"{base}/optimise/design_point/plots/pareto.png" not in targets  # a GA run: no Pareto front
    assert not any("dynamics_comparison" in t or "train" in t for t in targets)
