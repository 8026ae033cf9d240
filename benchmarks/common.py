"""Shared by the benchmark modules: the project root and the timers."""

from __future__ import annotations

import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def timed_calls(func, repeats: int, warm_up: bool = True):
    """(median wall s, median CPU s, last result, least CPU s) of ``repeats`` calls of ``func``
    (after one warm-up call unless ``warm_up`` is false). On a machine shared with other work the
    least CPU time is the steadiest figure."""
    if warm_up:
        func()
    walls, cpus, result = [], [], None
    for _ in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        result = func()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return statistics.median(walls), statistics.median(cpus), result, min(cpus)


def median_seconds(func, repeats: int) -> tuple[float, object]:
    """Median wall time (s) of ``repeats`` calls of ``func`` and the last result."""
    wall, _, result, _ = timed_calls(func, repeats, warm_up=False)
    return wall, result
