"""Supports of the gear bodies (issue 28): the closed forms against independent computations, the
pair-file keys, the default pair's values recomputed from their stated inputs, rigid supports as
the torsional limit of ISO 6336-1's n_E1, and the mesh damping as the mesh mode's modal damping."""

import math

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg

from gearmesh.body import mesh_body_compliance
from gearmesh.cli import main
from gearmesh.datasets.dynamics import build_pair_model
from gearmesh.dynamics import mesh_mode
from gearmesh.errors import GearmeshInputError
from gearmesh.gear import pair_geometry
from gearmesh.pairfile import example_pair, load_pair, pair_to_dict
from gearmesh.stiffness import iso6336_stiffness
from gearmesh.supports import in_series, read_supports, roller_bearing_stiffness, shaft_bending_stiffness

SUPPORT_KEYS = ("bearing_radial_stiffness_N_per_um", "bearing_axial_stiffness_N_per_um", "shaft_diameter_mm",
                "bearing_span_mm")


def _default_pair(**supports):
    data = {k: v for k, v in pair_to_dict(load_pair(example_pair("helical_z29_71_m5"))).items() if k not in SUPPORT_KEYS}
    data.update(supports)
    return load_pair(data)


def test_shaft_bending_against_the_unit_load_integral():
    """48EI/L³ against Maxwell–Mohr's δ = ∫ M m /(EI) dx of the simply supported beam, central load."""
    E, d, L = 210e9, 0.06, 0.15
    EI = E * math.pi * d**4 / 64
    moment = lambda x: 0.5 * min(x, L - x)  # unit central load: M = m
    delta = scipy.integrate.quad(lambda x: moment(x) ** 2 / EI, 0, L, points=[L / 2])[0]
    assert shaft_bending_stiffness(E, d, L) == pytest.approx(1 / delta, rel=1e-10)
    assert in_series(2e9, math.inf, 2e9) == pytest.approx(1e9)


def test_roller_bearing_stiffness_is_the_tangent_of_palmgrens_law():
    """Tangent = 1/(dδ/dF) by a central difference of the deflection δ(F) it is built from."""
    Z, length, alpha = 15, 0.0125, math.radians(15)

    def radial_deflection(F):  # m: Q_max = 4.08 F/(Z cos α), two raceways, δ_r = δ_n / cos α
        q = 4.08 * F / (Z * math.cos(alpha))
        return 2 * 3.84e-5 * q**0.9 / (length * 1e3) ** 0.8 * 1e-3 / math.cos(alpha)

    def axial_deflection(F):
        q = F / (Z * math.sin(alpha))
        return 2 * 3.84e-5 * q**0.9 / (length * 1e3) ** 0.8 * 1e-3 / math.sin(alpha)

    F, h = 6000.0, 1.0
    k_r, k_a = roller_bearing_stiffness(F, F, Z, length, alpha)
    assert k_r == pytest.approx(2 * h / (radial_deflection(F + h) - radial_deflection(F - h)), rel=1e-6)
    assert k_a == pytest.approx(2 * h / (axial_deflection(F + h) - axial_deflection(F - h)), rel=1e-6)


def test_default_pair_supports_follow_from_their_stated_inputs():
    """helical_z29_71_m5.yaml's numbers recomputed from its comment: tapered roller bearings 30212 / 30228
    (α 15°, roller (D − d)/4, length = diameter, pitch 1.4 diameters), the design load, spans 150/180 mm."""
    pair = load_pair(example_pair("helical_z29_71_m5"))
    geom = pair_geometry(pair)
    f_bt = 1000.0 / float(geom.base_radius[0])
    f_a = f_bt * math.tan(geom.base_helix_angle)
    expected_r, expected_a = [], []
    for d, D in ((60, 110), (140, 250)):
        dw = 0.25 * (D - d)
        z = round(math.pi * 0.5 * (d + D) / (1.4 * dw))
        k_r, k_a = roller_bearing_stiffness(f_bt / 2, f_a, z, dw * 1e-3, math.radians(15))
        expected_r.append(2 * k_r)
        expected_a.append(k_a)
    sup = pair.supports
    assert not sup.defaulted
    assert np.allclose(sup.bearing_radial, expected_r, rtol=2e-3)
    assert np.allclose(sup.bearing_axial, expected_a, rtol=2e-3)
    E = pair.material.youngs_modulus
    assert sup.radial(E)[0] == pytest.approx(in_series(expected_r[0], shaft_bending_stiffness(E, 0.06, 0.15)),
                                             rel=2e-3)


