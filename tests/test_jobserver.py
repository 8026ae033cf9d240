"""The job server: a job run by a fork of the warm server gives what the job run alone gives, bit
for bit; its failures reach the script; a killed script takes its job with it; no server, no
difference."""

from __future__ import annotations

import json
import os
import pickle
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import psutil
import pytest

from gearmesh import jobserver
from gearmesh.codeversion import versioned
from gearmesh.io import read_dataset

pytest.importorskip("snakemake")
from snakemake.iocontainers import InputFiles, Log, OutputFiles, Params, Snakemake, Wildcards  # noqa: E402

pytestmark = pytest.mark.skipif(os.name != "posix", reason="the job server forks (POSIX only)")


def _job(root: Path, out: Path, function: str, settings: dict, figures: str | None = None,
         outputs: dict | None = None, pair: str = "low_fluctuation_pair1") -> Snakemake:
    """The Snakemake object of a pair-stage job of ``pair``, as a script rule gets it."""
    params = {"function": versioned(function), "settings": settings}
    if figures:
        params["figures"] = versioned(figures)
    return Snakemake(InputFiles(fromdict={"pair": str(root / f"config/pairs/{pair}.yaml")}),
                     OutputFiles(fromdict=outputs or {"nc": str(out / "result.nc")}), Params(fromdict=params),
                     Wildcards(fromdict={"pair": pair}), 1, None, Log([str(out / "job.log")]),
                     {"study": "test"}, "test_rule", None)


def _script(job: Snakemake, tmp: Path, env: dict) -> subprocess.Popen:
    """What workflow/scripts/pair_stage.py does, in a process of its own."""
    blob = tmp / f"job{time.monotonic_ns()}.pickle"
    blob.write_bytes(pickle.dumps(job))
    code = ("import pickle, sys; from gearmesh.jobserver import run; "
            f"run(pickle.loads(open({str(blob)!r}, 'rb').read()), 'run_pair_stage')")
    return subprocess.Popen([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)


@pytest.fixture(scope="module", autouse=True)
def kernels_in_numba_cache():
    """numba's on-disk cache holding the kernels, so that the run's compiler (jobserver.compile_ahead)
    only checks them and the tests' jobs load them instead of waiting for a compile of seconds."""
    if not jobserver.kernels_cached():
        subprocess.run([sys.executable, "-c", "from gearmesh.jobserver import warm_kernels; warm_kernels()"],
                       check=True, timeout=600)
    assert jobserver.kernels_cached()


@pytest.fixture
def server(monkeypatch):
    """A server for this test, as the Snakefile's onstart starts one; stopped afterwards."""
    monkeypatch.delenv(jobserver.ENV, raising=False)
    path = jobserver.start(["gearmesh.pipeline", "gearmesh.datasets.geometry", "gearmesh.plots.geometry",
                            "gearmesh.datasets.stiffness"])
    assert path is not None and os.environ[jobserver.ENV] == path
    yield SimpleNamespace(path=path, env=dict(os.environ), process=jobserver._server)
    jobserver.stop()
    assert not Path(path).exists()


@pytest.mark.workflow
def test_a_job_on_the_server_equals_the_job_alone(root, tmp_path, server):
    settings = {"positions": 24}
    results = {}
    for where, env in (("server", server.env), ("alone", {**server.env, jobserver.ENV: "off"})):
        out = tmp_path / where
        outputs = {"nc": str(out / "contact_lines.nc"), "contact_length": str(out / "contact_length.png"),
                   "contact_lines": str(out / "contact_lines.png")}
        job = _job(root, out, "gearmesh.datasets.geometry:contact_lines_dataset", settings,
                   "gearmesh.plots.geometry:contact_lines_figures", outputs)
        proc = _script(job, tmp_path, env)
        _, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, err
        results[where] = read_dataset(out / "contact_lines.nc")
        assert (out / "contact_lines.png").stat().st_size > 1000
        log = (out / "job.log").read_text()
        assert "done in" in log
        # the child of the warm server starts working without importing anything
        startup_cpu = float(log.rsplit("CPU ", 1)[1].split(" s")[0])
        if where == "server":
            assert startup_cpu < 0.2, log
    a, b = results["server"], results["alone"]
    assert set(a.data_vars) == set(b.data_vars)
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
    assert a.attrs["config_json"] == b.attrs["config_json"]


@pytest.mark.workflow
def test_a_job_on_the_server_rounds_as_the_one_thread_job_snakemake_runs(root, tmp_path, server):
    """The system deflection of the default pair is an ill-conditioned solve (stiff bearings on a
    slender shaft) whose last digits follow how BLAS splits it into threads: on the server it gives
    bit for bit what the job gives in a process of its own with Snakemake's settings of a one-thread
    job (its thread variables at 1), whatever the machine's cores."""
    results = {}
    alone = {**server.env, jobserver.ENV: "off", **dict.fromkeys(jobserver.THREAD_VARIABLES, "1")}
    for where, env in (("server", server.env), ("alone", alone)):
        out = tmp_path / where
        job = _job(root, out, "gearmesh.datasets.stiffness:stiffness_dataset",
                   {"slices": 20, "positions": 24, "method": "transition"}, pair="helical_z29_71_m5")
        proc = _script(job, tmp_path, env)
        _, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, err
        results[where] = read_dataset(out / "result.nc")
    a, b = results["server"], results["alone"]
    assert float(a["shaft_misalignment_compliance"]) != 0.0  # the pair's shafts deflect
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)


