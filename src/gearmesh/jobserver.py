"""A warm process that runs a local workflow's jobs by fork: Python's start-up and the imports
are paid once per run instead of once per job.

Snakemake starts the job of every ``script:`` rule as a new Python process, which then imports
what the job needs: xarray and pandas, scipy.interpolate, matplotlib, numba — about a second of
CPU before any work, more than most jobs of a study then spend working. For a local run the
Snakefile starts one server per run (:func:`start`, from ``onstart``), or takes the one ``gearmesh
run`` started before Snakemake read the Snakefile (:func:`start_ahead`): it imports the modules of
the study's rules, then forks one child per job from that imported, otherwise untouched state.
Between jobs it warms that state further (:func:`warm_steps`): it imports what jobs import inside
functions (:data:`WARM_MODULES`) and loads the compiled kernels from numba's on-disk cache, which
every job would otherwise do again (0.3–1 s of CPU a job on the default study, measured).
A job's script (``workflow/scripts/*.py``) calls :func:`run`, which hands the job's Snakemake
object and its standard streams to the server and exits with the child's exit code; the child
runs the same :mod:`gearmesh.pipeline` function the script would have run, so a job's results
do not depend on where it ran (tested bit for bit). Without a server — a cluster run, a
``--use-conda`` or container run (the job's Python is not the server's), a platform without
``fork``, ``GEARMESH_JOBSERVER=off``, or a server that is not there — the script runs the
function itself.

Lifetimes: the server exits when the run ends (:func:`stop`, from ``onsuccess``/``onerror``:
its running children finish their jobs) or when the Snakemake process that started it is gone
(killed: it kills its running children first, within a tenth of a second); a child is killed when its
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

import atexit
import functools
import gc
import importlib
import os
import pickle
import select
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
from typing import Any, Callable, Iterable

#: The environment variable that names the run's socket ("off" disables the server).
ENV = "GEARMESH_JOBSERVER"
#: The environment variable that tells the job when its process (its script) started: the
#: pipeline measures the job's start-up from it, without importing this module.
STARTED_ENV = "GEARMESH_JOB_STARTED"
_HEADER = struct.Struct("!Q")
_CODE = struct.Struct("!i")
_server: subprocess.Popen | None = None
#: The server's socket and the modules it imported (:func:`start`, :func:`start_ahead`).
_server_path: str | None = None
_server_modules: frozenset[str] = frozenset()
#: The process compiling the kernels ahead of the jobs (:func:`compile_ahead`), and the read end of
#: a pipe whose only write end it holds: end of file once it has exited.
_compiler: subprocess.Popen | None = None
_compiled: int | None = None
#: What Snakemake sets to a job's thread count for the linear-algebra libraries (OpenBLAS reads it
#: once, when numpy loads it): the server's children are one-thread jobs with the same settings as
#: the job's own process would have, so that BLAS splits its work, and rounds, as it does there
#: (a multi-threaded LAPACK solve of the system deflection differs in the 8th digit).
THREAD_VARIABLES = ("OMP_NUM_THREADS", "GOTO_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")
#: glibc's malloc settings for the server and its jobs (``GLIBC_TUNABLES``, read when a process
#: starts; other C libraries ignore it): numpy's arrays of up to 32 MiB from the heap, not each a
#: fresh mapping, and freed memory kept for the next array, not handed back to the kernel, so that
#: a job does not fault in fresh zeroed pages for every temporary (by default glibc maps anything
#: above 128 KiB anew and returns heap tops above twice that: 59% of the default study's page
#: faults and 44% of its system time, measured). Numbers: glibc's upper limit of the mmap threshold
#: on 64-bit (``DEFAULT_MMAP_THRESHOLD_MAX``), and a trim threshold above any job's heap.
MALLOC_TUNABLES = {"glibc.malloc.mmap_threshold": str(32 << 20), "glibc.malloc.trim_threshold": str(1 << 30)}
#: Third-party modules the package imports inside functions (``import gearmesh`` stays light for
#: a command-line call), and those saving a PNG figure imports: imported once by the server
#: instead of by every job (tests/test_jobserver.py: every function-level import of the modules a
#: job can run is here). One that is not installed is skipped.
WARM_MODULES = ("jsonschema", "netCDF4", "numba", "numpy", "psutil", "pyamg", "pygad", "scipy.fft", "scipy.integrate",
                "scipy.interpolate", "scipy.linalg", "scipy.optimize", "scipy.sparse", "scipy.sparse.linalg",
                "scipy.stats", "scipy.stats.qmc", "skfem", "skfem.models.elasticity", "triangle", "xarray", "yaml",
                "matplotlib.backends.backend_agg", "mpl_toolkits.axes_grid1", "PIL.Image")


# --------------------------------------------------------------------------------------
# The job's side (workflow/scripts/*.py)
# --------------------------------------------------------------------------------------


def run(smk: Any, entry: str) -> None:
    """Run the job ``smk`` (the Snakemake object of a ``script:`` rule) through the pipeline
    function ``entry`` (e.g. "run_pair_stage"): in a child of the run's server when there is
    one, here otherwise. Exits with the job's exit code.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The job's Snakemake object (``input``, ``output``, ``params``, ``log``, ``threads``, ...).
    entry : str
        Name of the :mod:`gearmesh.pipeline` function that runs the job, e.g. ``"run_job"``.

    Returns
    -------
    None
        Returns only when the job ran here and succeeded; a job run on the server exits this
        process with its exit code (``SystemExit``), and a failed job exits non-zero.

    References
    ----------
    .. [1] Snakemake documentation, "Snakefiles and Rules": external scripts (the ``script``
       directive and its ``snakemake`` object).
    .. [2] Python documentation, :func:`socket.send_fds` (Python 3.9+): the streams' descriptors
       passed to the server.
    """
    code = _run_on_server(smk, entry)
    if code is not None:  # the script's work is done: its last collection would only traverse
        gc.freeze()  # Snakemake's modules (about 10 ms of each job's script, measured)
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
    if not path or path == "off" or not hasattr(socket, "send_fds") or getattr(smk, "threads", 1) != 1:
        return None  # no server, or a job of several threads (the server's children have one)
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
    ``create_time`` adds (up to a second: more than a job's start-up).

    Returns
    -------
    float or None
        Seconds since the epoch (s); None where /proc cannot be read.

    References
    ----------
    .. [1] proc(5), Linux manual page: ``/proc/[pid]/stat`` field 22 (``starttime``, clock ticks
       after boot) and ``/proc/uptime``.
    """
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
    fork and descriptor passing, not disabled by ``GEARMESH_JOBSERVER=off``.

    Parameters
    ----------
    workflow : snakemake.workflow.Workflow
        The run's workflow object (the Snakefile's ``workflow``): its deployment methods and
        whether it executes locally.

    Returns
    -------
    bool
        True when a server should be started.
    """
    if os.environ.get(ENV) == "off" or not _platform_serves():
        return False
    methods = {str(m).lower() for m in workflow.deployment_settings.deployment_method}
    if any(m for m in methods if any(k in m for k in ("conda", "apptainer", "singularity", "env_modules"))):
        return False
    return bool(workflow.local_exec) and not workflow.remote_exec


def _platform_serves() -> bool:
    """Whether a server can run here: ``fork`` and descriptor passing (``socket.send_fds``)."""
    return os.name == "posix" and hasattr(socket, "send_fds")


def start(modules: Iterable[str], timeout: float = 5.0) -> str | None:
    """Start the run's server with ``modules`` imported, export its socket in ``GEARMESH_JOBSERVER``
    for the jobs, and return the socket path (None if it did not come up within ``timeout``).

    A server this process started ahead for at least these modules (:func:`start_ahead`:
    ``gearmesh run``) becomes the run's instead. The server runs with one BLAS thread
    (:data:`THREAD_VARIABLES`) and the malloc settings of :data:`MALLOC_TUNABLES` (the user's own
    ``GLIBC_TUNABLES`` win). The kernels' compiler (:func:`compile_ahead`, started here unless the
    Snakefile already did) is handed to the server, whose jobs wait for it before they would
    compile a kernel themselves.

    Parameters
    ----------
    modules : iterable of str
        Dotted names of the modules the server imports before it takes jobs
        (:func:`rule_modules`).
    timeout : float
        How long to wait for the server's socket (s, default 5).

    Returns
    -------
    str or None
        The socket's path, also exported in ``GEARMESH_JOBSERVER``; None when the server exited
        or did not listen within ``timeout`` (it is stopped, and the jobs run alone).

    References
    ----------
    .. [1] The GNU C Library Reference Manual, chapter "Tunables": memory allocation tunables
       (``glibc.malloc.mmap_threshold``, ``glibc.malloc.trim_threshold``).
    """
    modules = list(modules)
    if _server is None or _server.poll() is not None or not set(modules) <= _server_modules:
        _stop_server()
        _spawn(modules)
    deadline = time.monotonic() + timeout
    while not os.path.exists(_server_path):
        if _server.poll() is not None or time.monotonic() > deadline:
            _stop_server()
            return None
        time.sleep(0.01)
    os.environ[ENV] = _server_path
    return _server_path


def start_ahead(modules: Iterable[str]) -> None:
    """Start a server with ``modules`` imported before Snakemake reads the Snakefile, without
    handing it to any job yet: its imports and the kernels' compile run on a free core while
    Snakemake builds its DAG, single-threaded. The Snakefile's ``onstart`` makes it the run's
    (:func:`start`); a run that ends without (a refused study, a cluster run) stops it at exit.
    Nothing where a server cannot run (no ``fork`` or descriptor passing) or where
    ``GEARMESH_JOBSERVER`` is set already (``off``, or a server of an outer run).

    Parameters
    ----------
    modules : iterable of str
        Dotted names of the modules the server imports (:func:`stage_modules`).

    Returns
    -------
    None
    """
    if _server is None and ENV not in os.environ and _platform_serves():
        atexit.register(stop)
        _spawn(list(modules))


def stage_modules() -> list[str]:
    """The modules of every stage's and every table's function and figures
    (:func:`gearmesh.registry.stages`) and the pipeline: what any study's rules can name
    (:func:`rule_modules`).

    Returns
    -------
    list of str
        Sorted dotted module names.
    """
    from .registry import stages

    jobs = [job for stage in stages().values() for job in (stage, *stage.tables)]
    specs = [spec for job in jobs for spec in (job.function, job.draws) if spec]
    return sorted({"gearmesh.pipeline", *(spec.partition(":")[0] for spec in specs)})


#: The socket folders' name: the prefix, the PID of the run that started the server, a random tail.
FOLDER_PREFIX = "gearmesh-jobs-"


def _spawn(modules: list[str]) -> None:
    """Start a server that imports ``modules`` (``_server``; its socket will be ``_server_path``),
    its socket in a private folder named after this process; first the folders of runs that are
    gone (:func:`remove_stale_folders`)."""
    global _server, _server_path, _server_modules
    remove_stale_folders(tempfile.gettempdir())
    folder = tempfile.mkdtemp(prefix=f"{FOLDER_PREFIX}{os.getpid()}-")  # mode 0700: this user's jobs only
    path = os.path.join(folder, "socket")
    compile_ahead()
    _server = subprocess.Popen([sys.executable, "-m", "gearmesh.jobserver", "serve", path, str(os.getpid()),
                                str(_compiled), *modules], stdin=subprocess.DEVNULL, env=_environment(),
                               pass_fds=(_compiled,))
    _server_path, _server_modules = path, frozenset(modules)


def remove_stale_folders(parent: str) -> list[str]:
    """Remove the socket folders in ``parent`` of this user's runs that are gone.

    A server removes its folder when it stops, and so does the run that started it; a run killed
    together with its server (``kill -9`` of the process group, the out-of-memory killer) leaves
    it behind. A folder is stale when the process its name carries (:data:`FOLDER_PREFIX`, the
    run's PID) no longer exists; a folder of another user, of a process that lives (or of a new
    one that took its PID), or without a PID in its name is left alone.

    Parameters
    ----------
    parent : str
        The folder holding the socket folders (the system's temporary folder).

    Returns
    -------
    list of str
        The folders removed.
    """
    removed = []
    try:
        names = os.listdir(parent)
    except OSError:
        return removed
    for name in names:
        if not name.startswith(FOLDER_PREFIX):
            continue
        pid, sep, _ = name[len(FOLDER_PREFIX):].partition("-")
        if not (sep and pid.isdigit()):
            continue
        folder = os.path.join(parent, name)
        try:
            if os.stat(folder).st_uid != os.getuid():
                continue
            os.kill(int(pid), 0)
        except ProcessLookupError:
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
        except OSError:  # gone meanwhile, or a process of another user: not ours to judge
            continue
    return removed


def compile_ahead() -> None:
    """Start compiling the numba kernels (:func:`kernels`) in a process of their own, unless this
    process already started that: a fresh clone's compile (about 5 s of CPU) then runs on a free
    core while Snakemake reads the Snakefile and builds its DAG, single-threaded, instead of after
    the server has started. Where numba's cache already holds them the process only checks that
    (:func:`kernels_cached`) and exits. It ends with this process at the latest (:func:`stop`, or
    at exit: a dry run, a report).

    Returns
    -------
    None
        The compiler started (``_compiler``; ``_compiled`` reads end of file once it has exited).
    """
    global _compiler, _compiled
    if _compiler is not None:
        return
    read, write = os.pipe()
    _compiler = subprocess.Popen([sys.executable, "-m", "gearmesh.jobserver", "compile"], stdin=subprocess.DEVNULL,
                                 env=_environment(), pass_fds=(write,))
    os.close(write)
    _compiled = read
    atexit.register(_stop_compiler)


def _stop_compiler() -> None:
    """Stop the kernels' compiler if it still runs (the run is over) and close its pipe."""
    global _compiler, _compiled
    if _compiler is not None:
        if _compiler.poll() is None:
            _compiler.terminate()
        _compiler.wait()
        _compiler = None
    if _compiled is not None:
        os.close(_compiled)
        _compiled = None


def _compile() -> None:
    """The compiler's work (:func:`compile_ahead`): the kernels compiled into numba's cache where
    it lacks them; it stops when the process that started it is gone (Snakemake killed), as the
    server does."""
    parent = os.getppid()

    def exit_with_parent() -> None:  # numba's compiler (LLVM, through ctypes) lets this thread run
        while os.getppid() == parent:
            time.sleep(0.2)
        os._exit(1)

    threading.Thread(target=exit_with_parent, daemon=True).start()
    if not kernels_cached():
        warm_kernels()


def _environment() -> dict[str, str]:
    """The environment of the server and the compiler: this one, with Snakemake's thread variables
    of a one-thread job and :data:`MALLOC_TUNABLES` (the user's ``GLIBC_TUNABLES`` win)."""
    return {**os.environ, **dict.fromkeys(THREAD_VARIABLES, "1"), "GLIBC_TUNABLES": _tunables(os.environ)}


def _tunables(environ: dict[str, str]) -> str:
    """``GLIBC_TUNABLES`` for the server: the user's, with :data:`MALLOC_TUNABLES` where it sets
    none of its own."""
    given = [t for t in environ.get("GLIBC_TUNABLES", "").split(":") if t]
    names = {t.partition("=")[0] for t in given}
    return ":".join(given + [f"{k}={v}" for k, v in MALLOC_TUNABLES.items() if k not in names])


def stop() -> None:
    """Stop the run's server (its running children finish their jobs), remove its socket and stop
    the kernels' compiler if it still runs.

    SIGTERM, then SIGKILL if it has not exited within 10 s; ``GEARMESH_JOBSERVER`` is unset.

    Returns
    -------
    None
    """
    os.environ.pop(ENV, None)
    _stop_server()
    _stop_compiler()


def _stop_server() -> None:
    """Stop the server this process started, if any, and remove its socket's folder."""
    global _server, _server_path, _server_modules
    if _server is not None:
        _server.terminate()
        try:
            _server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            _server.kill()
            _server.wait()
        _server = None
    if _server_path is not None:
        shutil.rmtree(os.path.dirname(_server_path), ignore_errors=True)
    _server_path, _server_modules = None, frozenset()


def rule_modules(rules: Iterable[Any]) -> list[str]:
    """The gearmesh modules named by the rules' ``params.function`` and ``params.figures``
    ("package.module:function@digest", or a param function carrying it as ``.spec``), and the
    pipeline: what the server imports.

    Parameters
    ----------
    rules : iterable of snakemake.rules.Rule
        The workflow's rules (objects with an iterable ``params``).

    Returns
    -------
    list of str
        Sorted dotted module names, ``"gearmesh.pipeline"`` among them.
    """
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


def warm_steps(compiled: int) -> list[Callable[[], Any]]:
    """What the server does while no job waits, one step at a time (a job that arrives meanwhile
    waits for one step at most; a step that answers False is not done yet and is tried again):
    import :data:`WARM_MODULES`, then, once the kernels' compiler (:func:`compile_ahead`) has
    exited, load the compiled kernels from numba's cache. From the call on, a job forked while the
    compiler runs waits for it when it first calls a kernel and then loads that kernel from the
    cache (:func:`_after_compiler`): each kernel is compiled once per run (the dynamics sweep alone
    takes seconds), not again by every job that needs it meanwhile.

    Parameters
    ----------
    compiled : int
        Read end of the compiler's pipe: end of file once the compiler has exited.

    Returns
    -------
    list of callable
        The steps, in order, each called without arguments.
    """
    release = _after_compiler(compiled)

    def load() -> bool:
        if not select.select([compiled], [], [], 0)[0]:  # readable: end of file, the compiler has exited
            return False
        try:
            warm_kernels()
        finally:
            release()
        return True

    return [*(lambda m=m: importlib.import_module(m) for m in WARM_MODULES), _warm_png, load]


def kernels() -> tuple[Any, ...]:
    """The numba dispatchers of the compiled kernels the jobs call from Python (those the sweep
    calls compile into it).

    Returns
    -------
    tuple
        The dispatchers: the dynamics RK4 sweep (``integrate._sweep``) and the contact
        solver's load-sum and law-scale loops (``ltca_solve._kernel('loop')``, ``('scales')``).
    """
    from .dynamics import integrate
    from . import ltca_solve

    return integrate._sweep, ltca_solve._kernel("loop"), ltca_solve._kernel("scales")


def kernels_cached() -> bool:
    """Whether numba's on-disk cache holds every kernel of :func:`warm_kernels` for its module's
    current source (then loading them costs a fraction of a second); False when it cannot tell.

    Returns
    -------
    bool
        True when every kernel of :func:`kernels` has an index in numba's cache.
    """
    try:
        return all(len(k._cache._cache_file._load_index()) > 0 for k in kernels())
    except Exception:  # noqa: BLE001 - numba's cache internals: not knowing means compiling aside
        return False


def _after_compiler(done: int) -> Callable[[], None]:
    """Make this process (and every child it forks from now on) wait, before it compiles any of
    the :func:`kernels`, until the descriptor ``done`` (the read end of a pipe whose only write
    end the kernels' compiler holds) reads end of file: the compiler has exited, its cache written,
    and the kernel loads from numba's cache instead of compiling again. A compiler that died leaves
    the compile to the job, as without a server. numba compiles a dispatcher for new argument
    types through its ``_compile_for_args`` method, which tries the on-disk cache first: an
    instance attribute of that name is called in its place, and removed before the real one runs.
    Returns what ends the wait for good in this process (once it has loaded the kernels): the hook
    removed, ``done`` closed."""
    waiting = kernels()

    def unhook() -> None:
        for k in waiting:
            k.__dict__.pop("_compile_for_args", None)

    def wait_then_compile(kernel: Any, *args: Any, **kws: Any) -> Any:
        while os.read(done, 4096):  # nobody writes: returns b"" when the compiler has exited
            pass
        unhook()
        return kernel._compile_for_args(*args, **kws)

    def release() -> None:
        unhook()
        os.close(done)

    for kernel in waiting:
        kernel._compile_for_args = functools.partial(wait_then_compile, kernel)
    return release


def _warm_png() -> None:
    """The image plugins Pillow loads on its first save (matplotlib writes PNGs through it)."""
    from PIL import Image

    Image.preinit()


def warm_kernels() -> None:
    """Load every compiled kernel (numba, ``cache=True``) from its on-disk cache by running it once
    on a tiny problem through the functions the jobs call, so that it loads with the types the jobs
    use: the contact-driven dynamics of the shipped default pair (mesh force table: the load sums
    of :func:`gearmesh.ltca_solve.load_sums`; the RK4 sweep with its shooting,
    :mod:`gearmesh.dynamics.integrate`) and a tabulated contact solve of its points
    (:func:`gearmesh.ltca_solve.solve_contact_tabulated`). A fork inherits the loaded machine code.

    Returns
    -------
    None
        Its work is the side effect: the kernels loaded (compiled and cached where the cache
        lacks them).
    """
    import numpy as np

    from .dynamics.population import POPULATION_CONTACT, dynamic_factors, population_dynamics
    from .gear import pair_geometry
    from .pairfile import example_pair, load_pair
    from .ltca_solve import solve_contact_tabulated

    geom = pair_geometry(load_pair(example_pair("helical_z29_71_m5")))
    setup = population_dynamics(geom, [1000.0], [1000.0, 5000.0], positions=16, approaches=8,
                                contact=POPULATION_CONTACT.with_(points=5, method="transition"))
    dynamic_factors(setup, np.zeros((1, 2, 6)), np.zeros((1, 2)))
    layout = setup.layout
    solve_contact_tabulated(layout.gaps()[:2], layout.compliance[:2] - layout.law.linear, np.full(2, 1e4), layout.law)


def serve(path: str, parent: int, compiled: int, modules: Iterable[str]) -> None:
    """Listen on ``path``, import ``modules``, then fork a child per connection until the process
    ``parent`` (the Snakemake run) is gone or a SIGTERM arrives; in between, the
    :func:`warm_steps` (each in this one thread, so a fork never copies a half-done import).

    Parameters
    ----------
    path : str
        The socket's path (in a private directory, removed on exit).
    parent : int
        Process id of the Snakemake run; the server stops (killing its children) when it is gone.
    compiled : int
        Read end of the kernels' compiler's pipe (:func:`compile_ahead`, :func:`warm_steps`).
    modules : iterable of str
        Dotted module names to import first; one that fails fails in the job, with its message.

    Returns
    -------
    None
        When the run ended and every child was reaped.

    References
    ----------
    .. [1] Python documentation, :func:`gc.freeze` ("right before fork()": copy-on-write
       friendly), :func:`os.fork`, :func:`socket.recv_fds`.
    """
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
    children: set[int] = set()
    steps = warm_steps(compiled)
    while not stopping and os.getppid() == parent:
        _reap(children)
        # idle, it looks for the end of the run every 50 ms (a SIGTERM does not interrupt accept,
        # PEP 475): the run's stop waited up to half a second for it, at the end of every run
        listener.settimeout(0.01 if steps else 0.05)
        try:
            conn, _ = listener.accept()
        except (TimeoutError, InterruptedError):
            if steps:
                try:  # best effort: a step that fails leaves that work to the jobs
                    if steps[0]() is not False:
                        steps.pop(0)
                except Exception:  # noqa: BLE001
                    steps.pop(0)
            continue
        # the server's objects out of reach of the child's garbage collector, whose passes would
        # otherwise write to each of them and so copy every page of the server's heap it touches
        # (Python's gc.freeze, "right before fork()"): 12% of the default study's page faults, measured
        gc.freeze()
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
    if sys.argv[1] == "compile":
        _compile()
    else:
        serve(sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5:])