@pytest.mark.parametrize("spec, field", [
    ({"bearing_radial_stiffness_N_per_um": -5, "bearing_axial_stiffness_N_per_um": 10},
     "bearing_radial_stiffness_N_per_um"),
    ({"bearing_radial_stiffness_N_per_um": [100, "soft"], "bearing_axial_stiffness_N_per_um": 10},
     "bearing_radial_stiffness_N_per_um[1]"),
    ({"bearing_radial_stiffness_N_per_um": [1, 2, 3], "bearing_axial_stiffness_N_per_um": 10},
     "bearing_radial_stiffness_N_per_um"),
    ({"bearing_radial_stiffness_N_per_um": 100}, "bearing_axial_stiffness_N_per_um"),
    ({"bearing_radial_stiffness_N_per_um": 100, "bearing_axial_stiffness_N_per_um": 10, "shaft_diameter_mm": 60},
     "bearing_span_mm"),
    ({"shaft_diameter_mm": 60, "bearing_span_mm": 100}, "bearing_radial_stiffness_N_per_um"),
    ({"bearing_radial_stiffness_N_per_um": 100, "bearing_axial_stiffness_N_per_um": 10, "shaft_diameter_mm": 0,
      "bearing_span_mm": 100}, "shaft_diameter_mm"),
    # a span with the gear's placement but no shaft: the shaft's diameter is named, not a KeyError
    ({"bearing_radial_stiffness_N_per_um": 100, "bearing_axial_stiffness_N_per_um": 10, "bearing_span_mm": 100,
      "torque_side": "leading"}, "shaft_diameter_mm"),
])
def test_bad_supports_get_one_error_naming_the_key(spec, field):
    with pytest.raises(GearmeshInputError) as err:
        read_supports(spec)
    assert err.value.field == field


def test_bad_supports_in_a_pair_file_exit_2(tmp_path, capsys):
    text = example_pair("helical_z29_71_m5").read_text().replace("bearing_axial_stiffness_N_per_um: [230, 458]",
                                                              "bearing_axial_stiffness_N_per_um: [230, stiff]")
    path = tmp_path / "helical_z29_71_m5.yaml"
    path.write_text(text)
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("gearmesh: error: bearing_axial_stiffness_N_per_um[1]") and len(err.strip().splitlines()) == 1


def test_supports_round_trip_and_default():
    pair = _default_pair(bearing_radial_stiffness_N_per_um=["rigid", 500], bearing_axial_stiffness_N_per_um="rigid")
    assert load_pair(pair_to_dict(pair)).supports == pair.supports
    assert pair.supports.bearing_radial == (math.inf, 5e8)
    default = _default_pair()
    assert default.supports.defaulted and default.supports.bearing_radial == (1.5e8, 1.5e8)
    assert "the low-fluctuation paper" in default.supports.describe(210e9)