@pytest.mark.workflow
def test_a_job_forked_while_the_kernels_compile_waits_and_loads_them(root, tmp_path, monkeypatch):
    """A fresh clone (numba's cache empty: here a cache folder of its own): the run's compiler
    (started by the Snakefile, or here by the server's start) compiles the kernels, and a dynamics
    job forked meanwhile waits for it and loads the sweep from the cache the compiler wrote instead
    of compiling it a second time (numba's cache log, on the job's standard output: 'data saved' is
    a compile, 'data loaded' a load)."""
    monkeypatch.delenv(jobserver.ENV, raising=False)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "numba"))
    monkeypatch.setenv("NUMBA_DEBUG_CACHE", "1")
    path = jobserver.start(["gearmesh.pipeline", "gearmesh.datasets.dynamics"])
    try:
        assert path is not None
        compiler = psutil.Process(jobserver._compiler.pid)
        server = psutil.Process(jobserver._server.pid)
        job = _job(root, tmp_path, "gearmesh.datasets.dynamics:dynamics_dataset",
                   {"speeds_rpm": {"start": 20000, "stop": 30000, "step": 5000}, "sample_speeds_rpm": [27000],
                    "transient_tau": 4.0, "record_cycles": 4, "points_per_cycle": 32, "max_order": 4})
        proc = _script(job, tmp_path, dict(os.environ))
        while not server.children() and proc.poll() is None:
            time.sleep(0.01)
        assert compiler.is_running(), "the compiler finished before the job started: nothing tested"
        out, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, err
        assert "integrate._sweep" in out and "data loaded" in out, out
        assert "data saved" not in out, out
    finally:
        jobserver.stop()
    assert jobserver._compiler is None and not compiler.is_running()


