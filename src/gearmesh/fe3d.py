"""Three-dimensional finite-element tooth compliance: the reference the 2-D models are judged by.

The 2-D tooth models of :mod:`gearmesh.stiffness` and :mod:`gearmesh.fe` cut the face into
transverse slices in plane stress (the potential-energy cantilevers' E and G) or plane
strain (:mod:`gearmesh.fe`). Neither is right at the free faces, and neither knows that a
helical contact line loads the tooth obliquely. This module solves the gear in 3-D.

Model
-----
* Domain: the ring of the gear from the bore to the root circle with the loaded tooth and
  ``neighbours`` teeth each side (:func:`gearmesh.fe.sector_outline` with ``ring=True``:
  the transverse section of the 2-D model, far teeth closed by the root circle), extruded
  over the face width b in ``layers`` equal layers and, for a helical gear, twisted with the
  helix: the section at axial position z is the transverse section turned by
  θ(z) = z·tan β / r (the lead of the helicoid; ISO 21771), so every flank is the exact
  involute helicoid through the section's vertices.
* Elements: each prism of the extruded triangles is cut into three tetrahedra with the
  diagonal of every side face from the higher-numbered bottom vertex to the lower-numbered
  top vertex (a conforming mesh); quadratic (P2, 10-node) tetrahedra, linear elasticity,
  E and ν of the pair (Timoshenko & Goodier, Theory of Elasticity, 1970, §§ 83–85).
  Every point of the bore surface is held.
* Load: a uniform load per unit face width along one contact line on the right flank of
  the loaded tooth, normal to the flank (for an involute helicoid the normal lies in the
  plane of action at βb to the transverse plane: its transverse part is the line of action
  n of the 2-D model, its axial part sin βb). The line is the straight generator of the
  helicoid in the plane of action: in the section z it touches the involute at the roll
  length ρ(z) = ρ₀ + s·r_b·θ(z) (s = ±1 from the turn of the section), clipped to the active
  flank [ρ_SAP, ρ_EAP]; the load acts at the mesh vertices where the line crosses the layers
  (the 2-D section carries every roll length a line passes through as a vertex), weighted
  by the trapezoidal rule in z.
* Read-out: as in 2-D (Weber 1949; Cornell 1981), the tooth deflection of the section z is
  the displacement along the load direction of the point C(z) where the transverse load
  line crosses the tooth centre line, so the flattening under the load (the local contact
  part) stays out. The line compliance reported is the load-weighted mean of that
  deflection per unit load per unit face width, in the transverse convention of the slice
  model: c_t = δ_n / (q_n cos²βb) with δ_n the normal deflection and q_n the normal load per
  unit axial length (the slice model's δ_t = c_t·q_t with q_t = q_n cos βb, δ_n = δ_t cos βb).
  Under a uniform load the slice model's prediction for the same line is the mean of its
  slice compliance c_t(ρ(z)) over the loaded z.
* Solver: a sparse LU factorisation (one for every line) up to :data:`DIRECT_LIMIT`
  unknowns; above, conjugate gradients preconditioned by smoothed-aggregation algebraic
  multigrid (pyamg, the optional extra ``gearmesh[fe3d]``; Vaněk, Mandel & Brezina 1996) with
  the six rigid-body modes as near-null space, relative residual 1e-10 (bounded memory; on
  quadratic tetrahedra it needed 40–90 iterations and was slower than the direct solve at
  the sizes of docs/validation.md). Assembly in blocks of elements (bounded memory).
* Bounds (checked in the tests and docs/validation.md): plane strain is the 3-D problem
  with the axial displacement held, so the 3-D compliance of a spur tooth under a uniform
  line load is at least the plane-strain one; the plane-stress stress field is statically
  admissible in 3-D, so by the complementary-energy principle the 3-D compliance is at
  most the plane-stress one (both exactly for the work-conjugate displacement, nearly so
  for the C read-out).

No factor is fitted: the inputs are the profile, E, ν, the bore and the face width.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry
from .tooth import contact_point, tooth_model

__all__ = ["DEFAULT_NEIGHBOURS", "extrude", "gear_model_3d", "GearModel3D", "line_compliance_3d",
           "LineCompliance3D", "richardson"]

#: teeth kept each side of the loaded one on the ring (2-D: 2 teeth within 0.4 %, 3 within 0.1 %
#: of the whole gear for the low-fluctuation paper pair 1's pinion, docs/validation.md)
DEFAULT_NEIGHBOURS = 3
#: element edge on the loaded tooth's boundary in normal modules, then 2x, 4x, 8x away (fe.GRADING)
DEFAULT_SIZE = 0.2
#: relative residual of the preconditioned conjugate gradients
TOLERANCE = 1e-10
SOLVERS = ("auto", "direct", "amg")
#: largest system factorised directly: about 1 GB of LU factors (88 M entries measured at 82 k
#: unknowns, the low-fluctuation paper pair 1's pinion); above, CG + algebraic multigrid (bounded memory)
DIRECT_LIMIT = 150_000
#: read-out points of C per layer along a loaded line (their mean is the line's deflection)
READ = 8
#: elements per assembly block (about 30 MB of element matrices per thousand P2 tetrahedra)
BLOCK = 8000


def extrude(points: np.ndarray, triangles: np.ndarray, z: np.ndarray, twist: float):
    """Tetrahedral mesh (skfem ``MeshTet``) of the triangles (3, T) on the vertices (2, N) (m)
    extruded through the layers ``z`` (K,) (m), the section at z turned by ``twist``·z (rad,
    counter-clockwise about +z). Vertex i of layer k is 3-D vertex k·N + i.

    Each prism is cut into three tetrahedra so that the diagonal of every side face runs
    from its higher-numbered bottom vertex to its lower-numbered top vertex: neighbouring
    prisms cut a shared face alike, so the mesh is conforming.

    Parameters
    ----------
    points : ndarray
        (2, N) section vertices (m).
    triangles : ndarray
        (3, T) vertex indices of the section's triangles.
    z : ndarray
        (K,) layer positions along the axis (m), increasing.
    twist : float
        Turn of the section per unit z (rad/m; tan β / r for the helix, ISO 21771).

    Returns
    -------
    skfem.MeshTet
        (3, K·N) vertices (m) and 3·(K − 1)·T positively oriented tetrahedra.
    """
    from skfem import MeshTet

    n = points.shape[1]
    k = z.size
    th = twist * z
    c, s = np.cos(th)[:, None], np.sin(th)[:, None]
    x = points[0][None, :] * c - points[1][None, :] * s
    y = points[0][None, :] * s + points[1][None, :] * c
    p = np.vstack([x.ravel(), y.ravel(), np.repeat(z, n)])
    tri = np.sort(triangles, axis=0)  # v0 < v1 < v2 by global index
    v0, v1, v2 = tri
    layers = np.arange(k - 1)[:, None] * n
    b0, b1, b2 = (v + layers for v in (v0, v1, v2))
    t0, t1, t2 = b0 + n, b1 + n, b2 + n
    tets = np.stack([
        np.stack([b0, b1, b2, t0]),
        np.stack([b1, b2, t0, t1]),
        np.stack([b2, t0, t1, t2]),
    ])  # (3 tets, 4 vertices, K-1, T)
    t = tets.transpose(1, 0, 2, 3).reshape(4, -1)
    # positive orientation (skfem's mappings take |det J|, but keep the mesh tidy)
    a, b, cc, d = (p[:, t[i]] for i in range(4))
    vol = np.einsum("ij,ij->j", np.cross(b - a, cc - a, axis=0), d - a)
    flip = vol < 0
    t[[1, 2]][:, flip] = t[[2, 1]][:, flip]
    t2 = t.copy()
    t2[1, flip], t2[2, flip] = t[2, flip], t[1, flip]
    return MeshTet(np.ascontiguousarray(p), np.ascontiguousarray(t2))


@dataclass(frozen=True, eq=False)
class GearModel3D:
    """A meshed, assembled 3-D gear ready for loads: ``basis`` (P2 vector), the free dofs,
    the free stiffness matrix and its multigrid hierarchy; the 2-D section it was extruded
    from (``sector``, ``profile``), the layers ``z`` (m) and the ``twist`` (rad/m)."""

    geom: PairGeometry
    gear: int
    basis: object
    free: np.ndarray
    stiffness: object
    multigrid: object  # the LU factors (solver 'direct') or the pyamg hierarchy ('amg')
    solver: str
    sector: object
    profile: object
    load_rolls: np.ndarray
    section_vertices: int  # vertices of the 2-D section mesh (3-D vertex k·N + i: vertex i of layer k)
    z: np.ndarray
    twist: float
    roll_sign: int
    size: float
    layers: int
    neighbours: int
    setup_seconds: float

    @property
    def n_dofs(self) -> int:
        return int(self.basis.N)

    @property
    def n_elements(self) -> int:
        return int(self.basis.mesh.t.shape[1])


def _assemble(basis_of, mesh, lam: float, mu: float, n_dofs: int):
    """Σ over element blocks of ∫ σ(u):ε(v) dV (skfem), memory bounded by :data:`BLOCK`."""
    from scipy.sparse import csr_matrix
    from skfem import asm
    from skfem.models.elasticity import linear_elasticity

    form = linear_elasticity(lam, mu)
    k = csr_matrix((n_dofs, n_dofs))
    m = mesh.t.shape[1]
    for start in range(0, m, BLOCK):
        k = k + asm(form, basis_of(np.arange(start, min(start + BLOCK, m)))).tocsr()
    return k


def _rigid_modes(locations: np.ndarray) -> np.ndarray:
    """The six rigid-body displacement fields (N, 6) at dof locations (3, N/3 per component)
    ordered as the dofs (x, y, z of one node consecutive)."""
    x = locations
    n = x.shape[1]
    b = np.zeros((n, 6))
    comp = np.arange(n) % 3
    for c in range(3):
        b[comp == c, c] = 1.0
    # rotations about x, y, z: ω × r
    rx, ry, rz = x[0], x[1], x[2]
    b[comp == 1, 3], b[comp == 2, 3] = -rz[comp == 1], ry[comp == 2]
    b[comp == 0, 4], b[comp == 2, 4] = rz[comp == 0], -rx[comp == 2]
    b[comp == 0, 5], b[comp == 1, 5] = -ry[comp == 0], rx[comp == 1]
    return b


def roll_sign() -> int:
    """Sign s of dρ = s·r_b·dθ: turning the section counter-clockwise by dθ moves the right
    flank's contact with a fixed line of action to the roll length ρ − r_b·dθ (the base
    point of every roll lies counter-clockwise of the involute's origin by ρ/r_b, and the
    turn carries the base point of ρ − r_b·dθ onto the fixed tangent point). Checked in the
    tests: the contact points of every section lie in the plane of action.

    Returns
    -------
    int
        s = −1.
    """
    return -1


def gear_model_3d(geom: PairGeometry, gear: int, load_rolls, size: float = DEFAULT_SIZE,
                  layers: int | None = None, neighbours: int = DEFAULT_NEIGHBOURS,
                  face_width: float | None = None, solver: str = "auto") -> GearModel3D:
    """Mesh, assemble and prepare the multigrid of gear ``gear`` (0 pinion, 1 gear) in 3-D.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    load_rolls : array_like
        Every roll length (m) a load line will cross a layer at (vertices of the section's right flank).
    size : float
        Boundary element edge on the loaded tooth in normal modules (default 0.2;
        :func:`gearmesh.fe.sector_outline`).
    layers : int, optional
        Number of equal layers over the face (default: the face width over the loaded tooth's edge, rounded up).
    neighbours : int
        Teeth kept each side of the loaded one on the ring (default 3).
    face_width : float, optional
        Face width (m); defaults to the pair's.
    solver : {'auto', 'direct', 'amg'}
        'direct' (sparse LU, one factorisation for every line), 'amg' (CG with smoothed-aggregation
        multigrid, pyamg) or 'auto' (default: direct up to :data:`DIRECT_LIMIT` unknowns).

    Returns
    -------
    GearModel3D
        The assembled model: layers ``z`` (m), ``twist`` (rad/m), the solver's factors or hierarchy.
    """
    from skfem import Basis, ElementTetP2, ElementVector

    from . import fe, fe_elastic

    if solver not in SOLVERS:
        raise GearmeshInputError("solver", solver, f"must be one of {list(SOLVERS)}")
    if layers is not None and (int(layers) != layers or layers < 1):
        raise GearmeshInputError("layers", layers, "must be a whole number >= 1")
    t0 = time.perf_counter()
    rolls = np.unique(np.asarray(load_rolls, dtype=float))
    profile, sector = fe.gear_sector(geom, gear, rolls, size, neighbours, ring=True)
    mesh2 = fe_elastic.triangulate(sector.vertices, sector.segments, max_area=fe.AREA_FACTOR * sector.sizes[-1] ** 2,
                           holes=sector.holes)
    b = float(geom.face_width if face_width is None else face_width)
    h = size * geom.pair.normal_module
    n_layers = int(math.ceil(b / h)) if layers is None else int(layers)
    z = np.linspace(-0.5 * b, 0.5 * b, n_layers + 1)
    twist = math.tan(geom.pair.helix_angle) / float(geom.reference_radius[gear])
    mesh = extrude(mesh2.p, mesh2.t, z, twist)
    elem = ElementVector(ElementTetP2())
    basis = Basis(mesh, elem, intorder=2)
    mat = geom.pair.material
    lam, mu = fe_elastic.lame_parameters(mat.youngs_modulus, mat.poisson_ratio, "strain")  # 3-D Lamé constants
    k = _assemble(lambda idx: Basis(mesh, elem, intorder=2, elements=idx), mesh, lam, mu, basis.N)
    r_int = sector.bore_radius
    fixed = basis.get_dofs(lambda x: np.hypot(x[0], x[1]) <= r_int * (1 + 1e-9)).all()
    free = np.setdiff1d(np.arange(basis.N), fixed)
    kff = k[free][:, free].tocsr()
    if solver == "auto":
        solver = "direct" if free.size <= DIRECT_LIMIT else "amg"
    if solver == "direct":
        from scipy.sparse.linalg import splu

        # symmetric positive definite: minimum degree on A+Aᵀ, diagonal pivots (as fe_elastic.elastic_solver)
        ml = splu(kff.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    else:  # 'amg'
        import pyamg
        from scipy.sparse import bsr_matrix

        near_null = _rigid_modes(basis.doflocs[:, free])
        ml = pyamg.smoothed_aggregation_solver(bsr_matrix(kff, blocksize=(3, 3)), B=near_null, symmetry="symmetric",
                                               max_coarse=500)
    return GearModel3D(geom=geom, gear=gear, basis=basis, free=free, stiffness=kff, multigrid=ml, solver=solver,
                       sector=sector,
                       profile=profile, load_rolls=rolls,
                       section_vertices=int(mesh2.p.shape[1]), z=z, twist=twist, roll_sign=roll_sign(),
                       size=float(size), layers=n_layers, neighbours=int(neighbours),
                       setup_seconds=time.perf_counter() - t0)


@dataclass(frozen=True, eq=False)
class LineCompliance3D:
    """3-D line compliances of one gear: for each contact line r (its roll length ``rho0`` at
    z = 0, m) the load-weighted mean tooth deflection per unit load per unit face width,
    ``compliance`` (m²/N, transverse convention, module docstring); ``deflection`` (R, K)
    the normal deflection of C(z_k) per unit normal load per unit axial length (m²/N, NaN
    where the line is off the active flank), ``weights`` (R, K) the trapezoidal load
    weights (m), ``rho`` (R, K) the roll length of each layer's contact point (m).
    ``iterations`` and ``seconds``: the solver's work per line."""

    rho0: np.ndarray
    compliance: np.ndarray
    deflection: np.ndarray
    weights: np.ndarray
    rho: np.ndarray
    z: np.ndarray
    load_angle: np.ndarray
    iterations: np.ndarray
    seconds: np.ndarray
    n_dofs: int
    n_elements: int
    size: float
    layers: int


def line_rolls(geom: PairGeometry, gear: int, rho0, z: np.ndarray) -> np.ndarray:
    """Roll length (R, K) in m of the contact of each line (``rho0`` at z = 0) in the section
    at each layer ``z``: ρ(z) = ρ₀ + s·z·tan βb (:func:`roll_sign`; r_b·θ(z) = z·tan βb).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (base helix angle βb in rad).
    gear : int
        0 pinion, 1 gear (the formula is the same for both).
    rho0 : array_like
        (R,) roll length (m) of each line at z = 0.
    z : ndarray
        (K,) layer positions (m).

    Returns
    -------
    ndarray
        (R, K) roll lengths (m).
    """
    return np.asarray(rho0, float)[:, None] + roll_sign() * math.tan(geom.base_helix_angle) * np.asarray(z)[None, :]


def layer_grid_rolls(geom: PairGeometry, gear: int, rho0, z: np.ndarray) -> np.ndarray:
    """Every roll length (m) the lines ``rho0`` touch at the layers ``z`` within the active
    flank: the vertices the 2-D section must carry.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (active flank [ρ_SAP, ρ_EAP] in m).
    gear : int
        0 pinion, 1 gear.
    rho0 : array_like
        (R,) roll length (m) of each line at z = 0.
    z : ndarray
        (K,) layer positions (m).

    Returns
    -------
    ndarray
        Sorted distinct roll lengths (m), equal ones up to 1e-9 m_n merged.
    """
    r = line_rolls(geom, gear, rho0, z)
    lo, hi = geom.rho_sap[gear], geom.rho_eap[gear]
    r = np.sort(r[(r >= lo - 1e-12) & (r <= hi + 1e-12)])
    # one vertex for rolls equal up to rounding (lines on one grid reach a roll by different sums)
    return r[np.concatenate([[True], np.diff(r) > 1e-9 * geom.pair.normal_module])]


def _solve(model: GearModel3D, f: np.ndarray):
    """Displacements (N,) for the load vector ``f`` (N,) and the CG iteration count."""
    u = np.zeros(model.basis.N)
    if model.solver == "direct":
        u[model.free] = model.multigrid.solve(f[model.free])
        return u, 0
    residuals: list[float] = []
    u[model.free] = model.multigrid.solve(f[model.free], tol=TOLERANCE, accel="cg", residuals=residuals, maxiter=1000)
    return u, len(residuals) - 1


def line_compliance_3d(model: GearModel3D, rho0, transverse_only: bool = False) -> LineCompliance3D:
    """Load ``model`` along the contact lines whose right-flank roll length at z = 0 is each of
    ``rho0`` (m) and read the tooth deflection at C(z) (module docstring). Every roll a line
    touches at a layer must be one of the model's ``load_rolls``. ``transverse_only``: the
    slice model's load instead (the transverse part n alone, read along n), to separate the
    effect of the axial part of the flank normal.

    Parameters
    ----------
    model : GearModel3D
        The factorised 3-D gear (:func:`gear_model_3d`).
    rho0 : array_like
        (m,) right-flank roll lengths of the contact lines at z = 0 (m).
    transverse_only : bool
        Load and read along the transverse n alone (the slice model's load).

    Returns
    -------
    LineCompliance3D
        Per line its compliance (m/N per m of contact line; with ``transverse_only`` per m of
        face, transverse), the deflections and weights per layer, the load angles and the
        solver's iterations and times.
    """
    geom, gear = model.geom, model.gear
    rho0 = np.atleast_1d(np.asarray(rho0, dtype=float))
    z = model.z
    n2 = model.section_vertices  # the section's outline vertices keep their indices in its mesh
    rho = line_rolls(geom, gear, rho0, z)
    active = (rho >= geom.rho_sap[gear] - 1e-12) & (rho <= geom.rho_eap[gear] + 1e-12)
    tm = tooth_model(geom, gear, "transition", model.profile)
    cb = math.cos(geom.base_helix_angle)
    load_vertices = model.sector.right_loads  # indices of model.load_rolls on the right flank
    out_def = np.full(rho.shape, np.nan)
    weights = np.zeros(rho.shape)
    alpha = np.full(rho.shape, np.nan)
    iters = np.zeros(rho0.size, int)
    means = np.full(rho0.size, np.nan)
    secs = np.zeros(rho0.size)
    dz = np.diff(z)
    for r in range(rho0.size):
        ks = np.flatnonzero(active[r])
        if ks.size == 0:
            continue
        w = _layer_weights(active[r], dz, ks)
        idx = _nearest_load_rolls(model, rho[r, ks])
        a1 = contact_point(tm, rho[r, ks])[2]
        alpha[r, ks] = a1
        normal = _load_normal(model, a1, z[ks], transverse_only)
        vert3 = ks * n2 + load_vertices[idx]
        f = np.zeros(model.basis.N)
        dofs = model.basis.nodal_dofs[:, vert3]  # (3, k)
        for c in range(3):
            np.add.at(f, dofs[c], normal[c] * w[ks])
        t0 = time.perf_counter()
        u, it = _solve(model, f)
        secs[r] = time.perf_counter() - t0
        iters[r] = it
        # C(z): where the transverse load line crosses the centre line, turned with the section,
        # at the layers (the profile along the face) and at READ points per layer over the loaded
        # run (the mean): by reciprocity the mean over a continuous line of C is the deflection,
        # at the lumped load points, under a smooth line load at C, so the lumping error falls
        # as (Δz/|PC|)² instead of being the near field of a point load
        out_def[r, ks] = np.einsum("ik,ik->k", normal, _probe_c(model, tm, rho[r, ks], z[ks], u))
        means[r] = _mean_line_deflection(model, tm, rho[r, ks], z[ks], normal, u) if ks.size > 1 else out_def[r, ks[0]]
        weights[r] = w
    mean = means
    return LineCompliance3D(rho0=rho0, compliance=mean if transverse_only else mean / cb**2, deflection=out_def, weights=weights, rho=rho, z=z,
                            load_angle=alpha, iterations=iters, seconds=secs, n_dofs=model.n_dofs,
                            n_elements=model.n_elements, size=model.size, layers=model.layers)


def _layer_weights(active: np.ndarray, dz: np.ndarray, ks: np.ndarray) -> np.ndarray:
    """Trapezoidal weights (layers,) over the run ``ks`` of loaded layers (ends: half a layer;
    one layer alone: 1)."""
    w = np.zeros(active.size)
    w[ks] = 0.5 * (np.concatenate([[0.0], dz])[ks] * active[np.maximum(ks - 1, 0)]
                   + np.concatenate([dz, [0.0]])[ks] * active[np.minimum(ks + 1, active.size - 1)])
    if ks.size == 1:
        w[ks] = 1.0
    return w


def _nearest_load_rolls(model: GearModel3D, rho: np.ndarray) -> np.ndarray:
    """Indices into ``model.load_rolls`` of the load vertices at the rolls ``rho`` (m); an error
    where a contact line crosses a layer between them."""
    rolls = model.load_rolls
    idx = np.clip(np.searchsorted(rolls, rho), 1, rolls.size - 1)
    idx = np.where(np.abs(rolls[idx - 1] - rho) < np.abs(rolls[idx] - rho), idx - 1, idx)  # the nearest vertex roll
    if not np.all(np.abs(rolls[idx] - rho) < 1e-9 * model.geom.pair.normal_module):
        raise ValueError("a contact line crosses a layer between the section's load vertices")
    return idx


def _load_normal(model: GearModel3D, a1: np.ndarray, z: np.ndarray, transverse_only: bool) -> np.ndarray:
    """Unit load directions (3, k) at layers ``z`` (m) for load angles ``a1`` (rad): the
    transverse line of action into the tooth (the 2-D model's n) turned with the section, as
    the flank normal (transverse part n·cos βb, axial part along the helix) or, with
    ``transverse_only``, n alone."""
    th = model.twist * z
    nx0, ny0 = -np.cos(a1), -np.sin(a1)
    nx = nx0 * np.cos(th) - ny0 * np.sin(th)
    ny = nx0 * np.sin(th) + ny0 * np.cos(th)
    if transverse_only:
        return np.vstack([nx, ny, np.zeros(z.size)])
    cb, sb = math.cos(model.geom.base_helix_angle), math.sin(model.geom.base_helix_angle)
    return np.vstack([nx * cb, ny * cb, np.full(z.size, _axial_sign(model) * sb)])


def _mean_line_deflection(model: GearModel3D, tm, rho: np.ndarray, z: np.ndarray, normal: np.ndarray,
                          u: np.ndarray) -> float:
    """Mean deflection (m) along ``normal`` of the points C over the loaded run (layers ``z``,
    rolls ``rho``), read at :data:`READ` points per layer."""
    t = (np.arange(READ * (z.size - 1)) + 0.5) / READ
    zz = np.interp(t, np.arange(z.size), z)
    rr = np.interp(t, np.arange(z.size), rho)
    nn = np.vstack([np.interp(t, np.arange(z.size), normal[i]) for i in range(3)])
    return float(np.mean(np.einsum("ik,ik->k", nn, _probe_c(model, tm, rr, zz, u))))


def _probe_c(model: GearModel3D, tm, rho: np.ndarray, z: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Displacements (3, k) at the points C of the sections at ``z`` (m) for contacts at ``rho`` (m)."""
    x_p, y_p, a1, _ = contact_point(tm, rho)
    th = model.twist * z
    yc = y_p - x_p * np.tan(a1)
    span = model.z[-1] - model.z[0]
    cpts = np.vstack([-yc * np.sin(th), yc * np.cos(th), np.clip(z, model.z[0] + 1e-9 * span, model.z[-1] - 1e-9 * span)])
    v = model.basis.probes(cpts) @ u
    n = z.size
    return np.vstack([v[:n], v[n:2 * n], v[2 * n:]])


def _axial_sign(model: GearModel3D) -> float:
    """Sign a of the axial part of the inward flank normal n·cos βb + a·sin βb·ẑ (right flank).

    The normal lies in the plane of action, perpendicular to the contact line, whose
    transverse point moves along n by dℓ/dz = −s·r_b·twist = ∓tan βb per unit z (n points
    into the tooth, against the direction of unwinding; s of :func:`roll_sign`); so
    a = −sign(dℓ/dz) = s·sign(twist). Checked in the tests (normal ⟂ contact line)."""
    if model.twist == 0.0:
        return 1.0
    return float(roll_sign() * np.sign(model.twist))


def richardson(values, ratio: float) -> dict[str, float]:
    """Extrapolate the last three of a sequence of results on meshes refined by ``ratio``
    (h_{i+1} = h_i / ratio): observed order p = ln((c₁−c₂)/(c₂−c₃))/ln ratio and
    c∞ = c₃ + (c₃ − c₂)/(ratio^p − 1) (Richardson; Roache 1998, Verification and Validation
    in Computational Science, §5). NaN order when the differences do not shrink
    monotonically; then c∞ is the finest value.

    Parameters
    ----------
    values : sequence of float
        Results from coarse to fine (at least three; any units).
    ratio : float
        Refinement ratio of successive meshes (> 1).

    Returns
    -------
    dict of str to float
        ``order`` p (-), ``limit`` c∞ and ``error_estimate`` |c∞ − c₃| (units of ``values``).

    References
    ----------
    .. [1] Roache P.J., *Verification and Validation in Computational Science and Engineering*,
       Hermosa Publishers, 1998, §5.
    """
    c1, c2, c3 = (float(v) for v in values[-3:])
    d1, d2 = c1 - c2, c2 - c3
    if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return {"order": math.nan, "limit": c3, "error_estimate": abs(d2)}
    p = math.log(d1 / d2) / math.log(ratio)
    lim = c3 + (c3 - c2) / (ratio**p - 1)
    return {"order": p, "limit": lim, "error_estimate": abs(lim - c3)}
