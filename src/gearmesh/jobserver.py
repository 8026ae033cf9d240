"""A warm process that runs a local workflow's jobs by fork: Python's start-up and the imports
are paid once per run instead of once per job.

Snakemake starts the job of every ``script:`` rule as a new Python process, which then imports
what the job needs: xarray and pandas, scipy.interpolate, matplotlib, numba — about a second of
CPU before any work, more than most jobs of a study then spend working. For a local run the
Snakefile starts one server per run (:func:`start`, from ``onstart``): it imports the modules of
the study's rules, then forks one child per job from that imported, otherwise untouched state.
A job's script (``workflow/scripts/*.py``) calls :func:`run`, which hands the job's Snakemake
object and its standard streams to the server and exits with the child's exit code; the child
runs the same :mod:`gearmesh.pipeline` function the script would have run, so a job's results
do not depend on where it ran (tested bit for bit). Without a server — a cluster run, a
``--use-conda`` or container run (the job's Python is not the server's), a platform without
``fork``, ``GEARMESH_JOBSERVER=off``, or a server that is not there — the script runs the
function itself.

Lifetimes: the server exits when the run ends (:func:`stop`, from ``onsuccess``/``onerror``:
its running children finish their jobs) or when the Snakemake process that started it is gone
(killed: it kills its running children first, within half a second); a child is killed when its
job's script is (Snakemake cancelling the job, Ctrl-C), so no job goes on working after its
controller stopped waiting for it. A job its script runs itself (no server) has a watcher of its
own that does the same (:func:`gearmesh.io.stop_with_controller`). The socket lives in a private temporary directory (mode 0700): only the user who
started the run can hand the server a job.

Protocol (one connection per job): the script sends its standard streams' descriptors with an
8-byte big-endian length, then the pickled job; the child answers ``S`` when it starts the job,
then ``E`` and the exit code (4 bytes, big-endian). A connection that closes before ``S`` never
started the job, and the script runs it itself; one that closes after ``S`` lost it (exit 1).
"""

from __future__ import annotations

import importlib
import os
import pickle
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from typing import Any, Iterable

#: The environment variable that names the run's socket ("off" disables the server).
ENV = "GEARMESH_JOBSERVER"
#: The environment variable that tells the job when its process (its script) started: the
#: pipeline measures the job's start-up from it, without importing this module.
STARTED_ENV = "GEARMESH_JOB_STARTED"
_HEADER = struct.Struct("!Q")
_CODE = struct.Struct("!i")
_server: subprocess.Popen | None = None


# --------------------------------------------------------------------------------------
# The job's side (workflow/scripts/*.py)
# --------------------------------------------------------------------------------------


def run(smk: Any, entry: str) -> None:
    """Run the job ``smk`` (the Snakemake object of a ``script:`` rule) through the pipeline
    function ``entry`` (e.g. "run_pair_stage"): in a child of the run's server when there is
    one, here otherwise. Exits with the job's exit code."""
    code = _run_on_server(smk, entry)
    if code is not None:
        sys.exit(code)
    started = process_start_time()
    if started is not None:  # what the job's log measures its start-up from (gearmesh.pipeline)
        os.environ[STARTED_ENV] = repr(started)
    from . import pipeline
    from .io import stop_with_controller

    with stop_with_controller():  # killed with its Snakemake (kill -9), as a job on the server is
        getattr(pipeline, entry)(smk)


def _run_on_server(smk: Any, entry: str) -> int | None:
    """The job's exit code from the server, or None when no server took the job."""
    path = os.environ.get(ENV, "")
    if not path or path == "off" or not hasattr(socket, "send_fds"):
        return None
    try:
        conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        conn.connect(path)
    except OSError:
        return None
    with conn:
        payload = pickle.dumps({"entry": entry, "smk": smk, "cwd": os.getcwd(), "started": process_start_time()})
        try:
            socket.send_fds(conn, [_HEADER.pack(len(payload))], [0, 1, 2])
            conn.sendall(payload)
            if _recv_exactly(conn, 1) != b"S":
                return None  # the server closed before starting the job: run it here
        except OSError:
            return None
        try:
            tag = _recv_exactly(conn, 1)
            if tag == b"E":
                return _CODE.unpack(_recv_exactly(conn, _CODE.size))[0]
        except OSError:
            pass
    print("gearmesh: error: the job's process on the job server died before it finished "
          "(killed, or out of memory); rerun it, or set GEARMESH_JOBSERVER=off to run jobs alone",
          file=sys.stderr)
    return 1


