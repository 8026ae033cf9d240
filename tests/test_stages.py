"""The stage declarations (gearmesh.settings STAGE, gearmesh.stages) and the workflow derived
from them (gearmesh.plan): what the workflow's rules, targets and upstream checks derive from is
itself consistent."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

from gearmesh import plan
from gearmesh.config import load_study, study_excitation
from gearmesh.registry import stage_of, stages
from gearmesh.stages import Read, Stage, dependencies, ltca_drives, method_fe, required_sections, resolve

ROOT = Path(__file__).resolve().parents[1]
STUDIES = [ROOT / "config/config.yaml", *sorted((ROOT / "config/studies").glob("*.yaml"))]
#: The wildcards of a result's path by the stage's scope.
WILDCARDS = {"study": set(), "pair": {"pair"}, "variant": {"pair", "variant"}, "run": {"pair", "run"}}


def _jobs():
    """Every declared job: (section, stage or table)."""
    return [(s, job) for s, stage in stages().items() for job in (stage, *stage.tables)]


@pytest.mark.parametrize("section", sorted(stages()))
def test_a_stage_writes_one_file_under_the_wildcards_of_its_scope(section):
    stage = stage_of(section)
    assert "/" not in stage.writes and "{" not in stage.writes and stage.writes.endswith(".nc")
    path = stage.path()
    assert set(re.findall(r"{(\w+)}", path)) == WILDCARDS[stage.scope] | {"study"}
    assert stage.path(study="s", pair="p", variant="v", run="r").startswith("results/s/")


def test_no_two_jobs_write_the_same_file_and_every_read_is_a_stage():
    declared = stages()
    paths = [job.path() for _, job in _jobs() if job.writes]
    assert len(paths) == len(set(paths))
    names = [s for s in declared] + [job.name for _, stage in declared.items() for job in stage.tables]
    assert len(names) == len(set(names))  # rule names
    for section, job in _jobs():
        for read in job.reads:
            assert read.stage in declared, (section, read.stage)
            upstream = declared[read.stage]
            # a result of the job's own pair (and variant): never of a finer scope than the reader's
            finer = {"variant"} if read.every_variant else WILDCARDS[upstream.scope] if read.every_pair else set()
            assert WILDCARDS[upstream.scope] <= WILDCARDS[job.scope] | finer, (section, read.stage)


@pytest.mark.parametrize("section, job", _jobs(), ids=lambda v: v if isinstance(v, str) else "")
def test_every_declared_function_resolves_and_takes_what_its_job_gives(section, job):
    """A declared function name is a checked link: it imports; a stage's function takes its
    settings, the results it reads, the sections it carries (by name or through ``**``); a
    table's takes the results it reads; a plot function takes (inputs, outputs)."""
    from gearmesh.schema import key_of, settings_fields
    from gearmesh.registry import stage_sections

    params = inspect.signature(resolve(job.function)).parameters
    wanted = {r.argument for r in job.reads}
    if isinstance(job, Stage):
        cls = dict(stage_sections())[section if job.scope != "run" else f"{section}.NAME"]
        wanted |= {key_of(f) for f in settings_fields(cls)} | set(job.carries)
        wanted |= {"variant"} if job.variant_name else set()
        wanted -= {"pairs"} if job.scope == "study" else set()  # the pairs come as the first argument
    if not job.writes:  # a figure job: the plot function itself
        wanted = {"inputs", "outputs"}
    if not any(p.kind is p.VAR_KEYWORD for p in params.values()):
        assert wanted <= set(params), (job.function, wanted - set(params))
    if job.writes and job.draws:
        assert list(inspect.signature(resolve(job.draws)).parameters)[:2] == ["inputs", "outputs"], job.draws


def test_every_caption_is_declared_once_and_every_declared_caption_exists():
    files = {p.stem for p in (ROOT / "workflow/report").glob("*.rst")} - {"workflow"}
    declared = [f.caption_name for _, job in _jobs() for f in job.figures] + [job.stem for _, job in _jobs() if job.csv]
    assert set(declared) <= files, set(declared) - files
    assert files <= set(declared), f"captions no job uses: {files - set(declared)}"


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


def test_the_fe_tables_are_read_when_the_method_is_fe_a_section_left_out_by_its_default():
    stage = Stage("m:f", "x.nc", "pair", reads=(Read("fe_compliance", method_fe()),
                                                Read("stiffness", method_fe("other"))))
    config = {"x": {"method": "fe"}, "other": {"method": "transition"}}
    assert [r.when(config, "x") for r in stage.reads] == [True, False]
    assert stage_of("optimise").reads[0].when({"impact": {"method": "fe"}}, "optimise")
    # the optimiser without an impact section takes the declared impact model, whose tooth is the FE tooth
    assert stage_of("optimise").reads[0].when(plan.filled({"optimise": {}}), "optimise")
    assert not stage_of("optimise").reads[0].when(plan.filled({"impact": {"method": "improved"}}), "optimise")


def test_a_stage_needs_the_sections_of_the_stages_it_always_reads():
    assert required_sections(stage_of("rating")) == ("ltca",)
    assert set(required_sections(stage_of("signoff"))) == {"impact", "ltca", "rating"}
    assert required_sections(stage_of("dynamics")) == ("stiffness",)


@pytest.mark.parametrize("study", STUDIES, ids=lambda p: p.stem)
def test_every_rule_of_a_study_runs_its_declared_function_and_writes_its_declared_file(study):
    """The rules of each study (gearmesh.plan): a stage's rule is named as its section, writes the
    stage's file as its ``nc`` output and runs the stage's function (what gearmesh.upstream
    compares: rule name = config section); every figure's caption file exists."""
    config = load_study(study)
    declared = stages()
    for rule in plan.rules(config):
        if rule.name in declared:
            stage = declared[rule.name]
            assert rule.outputs["nc"].path == stage.path()
            assert rule.params["function"].spec.partition("@")[0] == stage.function
        for output in rule.outputs.values():
            if output.caption:
                assert (ROOT / "workflow/report" / f"{output.caption}.rst").is_file(), output.caption
    assert (ROOT / "workflow/rules" / plan.SCRIPT).resolve().is_file()