@pytest.mark.workflow
def test_the_compiler_of_a_run_that_ends_early_is_stopped(tmp_path):
    """A run that ends before its jobs (a dry run, a report, a refused input after the Snakefile
    started the compiler) does not leave the kernels' compiler running: it is stopped at exit
    (here with numba's cache empty, so the compiler would otherwise work for seconds)."""
    code = ("import time; from gearmesh import jobserver; jobserver.compile_ahead(); "
            "print(jobserver._compiler.pid, flush=True); time.sleep(0.3)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                         env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)})
    assert out.returncode == 0, out.stderr
    assert not psutil.pid_exists(int(out.stdout.split()[0]))


@pytest.mark.workflow
def test_a_failing_job_reports_its_error_and_exit_code(root, tmp_path, server):
    job = _job(root, tmp_path, "gearmesh.datasets.geometry:contact_lines_dataset", {"positions": -3})
    proc = _script(job, tmp_path, server.env)
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 2
    assert "gearmesh: error:" in err and "positions" in err
    assert not (tmp_path / "result.nc").exists()


@pytest.mark.workflow
def test_a_killed_script_takes_its_job_with_it(root, tmp_path, server):
    # a stiffness job of many slices runs for seconds: kill its script while it works
    job = _job(root, tmp_path, "gearmesh.datasets.stiffness:stiffness_dataset",
               {"slices": 4000, "positions": 720})
    proc = _script(job, tmp_path, server.env)
    server_process = psutil.Process(server.process.pid)
    deadline = time.monotonic() + 60
    while not server_process.children() and time.monotonic() < deadline:
        time.sleep(0.05)
    (child,) = server_process.children()
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=10)
    child.wait(timeout=10)  # psutil.TimeoutExpired if the job outlived its script
    assert not (tmp_path / "result.nc").exists()


@pytest.mark.workflow
def test_without_a_server_the_script_runs_the_job_itself(root, tmp_path, monkeypatch):
    monkeypatch.setenv(jobserver.ENV, str(tmp_path / "no-such-socket"))
    job = _job(root, tmp_path, "gearmesh.datasets.geometry:contact_lines_dataset", {"positions": 12})
    proc = _script(job, tmp_path, dict(os.environ))
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    assert read_dataset(tmp_path / "result.nc").sizes["position"] == 12


@pytest.mark.parametrize("methods, local, remote, wanted", [
    (set(), True, False, True),
    ({"conda"}, True, False, False),            # the job's Python is the conda environment's
    ({"apptainer"}, True, False, False),
    (set(), False, False, False),               # a cluster run: every job a process of its own
    (set(), True, True, False),                 # a job step on a node
])
def test_only_a_local_run_in_this_python_uses_a_server(monkeypatch, methods, local, remote, wanted):
    monkeypatch.delenv(jobserver.ENV, raising=False)
    workflow = SimpleNamespace(deployment_settings=SimpleNamespace(deployment_method=methods),
                               local_exec=local, remote_exec=remote)
    assert jobserver.wanted(workflow) is wanted
    monkeypatch.setenv(jobserver.ENV, "off")
    assert jobserver.wanted(SimpleNamespace(deployment_settings=SimpleNamespace(deployment_method=set()),
                                            local_exec=True, remote_exec=False)) is False


#: 100 times: 16 arrays of 1 MiB made, written and dropped together (as a numpy expression's
#: temporaries are); prints the page faults it took.
CHURN = ("import resource, numpy as np; a = np.ones(8); before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt\n"
         "for _ in range(100): a = [np.ones(1 << 17) for _ in range(16)]\n"
         "print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)")


@pytest.mark.skipif(os.name != "posix" or os.confstr("CS_GNU_LIBC_VERSION") is None, reason="glibc's malloc")
def test_the_servers_malloc_settings_spare_a_job_the_page_faults_of_its_temporaries(monkeypatch):
    """With the server's ``GLIBC_TUNABLES`` a process whose temporaries come and go together reuses
    their memory (two rounds' 32 MiB faulted in once: 8192 pages), where glibc's defaults hand the
    heap's freed top back to the kernel and fault it in again (about 2000 pages a round, measured)."""
    monkeypatch.delenv("GLIBC_TUNABLES", raising=False)
    faults = {}
    for name, tunables in (("default", ""), ("server", jobserver._tunables(os.environ))):
        out = subprocess.run([sys.executable, "-c", CHURN], capture_output=True, text=True, timeout=60,
                             env={**os.environ, "GLIBC_TUNABLES": tunables}, check=True)
        faults[name] = int(out.stdout)
    assert faults["server"] < 3 * 4096 < 10 * 4096 < faults["default"], faults


