# The study's pairs and variants checked before any job runs, the wildcards, and the run's start
# and end. No physics here, and no functions: the rules come from the stage declarations
# (gearmesh.plan, workflow/rules/stages.smk).
import sys

from gearmesh.config import check_study
from gearmesh.errors import GearmeshInputError
from gearmesh import jobserver
from gearmesh.io import remove_stale_temporaries
from gearmesh.launch import cancel_timers

STUDY = config["study"]
ENV = "../envs/gearmesh.yaml"

# Every pair and variant of the study is loaded and checked before any job runs, so a bad
# input stops the workflow with one message and no partial output.
try:
    PAIRS = check_study(config)
except GearmeshInputError as exc:
    print(f"gearmesh: error: {exc}", file=sys.stderr)
    sys.exit(2)

# A local run compiles numba's kernels in a process of its own from here on (gearmesh.jobserver:
# a fresh clone's seconds of compiling on a free core while Snakemake builds the DAG; with the
# kernels cached, a check), and hands that process to its job server at onstart.
if jobserver.wanted(workflow):
    jobserver.compile_ahead()


wildcard_constraints:
    study=STUDY,
    pair="|".join(PAIRS),
    variant="|".join(config["variants"]),
    run="|".join(config.get("optimise") or {}) or "^$",


# A job killed outright (kill -9, a lost node) skips the cleanup of its atomic write and leaves
# .NAME.PID.tmp.* beside its target: remove them before any job of this run starts.
# A local run then starts its job server: one process that imports the modules of the study's
# rules once and forks a child per job (gearmesh.jobserver; GEARMESH_JOBSERVER=off runs every
# job in a process of its own, as a cluster run does), or takes the one `gearmesh run` started
# ahead of Snakemake; a run whose jobs do not run here stops that one.
onstart:
    remove_stale_temporaries("results")
    if jobserver.wanted(workflow):
        jobserver.start(jobserver.rule_modules(workflow.rules))
    else:
        jobserver.stop()


# The run is over: its server stopped, and Snakemake's job-rate timers, which would keep its
# process alive for up to a second more, cancelled (gearmesh.launch.cancel_timers).
onsuccess:
    jobserver.stop()
    cancel_timers()


onerror:
    jobserver.stop()
    cancel_timers()
