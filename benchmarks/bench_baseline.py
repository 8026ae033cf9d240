"""The package as it was before issue 17's kernel work, callable beside today's, so that a
benchmark measures old and new in one run on one machine.

``baseline_call(module, function, *args)`` runs ``function(*args)`` of a benchmark module of this
folder in a child process whose ``gearmesh`` is the source tree of commit :data:`BASELINE` (the
main branch when the GA/impact/dynamics speed work of issue 17 began), and returns its result.
The tree is taken from git once (``git archive``) into a folder under the system's temporary
directory, where numba also caches the old compiled loops, so only the first run compiles. The
benchmark functions called this way time themselves and use only the API both versions share.
Without git history (a source archive) it returns None and the benchmark reports no baseline.
"""

from __future__ import annotations

import io
import os
import pickle
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

from common import ROOT

#: main when the work began (after "LICENSE: the MIT text pyproject declares").
BASELINE = "568c63b7c664b2ff0ad3b76302db28974c28af34"
BASELINE_NAME = f"gearmesh at {BASELINE[:7]} (before issue 17's GA/impact/dynamics kernels), same run"


def baseline_source() -> Path | None:
    """The folder holding the baseline's ``gearmesh`` package (extracted once), or None."""
    target = Path(tempfile.gettempdir()) / f"gearmesh-baseline-{BASELINE[:12]}"
    if (target / "gearmesh" / "__init__.py").exists():
        return target
    try:
        tar = subprocess.run(["git", "-C", str(ROOT), "archive", BASELINE, "src/gearmesh"], check=True,
                             capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    partial = target.with_name(target.name + f".{os.getpid()}.tmp")
    with tarfile.open(fileobj=io.BytesIO(tar)) as archive:
        archive.extractall(partial, filter="data")
    (partial / "src" / "gearmesh").rename(partial / "gearmesh")
    try:
        partial.rename(target)
    except OSError:  # another run extracted it meanwhile
        pass
    return target


def baseline_call(module: str, function: str, *args):
    """``module.function(*args)`` run with the baseline's gearmesh in a child process (its result,
    pickled back), or None without the baseline's source."""
    source = baseline_source()
    if source is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        request, answer = Path(tmp) / "request.pkl", Path(tmp) / "answer.pkl"
        request.write_bytes(pickle.dumps((module, function, args)))
        code = ("import importlib, pickle, sys\n"
                f"sys.path[:0] = [{str(source)!r}, {str(Path(__file__).parent)!r}]\n"
                f"module, function, args = pickle.loads(open({str(request)!r}, 'rb').read())\n"
                "import gearmesh\n"
                f"assert gearmesh.__file__.startswith({str(source)!r}), gearmesh.__file__\n"
                "result = getattr(importlib.import_module(module), function)(*args)\n"
                f"open({str(answer)!r}, 'wb').write(pickle.dumps(result))\n")
        env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
        subprocess.run([sys.executable, "-c", code], check=True, env=env)
        return pickle.loads(answer.read_bytes())
