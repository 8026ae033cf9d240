"""Shared by the benchmark modules: the project root, the timers, the study's settings as the
workflow hands them to a stage, and the equality checks every benchmark row carries.

Equality: a row that compares today's code with a baseline carries ``max_rel_diff`` (the largest
relative difference of the results) and ``equal`` (whether it is within ``tolerance``, 1e-6 unless
the row says otherwise and says why: ``expected_difference`` and the bound it checks).
``benchmarks/run.py`` exits non-zero when a row's ``equal`` is false, never on a time.
"""

from __future__ import annotations

import contextlib
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASE_PAIR = ROOT / "config/pairs/helical_z29_71_m5.yaml"
#: The equality every baseline must meet unless a row states why a difference is expected.
TOLERANCE = 1e-6


def timed_calls(func, repeats: int, warm_up: bool = True):
    """(median wall s, median CPU s, last result, least CPU s) of ``repeats`` calls of ``func``
    (after one warm-up call unless ``warm_up`` is false). On a machine shared with other work the
    least CPU time is the steadiest figure."""
    if warm_up:
        func()
    walls, cpus, result = [], [], None
    for _ in range(max(1, repeats)):
        c0, w0 = time.process_time(), time.perf_counter()
        result = func()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return statistics.median(walls), statistics.median(cpus), result, min(cpus)


def median_seconds(func, repeats: int) -> tuple[float, object]:
    """Median wall time (s) of ``repeats`` calls of ``func`` and the last result."""
    wall, _, result, _ = timed_calls(func, repeats, warm_up=False)
    return wall, result


def max_rel_diff(new, reference) -> float:
    """Largest |new − reference|/|reference| over the entries (inf where one is finite and the
    other not, or where the reference is 0 and ``new`` is not)."""
    a, b = np.asarray(new, dtype=float), np.asarray(reference, dtype=float)
    if a.shape != b.shape:
        return float("inf")
    if not np.array_equal(np.isfinite(a), np.isfinite(b)):
        return float("inf")
    ok = np.isfinite(b)
    a, b = a[ok], b[ok]
    if not a.size:
        return 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(b != 0, np.abs(a - b) / np.abs(b), np.where(a == b, 0.0, np.inf))
    return float(rel.max())


def equality(new, reference, tolerance: float = TOLERANCE) -> dict:
    """The equality fields of a row: ``max_rel_diff`` of ``new`` against ``reference`` (one array
    or matching sequences of arrays) and whether it is within ``tolerance``."""
    pairs = list(zip(new, reference)) if isinstance(new, (list, tuple)) else [(new, reference)]
    diff = max(max_rel_diff(a, b) for a, b in pairs)
    return {"max_rel_diff": diff, "tolerance": tolerance, "equal": bool(diff <= tolerance)}


def bounded_difference(diff: float, bound: float, why: str) -> dict:
    """The equality fields of a row whose baseline differs from today's code for a stated reason:
    ``max_rel_diff``, the ``expected_difference`` (why) and whether the difference is within the
    ``bound`` that reason gives."""
    return {"max_rel_diff": float(diff), "expected_difference": why, "bound": float(bound),
            "equal": bool(diff <= bound)}


def study_config() -> dict:
    """The default study's config (config/config.yaml)."""
    import yaml

    return yaml.safe_load((ROOT / "config/config.yaml").read_text())


def stage_settings(section: str, run: str | None = None, config: dict | None = None) -> dict:
    """The settings the workflow hands the stage of config section ``section`` (its run ``run``
    for a stage per run), as workflow/rules/common.smk's stage_params builds them: the section
    (or the run's entry) and the sections its stage declaration carries."""
    from gearmesh.registry import stage_of

    config = study_config() if config is None else config
    own = config[section][run] if run is not None else config.get(section, {})
    return {**own, **{s: config.get(s) for s in stage_of(section).carries}}


class Swap:
    """Every reference to ``module.name`` in the loaded ``gearmesh`` modules replaced by
    ``make_replacement(original)`` inside a ``with`` block, and the calls counted. A target the
    package no longer has is left out (``missing``); :func:`swapped` raises when the benchmarked code
    called none of the replacements, so that a baseline cannot silently become the code it is
    compared with when that code stops calling what the benchmark replaces."""

    def __init__(self, target: str, make_replacement):
        import importlib

        module, _, self.name = target.rpartition(".")
        self.target = target
        self.original = getattr(importlib.import_module(module), self.name, None)
        self.missing = self.original is None
        self.calls = 0
        self._patched: list = []
        if self.missing:
            return
        inner = make_replacement(self.original)

        def counted(*args, **kwargs):
            self.calls += 1
            return inner(*args, **kwargs)

        self.replacement = counted

    def __enter__(self) -> "Swap":
        if self.missing:
            return self
        for mod in list(sys.modules.values()):
            if getattr(mod, "__name__", "").startswith("gearmesh") and getattr(mod, self.name, None) is self.original:
                setattr(mod, self.name, self.replacement)
                self._patched.append(mod)
        return self

    def __exit__(self, *exc) -> None:
        for mod in self._patched:
            setattr(mod, self.name, self.original)
        self._patched.clear()


@contextlib.contextmanager
def swapped(*swaps: Swap):
    """All of ``swaps`` at once; yields the list of the targets that were called (filled on leaving)
    and raises on leaving when none was (:class:`Swap`)."""
    called: list[str] = []
    with contextlib.ExitStack() as stack:
        for s in swaps:
            stack.enter_context(s)
        before = [s.calls for s in swaps]
        yield called
        called.extend(s.target for s, b in zip(swaps, before) if s.calls > b)
    if not called:
        raise RuntimeError(f"the baseline replaced {[s.target for s in swaps if not s.missing]} but the benchmarked "
                           "code called none of them: it no longer computes through them, so the baseline would be "
                           "the code it is compared with; update the benchmark")
