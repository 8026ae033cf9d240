"""The mesh force table (gearmesh.meshforce): the compiled tabulation against each point's contact
law inverted on its own by Newton's method, for both contact laws, and its fallback beyond the
universal inverse's table."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearmesh.gear import load_pair, pair_geometry
from gearmesh.ltca import _TABLE_LOG_Y, _invert, _universal_inverse
from gearmesh.meshforce import _tabulate_rows, table_layout, tabulate

PAIR = Path(__file__).resolve().parents[1] / "config" / "pairs" / "seed000_case.yaml"


@pytest.fixture(scope="module")
def geom():
    return pair_geometry(load_pair(PAIR))


@pytest.mark.parametrize("law", ["palmgren", "linear"])
def test_table_is_the_sum_of_each_points_own_inversion(geom, law):
    """F, dF/dx and the entering pair's load at every (row, approach): Σ over the points of the
    root of c·q + coef·q^m = x − g by Newton per point (:func:`gearmesh.ltca._invert`), to 1e-12."""
    layout = table_layout(geom, positions=16, points=20, contact_law_name=law)
    params = np.zeros((2, 6))
    params[0] = [0.0, 15e-6, 0.0, 2e-3, 8e-6, 5e-3]
    gap = layout.gaps(params, (4e-6, -3e-6))
    force = 3 * 1000.0 / float(geom.base_radius[0])
    table = tabulate(layout, gap, force, approaches=12)
    d = table.gap_min[:, None, None] + table.approach[None, :, None] - gap[:, None, :]
    q, dq = _invert(np.where(np.isfinite(d), d, -1.0), np.broadcast_to(layout.compliance[:, None, :], d.shape),
                    layout.law.coefficient, layout.law.exponent)
    for got, want in ((table.force, q.sum(axis=2)), (table.stiffness, dq.sum(axis=2)),
                      (table.enter_force, np.where(layout.enter_mask[:, None, :], q, 0.0).sum(axis=2))):
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * float(np.max(want)))
    assert np.all(table.force[:, -1] >= force * (1 - 1e-12))  # every row reaches force_max


def test_points_beyond_the_universal_table_are_flagged():
    """A point whose y = d/(c·Q) lies below the universal table (ln y < −80) is not summed but its
    row flagged, for the exact inversion."""
    m, coef = 1 / 1.11, 1e-9
    v_tab, s_tab = _universal_inverse(m)
    lo, _, h = _TABLE_LOG_Y
    c = 1e-10
    big_q = (coef / c) ** (1 / (1 - m))
    gap = np.array([[0.0, 1e-3], [0.0, 1.0]])
    u = np.array([0.0, 1e-40 * c * big_q, 1e-6])  # the middle column: y = 1e-40 on point 0 (ln y ≈ −92)
    out = [np.zeros((2, 3)) for _ in range(3)]
    outside = np.zeros(2, dtype=bool)
    _tabulate_rows(gap, np.full((2, 2), c), np.zeros((2, 2), dtype=bool), gap.min(axis=1), u, coef, m, v_tab, s_tab,
                   lo, h, *out, outside)
    assert outside.tolist() == [True, True]
    q, _ = _invert(np.array([1e-6]), c, coef, m)
    np.testing.assert_allclose(out[0][:, 2], q[0], rtol=1e-12)  # the points inside the table are summed
