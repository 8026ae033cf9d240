"""The 3-D finite-element tooth (gearmesh.fe3d): mesh, geometry of the helical load, the
plane-strain / plane-stress bounds and mesh convergence on coarse meshes (seconds)."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("skfem")
pytest.importorskip("triangle")

from pairs import low_fluctuation_pair1  # noqa: E402
from gearmesh import fe, fe3d  # noqa: E402
from gearmesh import slice_compliance as sc  # noqa: E402
from gearmesh.errors import GearmeshInputError  # noqa: E402
from gearmesh.gear import pair_geometry  # noqa: E402
from gearmesh.pairfile import load_pair


def test_extruded_mesh_is_conforming_and_keeps_the_volume():
    """Two triangles extruded through three layers: volume = area × height, positive
    orientation; twisted, each straight-edged layer is off by O(Δθ²), the whole by O(Δθ); every inner
    face shared by two tetrahedra (the side-face diagonals agree)."""
    p = np.array([[0.0, 1.0, 1.0, 0.0], [0.0, 0.0, 1.0, 1.0]]) + 2.0
    t = np.array([[0, 1, 2], [0, 2, 3]]).T

    def volumes(mesh):
        a, b, c, d = (mesh.p[:, mesh.t[i]] for i in range(4))
        return np.einsum("ij,ij->j", np.cross(b - a, c - a, axis=0), d - a) / 6

    assert volumes(fe3d.extrude(p, t, np.linspace(0.0, 0.5, 4), twist=0.0)).sum() == pytest.approx(0.5, rel=1e-12)
    errors = [abs(volumes(fe3d.extrude(p, t, np.linspace(0.0, 0.5, k + 1), twist=0.3)).sum() - 0.5) for k in (3, 6)]
    assert errors[1] == pytest.approx(errors[0] / 2, rel=0.05)
    mesh = fe3d.extrude(p, t, np.linspace(0.0, 0.5, 4), twist=0.3)
    assert np.all(volumes(mesh) > 0)
    faces = np.sort(np.concatenate([mesh.t[[0, 1, 2]], mesh.t[[0, 1, 3]], mesh.t[[0, 2, 3]], mesh.t[[1, 2, 3]]], axis=1),
                    axis=0)
    _, counts = np.unique(faces, axis=1, return_counts=True)
    assert set(counts.tolist()) <= {1, 2}
    assert (counts == 1).sum() == 2 * 2 + 3 * 4 * 2  # two end caps of 2 triangles, 4 sides × 3 layers × 2


def test_helical_contact_line_lies_in_the_plane_of_action_normal_to_the_load():
    """The load points of a line (roll ρ(z) in the section turned by θ(z)) lie on one plane
    tangent to the base cylinder, and the load direction (n cos βb, a sin βb) is normal to the
    line: the involute helicoid's generator and normal (geometry, not a convention)."""
    geom = pair_geometry(load_pair(low_fluctuation_pair1(helix_angle_deg=20)))
    z = np.linspace(-0.01, 0.01, 9)
    rho = fe3d.line_rolls(geom, 0, [0.5 * (geom.rho_sap[0] + geom.rho_eap[0])], z)[0]
    x, y, a1, _ = sc.contact_point(sc.tooth_model(geom, 0, "transition"), rho)
    twist = math.tan(geom.pair.helix_angle) / geom.reference_radius[0]
    th = twist * z
    pts = np.vstack([x * np.cos(th) - y * np.sin(th), x * np.sin(th) + y * np.cos(th), z])
    n = np.array([-math.cos(a1[0] + th[0]), -math.sin(a1[0] + th[0])])  # the section's n, turned
    assert np.allclose(np.array([-n[1], n[0]]) @ (pts[:2] - pts[:2, [0]]), 0.0, atol=1e-15)  # one plane
    assert math.hypot(*(np.array([-n[1], n[0]]) * (np.array([-n[1], n[0]]) @ pts[:2, 0]))) == pytest.approx(
        geom.base_radius[0], rel=1e-12)  # tangent to the base cylinder
    tangent = np.diff(pts, axis=1)
    cb, sb = math.cos(geom.base_helix_angle), math.sin(geom.base_helix_angle)
    sign = fe3d.roll_sign() * np.sign(twist)
    normal = np.array([n[0] * cb, n[1] * cb, sign * sb])
    assert np.allclose(normal @ tangent, 0.0, atol=1e-15)