def test_the_users_own_glibc_tunables_win():
    given = "glibc.malloc.trim_threshold=5:glibc.cpu.hwcaps=-AVX512F"
    tunables = jobserver._tunables({"GLIBC_TUNABLES": given}).split(":")
    assert tunables[:2] == given.split(":") and "glibc.malloc.mmap_threshold=33554432" in tunables
    assert [t for t in tunables if t.startswith("glibc.malloc.trim_threshold")] == ["glibc.malloc.trim_threshold=5"]


def test_the_server_imports_the_modules_its_rules_name():
    figures = lambda wildcards: None  # noqa: E731 - a param function, as the workflow's versioned_param
    figures.spec = "gearmesh.plots.ltca:ltca_figures@0123456789abcdef"
    rules = [SimpleNamespace(params=["gearmesh.datasets.ltca:ltca_dataset@0123456789abcdef", figures,
                                     {"positions": 3}]),
             SimpleNamespace(params=None)]
    assert jobserver.rule_modules(rules) == ["gearmesh.datasets.ltca", "gearmesh.pipeline", "gearmesh.plots.ltca"]


def test_a_server_started_ahead_imports_every_module_a_shipped_studys_rules_name():
    """``gearmesh run`` starts the server before Snakemake has built the rules, with
    jobserver.stage_modules(): the run takes it only when its rules name no other module
    (jobserver.start), so a module missing there would cost every run a second server. The
    recorded plans (tests/plans/*.json, every shipped study) name the functions of every job."""
    names = set()
    for plan in (Path(__file__).parent / "plans").glob("*.json"):
        for job in json.loads(plan.read_text())["jobs"]:
            names.update(v for v in job["params"].values() if isinstance(v, str) and v.startswith("gearmesh."))
    modules = {name.partition(":")[0] for name in names}
    assert len(modules) > 10 and "gearmesh.datasets.verdict" in modules
    assert modules <= set(jobserver.stage_modules())


@pytest.mark.workflow
def test_a_server_started_ahead_becomes_the_runs(monkeypatch):
    """The server ``gearmesh run`` starts ahead takes no job (no GEARMESH_JOBSERVER) until the
    Snakefile's onstart makes it the run's; a rule naming a module it did not import gets a new one."""
    monkeypatch.delenv(jobserver.ENV, raising=False)
    jobserver.start_ahead(["gearmesh.pipeline", "gearmesh.datasets.geometry"])
    try:
        ahead = jobserver._server
        assert ahead is not None and jobserver.ENV not in os.environ
        path = jobserver.start(["gearmesh.datasets.geometry", "gearmesh.pipeline"])
        assert jobserver._server is ahead and os.environ[jobserver.ENV] == path and Path(path).exists()
        other = jobserver.start(["gearmesh.pipeline", "gearmesh.datasets.stiffness"])
        assert jobserver._server is not ahead and ahead.poll() is not None and other != path
        assert not Path(path).exists() and Path(other).exists()
    finally:
        jobserver.stop()
    assert jobserver._server is None and jobserver.ENV not in os.environ


