"""The stage declarations (gearmesh.settings STAGE, gearmesh.stages): what the workflow's rules,
targets and upstream checks derive from is itself consistent."""

from __future__ import annotations

import re

import pytest

from gearmesh.config import study_excitation
from gearmesh.settings import stage_of, stages
from gearmesh.stages import Read, Stage, dependencies, ltca_drives, method_fe

#: The wildcards of a result's path by the stage's scope.
WILDCARDS = {"study": set(), "pair": {"pair"}, "variant": {"pair", "variant"}, "run": {"pair", "run"}}


@pytest.mark.parametrize("section", sorted(stages()))
def test_a_stage_writes_one_file_under_the_wildcards_of_its_scope(section):
    stage = stage_of(section)
    assert set(re.findall(r"{(\w+)}", stage.writes)) == WILDCARDS[stage.scope]
    assert stage.writes.endswith(".nc")
    assert stage.path(study="s", pair="p", variant="v", run="r").startswith("results/s/")


def test_no_two_stages_write_the_same_file_and_every_read_is_a_stage():
    declared = stages()
    paths = [s.writes for s in declared.values()]
    assert len(paths) == len(set(paths))
    for section, stage in declared.items():
        for read in stage.reads:
            assert read.stage in declared and read.stage != section, (section, read.stage)
            upstream = declared[read.stage]
            # a result of the job's own pair (and variant): never of a finer scope than the reader's
            assert WILDCARDS[upstream.scope] <= WILDCARDS[stage.scope] | ({"variant"} if read.every_variant else set())


@pytest.mark.parametrize("config", [
    {"dynamics": {}}, {"dynamics": {}, "ltca": {}}, {"dynamics": {"excitation": "contact"}, "ltca": {}},
    {"dynamics": {"excitation": "ltca"}}, {"dynamics": {"excitation": "tvms"}, "ltca": {}},
])
def test_the_ltca_drives_the_dynamics_by_one_rule(config):
    """The workflow's read of the LTCA (stages.ltca_drives) and the study checks'
    (config.study_excitation) are the one statement of gearmesh.choices.pair_excitation."""
    assert ltca_drives(config, "dynamics") == (study_excitation(config) == "ltca")
    dynamics = stage_of("dynamics")
    reads = {r.stage for r in dynamics.reads if r.when(config, "dynamics")}
    assert ("ltca" in reads) == (study_excitation(config) == "ltca")


def test_a_result_depends_on_its_section_and_the_sections_it_carries():
    impact = stage_of("impact")
    assert dependencies(impact, "impact", {"impact": {}, "tolerances": {"samples": 2}}) == ["impact", "tolerances"]
    assert dependencies(impact, "impact", {"impact": {}}) == ["impact"]
    assert dependencies(None, "lte_table", {"ltca": {}}) == []


def test_the_fe_tables_are_read_when_the_method_is_fe():
    stage = Stage("m:f", "{pair}/x.nc", "pair", reads=(Read("fe_compliance", method_fe()),
                                                       Read("stiffness", method_fe("other"))))
    config = {"x": {"method": "fe"}, "other": {"method": "transition"}}
    assert [r.when(config, "x") for r in stage.reads] == [True, False]
    assert stage_of("optimise").reads[0].when({"impact": {"method": "fe"}}, "optimise")


def test_every_stage_is_the_rule_of_its_name_writing_its_declared_file(monkeypatch):
    """The rule of each declared stage (the default study's and a study with every section's
    rule) writes the stage's file as its ``nc`` output and runs the stage's function: what
    gearmesh.upstream compares (rule name = config section) holds by construction."""
    pytest.importorskip("snakemake")
    from pathlib import Path

    from snakemake.api import SnakemakeApi
    from snakemake.settings.types import OutputSettings, ResourceSettings

    root = Path(__file__).resolve().parents[1]
    monkeypatch.chdir(root)
    with SnakemakeApi(OutputSettings(quiet=set())) as api:
        workflow = api.workflow(resource_settings=ResourceSettings(cores=1), snakefile=Path("Snakefile"),
                                workdir=Path("."))._workflow
        rules = {rule.name: rule for rule in workflow.rules}
    checked = 0
    for section, stage in stages().items():
        if section not in rules:
            continue  # a stage the default study's Snakefile has no rule for (signoff without its section)
        rule = rules[section]
        written = re.sub(r"{(\w+),[^}]*}", r"{\1}", str(rule.output.get("nc")))  # without the constraints
        assert written == stage.path(), section
        assert rule.params.get("function").spec.partition("@")[0] == stage.function, section
        checked += 1
    assert checked >= 12
