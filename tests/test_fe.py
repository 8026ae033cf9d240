"""Finite-element tooth compliance (gearmesh.fe): independent checks of the FE model and the
project's check of its potential-energy cantilevers. Coarse meshes: the whole file runs in
a few seconds."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from pairs import STEEL, low_fluctuation_pair1  # noqa: E402
from gearmesh.contact_model import ContactModel
from gearmesh import fe, fe_elastic, fe_tables  # noqa: E402
from gearmesh import slice_compliance as sc  # noqa: E402
from gearmesh import stiffness as st  # noqa: E402
from gearmesh.errors import GearmeshInputError  # noqa: E402
from gearmesh.gear import pair_geometry  # noqa: E402
from gearmesh.pairfile import load_pair

E, NU = 210e9, 0.3


@pytest.fixture(scope="module")
def p1():
    return pair_geometry(load_pair(low_fluctuation_pair1()))


def _mid_rolls(geom, gear, n=3):
    return np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], n)


# ----------------------------------------------------------------------------- the beam


def _cantilever_tip(length: float, depth: float, size: float, plane: str = "stress") -> float:
    """Mean deflection (m) of the free end of a cantilever of unit width, clamped at x = 0,
    under a unit end shear distributed parabolically over the end (Timoshenko & Goodier §21)."""
    from skfem import FacetBasis, LinearForm, asm

    v = np.array([[0, 0], [length, 0], [length, depth], [0, depth]], float)
    mesh = fe_elastic.triangulate(v, np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), max_area=0.5 * size**2)
    solver = fe_elastic.elastic_solver(mesh, E, NU, plane, clamped=lambda x: x[0] < 1e-12 * length)

    @LinearForm
    def shear(w, p):  # τ = 3F/(2h)·(1 − (2η/h)²), η from the axis: resultant F = 1 N per m
        eta = p.x[1] - 0.5 * depth
        return 1.5 / depth * (1 - (2 * eta / depth) ** 2) * w[1]

    end = mesh.facets_satisfying(lambda x: np.isclose(x[0], length))
    f = asm(shear, FacetBasis(mesh, solver.basis.elem, facets=end))
    u = solver.solve(f[:, None])
    t, _ = fe_elastic.section_rigid_motion(solver, u, (length * (1 - 1e-9), 0.0), (length * (1 - 1e-9), depth))
    return float(t[1, 0])


def _timoshenko_tip(length: float, depth: float) -> float:
    """Timoshenko beam: F L³/(3EI) + F L/(κGA), κ = 5/6 (rectangle), unit width, F = 1 N per m."""
    inertia, area, g = depth**3 / 12, depth, E / (2 * (1 + NU))
    return length**3 / (3 * E * inertia) + length / (5 / 6 * g * area)


@pytest.mark.parametrize("slenderness, tol", [(10, 0.005), (4, 0.02)])
def test_cantilever_beam_matches_timoshenko(slenderness, tol):
    """A clamped rectangle (plane stress, P2) against Timoshenko's beam: within 0.5 % at
    L/h = 10 and 2 % at L/h = 4 (the fully clamped edge adds a small root compliance
    that beam theory lacks)."""
    depth = 0.01
    length = slenderness * depth
    fe_tip = _cantilever_tip(length, depth, depth / 6)
    beam = _timoshenko_tip(length, depth)
    assert fe_tip == pytest.approx(beam, rel=tol)
    assert fe_tip > length**3 / (3 * E * depth**3 / 12)  # shear and root add to Euler-Bernoulli


def test_plane_strain_beam_is_stiffer_by_one_minus_nu_squared():
    """Plane strain: E' = E/(1−ν²) in bending (Timoshenko & Goodier §16)."""
    depth, length = 0.01, 0.1
    ratio = _cantilever_tip(length, depth, depth / 4, "strain") / _cantilever_tip(length, depth, depth / 4, "stress")
    assert ratio == pytest.approx(1 - NU**2, rel=0.01)


# ----------------------------------------------------------------------------- the tooth


