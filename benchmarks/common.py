"""Shared by the benchmark modules: the project root and the median timer."""

from __future__ import annotations

import statistics
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def median_seconds(func, repeats: int) -> tuple[float, object]:
    """Median wall time (s) of ``repeats`` calls of ``func`` and the last result."""
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result
