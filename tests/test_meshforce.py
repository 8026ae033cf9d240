"""The mesh force table (gearmesh.meshforce) and the compiled load sums it is made of
(gearmesh.ltca_solve.load_sums): against each point's contact law inverted on its own by Newton's
method, for both contact laws, and beyond the universal inverse's table."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from gearmesh.contact_model import TABLE_CONTACT
from gearmesh.body import RIGID_WEBS
from gearmesh.gear import pair_geometry
from gearmesh.ltca_solve import _invert, law_point_scales, load_sums
from gearmesh.ltca_model import ContactLaw
from gearmesh.pairfile import load_pair
from gearmesh.meshforce import table_layout, tabulate

PAIR = Path(__file__).resolve().parents[1] / "config" / "pairs" / "helical_z29_71_m5.yaml"


@pytest.fixture(scope="module")
def geom():
    """The teeth's table: rigid webs (the bodies' series term: tests/test_body.py)."""
    return pair_geometry(load_pair(PAIR).with_changes(body=RIGID_WEBS))


@pytest.mark.parametrize("law", ["palmgren", "linear"])
def test_table_is_the_sum_of_each_points_own_inversion(geom, law):
    """F, dF/dx and the entering pair's load at every (row, approach): Σ over the points of the
    root of c·q + coef·q^m = x − g by Newton per point (:func:`gearmesh.ltca_solve._invert`), to 1e-12."""
    layout = table_layout(geom, 16, TABLE_CONTACT.with_(points=20, contact_law=law))
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


def test_points_beyond_the_universal_table_are_inverted_exactly():
    """A point whose y = d/(c·Q) lies below the universal table (ln y < −80) sends its row to the
    exact inversion: the sums equal each point's own Newton root, with and without the mask."""
    law = ContactLaw("palmgren", 1e-9, 1 / 1.11, 0.0, 1e-3)
    c = 1e-10
    big_q = (law.coefficient / c) ** (1 / (1 - law.exponent))
    gap = np.array([[0.0, 1e-7], [0.0, np.inf]])
    x = np.array([[1e-40 * c * big_q, 1e-6, 2e-6], [1e-9, 1e-6, 2e-6]])  # row 0, column 0: ln y ≈ −92
    mask = np.array([[True, False], [False, False]])
    force, stiff, masked = load_sums(gap, np.full((2, 2), c), x, law, mask)
    d = x[:, :, None] - gap[:, None, :]
    q, dq = _invert(np.where(np.isfinite(d), d, -1.0), c, law.coefficient, law.exponent)
    np.testing.assert_allclose(force, q.sum(axis=2), rtol=1e-12)
    np.testing.assert_allclose(stiff, dq.sum(axis=2), rtol=1e-12)
    np.testing.assert_allclose(masked, np.where(mask[:, None, :], q, 0.0).sum(axis=2), rtol=1e-12)
    assert force[0, 0] > 0


#: A power law and a linear one, for the load sums' two branches.
_LAWS = [ContactLaw("palmgren", 1e-9, 1 / 1.11, 0.0, 1e-3), ContactLaw("linear", 0.0, 1.0, 0.0, 1e-3)]


@pytest.mark.parametrize("law", _LAWS)
def test_load_sums_of_chosen_rows_with_their_scales_are_those_of_the_rows_taken_out(law):
    """load_sums over ``rows`` of the full arrays, with the points' scales computed once
    (law_point_scales), gives bit for bit what it gives on those rows taken out and computing the
    scales itself: the Newton iteration of the tabulated solve passes the same points many times."""
    rng = np.random.default_rng(4)
    gap = np.where(rng.random((12, 30)) < 0.2, np.inf, rng.random((12, 30)) * 2e-6)
    comp = 1e-10 * (1 + rng.random((12, 30)))
    mask = rng.random((12, 30)) < 0.3
    rows = np.array([7, 2, 2, 11, 0])
    x = np.sort(rng.random((rows.size, 4)) * 3e-6, axis=1)
    alone = load_sums(gap[rows], comp[rows], x, law, mask[rows], points=True)
    chosen = load_sums(gap, comp, x, law, mask, points=True, scales=law_point_scales(comp, law), rows=rows)
    for a, b in zip(alone, chosen):
        np.testing.assert_array_equal(a, b)
    assert np.all(alone[0][:, -1] > 0) and np.any(alone[2] > 0)


@pytest.mark.parametrize("law", _LAWS)
def test_load_sums_with_shared_compliance_rows_are_those_of_the_rows_repeated(law):
    """load_sums with ``compliance_rows`` (rows at the same points: each distinct row's compliance
    and scales once) gives bit for bit what it gives with those compliances repeated row for row,
    over chosen rows too (and on those rows taken out), a row beyond the universal table (the Newton
    fallback) included."""
    rng = np.random.default_rng(5)
    comp = 1e-10 * (1 + rng.random((3, 30)))
    which = np.array([2, 0, 0, 1, 2, 1, 0, 1])
    gap = np.where(rng.random((which.size, 30)) < 0.2, np.inf, rng.random((which.size, 30)) * 2e-6)
    mask = rng.random(gap.shape) < 0.3
    rows = np.array([7, 2, 2, 5, 0])
    x = np.sort(rng.random((rows.size, 4)) * 3e-6, axis=1)
    if law.coefficient:  # a point below the universal table (ln y ≈ −92): its row summed again by invert_tabulated
        gap[rows[-1], 0] = 0.0
        c = comp[which[rows[-1]], 0]
        x[-1, 0] = 1e-40 * c * (law.coefficient / c) ** (1 / (1 - law.exponent))
    repeated = load_sums(gap, comp[which], x, law, mask, points=True, scales=law_point_scales(comp[which], law),
                         rows=rows)
    shared = load_sums(gap, comp, x, law, mask, points=True, scales=law_point_scales(comp, law), rows=rows,
                       compliance_rows=which)
    alone = load_sums(gap[rows], comp[which[rows]], x, law, mask[rows], points=True)
    for a, b, c in zip(repeated, shared, alone):
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(a, c)
    assert np.all(repeated[0][:, -1] > 0)