def test_mesh_convergence(p1):
    """Compliance against element size (0.2, 0.1, 0.05 m_n on the loaded tooth): the
    differences shrink, and 0.1 → 0.05 moves the compliance by less than 0.5 %."""
    rho = _mid_rolls(p1, 0)
    c = [fe.tooth_compliance(p1, 0, rho, size=h).total for h in (0.2, 0.1, 0.05)]
    d1, d2 = np.abs(c[1] - c[0]), np.abs(c[2] - c[1])
    assert np.all(d2 < d1)
    assert np.all(d2 / c[2] < 0.005)


def test_symmetry_of_either_flank(p1):
    """The same load mirrored onto the left flank gives the same compliance (mesh not mirrored)."""
    res = fe.tooth_compliance(p1, 1, _mid_rolls(p1, 1, 4), size=0.15)
    assert np.allclose(res.total_left, res.total, rtol=3e-3)


def test_rim_thickness_wind_up_and_solid_disc_limit(p1):
    """Bore radius from 0.85 r_f down to 0.05 r_f (the rim thickens towards a solid disc).

    * The body's torsional wind-up (mean rotation of the root circle) is Lamé's annulus in
      torsion, r_b²/(4πG)·(1/r_int² − 1/r²) per unit width, within 0.5 %.
    * The local compliance (tooth and foundation relative to the body's rigid motion at the
      root circle) converges to the solid-disc value: it grows down to 0.2 r_f, and the last
      halving of the bore moves it by < 0.5 %. It *rises* as the rim thickens: a clamped bore close under
      the root is a rigid support, so a thin rim on a clamped bore is stiffer, as in
      Sainsot et al. (2004), whose foundation term grows with h_f = r_f/r_int.
    * The clamped total keeps growing (wind-up ~ 1/r_int², net-force shift ~ log r_int):
      global body modes, not a tooth property.
    """
    rf, rb = float(p1.root_radius[0]), float(p1.base_radius[0])
    g = E / (2 * (1 + NU))
    rho = np.array([p1.rho_sap[0], p1.rho_eap[0]])
    res = [fe.tooth_compliance(p1, 0, rho, size=0.2, bore_radius=f * rf) for f in (0.85, 0.5, 0.2, 0.1, 0.05)]
    for r, f in zip(res, (0.85, 0.5, 0.2, 0.1, 0.05)):
        lame = rb**2 / (4 * math.pi * g) * (1 / (f * rf) ** 2 - 1 / r.wind_up_radius**2)
        assert r.wind_up == pytest.approx(np.full(2, lame), rel=5e-3)
    local = np.array([r.local for r in res])
    total = np.array([r.total for r in res])
    assert np.all(np.diff(local[:3], axis=0) > 0)  # 0.85 → 0.5 → 0.2 r_f; below, within the mesh's noise
    assert np.all(np.abs(local[-1] - local[-2]) / local[-1] < 0.005)
    assert np.all(np.diff(total, axis=0) > 0)


def test_fe_agrees_with_pem_for_thin_long_teeth():
    """Where the cantilever's assumptions hold best — a slender tooth (αn 16°, addendum 1.5,
    dedendum 1.75 m_n, 60 teeth) loaded at the tip, plane stress as the PEM's E and G — the
    FE tooth deflection equals the PEM bending + shear + axial within 2 %, the body part
    Sainsot's foundation within 12 %, the total within 5 %. At the root of the active flank
    (a stubby cantilever) the beam part is not expected to agree."""
    geom = pair_geometry(load_pair({
        "name": "slender", "teeth": [60, 60], "normal_module_mm": 2, "normal_pressure_angle_deg": 16,
        "helix_angle_deg": 0, "face_width_mm": 20, "addendum_coefficient": 1.5, "dedendum_coefficient": 1.75,
        "bore_radius_mm": [30, 30], "material": dict(STEEL)}))
    rho = np.array([geom.rho_eap[0]])
    res = fe.tooth_compliance(geom, 0, rho, plane="stress", size=0.1)
    pem = sc.tooth_slice_compliance(sc.tooth_model(geom, 0, "transition"), rho)
    beam = pem["bending"] + pem["shear"] + pem["axial"]
    assert res.tooth[0] == pytest.approx(beam[0], rel=0.02)
    assert res.body[0] == pytest.approx(pem["fillet"][0], rel=0.12)
    assert res.total[0] == pytest.approx(beam[0] + pem["fillet"][0], rel=0.05)