def test_rigid_supports_give_the_torsional_model_and_isos_resonance():
    """Both directions rigid and, as ISO's c' assumes, rigid webs: one coordinate left (the relative
    rotation), the mesh mode at √(k/m_e), and the contact-excited resonance within 3 % of ISO
    6336-1's n_E1 = 30000/(π z1)·√(c_γα/m_red), m_red = J1* J2*/(J1* r_b2² + J2* r_b1²) (ISO
    6336-1:2019 §6.5.3, eqs. (6), (7)). A pair file that describes no body is the teeth alone, the
    same model; described solid discs held at the bore (gearmesh.body) put the bodies' tilt in
    series: the mode falls with √ of the mean stiffness, below n_E1."""
    pair = _default_pair(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid",
                         web_thickness_mm="rigid")
    bores_only = _default_pair(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid")
    assert mesh_body_compliance(pair_geometry(bores_only)) == 0.0
    alone = build_pair_model(bores_only, 1000.0, on="pinion", backlash_um=60, excitation="contact")
    geom = pair_geometry(pair)
    model = build_pair_model(pair, 1000.0, on="pinion", backlash_um=60, excitation="contact")
    assert model.n == 1
    k_t = model.meshes[0].k_mean * model.cos_beta_b**2
    J1, J2 = (float(j) for j in geom.inertia)
    rb1, rb2 = (float(r) for r in geom.base_radius)
    m_red = J1 * J2 / (J1 * rb2**2 + J2 * rb1**2)
    md = model.modes()
    assert abs(md["eigenvalue"][0]) == pytest.approx(math.sqrt(k_t / m_red), rel=1e-9)
    iso = iso6336_stiffness(geom)
    b = geom.face_width * 1e3
    n_e1 = 30000 / (math.pi * pair.teeth[0]) * math.sqrt(iso["c_gamma_alpha"] / (m_red / b))
    n_model = md["frequency_Hz"][0] / model.mesh_frequency_per_rpm
    assert n_model == pytest.approx(n_e1, rel=0.03)
    assert alone.modes()["frequency_Hz"][0] / alone.mesh_frequency_per_rpm == pytest.approx(n_model, rel=1e-12)
    solid = _default_pair(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um="rigid",
                          hub_diameter_mm=[60.0, 140.0])  # solid discs held at the bore on rigid supports
    c_body = mesh_body_compliance(pair_geometry(solid))
    with_body = build_pair_model(solid, 1000.0, on="pinion", backlash_um=60, excitation="contact")
    k_body = with_body.meshes[0].k_mean * with_body.cos_beta_b**2  # along the transverse line, as c_body
    assert k_body == pytest.approx(1 / (1 / k_t + c_body), rel=0.01)  # in series, K(t)'s ripple aside
    n_body = with_body.modes()["frequency_Hz"][0] / with_body.mesh_frequency_per_rpm
    assert n_body == pytest.approx(n_model * math.sqrt(k_body / k_t), rel=1e-9)
    assert n_body < 0.85 * n_e1  # the thin discs' tilt, which ISO's c' does not have (docs/validation.md)


@pytest.mark.parametrize("excitation", ["contact", "tvms"])
def test_mesh_damping_is_the_mesh_modes_modal_damping(excitation):
    """The stated ζ is found in the complex eigenvalues of the *unreduced* system (rigid-body
    rotation kept, its zero eigenvalues dropped), built from the model's full matrices."""
    pair = load_pair(example_pair("helical_z29_71_m5"))
    model = build_pair_model(pair, 1000.0, on="pinion", backlash_um=60, excitation=excitation, damping_ratio=0.07)
    full = model.full
    g = full["G"][0]
    k, c = model.meshes[0].k_mean, model.damping[0]
    M = full["M"]
    K = full["K_bearing"] + k * np.outer(g, g)
    C = full["C_bearing"] + c * np.outer(g, g)
    n = M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
    lam, vec = scipy.linalg.eig(A)
    keep = (lam.imag > 1e-6 * np.max(np.abs(lam)))
    lam, phi = lam[keep], vec[:n, keep]
    phi = np.real(phi * np.exp(-1j * np.angle(phi[np.argmax(np.abs(phi), axis=0), np.arange(phi.shape[1])])))
    mesh_share = k * (g @ phi) ** 2 / np.einsum("ij,ik,kj->j", phi, K, phi)
    i = int(np.argmax(mesh_share))
    assert -lam[i].real / abs(lam[i]) == pytest.approx(0.07, rel=1e-6)
    assert model.modes()["damping_ratio"][mesh_mode(model)] == pytest.approx(0.07, rel=1e-6)


def test_rigid_radial_supports_in_the_dataset_are_zero_displacements():
    """Radial supports rigid, axial compliant: the dataset keeps its (gear, direction) layout, x and
    y are exactly zero, z moves, and the attrs state the supports and what ζ means."""
    from gearmesh.datasets.dynamics import dynamics_dataset

    pair = _default_pair(bearing_radial_stiffness_N_per_um="rigid", bearing_axial_stiffness_N_per_um=[230, 458])
    ds = dynamics_dataset(pair, torques_Nm=1000.0, speeds_rpm=[3000.0, 5000.0], sample_speeds_rpm=[5000.0],
                          backlash_um=60, excitation="tvms", refine_resonances=False, method="transition",
                          slices=50, positions=64)
    for name in ("displacement_std", "displacement_series", "velocity_peak_to_peak"):
        v = ds[name].sel(direction=["x", "y"]) if "direction" in ds[name].dims else None
        assert v is not None and np.all(v.values == 0), name
        assert np.any(ds[name].sel(direction="z").values != 0), name
    assert "from the pair file" in ds.attrs["supports"] and "rigid" in ds.attrs["supports"]
    assert "the teeth alone" in ds.attrs["gear_body"]  # no body described: the teeth alone, named in the result
    assert "mesh mode" in ds.attrs["damping_ratio_meaning"]


@pytest.mark.parametrize("scale", [0.1, 1.0, 10.0, math.inf])
def test_damping_search_by_the_determinant_lemma_matches_the_eigenvalue_secant(scale):
    """The fast damper (a root on the ζ-ray, :func:`_ray_damping_scale`) against the secant on the
    complex eigenvalues of the state matrix, supports scaled from soft to rigid: the same scale to
    1e-8, and the damped model's mesh mode has the stated ζ."""
    from dataclasses import replace

    from gearmesh.dynamics import model as dm

    geom = pair_geometry(load_pair(example_pair("helical_z29_71_m5")))
    sup = geom.pair.supports
    kr, ka = np.mean(sup.radial(geom.pair.material.youngs_modulus)), np.mean(sup.axial())
    bare = dm.pair_model(geom, 1000.0, np.full(64, 7e8), excitation="tvms", mesh_damping=0.0,
                         bearing={"k_radial": float(kr * scale), "k_axial": float(ka * scale)})
    c0 = np.array([2 * 0.07 * math.sqrt(7e8 * dm._equivalent_mass(bare.cos_beta_b, geom.base_radius, geom.inertia))])
    s_ray, s_secant = dm._ray_damping_scale(bare, c0, 0.07), dm._secant_damping_scale(bare, c0, 0.07)
    assert s_ray == pytest.approx(s_secant, rel=1e-8)
    damped = replace(bare, damping=s_ray * c0)
    assert damped.modes()["damping_ratio"][mesh_mode(damped)] == pytest.approx(0.07, rel=1e-9)


def test_bearings_that_damp_the_mesh_mode_enough_leave_no_mesh_damper():
    """Bearing dampers of 10⁵ N·s/m already damp the mesh mode beyond ζ = 0.02: the search falls back
    to the eigenvalue secant, which returns no damper (not a negative one)."""
    geom = pair_geometry(load_pair(example_pair("helical_z29_71_m5")))
    from gearmesh.dynamics import model as dm

    model = dm.pair_model(geom, 1000.0, np.full(64, 3e8), excitation="tvms", damping_ratio=0.02,
                          bearing={"c_radial": 1e5, "c_axial": 1e5})
    assert model.damping[0] == 0.0
    assert model.modes()["damping_ratio"][mesh_mode(model)] > 0.02