def test_a_new_server_removes_the_socket_folders_of_runs_that_are_gone(monkeypatch):
    """A run killed with its server (kill -9 of the group) leaves its socket folder; the next
    server removes the folders named after a process that no longer exists, and only those."""
    monkeypatch.delenv(jobserver.ENV, raising=False)
    from test_bad_inputs import _dead_pid

    gone = _dead_pid()
    prefix = jobserver.FOLDER_PREFIX
    parent = Path(tempfile.mkdtemp(prefix="gm"))  # short: a socket's path has at most 107 bytes
    try:
        stale = parent / f"{prefix}{gone}-x1"
        kept = [parent / f"{prefix}{os.getpid()}-x2", parent / f"{prefix}nopid", parent / "other-1-x3"]
        for folder in (stale, *kept):
            folder.mkdir()
            (folder / "socket").write_bytes(b"")
        assert jobserver.remove_stale_folders(str(parent)) == [str(stale)]
        assert not stale.exists() and all(folder.exists() for folder in kept)
        monkeypatch.setattr(tempfile, "tempdir", str(parent))  # the server's own folder there too
        stale.mkdir()
        path = jobserver.start(["gearmesh.pipeline"])
        try:
            assert path is not None and not stale.exists()
            assert Path(path).parent.name.startswith(f"{prefix}{os.getpid()}-")
        finally:
            jobserver.stop()
        assert not Path(path).parent.exists() and all(folder.exists() for folder in kept)
    finally:
        shutil.rmtree(parent)


def _job_modules() -> set[str]:
    """Every gearmesh module a job can run: the closure (imports inside functions included) of
    every stage's and table's function and plot function, and of the pipeline."""
    from gearmesh.codeversion import module_closure
    from gearmesh.registry import stages

    specs = {"gearmesh.pipeline:run"}
    for stage in stages().values():
        for job in (stage, *stage.tables):
            specs.update(s for s in (job.function, job.draws) if s)
    return {name for spec in specs for name in module_closure(spec.partition(":")[0])}


def _function_level_imports() -> set[str]:
    """Every third-party module the modules a job can run import inside a function (``from X
    import y`` also names X.y when that is a module)."""
    import ast
    import importlib.util

    from gearmesh.codeversion import module_file

    found: set[str] = set()
    for module in _job_modules():
        for fn in ast.walk(ast.parse(module_file(module).read_text(encoding="utf-8"))):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if isinstance(node, ast.Import):
                    found.update(a.name for a in node.names)
                elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                    found.add(node.module)
                    for a in node.names:
                        name = f"{node.module}.{a.name}"
                        try:
                            if importlib.util.find_spec(name) is not None:
                                found.add(name)
                        except (ImportError, ValueError):
                            pass
    return {m for m in found if m.split(".")[0] not in sys.stdlib_module_names and m.split(".")[0] != "gearmesh"}


def test_the_server_warms_every_module_the_package_imports_inside_functions():
    """The server imports what jobs import inside functions, so that no job pays for it: every
    function-level third-party import of the modules a job can run is in WARM_MODULES (a package
    counts as imported with any of its submodules)."""
    assert {"gearmesh.datasets.dynamics", "gearmesh.plots.impact", "gearmesh.tolerance"} <= _job_modules()
    warm = set(jobserver.WARM_MODULES)
    missing = {m for m in _function_level_imports() if m not in warm and not any(w.startswith(m + ".") for w in warm)}
    assert not missing, f"add to gearmesh.jobserver.WARM_MODULES: {sorted(missing)}"