def test_load_direction_is_the_line_of_action(p1):
    """The FE load points are the involute points of the stiffness module, the load line is
    tangent to the base circle (distance r_b from the centre)."""
    rho = _mid_rolls(p1, 0, 5)
    profile, sector = fe.gear_sector(p1, 0, rho, size=0.3)
    x, y, a1, _ = sc.contact_point(sc.tooth_model(p1, 0, "transition"), rho)
    assert np.allclose(sector.vertices[sector.right_loads], np.column_stack([x, y]), rtol=0, atol=1e-12)
    assert np.allclose(np.abs(x * np.sin(a1) - y * np.cos(a1)), p1.base_radius[0], rtol=1e-12)


def test_sector_converges_to_the_whole_gear(p1):
    """A sector with free cuts is more compliant than the whole gear and approaches it as it
    keeps more teeth."""
    rho = np.array([p1.rho_sap[0]])
    c = [fe.tooth_compliance(p1, 0, rho, size=0.2, neighbours=k).total[0] for k in (1, 3, 7, None)]
    assert c[0] > c[1] > c[2] > c[3]
    assert (c[2] - c[3]) / c[3] < 0.02


# ----------------------------------------------------------------------------- as a method


def test_fe_is_a_stiffness_method(p1):
    """``method='fe'`` builds the same SliceComplianceTable and runs through mesh_stiffness
    and the LTCA's model; the table is computed once per gear (cache)."""
    from gearmesh.ltca_model import ltca_model

    tabs = (sc.slice_compliance_table(p1, 0, "fe"), sc.slice_compliance_table(p1, 1, "fe"))
    assert tabs[0].method == "fe" and isinstance(tabs[0], sc.SliceComplianceTable)
    variant = pair_geometry(load_pair(low_fluctuation_pair1(name="renamed", face_width_mm=25)))
    assert fe_tables.fe_tooth_compliance_cached(p1, 0) is fe_tables.fe_tooth_compliance_cached(variant, 0)  # same section
    assert np.all(np.diff(tabs[0].total(tabs[0].rho)) > 0)  # more compliant towards the tip
    k = st.mesh_stiffness(p1, 60, method="fe", tables=tabs)
    assert np.isinf(k.components["shear_pinion"]).all()  # no separate shear compliance in 2-D
    ref = st.mesh_stiffness(p1, 60, method="transition", components=False)
    assert 1.0 < k.mean / ref.mean < 1.5  # the FE tooth is stiffer than the transition PEM
    model = ltca_model(p1, 8, ContactModel(points=10, method="fe"), tables=tabs)
    assert model.method == "fe"


def test_refusals(p1):
    with pytest.raises(GearmeshInputError):
        fe.tooth_compliance(p1, 0, [p1.rho_eap[0]], plane="shell")
    with pytest.raises(GearmeshInputError):
        fe.tooth_compliance(p1, 0, [p1.rho_eap[0] * 1.5])
    with pytest.raises(GearmeshInputError):
        fe.tooth_compliance(p1, 0, [p1.rho_eap[0]], size=0)
    with pytest.raises(GearmeshInputError):
        sc.tooth_model(p1, 0, "fe")  # no cantilever behind the FE method


