"""One contact compliance (issue 28): the linear TVMS with the LTCA law's tangent at the load is the
LTCA's own loaded (tangent) stiffness on the same contact lines, and the tangent scales as the law says."""


import numpy as np
import pytest

from gearmesh.contact_model import ContactModel
from gearmesh.gear import pair_geometry
from gearmesh.ltca import contact_tangent_compliance, ltca
from gearmesh.ltca_model import contact_law
from gearmesh.pairfile import example_pair, load_pair
from gearmesh.stiffness import hertz_compliance_transverse, mesh_stiffness


@pytest.fixture(scope="module")
def geom():
    return pair_geometry(load_pair(example_pair("helical_z29_71_m5")))


def test_tvms_with_the_tangent_is_the_ltcas_stiffness(geom):
    """Unmodified pair, 1000 N·m, the LTCA without tip-edge candidates beyond the active zone
    (corner_extension 0: the same contact lines as the slice model): mean tangent stiffness within
    0.5 % (the line load varies along the lines; the TVMS takes its mean)."""
    t1 = 1000.0
    k = mesh_stiffness(geom, n_positions=64, method="transition", components=False,
                       contact_compliance=contact_tangent_compliance(geom, t1)).mean
    res = ltca(geom, [t1], 64, ContactModel(points=200, method="transition", extension=0.0))
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


def test_edge_tangent_is_the_ltcas_stiffness_beyond_the_active_zone(geom):
    """The LTCA's tangent (the sum of every loaded point's tangent) against finite differences of two
    solves at F and F(1 + 1e-6); the tip-edge part of it is positive, below the whole, and a 20 µm
    tip relief over 3 mm takes most of it away (fewer tips reach the mating flank under load)."""
    from gearmesh.ltca import edge_tangent_stiffness

    res = ltca(geom, [1000.0], 32, ContactModel(points=50, method="transition"))
    k_edge = edge_tangent_stiffness(res)[0]
    assert np.any(k_edge > 0) and np.all(k_edge >= 0) and np.all(k_edge < res.stiffness[0])
    # the tangent is the mesh's at its misalignment (the shafts' f_sh follows the mean load, not the ripple)
    res2 = ltca(geom, [1000.0 * (1 + 1e-6)], 32, ContactModel(points=50, method="transition"),
                misalignment=res.misalignment)
    fd = (res2.force[0] - res.force[0]) / (res2.lte[0] - res.lte[0])
    np.testing.assert_allclose(res.stiffness[0], fd, rtol=1e-4)
    pair = load_pair(example_pair("helical_z29_71_m5"))
    relieved = pair_geometry(pair.with_changes(modification=tuple(_relief(m) for m in pair.modification)))
    k_rel = edge_tangent_stiffness(ltca(relieved, [1000.0], 32, ContactModel(points=50, method="transition")))[0]
    assert np.mean(k_rel) < 0.5 * np.mean(k_edge)


def _relief(mod):
    from dataclasses import replace

    return replace(mod, tip_relief=20e-6, tip_relief_length=3e-3)


def test_tvms_with_the_loaded_extension_is_the_ltcas_stiffness(geom):
    """The linear TVMS (tangent contact term) plus the LTCA's tip-edge tangent at the same load is the
    LTCA's tangent stiffness on the same rolls: mean within 0.5 %, every position within 3 %."""
    from gearmesh.ltca import with_loaded_extension

    t1 = 1000.0
    K = mesh_stiffness(geom, n_positions=64, method="transition", components=False,
                       contact_compliance=contact_tangent_compliance(geom, t1)).K
    K_ext = with_loaded_extension(geom, K, t1, contact=ContactModel(method="transition"))
    k_l = ltca(geom, [t1], 64, ContactModel(points=50, method="transition")).stiffness[0]
    assert np.mean(K_ext) > 1.05 * np.mean(K)  # the unrelieved tips carry load beyond the zone
    assert np.mean(K_ext) == pytest.approx(np.mean(k_l), rel=5e-3)
    np.testing.assert_allclose(K_ext, k_l, rtol=3e-2)


def test_tvms_and_contact_put_the_mesh_mode_within_3_percent():
    """Issue 28's 'done when': the default pair at 1000 N·m, its own supports and rigid ones."""
    from gearmesh.datasets.dynamics import build_pair_model
    from gearmesh.dynamics import mesh_mode
    from gearmesh.pairfile import pair_to_dict

    data = pair_to_dict(load_pair(example_pair("helical_z29_71_m5")))
    rigid = {k: v for k, v in data.items() if k not in ("shaft_diameter_mm", "bearing_span_mm")}
    rigid.update(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid")
    for pair in (load_pair(data), load_pair(rigid)):
        n = {}
        for exc in ("tvms", "contact"):
            m = build_pair_model(pair, 1000.0, on="pinion", backlash_um=60, excitation=exc, method="transition",
                                 slices=100, positions=64)
            n[exc] = m.modes()["frequency_Hz"][mesh_mode(m)]
        assert n["tvms"] == pytest.approx(n["contact"], rel=0.03)
