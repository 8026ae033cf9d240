"""Generic 2-D linear elasticity for the finite-element tooth (:mod:`gearmesh.fe`): Lamé constants
of plane strain and plane stress, quality triangulation, P2 assembly and one sparse LU per mesh
(scikit-fem), point loads, displacement probes and the rigid motion of a section.

Nothing here knows a gear: :mod:`gearmesh.fe` builds the gear sector and reads the tooth's
compliance with these tools, and :func:`gearmesh.stress.fe_fillet_stress` the root stress.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import GearmeshInputError

__all__ = ["PLANES", "DEFAULT_PLANE", "lame_parameters", "triangulate", "ElasticSolver", "elastic_solver",
           "point_load_matrix", "probe_displacements", "section_rigid_motion", "rigid_displacement",
           "resample_polyline"]

PLANES = ("strain", "stress")
DEFAULT_PLANE = "strain"




def lame_parameters(youngs_modulus: float, poisson_ratio: float, plane: str = DEFAULT_PLANE) -> tuple[float, float]:
    """Lamé constants (λ, μ) in Pa of plane strain or plane stress (Timoshenko & Goodier §§8, 16).

    Plane strain λ = Eν/((1+ν)(1−2ν)); plane stress λ* = 2λμ/(λ+2μ) = Eν/(1−ν²); μ = E/(2(1+ν)).

    Parameters
    ----------
    youngs_modulus, poisson_ratio : float
        E (Pa) and ν (-).
    plane : {'strain', 'stress'}
        Plane state (default 'strain').
    """
    if plane not in PLANES:
        raise GearmeshInputError("plane", plane, f"must be one of {list(PLANES)}")
    e, nu = float(youngs_modulus), float(poisson_ratio)
    mu = e / (2.0 * (1.0 + nu))
    lam = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)) if plane == "strain" else e * nu / (1.0 - nu**2)
    return lam, mu


def triangulate(vertices: np.ndarray, segments: np.ndarray, max_area: float, min_angle: float = 30.0,
                holes: np.ndarray | None = None):
    """Quality triangulation (skfem ``MeshTri``) of a planar straight-line graph, by Triangle's
    ``p`` (respect the segments), ``q`` (minimum angle) and ``a`` (maximum area) switches. The
    input vertices keep their indices in the mesh (checked), so a load can be put on one.

    Parameters
    ----------
    vertices, segments : ndarray
        (N, 2) vertices (m) and (S, 2) vertex index pairs.
    max_area, min_angle : float
        Largest triangle area (m²) and smallest angle (degrees, default 30).
    holes : ndarray, optional
        (H, 2) a point inside each hole (m).
    """
    import triangle
    from skfem import MeshTri

    pslg = {"vertices": np.asarray(vertices, float), "segments": np.asarray(segments)}
    if holes is not None and len(holes):
        pslg["holes"] = np.asarray(holes, float)
    area = np.format_float_positional(float(max_area), precision=6, unique=False, fractional=False)
    out = triangle.triangulate(pslg, f"pq{min_angle:g}a{area}")  # Triangle reads no exponent
    p = out["vertices"]
    if not np.array_equal(p[:len(vertices)], vertices):
        raise RuntimeError("Triangle renumbered the input vertices")
    return MeshTri(np.ascontiguousarray(p.T), np.ascontiguousarray(out["triangles"].T))


@dataclass(frozen=True, eq=False)
class ElasticSolver:
    """A factorised linear-elastic problem: ``basis`` (P2 vector), free dofs and the LU of K_ff."""

    basis: object
    free: np.ndarray
    lu: object

    def solve(self, loads: np.ndarray) -> np.ndarray:
        """Displacements (N, m) in m for nodal loads (N, m) in N (per m of width), clamped dofs zero."""
        loads = np.asarray(loads, dtype=float)
        u = np.zeros_like(loads)
        u[self.free] = self.lu.solve(np.ascontiguousarray(loads[self.free]))
        return u


def elastic_solver(mesh, youngs_modulus: float, poisson_ratio: float, plane: str, clamped) -> ElasticSolver:
    """Assemble ∫ σ(u):ε(v) dA with P2 triangles and factorise it, the facets where
    ``clamped(x)`` (x: (2, n) facet midpoints → bool) held at zero displacement.

    Parameters
    ----------
    mesh : skfem.MeshTri
        The triangulation (:func:`triangulate`), coordinates in m.
    youngs_modulus : float
        E (Pa).
    poisson_ratio : float
        ν (1).
    plane : {'strain', 'stress'}
        The plane state (:func:`lame_parameters`).
    clamped : callable
        ``clamped(x)`` → bool for facet midpoints x (2, n) (m): the facets held at zero
        displacement.

    Returns
    -------
    ElasticSolver
        The P2 vector basis, the free degrees of freedom and the sparse LU of the stiffness
        matrix restricted to them (per unit thickness, N/m).

    Raises
    ------
    RuntimeError
        When no facet is clamped (the problem is singular).

    References
    ----------
    .. [1] Timoshenko S. P., Goodier J. N., *Theory of Elasticity*, 3rd ed., McGraw-Hill, 1970,
       §§8, 16 (plane strain and plane stress).
    """
    from skfem import Basis, ElementTriP2, ElementVector, asm
    from skfem.models.elasticity import linear_elasticity

    basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=4)
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio, plane)
    k = asm(linear_elasticity(lam, mu), basis)
    fixed = basis.get_dofs(lambda x: clamped(x)).all()
    if fixed.size == 0:
        raise RuntimeError("no clamped facet: the elastic problem is singular")
    free = np.setdiff1d(np.arange(basis.N), fixed)
    # symmetric positive definite: minimum degree on A+Aᵀ and diagonal pivots keep the fill small
    from scipy.sparse.linalg import splu  # here, not at import: scipy costs a job ~0.5 s of start-up

    lu = splu(k[free][:, free].tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    return ElasticSolver(basis=basis, free=free, lu=lu)


def point_load_matrix(solver: ElasticSolver, vertices: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Nodal load vectors (N, m): a unit force (N per m of width) along ``directions`` (m, 2)
    at mesh vertices ``vertices`` (m,).

    Parameters
    ----------
    solver : ElasticSolver
        The factorised problem (its basis numbers the degrees of freedom).
    vertices : ndarray
        (m,) indices of the mesh vertices loaded, one per load case.
    directions : ndarray
        (m, 2) unit directions of the forces.

    Returns
    -------
    ndarray
        (N, m) load vectors, N the basis' degrees of freedom (N/m of width).
    """
    dofs = solver.basis.nodal_dofs[:, np.asarray(vertices)]  # (2, m)
    f = np.zeros((solver.basis.N, len(vertices)))
    cols = np.arange(len(vertices))
    f[dofs[0], cols] = directions[:, 0]
    f[dofs[1], cols] = directions[:, 1]
    return f


