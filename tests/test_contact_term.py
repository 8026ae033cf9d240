"""One contact compliance (issue 28): the linear TVMS with the LTCA law's tangent at the load is the
LTCA's own loaded (tangent) stiffness on the same contact lines, and the tangent scales as the law says."""

import math

import numpy as np
import pytest

from gearmesh.gear import example_pair, load_pair, pair_geometry
from gearmesh.ltca import contact_law, contact_tangent_compliance, ltca
from gearmesh.stiffness import hertz_compliance_transverse, mesh_stiffness


@pytest.fixture(scope="module")
def geom():
    return pair_geometry(load_pair(example_pair("seed000_case")))


def test_tvms_with_the_tangent_is_the_ltcas_stiffness(geom):
    """Unmodified pair, 1000 N·m, the LTCA without tip-edge candidates beyond the active zone
    (corner_extension 0: the same contact lines as the slice model): mean tangent stiffness within
    0.5 % (the line load varies along the lines; the TVMS takes its mean)."""
    t1 = 1000.0
    k = mesh_stiffness(geom, n_positions=64, method="transition", components=False,
                       contact_compliance=contact_tangent_compliance(geom, t1)).mean
    res = ltca(geom, [t1], positions=64, points=200, method="transition", extension=0.0)
    assert float(np.mean(res.stiffness[0, :64])) == pytest.approx(k, rel=5e-3)
    k_ys = mesh_stiffness(geom, n_positions=64, method="transition", components=False).mean
    assert k_ys > 1.1 * k  # Yang & Sun's constant is the stiffer contact (docs/validation.md)


def test_tangent_compliance_is_the_laws_derivative(geom):
    """c = dδ_t/df of Palmgren's law at f = F_bt/(b εα), by a central difference, and ∝ f^-0.1."""
    t1 = 1000.0
    f = t1 / float(geom.base_radius[0]) / (geom.face_width * geom.eps_alpha)
    law = contact_law(geom, 1.0)
    h = 1e-4 * f
    numeric = (law.coefficient * (f + h) ** law.exponent - law.coefficient * (f - h) ** law.exponent) / (2 * h)
    assert contact_tangent_compliance(geom, t1) == pytest.approx(numeric, rel=1e-7)
    assert contact_tangent_compliance(geom, 2 * t1) / contact_tangent_compliance(geom, t1) == pytest.approx(2**-0.1)
    assert contact_tangent_compliance(geom, t1) > 3 * hertz_compliance_transverse(geom)
    with pytest.raises(Exception):
        contact_tangent_compliance(geom, -1.0)