def _recv_exactly(conn: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = conn.recv(n - len(data))
        if not chunk:
            raise ConnectionError("closed")
        data += chunk
    return data


def process_start_time() -> float | None:
    """When this process started (epoch seconds, to the kernel's clock tick), or None off Linux.

    From /proc: the start in clock ticks since boot against the uptime, both since boot, so the
    result does not carry the whole-second rounding of the boot time that psutil's
    ``create_time`` adds (up to a second: more than a job's start-up)."""
    try:
        with open("/proc/self/stat", encoding="ascii") as stat, open("/proc/uptime", encoding="ascii") as up:
            start_ticks = int(stat.read().rsplit(")", 1)[1].split()[19])  # field 22, starttime
            uptime = float(up.read().split()[0])
        return time.time() - (uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return None


# --------------------------------------------------------------------------------------
# The controller's side (Snakefile onstart / onsuccess / onerror)
# --------------------------------------------------------------------------------------


def wanted(workflow: Any) -> bool:
    """Whether a run of ``workflow`` (Snakemake's object) should use a server: a local run whose
    jobs run with this Python (no conda, container or environment modules), on a platform with
    fork and descriptor passing, not disabled by ``GEARMESH_JOBSERVER=off``."""
    if os.environ.get(ENV) == "off" or os.name != "posix" or not hasattr(socket, "send_fds"):
        return False
    methods = {str(m).lower() for m in workflow.deployment_settings.deployment_method}
    if any(m for m in methods if any(k in m for k in ("conda", "apptainer", "singularity", "env_modules"))):
        return False
    return bool(workflow.local_exec) and not workflow.remote_exec


def start(modules: Iterable[str], timeout: float = 5.0) -> str | None:
    """Start the run's server with ``modules`` imported, export its socket in ``GEARMESH_JOBSERVER``
    for the jobs, and return the socket path (None if it did not come up within ``timeout``)."""
    global _server
    folder = tempfile.mkdtemp(prefix="gearmesh-jobs-")  # mode 0700: this user's jobs only
    path = os.path.join(folder, "socket")
    _server = subprocess.Popen([sys.executable, "-m", "gearmesh.jobserver", path, str(os.getpid()), *modules],
                               stdin=subprocess.DEVNULL)
    deadline = time.monotonic() + timeout
    while not os.path.exists(path):
        if _server.poll() is not None or time.monotonic() > deadline:
            stop()
            return None
        time.sleep(0.01)
    os.environ[ENV] = path
    return path


def stop() -> None:
    """Stop the run's server (its running children finish their jobs) and remove its socket."""
    global _server
    path = os.environ.pop(ENV, None)
    if _server is not None:
        _server.terminate()
        try:
            _server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            _server.kill()
            _server.wait()
        _server = None
    if path and path != "off":
        shutil.rmtree(os.path.dirname(path), ignore_errors=True)


def rule_modules(rules: Iterable[Any]) -> list[str]:
    """The gearmesh modules named by the rules' ``params.function`` and ``params.figures``
    ("package.module:function@digest", or a param function carrying it as ``.spec``), and the
    pipeline: what the server imports."""
    modules = {"gearmesh.pipeline"}
    for rule in rules:
        for value in getattr(rule, "params", None) or []:
            value = getattr(value, "spec", value)
            if isinstance(value, str) and value.startswith("gearmesh.") and ":" in value:
                modules.add(value.partition(":")[0])
    return sorted(modules)


# --------------------------------------------------------------------------------------
# The server
# --------------------------------------------------------------------------------------


def serve(path: str, parent: int, modules: Iterable[str]) -> None:
    """Listen on ``path``, import ``modules``, then fork a child per connection until the process
    ``parent`` (the Snakemake run) is gone or a SIGTERM arrives."""
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path + ".tmp")
    listener.listen(128)
    os.replace(path + ".tmp", path)  # jobs connect only once it listens
    stopping = []
    signal.signal(signal.SIGTERM, lambda *_: stopping.append(True))
    for module in modules:  # a module that fails to import fails in the job, with its message
        try:
            importlib.import_module(module)
        except Exception:  # noqa: BLE001
            pass
    listener.settimeout(0.5)
    children: set[int] = set()
    while not stopping and os.getppid() == parent:
        _reap(children)
        try:
            conn, _ = listener.accept()
        except (TimeoutError, InterruptedError):
            continue
        pid = os.fork()
        if pid == 0:
            listener.close()
            _child(conn)
        children.add(pid)
        conn.close()
    listener.close()
    shutil.rmtree(os.path.dirname(path), ignore_errors=True)  # also when the run was killed
    if not stopping:  # the run's Snakemake is gone (kill -9): nobody waits for its jobs, they stop now
        for pid in children:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
    while children:
        _reap(children, block=True)


def _reap(children: set[int], block: bool = False) -> None:
    """Collect finished ``children`` (their CPU time then counts for this process's parent) and
    forget them; ``block``: wait for one."""
    while children:
        try:
            pid, _ = os.waitpid(-1, 0 if block else os.WNOHANG)
        except ChildProcessError:
            children.clear()
            return
        if pid == 0:
            return
        children.discard(pid)
        if block:
            return


def _child(conn: socket.socket) -> None:
    """One job in a forked child: take the job's streams, run it, answer its exit code. Never returns."""
    code = 1
    try:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        conn.settimeout(None)
        header, fds, _, _ = socket.recv_fds(conn, _HEADER.size, 3)
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        sys.stdin, sys.stdout, sys.stderr = (open(i, mode, closefd=False) for i, mode in ((0, "r"), (1, "w"), (2, "w")))
        job = pickle.loads(_recv_exactly(conn, _HEADER.unpack(header)[0]))
        os.chdir(job["cwd"])
        conn.sendall(b"S")
        # the job's script gone (cancelled, killed) = this job stops: nobody waits for it
        threading.Thread(target=_die_with, args=(conn,), daemon=True).start()
        if job["started"] is not None:
            os.environ[STARTED_ENV] = repr(job["started"])
        from . import pipeline

        try:
            getattr(pipeline, job["entry"])(job["smk"])
            code = 0
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except BaseException:  # noqa: BLE001 - report anything, then answer
        traceback.print_exc()
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
            conn.sendall(b"E" + _CODE.pack(code))
        except Exception:  # noqa: BLE001
            pass
        os._exit(code)


def _die_with(conn: socket.socket) -> None:
    """Wait for the job's script to close the connection (it only does when it is gone)."""
    try:
        while conn.recv(1):
            pass
    except OSError:
        pass
    os.kill(os.getpid(), signal.SIGKILL)


if __name__ == "__main__":
    serve(sys.argv[1], int(sys.argv[2]), sys.argv[3:])