def probe_displacements(solver: ElasticSolver, u: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Displacements (2, n, m) in m at ``points`` (2, n) of the solutions ``u`` (N, m).

    Parameters
    ----------
    solver : ElasticSolver
        The factorised problem whose basis interpolates ``u``.
    u : ndarray
        (N, m) nodal displacements (m) of m load cases.
    points : ndarray
        (2, n) points (m).
    """
    n = points.shape[1]
    v = solver.basis.probes(np.asarray(points, dtype=float)) @ u  # rows: x of all points, then y
    return np.stack([v[:n], v[n:]])


def section_rigid_motion(solver: ElasticSolver, u: np.ndarray, a, b, n: int = 201):
    """Least-squares rigid motion of the straight section from ``a`` to ``b`` (m): the
    translation t (2, m) of its midpoint M and its rotation ω (m,) (rad, counter-clockwise),
    so that a point X attached to the section moves by t + ω ẑ×(X − M).

    Along the section (unit direction e, coordinate s from M) the mean of u·e and of u·e⊥
    give t and ∫s u·e⊥ ds/∫s² ds gives ω: the mean displacement and rotation of a plane
    section of Timoshenko's beam kinematics (``n`` midpoint samples, equal weights).

    Parameters
    ----------
    solver : ElasticSolver
        The factorised problem whose basis interpolates ``u``.
    u : ndarray
        (N, m) nodal displacements (m) of m load cases.
    a, b : array_like
        (2,) the section's end points (m).
    n : int
        Midpoint samples along the section.

    Returns
    -------
    t : ndarray
        (2, m) translation of the section's midpoint (m).
    omega : ndarray
        (m,) rotation of the section (rad, counter-clockwise).
    """
    a, b = np.asarray(a, float), np.asarray(b, float)
    s = (np.arange(n) + 0.5) / n - 0.5  # midpoint rule: the ends may sit on a curved boundary
    m = 0.5 * (a + b)
    pts = m[:, None] + np.outer(b - a, s)
    d = probe_displacements(solver, u, pts)  # (2, n, m)
    length = float(np.hypot(*(b - a)))
    e = (b - a) / length
    ep = np.array([-e[1], e[0]])
    ue = np.einsum("i,inm->nm", e, d)
    up = np.einsum("i,inm->nm", ep, d)
    sl = s * length
    omega = (sl @ up) / (sl @ sl)
    t = np.outer(e, ue.mean(axis=0)) + np.outer(ep, up.mean(axis=0))
    return t, omega


def rigid_displacement(t: np.ndarray, omega: np.ndarray, centre, point) -> np.ndarray:
    """Displacement (2, m) of ``point`` under the rigid motion (t, ω) about ``centre`` (m).

    Parameters
    ----------
    t : ndarray
        (2, m) translation of ``centre`` (m).
    omega : ndarray
        (m,) rotation (rad, counter-clockwise).
    centre, point : array_like
        (2,) the centre of the rotation and the point moved (m).

    Returns
    -------
    ndarray
        (2, m) displacement of ``point`` (m): t + ω ẑ×(point − centre).
    """
    d = np.asarray(point, float) - np.asarray(centre, float)
    return t + np.outer(np.array([-d[1], d[0]]), omega)


def resample_polyline(points: np.ndarray, spacing: float) -> np.ndarray:
    """Points (k, 2) equally spaced by arc length along a dense polyline, both ends kept.

    Parameters
    ----------
    points : ndarray
        (n, 2) the polyline (m).
    spacing : float
        Largest distance between the output points (m).
    """
    seg = np.hypot(*np.diff(points, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    k = max(int(math.ceil(s[-1] / spacing)), 1)
    t = np.linspace(0.0, s[-1], k + 1)
    return np.column_stack([np.interp(t, s, points[:, 0]), np.interp(t, s, points[:, 1])])