@pytest.mark.workflow
def test_after_the_warm_steps_a_job_loads_no_kernel_and_imports_nothing_heavy(root, tmp_path):
    """In a process warmed as the server warms itself, a contact-driven dynamics job of another pair
    and its figures load no compiled kernel (no new numba specialisation: the warm-up used the types
    the jobs use) and import no module of the heavy libraries."""
    code = f"""
import os, sys, time, numpy as np
from gearmesh import jobserver
jobserver.compile_ahead()
steps = jobserver.warm_steps(os.dup(jobserver._compiled))  # the server's own copy of the compiler's pipe
while steps:  # as the server runs them (a step answering False waits for the compiler)
    if steps[0]() is not False:
        steps.pop(0)
    else:
        time.sleep(0.05)
assert jobserver.kernels_cached()
from gearmesh.dynamics import integrate
from gearmesh import ltca_solve
kernels = [integrate._sweep, ltca_solve._COMPILED["loop"], ltca_solve._COMPILED["scales"]]  # the others compile into _sweep
before = [len(k.signatures) for k in kernels]
modules = set(sys.modules)
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import load_pair
from gearmesh.contact_model import TABLE_CONTACT
from gearmesh.meshforce import mesh_force_table
from gearmesh.dynamics.model import pair_model
from gearmesh.dynamics.integrate import simulate
geom = pair_geometry(load_pair({str(root / 'config/pairs/low_fluctuation_pair1.yaml')!r}))
table = mesh_force_table(geom, 4 * 300 / geom.base_radius[0], positions=32, approaches=16,
                         contact=TABLE_CONTACT.with_(points=10, method="transition"))
simulate(pair_model(geom, 300.0, None, contact=table), [2000.0, 3000.0])
from gearmesh.ltca_solve import solve_contact_tabulated
from gearmesh.meshforce import table_layout
layout = table_layout(geom, 32, TABLE_CONTACT.with_(points=10, method="transition"))
solve_contact_tabulated(layout.gaps()[:3], layout.compliance[:3] - layout.law.linear, np.full(3, 1e4), layout.law)
after = [len(k.signatures) for k in kernels]
heavy = sorted(m for m in set(sys.modules) - modules
               if m.split(".")[0] in ("scipy", "numba", "matplotlib", "PIL", "netCDF4", "jsonschema", "pygad"))
print(before, after, heavy)
assert before == after and all(before), (before, after)
assert not heavy, heavy
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:] + out.stdout


@pytest.mark.workflow
def test_the_compiler_of_a_killed_run_stops(tmp_path):
    """kill -9 of the Snakemake process that started the kernels' compiler (numba's cache empty,
    so it would compile for seconds) stops the compiler within a second, as it stops the server."""
    code = ("import time; from gearmesh import jobserver; jobserver.compile_ahead(); "
            "print(jobserver._compiler.pid, flush=True); time.sleep(600)")
    parent = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                              env={**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)})
    try:
        compiler = psutil.Process(int(parent.stdout.readline()))
        time.sleep(0.5)
        assert compiler.is_running() and compiler.status() != psutil.STATUS_ZOMBIE, "nothing to stop"
        parent.kill()
        parent.wait()
        compiler.wait(timeout=3)  # psutil.TimeoutExpired if it compiled on
    finally:
        parent.kill()


#: A stand-in for the Snakemake run: starts a server as the Snakefile's onstart does, says its
#: socket, then waits to be killed.
PARENT = ("import sys, time; from gearmesh import jobserver; "
          "print(jobserver.start(['gearmesh.pipeline', 'gearmesh.datasets.stiffness']), flush=True); time.sleep(600)")


def test_killing_the_controller_stops_the_jobs_on_its_server(root, tmp_path, monkeypatch):
    """After kill -9 of Snakemake up to five jobs ran on to completion: the server, seeing its run
    gone, kills its running children, and their scripts end (exit 1, one line)."""
    monkeypatch.delenv(jobserver.ENV, raising=False)
    parent = subprocess.Popen([sys.executable, "-c", PARENT], stdout=subprocess.PIPE, text=True)
    try:
        path = parent.stdout.readline().strip()
        assert Path(path).exists(), path
        (server,) = [p for p in psutil.Process(parent.pid).children() if "serve" in p.cmdline()]  # not the compiler
        job = _job(root, tmp_path, "gearmesh.datasets.stiffness:stiffness_dataset", {"slices": 4000, "positions": 720})
        script = _script(job, tmp_path, {**os.environ, jobserver.ENV: path})
        deadline = time.monotonic() + 60
        while not server.children() and time.monotonic() < deadline:
            time.sleep(0.05)
        (child,) = server.children()
        parent.kill()
        parent.wait()
        child.wait(timeout=5)  # psutil.TimeoutExpired if the job ran on
        _, err = script.communicate(timeout=10)
        assert script.returncode == 1 and "died before it finished" in err, err
        server.wait(timeout=5)
        assert not (tmp_path / "result.nc").exists()
    finally:
        parent.kill()
