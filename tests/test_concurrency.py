"""Runs that share a checkout, and jobs that outlive their run (issue 20).

Two studies run at once in one checkout (Snakemake's lock allows it: their outputs differ) and
neither loses a job to the other's start-up cleanup; a job whose Snakemake was killed, or whose
output another process wrote meanwhile, writes nothing."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest
import yaml

from gearmesh.io import host_name
from test_workflow import _package_env, _scratch_workflow

needs_snakemake = pytest.mark.skipif(
    not (Path(sys.executable).parent / "snakemake").exists(), reason="snakemake not installed")


def _study(name: str, pair: str) -> dict:
    return {"study": name, "pairs": [pair], "contact_lines": {"positions": 24},
            "geometry": {"involute_points": 20, "fillet_points": 10, "face_points": 5},
            "stiffness": {"slices": 40, "positions": 24}}


@pytest.mark.workflow
@needs_snakemake
def test_two_studies_run_at_once_in_one_checkout_and_lose_no_job(root, tmp_path):
    """Each run's start-up removes only temporaries no live process writes: a temporary of a live
    writer planted in the other study's folder (as a job in flight) survives both start-ups, one of
    a dead writer goes; both runs finish every job."""
    work = _scratch_workflow(root, tmp_path, _study("one", "low_fluctuation_pair1"))
    (work / "two.yaml").write_text(yaml.safe_dump(_study("two", "low_fluctuation_pair2")))
    folder = work / "results/one/low_fluctuation_pair1"
    folder.mkdir(parents=True)
    writer = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(600)"])  # a job in flight
    dead = subprocess.Popen([sys.executable, "-c", ""])
    dead.wait()
    in_flight = folder / f".stiffness.{host_name()}.{writer.pid}.tmp.nc"
    debris = folder / f".geometry.{host_name()}.{dead.pid}.tmp.nc"
    for path in (in_flight, debris):
        path.write_bytes(b"CDF\x01")
    exe = str(Path(sys.executable).parent / "snakemake")
    try:
        runs = [subprocess.Popen([exe, "--cores", "1", "--configfile", config], cwd=work, env=_package_env(
            work / "package"), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            for config in ("test_config.yaml", "two.yaml")]
        outputs = [run.communicate(timeout=300)[0] for run in runs]
        assert in_flight.exists()
    finally:
        writer.kill()
        writer.wait()
    for run, output in zip(runs, outputs):
        assert run.returncode == 0, output[-3000:]
    assert not debris.exists()
    for study, pair in (("one", "low_fluctuation_pair1"), ("two", "low_fluctuation_pair2")):
        base = work / "results" / study / pair
        for name in ("geometry.nc", "contact_lines.nc", "stiffness.nc", "plots/stiffness.png"):
            assert (base / name).stat().st_size > 0, (study, name)


#: A job: enters gearmesh.io.job_outputs, says "ready", waits for a line on stdin, then writes its
#: output atomically and says what happened.
JOB = textwrap.dedent("""
    import sys
    from gearmesh.io import OutputError, atomic_output, job_outputs
    with job_outputs():
        print("ready", flush=True)
        sys.stdin.readline()
        try:
            with atomic_output(sys.argv[1]) as tmp:
                tmp.write_text("this job's result")
        except OutputError as exc:
            print(f"refused: {exc}", flush=True)
            sys.exit(3)
    print("written", flush=True)
""")

#: A stand-in for Snakemake: a file named ``snakemake`` that starts the job and waits.
CONTROLLER = textwrap.dedent("""
    import subprocess, sys, time
    subprocess.Popen([sys.executable, "-c", sys.argv[1], sys.argv[2]])
    time.sleep(600)
""")


def _start(tmp_path: Path, target: Path) -> tuple[subprocess.Popen, str]:
    controller = tmp_path / "bin" / "snakemake"
    controller.parent.mkdir(exist_ok=True)
    controller.write_text(CONTROLLER)
    proc = subprocess.Popen([sys.executable, str(controller), JOB, str(target)], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "ready"
    return proc, proc.stdout


def _go(proc: subprocess.Popen, stdout) -> str:
    proc.stdin.write("go\n")
    proc.stdin.flush()
    return stdout.readline().strip()


@pytest.mark.workflow
@pytest.mark.skipif(os.name != "posix", reason="process tree of a POSIX run")
def test_a_job_writes_while_its_snakemake_lives(tmp_path):
    target = tmp_path / "results/ltca.nc"
    proc, stdout = _start(tmp_path, target)
    try:
        assert _go(proc, stdout) == "written"
        assert target.read_text() == "this job's result"
    finally:
        proc.kill()
        proc.wait()


@pytest.mark.workflow
@pytest.mark.skipif(os.name != "posix", reason="process tree of a POSIX run")
def test_a_job_whose_snakemake_was_killed_writes_nothing(tmp_path):
    """kill -9 of the controller leaves its jobs running as orphans, writing while a recovery run
    remakes the same files: the orphan discards its result instead."""
    target = tmp_path / "results/ltca.nc"
    proc, stdout = _start(tmp_path, target)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    line = _go(proc, stdout)
    assert line.startswith(f"refused: {target} = 'not written': the Snakemake run that started this job is gone")
    assert not target.exists() and list(target.parent.iterdir()) == []


@pytest.mark.workflow
@pytest.mark.skipif(os.name != "posix", reason="process tree of a POSIX run")
def test_a_job_does_not_clobber_a_file_written_while_it_ran(tmp_path):
    """Snakemake removes a job's outputs before it starts: a file there at the rename was written
    by another process meanwhile (a newer run's job, or an orphan), and is left as it is."""
    target = tmp_path / "results/ltca.nc"
    proc, stdout = _start(tmp_path, target)
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text("the newer run's result")
        line = _go(proc, stdout)
        assert line.startswith(f"refused: {target} = 'not written': another process wrote it while this job ran")
        assert target.read_text() == "the newer run's result"
        assert sorted(p.name for p in target.parent.iterdir()) == ["ltca.nc"]
    finally:
        proc.kill()
        proc.wait()


#: A long job under its controller's watch (gearmesh.io.stop_with_controller): says its pid, then
#: works in a loop that never yields the interpreter.
LONG_JOB = textwrap.dedent("""
    import os
    from gearmesh.io import stop_with_controller
    with stop_with_controller(interval=0.1):
        print(os.getpid(), flush=True)
        while True:
            pass
""")


@pytest.mark.skipif(os.name != "posix", reason="process tree of a POSIX run")
def test_a_job_stops_when_its_snakemake_is_killed(tmp_path):
    """kill -9 of the controller left its jobs running to completion (issue 39 item 8)."""
    import psutil

    controller = tmp_path / "bin" / "snakemake"
    controller.parent.mkdir(exist_ok=True)
    controller.write_text(CONTROLLER.replace("sys.argv[2]]", "'x']"))
    proc = subprocess.Popen([sys.executable, str(controller), LONG_JOB], stdout=subprocess.PIPE, text=True)
    job = psutil.Process(int(proc.stdout.readline()))
    time.sleep(0.5)
    assert job.is_running() and job.status() != psutil.STATUS_ZOMBIE  # the watcher leaves a live controller's job
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    job.wait(timeout=5)  # psutil.TimeoutExpired if the job ran on