@pytest.fixture(scope="module")
def narrow_spur():
    """The low-fluctuation paper pair 1's pinion as a spur gear of face width 3 m_n: a few layers."""
    return pair_geometry(load_pair(low_fluctuation_pair1(helix_angle_deg=0, face_width_mm=5.25)))


def _levels(geom, sizes, rho0):
    out = []
    for size in sizes:
        layers = max(int(math.ceil(geom.face_width / (2 * size * geom.pair.normal_module))), 2)
        model = fe3d.gear_model_3d(geom, 0, rho0, size=size, layers=layers, solver="direct")
        out.append(float(fe3d.line_compliance_3d(model, rho0).compliance[0]))
    return out


def test_3d_converges_between_plane_strain_and_plane_stress(narrow_spur):
    """Three coarse meshes (element edge 0.8, 0.56, 0.4 m_n on the loaded tooth): the 3-D
    compliance of a spur tooth under a uniform line load rises with refinement with shrinking
    steps (conforming elements are too stiff), and at each level lies between 2-D plane strain
    (the 3-D problem with the axial displacement held: a lower bound) and plane stress
    (statically admissible in 3-D: an upper bound) on the same section mesh."""
    geom = narrow_spur
    rho0 = np.array([0.5 * (geom.rho_sap[0] + geom.rho_eap[0])])
    sizes = (0.8, 0.56, 0.4)
    c3 = _levels(geom, sizes, rho0)
    assert c3[0] < c3[1] < c3[2]
    assert c3[2] - c3[1] < c3[1] - c3[0]
    for c, size in zip(c3, sizes):
        strain = fe.tooth_compliance(geom, 0, rho0, "strain", size, fe3d.DEFAULT_NEIGHBOURS, ring=True).total[0]
        stress = fe.tooth_compliance(geom, 0, rho0, "stress", size, fe3d.DEFAULT_NEIGHBOURS, ring=True).total[0]
        assert strain < c < stress
    ext = fe3d.richardson(c3, 0.8 / 0.56)
    assert ext["limit"] > c3[2] and ext["order"] > 0


def test_multigrid_and_direct_solvers_agree(narrow_spur):
    """CG with smoothed-aggregation multigrid (pyamg, rigid-body near-null space) gives the
    direct solution to its tolerance."""
    pytest.importorskip("pyamg")
    geom = narrow_spur
    rho0 = np.array([geom.rho_eap[0]])
    direct = fe3d.line_compliance_3d(fe3d.gear_model_3d(geom, 0, rho0, size=1.1, layers=2, solver="direct"), rho0)
    amg = fe3d.line_compliance_3d(fe3d.gear_model_3d(geom, 0, rho0, size=1.1, layers=2, solver="amg"), rho0)
    assert amg.iterations[0] > 0
    assert amg.compliance[0] == pytest.approx(direct.compliance[0], rel=1e-7)


def test_richardson_recovers_a_known_limit():
    h = np.array([0.4, 0.2, 0.1])
    ext = fe3d.richardson(3.0 - 0.7 * h**2, 2.0)
    assert ext["order"] == pytest.approx(2.0, rel=1e-12)
    assert ext["limit"] == pytest.approx(3.0, rel=1e-12)
    assert math.isnan(fe3d.richardson([1.0, 2.0, 1.5], 2.0)["order"])  # oscillating: no order claimed


def test_refusals(narrow_spur):
    rho0 = [narrow_spur.rho_eap[0]]
    with pytest.raises(GearmeshInputError):
        fe3d.gear_model_3d(narrow_spur, 0, rho0, size=1.1, layers=2, solver="cholesky")
    with pytest.raises(GearmeshInputError):
        fe3d.gear_model_3d(narrow_spur, 0, rho0, size=1.1, layers=0)