def test_fe_compliance_dataset(tmp_path):
    """The workflow's fe_compliance.nc: every variable with units and long_name; the FE column
    equals tooth_compliance; plane strain stiffer than plane stress; the figure is drawn."""
    from gearmesh.datasets.fe import fe_compliance_dataset
    from gearmesh.plots.fe import plot_fe_compliance

    pair = load_pair(low_fluctuation_pair1())
    ds = fe_compliance_dataset(pair, size=0.3, roll_nodes=5)
    for name in ds.variables:
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    geom = pair_geometry(pair)
    direct = fe.tooth_compliance(geom, 1, ds["roll"].values[1], size=0.3)
    assert np.allclose(ds["fe_compliance"].values[1], direct.total, rtol=1e-12)
    assert np.all(ds["fe_compliance"].values < ds["fe_compliance_plane_stress"].values)
    assert plot_fe_compliance(ds, tmp_path / "fe.png").stat().st_size > 10_000


def test_workflow_tables_are_read_not_recomputed(monkeypatch):
    """A stage handed its pair's fe_compliance.nc takes the FE tables from it (no meshing) and
    they equal the file's columns; a file of another geometry is refused."""
    from gearmesh.datasets.fe import fe_compliance_dataset
    from gearmesh.datasets.stiffness import stiffness_dataset

    pair = load_pair(low_fluctuation_pair1())
    geom = pair_geometry(pair)
    ds = fe_compliance_dataset(pair, size=0.3, roll_nodes=5)
    monkeypatch.setattr(fe_tables, "_CACHE", {})
    monkeypatch.setattr(fe_tables, "tooth_compliance", lambda *a, **k: pytest.fail("meshed although the table was given"))
    fe_tables.seed_cache(ds, geom)
    for gear in (0, 1):
        table = fe_tables.fe_slice_compliance_table(geom, gear, n_roll=5, size=0.3)
        np.testing.assert_array_equal(table.values["bending"] + table.values["fillet"], ds["fe_compliance"].values[gear])
    other = pair_geometry(load_pair(low_fluctuation_pair1(teeth=[31, 49])))
    with pytest.raises(GearmeshInputError, match="fe_compliance"):
        fe_tables.seed_cache(ds, other)
    # through a stage: the default settings' file, then stiffness_dataset(method='fe') reads it
    monkeypatch.undo()
    full = fe_compliance_dataset(pair)
    monkeypatch.setattr(fe_tables, "_CACHE", {})
    monkeypatch.setattr(fe_tables, "tooth_compliance", lambda *a, **k: pytest.fail("meshed although the table was given"))
    out = stiffness_dataset(pair, method="fe", slices=20, positions=24, fe_compliance=full)
    assert float(out["mean_stiffness"]) > 0


# ----------------------------------------------------------------------------- where the compliance sits


def _slender():
    return pair_geometry(load_pair({
        "name": "slender", "teeth": [60, 60], "normal_module_mm": 2, "normal_pressure_angle_deg": 16,
        "helix_angle_deg": 0, "face_width_mm": 20, "addendum_coefficient": 1.5, "dedendum_coefficient": 1.75,
        "bore_radius_mm": [30, 30], "material": dict(STEEL)}))


def test_tooth_and_body_split_on_one_mesh(p1):
    """The tooth on a rigid base (clamped on its root chord), the body under a rigid tooth and
    their coupling add up to the whole gear; the coupling (the root section's warping, which
    no cantilever-plus-foundation model has) is positive and under 12 % of the total; the
    rigid-tooth limit is reached (E × 1e4 vs × 1e5 within 0.1 %)."""
    rho = _mid_rolls(p1, 0)
    res = fe.tooth_body_split(p1, 0, rho, size=0.2)
    assert np.allclose(res.tooth_rigid_base + res.body_rigid_tooth + res.interaction, res.total, rtol=1e-12)
    assert np.all(res.interaction > 0) and np.all(res.interaction < 0.12 * res.total)
    whole = fe.tooth_compliance(p1, 0, rho, "stress", size=0.2).total
    assert np.allclose(res.total, whole, rtol=0.01)  # the chord segment only changes the mesh
    old = fe.RIGID
    try:
        fe.RIGID = 1e5
        stiffer = fe.tooth_body_split(p1, 0, rho, size=0.2).body_rigid_tooth
    finally:
        fe.RIGID = old
    assert np.allclose(stiffer, res.body_rigid_tooth, rtol=1e-3)


