"""The workflow's plan of a study, as data: every job of the study's DAG (all forced) with its
rule, wildcards, inputs, outputs (report caption, category, subcategory), log, params (function
names without their code digest; other values by the sha256 of their JSON), localrule, priority,
script and conda environment, and the rules Snakemake defines.

``tests/plans/`` keeps the plan of each shipped study and of ``tests/plans/*.yaml``, first
recorded from the hand-written rules (18517d5) with the deliberate changes of the generated
ones applied (the sign-off rule named as its section, ``signoff``; one script for every rule;
only the rules a study runs defined; the engagement table's figure no longer a target of its own,
it comes with the table); ``tests/test_workflow_plan.py`` compares. After a deliberate change of
the plan: ``python tests/workflow_plan.py --write`` and read the diff."""

from __future__ import annotations

import hashlib
import json
import os
import re
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
PLANS = Path(__file__).resolve().parent / "plans"


def studies() -> dict[str, list[str]]:
    """Each recorded study by name: its config files (none: the default study)."""
    out = {"default": []}
    out.update({p.stem: [str(p.relative_to(ROOT))] for p in sorted((ROOT / "config/studies").glob("*.yaml"))})
    out.update({p.stem: [str(p)] for p in sorted(PLANS.glob("*.yaml"))})
    return out


def _value(value: Any) -> Any:
    """A param as the plan keeps it: a versioned function name without its digest, else a digest."""
    text = str.__str__(value) if isinstance(value, str) else None
    if text is not None and re.match(r"^gearmesh\.[\w.]+:\w+(@|$)", text):
        return text.partition("@")[0]
    data = json.dumps(value, sort_keys=True, default=str)
    return "sha256:" + hashlib.sha256(data.encode()).hexdigest()[:16]


def _files(namedlist: Any) -> dict[str, Any]:
    """Named files (a name of a list of files: the list), unnamed ones under ''."""
    items = [str(f) for f in namedlist]
    out: dict[str, Any] = {}
    named: set[int] = set()
    for name, (first, end) in namedlist._names.items():
        out[name] = items[first] if end is None else items[first:end]
        named.update([first] if end is None else range(first, end))
    rest = [f for i, f in enumerate(items) if i not in named]
    if rest:
        out[""] = sorted(rest)
    return out


def _outputs(job: Any) -> list[dict[str, Any]]:
    names = {first: name for name, (first, _) in job.output._names.items()}
    out = []
    for i, f in enumerate(job.output):
        item: dict[str, Any] = {"name": names.get(i), "path": str(f)}
        report = job.rule.output[i].flags.get("report")
        if report is not None:
            item.update(caption=os.path.relpath(str(report.caption), ROOT) if report.caption else None,
                        category=report.category, subcategory=report.subcategory)
        out.append(item)
    return out


def plan(configfiles: list[str]) -> dict[str, Any]:
    """The plan of the study of ``configfiles`` (relative to the repository root)."""
    from snakemake.api import SnakemakeApi
    from snakemake.settings.types import ConfigSettings, DAGSettings, OutputSettings, ResourceSettings

    here = os.getcwd()
    os.chdir(ROOT)
    try:
        with SnakemakeApi(OutputSettings(quiet={"all"})) as api:
            wapi = api.workflow(resource_settings=ResourceSettings(cores=1), snakefile=Path("Snakefile"),
                                config_settings=ConfigSettings(configfiles=[Path(c) for c in configfiles]),
                                workdir=Path("."))
            wf = wapi._workflow
            wapi.dag(DAGSettings(forceall=True))
            wf._prepare_dag(forceall=True, ignore_incomplete=True, lock_warn_only=True, nolock=True)
            wf._build_dag()
            jobs = []
            for job in wf.dag.jobs:
                rule = job.rule
                jobs.append({"rule": rule.name, "wildcards": dict(job.wildcards_dict), "input": _files(job.input),
                             "output": _outputs(job), "log": [str(f) for f in job.log],
                             "localrule": rule.name in wf._localrules, "priority": rule.priority,
                             "params": {k: _value(v) for k, v in job.params.items()},
                             "script": rule.script, "conda": None if rule.conda_env is None else str(rule.conda_env)})
            return {"rules": sorted(r.name for r in wf.rules),
                    "jobs": sorted(jobs, key=lambda j: (j["rule"], sorted(j["wildcards"].items())))}
    finally:
        os.chdir(here)


def dumps(data: dict[str, Any]) -> str:
    """The plan as JSON, one job a line (a change shows as the lines of its jobs)."""
    jobs = ",\n".join(json.dumps(j, sort_keys=True) for j in data["jobs"])
    return f'{{"rules": {json.dumps(data["rules"])},\n"jobs": [\n{jobs}\n]}}\n'


if __name__ == "__main__":
    if sys.argv[1:] != ["--write"]:
        sys.exit("usage: python tests/workflow_plan.py --write   (records tests/plans/*.json)")
    for name, files in studies().items():
        (PLANS / f"{name}.json").write_text(dumps(plan(files)))
        print("wrote", PLANS / f"{name}.json")