def test_beam_and_foundation_against_their_fe_problems():
    """Slender tooth loaded at the tip (the cantilever's best case), plane stress: the FE tooth
    on a rigid base is within 8 % of the PEM beam (bending + shear + axial) and below it (the
    flared fillet is stiffer than a beam of its horizontal sections); the FE body under a
    rigid tooth is within 25 % of Sainsot's foundation and below it; Sainsot is nearer the
    body plus the coupling (its fit carried the root warping in the foundation)."""
    geom = _slender()
    rho = np.array([geom.rho_eap[0]])
    res = fe.tooth_body_split(geom, 0, rho, size=0.1)
    pem = sc.tooth_slice_compliance(sc.tooth_model(geom, 0, "transition"), rho)
    beam = pem["bending"] + pem["shear"] + pem["axial"]
    assert 0.92 < res.tooth_rigid_base[0] / beam[0] < 1.0
    assert 0.75 < res.body_rigid_tooth[0] / pem["fillet"][0] < 1.0
    assert abs(res.body_rigid_tooth[0] + res.interaction[0] - pem["fillet"][0]) < \
        abs(res.body_rigid_tooth[0] - pem["fillet"][0])


def test_tooth_in_plane_strain_on_a_body_in_plane_stress_lies_between(p1):
    rho = _mid_rolls(p1, 1)
    mixed = fe.tooth_body_split(p1, 1, rho, "strain", size=0.2, body_plane="stress").total
    strain = fe.tooth_body_split(p1, 1, rho, "strain", size=0.2).total  # the same mesh
    stress = fe.tooth_body_split(p1, 1, rho, "stress", size=0.2).total
    assert np.all(strain < mixed) and np.all(mixed < stress)


def test_weber_approach_is_the_integral_of_johnsons_stresses():
    """Weber's closed form against a numerical integral of the strain along the axis of a
    Hertzian strip (Johnson 1985: σ_z, σ_x on the axis; plane strain and plane stress)."""
    from scipy.integrate import quad

    a, d = 1e-4, 1.5e-3
    p0 = 2.0 / (math.pi * a)  # unit resultant
    sz = lambda z: -p0 * a / math.sqrt(a * a + z * z)  # noqa: E731
    sx = lambda z: -p0 * ((a * a + 2 * z * z) / math.sqrt(a * a + z * z) - 2 * z) / a  # noqa: E731
    strain = -quad(lambda z: ((1 - NU**2) * sz(z) - NU * (1 + NU) * sx(z)) / E, 0, d, epsrel=1e-12)[0]
    stress = -quad(lambda z: (sz(z) - NU * sx(z)) / E, 0, d, epsrel=1e-12)[0]
    assert fe.weber_approach(d, a, E, NU, "strain") == pytest.approx(strain, rel=1e-9)
    assert fe.weber_approach(d, a, E, NU, "stress") == pytest.approx(stress, rel=1e-9)


def test_hertz_strip_against_point_load_and_weber(p1):
    """At C a Hertzian strip and a point load of the same resultant give the same deflection
    (0.2 %: Saint-Venant, |PC| ≫ a), so the point load of the stage is no approximation there;
    the FE approach of P to C falls with the half-width as Weber's log term,
    −2(1−ν²)/(πE) per unit ln a (3 %), within 15 % of Weber's half-plane value (the tooth is
    not a half-plane: a constant offset)."""
    rho = 0.5 * (p1.rho_sap[0] + p1.rho_eap[0])
    res = [fe.contact_approach(p1, 0, rho, a, size=0.1) for a in (0.05e-3, 0.2e-3)]
    for r in res:
        assert r.at_c == pytest.approx(r.point_at_c, rel=2e-3)
        assert r.approach == pytest.approx(r.weber, rel=0.15)
    slope = (res[0].approach - res[1].approach) / math.log(4.0)
    assert slope == pytest.approx(2 * (1 - NU**2) / (math.pi * E), rel=0.03)
