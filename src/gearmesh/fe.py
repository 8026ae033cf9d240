"""Finite-element tooth compliance of the hob-generated tooth (2-D linear elasticity, scikit-fem).

A fourth way to the per-unit-width slice compliance of :mod:`gearmesh.stiffness`, and the
project's own check of its potential-energy (PEM) cantilever models.

Model
-----
* Domain: a sector of the gear — the loaded tooth, ``neighbours`` teeth on each side, and
  the rim down to the bore — bounded by the project's own transverse profile
  (:func:`gearmesh.profile.tooth_profile`: root circle, trochoid fillet, involute, tip
  circle), mirrored for the left flank and repeated at the pitch angle 2π/z. The bore arc
  is clamped; the two radial cuts through the outermost root spaces are free.
* Linear elasticity in plane strain (default) or plane stress, per unit face width
  (thickness 1 m), with the Lamé constants λ = Eν/((1+ν)(1−2ν)) (plane strain) or
  λ* = Eν/(1−ν²) (plane stress), μ = E/(2(1+ν)) (Timoshenko & Goodier, Theory of
  Elasticity, 3rd ed., 1970, §§8, 16). Plane strain is the state of a transverse slice
  inside a face many modules wide (its neighbours hold it axially; Kiekbusch, Sappok,
  Sauer & Howard 2011, Strojniški vestnik 57:491, find 2-D plane strain close to 3-D for
  wide spur teeth); plane stress suits a thin disc, b ≲ m_n. The PEM cantilever formulas use
  E and G, i.e. plane stress; compare them in plane stress.
* Discretisation: quality triangles (Shewchuk's Triangle through the ``triangle`` package,
  minimum angle 30°), quadratic (P2) displacement elements, element edge ``size``·m_n on
  the loaded tooth, 2×, 4× on the next teeth, 8× on the others and the bore
  (:data:`GRADING`); one sparse LU factorisation per gear serves every load position.
* Load: a unit force per unit width at the contact point P of roll length ρ on the involute,
  along the line of action into the tooth, n = (−cos α1, −sin α1) in the tooth frame of
  :mod:`gearmesh.stiffness` (α1 the load angle of :func:`gearmesh.tooth.contact_point`).
* Local contact part removed as Weber (1949, "Formänderung und Profilrücknahme bei gerad-
  und schrägverzahnten Rädern", Schriftenreihe Antriebstechnik 11) and Cornell (1981, J.
  Mech. Des. 103:447) split the tooth deflection: the tooth deflection is the displacement,
  along n, of the point C where the line of action crosses the tooth centre line; the
  approach of P towards C (the flattening under the load, log-singular for a point load in
  2-D) is the local contact part, which the slice model carries in its Hertz term
  (:func:`gearmesh.slice_compliance.hertz_compliance_transverse`). So c_FE = n·u(C)/F replaces
  exactly c_b + c_s + c_a + c_f of the PEM tables.
* Split of c_FE into body and tooth (for the table's components): the rigid motion of the
  root section — the chord y = y_root of the transition cantilever, between the points
  where the fillet meets the root circle — fitted to the FE displacements in least squares
  (mean translation and mean rotation of a plane section, Timoshenko's section kinematics),
  carried to C, is the fillet-foundation part (Sainsot, Velex & Duverger 2004, J. Mech.
  Des. 126:748: the tooth a beam on the elastic body at the root circle); the rest is the
  tooth's own bending + shear + axial deflection (not separable in a 2-D continuum; the
  table carries it as 'bending', with 'shear' and 'axial' zero).

No factor is fitted: the only inputs are the profile, E, ν and the bore radius.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import GearmeshInputError
from .fe_elastic import (DEFAULT_PLANE, ElasticSolver, elastic_solver, lame_parameters, point_load_matrix,
                         probe_displacements, resample_polyline, section_rigid_motion, triangulate)
from .gear import PairGeometry
from .tooth import contact_point, require_stiffness_data, tooth_model

__all__ = [
    "DEFAULT_SIZE", "DEFAULT_NEIGHBOURS", "DEFAULT_ROLL_NODES", "sector_outline",
    "GearSector", "gear_sector", "ToothCompliance", "loaded_tooth", "tooth_compliance",
]

#: element edge on the loaded tooth in normal modules: the 17-node table within 0.42 % (max)
#: of a mesh 4× finer (0.0125 m_n) for seeds 001/003/004, under a second per gear (docs)
DEFAULT_SIZE = 0.05
#: None = the whole gear. A sector with free radial cuts converges slowly with the number of
#: teeth it keeps (the low-fluctuation paper pair 1's pinion, load at the SAP: 3 teeth +150 %, 7 teeth +0.4 %
#: against the whole gear), and the whole gear costs under a second.
DEFAULT_NEIGHBOURS = None
DEFAULT_ROLL_NODES = 17
#: largest triangle area as a multiple of (the coarsest spacing)²: the rim interior 4× coarser
#: than the bore; 0.07 % from a mesh 4× finer there (the improved potential-energy paper)
AREA_FACTOR = 16.0
#: boundary spacing on the loaded tooth, the next, ... in units of ``size`` (the last: all others)
GRADING = (1, 2, 4, 8)


# --------------------------------------------------------------------------------------
# The gear sector
# --------------------------------------------------------------------------------------


def _rotate(xy: np.ndarray, theta: float) -> np.ndarray:
    """Rotate points (n, 2) so that the +y axis goes to polar angle θ (rad, towards +x)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.column_stack([xy[:, 0] * c + xy[:, 1] * s, -xy[:, 0] * s + xy[:, 1] * c])


def _right_flank(profile, load_rolls: np.ndarray, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Right flank (n, 2) from the middle of the root space to the tip, at most ``spacing``
    apart, with the involute points of ``load_rolls`` (m) among its vertices; and their indices."""
    from .profile import rack_flank_envelope

    fil = profile.segment == 0
    fillet = resample_polyline(np.column_stack([profile.x[fil], profile.y[fil]]), spacing)
    rack, rb = profile.rack, profile.base_radius
    # involute arc length from the base circle is ρ²/(2 r_b): points uniform in arc length
    s0, s1 = profile.form_roll**2 / (2 * rb), float(np.nanmax(profile.roll)) ** 2 / (2 * rb)
    k = max(int(math.ceil((s1 - s0) / spacing)), 1)
    grid = np.sqrt(2 * rb * np.linspace(s0, s1, k + 1))
    arc = grid**2 / (2 * rb)
    load_arc = np.asarray(load_rolls) ** 2 / (2 * rb)
    near = np.min(np.abs(arc[:, None] - load_arc[None, :]), axis=1) < 0.3 * spacing if load_arc.size else \
        np.zeros(arc.size, bool)
    near[0] = False  # keep the form point
    rho = np.sort(np.concatenate([grid[~near], load_rolls]))
    rho = rho[np.concatenate([[True], np.diff(rho) > 1e-9 * spacing])]  # equal up to rounding: one vertex
    x, y, _, _ = rack_flank_envelope(rack, rho)
    flank = np.vstack([fillet[:-1], np.column_stack([x, y])])
    j = np.clip(np.searchsorted(rho, load_rolls), 1, rho.size - 1) if rho.size > 1 else np.zeros(len(load_rolls), int)
    if rho.size > 1:
        j = np.where(np.abs(rho[j - 1] - load_rolls) < np.abs(rho[j] - load_rolls), j - 1, j)
    idx = fillet.shape[0] - 1 + j
    return flank, idx


@dataclass(frozen=True, eq=False)
class GearSector:
    """The outline of a gear sector and the load points of its loaded tooth (tooth 0, centred on +y).

    ``vertices`` (N, 2) in m and ``segments`` (S, 2) index pairs: a closed polygon over the
    teeth, the radial cuts and the bore arc; for the whole gear (``full``) the tooth ring and
    the bore circle, with a hole at the centre. ``right_loads``/``left_loads``: vertex
    indices of the load points on the loaded tooth's flanks.
    """

    vertices: np.ndarray
    segments: np.ndarray
    holes: np.ndarray
    right_loads: np.ndarray
    left_loads: np.ndarray
    bore_radius: float
    full: bool
    sizes: tuple[float, ...]  # boundary spacing (m) on tooth |j| = 0, 1, 2, ... (last: the rest, cuts, bore)
    chord: np.ndarray | None = None  # vertex indices along the loaded tooth's root chord, left to right


def _tooth_outline(profile, load_rolls: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """One tooth from the left root-space middle over the tip to the right one (n, 2), and its
    right-flank load points (k, 2)."""
    flank, idx = _right_flank(profile, load_rolls, h)
    left = flank * np.array([-1.0, 1.0])
    corner = flank[-1]
    ra = float(np.hypot(*corner))
    half_tip = math.atan2(corner[0], corner[1])
    k = max(int(math.ceil(2 * ra * half_tip / h)), 1)
    th = np.linspace(-half_tip, half_tip, k + 1)[1:-1]
    tip = np.column_stack([ra * np.sin(th), ra * np.cos(th)])
    return np.vstack([left, tip, flank[::-1]]), flank[idx]


def _closed(start: int, n: int) -> np.ndarray:
    i = np.arange(start, start + n)
    return np.column_stack([i, np.roll(i, -1)])


def _insert_junctions(outer: np.ndarray, theta_f: float, pitch: float):
    """Insert into the outline (n, 2) the points of the loaded tooth (polar angle within
    ±pitch/2 of +y) at polar angles −θ_f and +θ_f (on the outline's segments, or an existing
    vertex within 1e-9 rad); returns the new outline and the two indices (left, right)."""
    phi = np.arctan2(outer[:, 0], outer[:, 1])  # from +y towards +x
    out = outer
    ends = []
    for target in (-theta_f, theta_f):
        phi = np.arctan2(out[:, 0], out[:, 1])
        hit = np.flatnonzero(np.abs(phi - target) < 1e-9)
        if hit.size:
            ends.append(int(hit[0]))
            continue
        i = np.flatnonzero((np.abs(phi[:-1]) <= 0.5 * pitch + 1e-12) & ((phi[:-1] - target) * (phi[1:] - target) < 0))
        if i.size != 1:
            raise RuntimeError("the root section's ends are not found once on the loaded tooth")
        i = int(i[0])
        p, q = out[i], out[i + 1]
        d = np.array([math.sin(target), math.cos(target)])  # the ray at polar angle target
        # p + t (q − p) on the ray: cross(d, p + t(q − p)) = 0
        cr = lambda v: d[0] * v[1] - d[1] * v[0]  # noqa: E731
        t = cr(p) / (cr(p) - cr(q))
        out = np.vstack([out[:i + 1], p + t * (q - p), out[i + 1:]])
        ends.append(i + 1)
    if ends[0] >= ends[1]:
        raise RuntimeError("root section ends out of order")
    return out, ends


def sector_outline(profile, teeth: int, bore_radius: float, load_rolls: np.ndarray, size: float,
                   neighbours: int | None = DEFAULT_NEIGHBOURS, ring: bool = False,
                   root_chord: float | None = None) -> GearSector:
    """Outline of the loaded tooth, ``neighbours`` teeth each side and the rim to the bore;
    the whole gear when ``neighbours`` is None or the sector would close. With ``ring`` the
    body is the whole ring (no radial cuts) and only the ``neighbours`` teeth each side of
    the loaded one are kept, the root circle closing the outline over the others (the
    3-D model's domain, :mod:`gearmesh.fe3d`: far teeth carry no load and stiffen the rim
    only slightly, measured in docs/validation.md). ``root_chord`` = θ_f (rad): the loaded
    tooth's root section — the chord between the points at polar angle ±θ_f where its flanks
    meet the root circle (the transition cantilever's root, Sainsot's S_f) — becomes an
    inner segment of the mesh (:func:`tooth_body_split`).

    ``size`` (m): boundary spacing on the loaded tooth, then :data:`GRADING` times it on
    the teeth next to it (the last factor on all others, the cuts and the bore). The load
    rolls (m) become vertices on both flanks of the loaded tooth.

    Parameters
    ----------
    profile : ToothProfile
        The transverse tooth profile (:func:`gearmesh.profile.tooth_profile`).
    teeth : int
        Number of teeth.
    bore_radius : float
        Bore radius (m).
    load_rolls : ndarray
        (k,) roll lengths of the load points (m).
    size : float
        Boundary spacing on the loaded tooth (m).
    neighbours, ring, root_chord
        As above.

    Returns
    -------
    GearSector
        Vertices, segments and holes for the triangulation, the load vertices on both flanks,
        the spacings and the root chord's vertices.
    """
    pitch = 2 * math.pi / teeth
    sizes = tuple(size * GRADING[k] for k in range(len(GRADING)))
    full = neighbours is None or 2 * neighbours + 1 >= teeth
    closed = full or ring
    js = range(-(teeth // 2), teeth - teeth // 2) if full else range(-neighbours, neighbours + 1)
    outer, loads = _teeth_outline(profile, load_rolls, js, full, pitch, sizes)
    rf = float(np.hypot(*outer[-1]))
    if root_chord is not None:
        outer, ends = _insert_junctions(outer, float(root_chord), pitch)
    if ring and not full:  # the root circle from the right-most root-space middle round to the left-most
        a0 = (neighbours + 0.5) * pitch
        ka = max(int(math.ceil(rf * (2 * math.pi - 2 * a0) / sizes[-1])), 8)
        th = np.linspace(a0, 2 * math.pi - a0, ka + 1)[1:-1]
        outer = np.vstack([outer, np.column_stack([rf * np.sin(th), rf * np.cos(th)])])
    verts, segments, holes = _rim(outer, rf, bore_radius, sizes[-1], ring, closed, len(js) * math.pi / teeth)
    chord = None
    if root_chord is not None:
        verts, segments, chord = _with_root_chord(verts, segments, ends, sizes[0])
    return GearSector(vertices=verts, segments=segments, holes=holes, right_loads=_vertex_indices(verts, loads, rf),
                      left_loads=_vertex_indices(verts, loads * np.array([-1.0, 1.0]), rf), bore_radius=bore_radius,
                      full=closed, sizes=sizes, chord=chord)


def _teeth_outline(profile, load_rolls: np.ndarray, js: range, full: bool, pitch: float, sizes: tuple[float, ...]):
    """The outline (n, 2) (m) over the tips of teeth ``js`` (the loaded one 0) and the load points
    (k, 2) on the loaded tooth's right flank; each tooth spaced by its ``sizes`` entry."""
    pieces = []
    for j in js:
        tooth, loads_j = _tooth_outline(profile, load_rolls if j == 0 else np.array([]), sizes[min(abs(j), len(sizes) - 1)])
        if j == 0:
            loads = loads_j
        keep_first = not full and j == js[0]  # otherwise the previous tooth ends at this root-space middle
        pieces.append(_rotate(tooth if keep_first else tooth[1:], j * pitch))
    return np.vstack(pieces), loads  # over the tips, ending at the right-most root-space middle


def _rim(outer: np.ndarray, rf: float, bore_radius: float, spacing: float, ring: bool, closed: bool, half: float):
    """Vertices, segments and holes of the domain: ``outer`` closed by the bore circle (a whole
    gear or ring: the bore a hole) or by two radial cuts at ±``half`` (rad) and the bore arc."""
    # the wind-up field grows as 1/r³ (the 2-D whole gear: at least 64 points; the 3-D ring: 32)
    kb = max(int(math.ceil(2 * math.pi * bore_radius / spacing)), 32 if ring else 64)
    if closed:
        th = np.linspace(0, 2 * math.pi, kb + 1)[:-1]
        bore = np.column_stack([bore_radius * np.sin(th), bore_radius * np.cos(th)])
        verts = np.vstack([outer, bore])
        return verts, np.vstack([_closed(0, len(outer)), _closed(len(outer), len(bore))]), np.zeros((1, 2))
    kr = max(int(math.ceil((rf - bore_radius) / spacing)), 1)
    r = np.linspace(rf, bore_radius, kr + 1)[1:]
    right_cut = np.column_stack([r * math.sin(half), r * math.cos(half)])
    th = np.linspace(half, -half, max(int(kb * half / math.pi), 2) + 1)[1:]
    bore = np.column_stack([bore_radius * np.sin(th), bore_radius * np.cos(th)])
    left_cut = np.column_stack([r[::-1][1:] * math.sin(-half), r[::-1][1:] * math.cos(-half)])
    verts = np.vstack([outer, right_cut, bore, left_cut])
    return verts, _closed(0, len(verts)), np.zeros((0, 2))


def _with_root_chord(verts: np.ndarray, segments: np.ndarray, ends, spacing: float):
    """The loaded tooth's root chord between vertices ``ends`` as an inner segment, its vertices
    spaced like the loaded tooth: (vertices, segments, the chord's vertex indices)."""
    a, b = verts[ends[0]], verts[ends[1]]
    kc = max(int(math.ceil(np.hypot(*(b - a)) / spacing)), 2)
    inner = a + np.outer(np.linspace(0.0, 1.0, kc + 1)[1:-1], b - a)
    first = len(verts)
    verts = np.vstack([verts, inner])
    chord = np.concatenate([[ends[0]], np.arange(first, first + len(inner)), [ends[1]]])
    return verts, np.vstack([segments, np.column_stack([chord[:-1], chord[1:]])]), chord


def _vertex_indices(verts: np.ndarray, points: np.ndarray, rf: float) -> np.ndarray:
    """Indices of the vertices at ``points`` (k, 2) (m); an error if one is not a vertex."""
    d = np.hypot(verts[:, None, 0] - points[None, :, 0], verts[:, None, 1] - points[None, :, 1])
    i = np.argmin(d, axis=0)
    if not np.all(d[i, np.arange(points.shape[0])] < 1e-9 * rf):
        raise RuntimeError("a load point is not a vertex of the outline")
    return i


def gear_sector(geom: PairGeometry, gear: int, load_rolls, size: float = DEFAULT_SIZE,
                neighbours: int | None = DEFAULT_NEIGHBOURS, bore_radius: float | None = None, ring: bool = False,
                root_chord: float | None = None):
    """(profile, sector) of gear ``gear``: the profile of :func:`gearmesh.profile.tooth_profile`
    and the sector outline (:func:`sector_outline`) with the load rolls as vertices.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    load_rolls : array_like
        Roll lengths (m) of the load points, on the involute.
    size : float
        Element edge on the loaded tooth in normal modules (default 0.05).
    neighbours : int or None
        Teeth each side of the loaded one (default None: the whole gear).
    bore_radius : float, optional
        Bore radius (m); defaults to the pair's.
    ring, root_chord
        As in :func:`sector_outline` (the whole ring with ``neighbours`` teeth each side; θ_f in rad).
    """
    from .profile import tooth_profile
    require_stiffness_data(geom)
    if not size > 0:
        raise GearmeshInputError("size", size, "must be positive (element edge in normal modules)")
    if neighbours is not None and (int(neighbours) != neighbours or neighbours < 0):
        raise GearmeshInputError("neighbours", neighbours, "must be a whole number >= 0, or None (whole gear)")
    profile = tooth_profile(geom, gear, n_fillet=400, n_involute=50)
    r_int = float(geom.pair.bore_radius[gear] if bore_radius is None else bore_radius)
    if not 0 < r_int < profile.root_radius:
        raise GearmeshInputError("bore_radius_mm", r_int * 1e3, "must lie between 0 and the root radius")
    rho = np.atleast_1d(np.asarray(load_rolls, dtype=float))
    if np.any(rho < profile.form_roll - 1e-12) or np.any(rho > np.nanmax(profile.roll) + 1e-12):
        raise GearmeshInputError("rho", rho.tolist(), "load rolls must lie on the involute (form point to tip)")
    sector = sector_outline(profile, geom.pair.teeth[gear], r_int, rho, size * geom.pair.normal_module,
                            None if neighbours is None else int(neighbours), ring=ring, root_chord=root_chord)
    return profile, sector


@dataclass(frozen=True, eq=False)
class ToothCompliance:
    """FE per-unit-width compliances (m²/N) of one tooth at roll lengths ``rho`` (m).

    ``total`` = n·u(C)/F (the tooth deflection without the local contact part, module
    docstring), ``body`` its part carried by the rigid motion of the root section
    (fillet foundation), ``tooth`` = total − body; ``total_left`` the same load mirrored
    onto the left flank (equal to ``total`` by symmetry, up to the mesh). ``wind_up``: the
    part of ``total`` carried by the mean rotation of the circle of radius ``wind_up_radius``
    (m, just inside the root circle) — the torsional wind-up of the body between bore and
    root circle, the n = 0 Fourier mode of the annulus (Lamé/Michell: r_b²/(4πG)·(1/r_int² −
    1/r²) per unit width); ``ring_shift`` the part carried by that circle's mean translation
    (n = 1 mode: the net tooth force moving the body on its bore, growing as log(r_f/r_int)
    as the bore shrinks, the 2-D Kelvin solution); ``local`` = total − wind_up − ring_shift,
    the tooth and its foundation relative to the rigid motion of the body at the root
    circle, which converges as the rim thickens. The three: whole gear only, NaN for a
    sector. ``load_angle`` α1
    (rad). Mesh: ``n_elements`` P2 triangles, ``n_dofs`` unknowns.
    """

    rho: np.ndarray
    total: np.ndarray
    body: np.ndarray
    tooth: np.ndarray
    total_left: np.ndarray
    wind_up: np.ndarray
    ring_shift: np.ndarray
    local: np.ndarray
    wind_up_radius: float
    load_angle: np.ndarray
    plane: str
    size: float
    neighbours: int
    n_elements: int
    n_dofs: int


def loaded_tooth(geom: PairGeometry, gear: int, rho: np.ndarray, plane: str = DEFAULT_PLANE, size: float = DEFAULT_SIZE,
                 neighbours: int | None = DEFAULT_NEIGHBOURS, bore_radius: float | None = None, ring: bool = False):
    """(profile, sector, tooth model, mesh, factorised solver) of gear ``gear`` with load points at
    roll lengths ``rho`` (m) on its loaded tooth, the bore clamped (:func:`tooth_compliance`'s model);
    an unknown ``plane`` refused before meshing.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; ``gear`` 0 pinion, 1 gear.
    rho : ndarray
        (m,) roll lengths of the load points (m).
    plane, size, neighbours, bore_radius
        As :func:`tooth_compliance`.
    ring : bool
        The ring domain of :mod:`gearmesh.fe3d` (no radial cuts).

    Returns
    -------
    tuple
        The profile, the :class:`GearSector`, the transition tooth model, the triangle mesh and
        the factorised :class:`~gearmesh.fe_elastic.ElasticSolver`.
    """
    lame_parameters(1.0, 0.3, plane)
    profile, sector = gear_sector(geom, gear, rho, size, neighbours, bore_radius, ring)
    model = tooth_model(geom, gear, "transition", profile)
    mat = geom.pair.material
    mesh = triangulate(sector.vertices, sector.segments, max_area=AREA_FACTOR * sector.sizes[-1] ** 2,
                       holes=sector.holes)
    r_int = sector.bore_radius
    solver = elastic_solver(mesh, mat.youngs_modulus, mat.poisson_ratio, plane,
                            clamped=lambda x: np.hypot(x[0], x[1]) <= r_int * (1 + 1e-9))
    return profile, sector, model, mesh, solver


def tooth_compliance(geom: PairGeometry, gear: int, rho, plane: str = DEFAULT_PLANE, size: float = DEFAULT_SIZE,
                     neighbours: int | None = DEFAULT_NEIGHBOURS, bore_radius: float | None = None,
                     ring: bool = False) -> ToothCompliance:
    """FE compliance of one tooth of gear ``gear`` under a unit load along the line of action
    at roll lengths ``rho`` (m), on either flank (module docstring for model and read-out).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    rho : array_like
        Roll lengths (m) on the involute.
    plane : {'strain', 'stress'}
        Plane state (default 'strain').
    size : float
        Element edge on the loaded tooth in normal modules (default 0.05).
    neighbours : int or None
        Teeth modelled on each side (default None: the whole gear, no cuts).
    bore_radius : float, optional
        Bore radius (m) overriding the pair's (rim-thickness studies).
    ring : bool
        The whole ring with only ``neighbours`` teeth each side (the domain of :mod:`gearmesh.fe3d`).

    Returns
    -------
    ToothCompliance
        ``total``, ``body``, ``tooth`` … per unit width (m²/N) at ``rho`` (m).
    """
    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    profile, sector, model, mesh, solver = loaded_tooth(geom, gear, rho, plane, size, neighbours, bore_radius, ring)
    x_p, y_p, alpha1, _ = contact_point(model, rho)
    ca, sa = np.cos(alpha1), np.sin(alpha1)
    n_right = np.column_stack([-ca, -sa])
    n_left = np.column_stack([ca, -sa])
    m = rho.size
    u = solver.solve(point_load_matrix(solver, np.concatenate([sector.right_loads, sector.left_loads]),
                                       np.vstack([n_right, n_left])))
    c = np.vstack([np.zeros(m), y_p - x_p * np.tan(alpha1)])  # where the load line crosses the centre line
    cols = np.arange(m)
    u_c = probe_displacements(solver, u, c)  # (2, m points, 2m cases)
    total = np.einsum("ik,ik->k", n_right.T, u_c[:, cols, cols])
    total_left = np.einsum("ik,ik->k", n_left.T, u_c[:, cols, m + cols])
    # fillet foundation: rigid motion of the root section carried to C
    rf, th = model.root_radius, model.theta_f
    a, b = np.array([-rf * math.sin(th), model.y_root]), np.array([rf * math.sin(th), model.y_root])
    t, omega = section_rigid_motion(solver, u[:, :m], a, b)
    d = c - (0.5 * (a + b))[:, None]
    u_body = t + np.vstack([-d[1], d[0]]) * omega
    body = np.einsum("ik,ik->k", n_right.T, u_body)
    wind, shift = np.full(m, np.nan), np.full(m, np.nan)
    if sector.full and neighbours is None:  # the body's torsional wind-up: mean rotation of a circle just inside the root circle
        r_ref = model.root_radius - 0.01 * geom.pair.normal_module
        phi = np.linspace(0.0, 2 * math.pi, 721)[:-1]
        ring = r_ref * np.vstack([np.sin(phi), np.cos(phi)])
        d = probe_displacements(solver, u[:, :m], ring)
        omega = np.mean(-ring[1][:, None] * d[0] + ring[0][:, None] * d[1], axis=0) / r_ref**2
        wind = omega * np.einsum("ik,ik->k", n_right.T, np.vstack([-c[1], c[0]]))
        shift = np.einsum("ki,ik->k", n_right, d.mean(axis=1))  # n = 1 mode: mean translation
    return ToothCompliance(rho=rho, total=total, body=body, tooth=total - body, total_left=total_left,
                           wind_up=wind, ring_shift=shift, local=total - wind - shift, wind_up_radius=r_ref if sector.full and neighbours is None else math.nan,
                           load_angle=alpha1, plane=plane, size=float(size), neighbours=-1 if neighbours is None else int(neighbours),
                           n_elements=int(mesh.t.shape[1]), n_dofs=int(solver.basis.N))


# --------------------------------------------------------------------------------------
# Where the compliance sits: tooth on a rigid base, body under a rigid tooth
# --------------------------------------------------------------------------------------

#: stiffening of the material taken as rigid (E × this): its own compliance becomes 1e-4 of itself
RIGID = 1.0e4


@dataclass(frozen=True, eq=False)
class ToothBodySplit:
    """Compliances per unit width (m²/N) at roll lengths ``rho`` (m), all read at C along the
    line of action (Weber's split) on one mesh (:func:`tooth_body_split`):

    ``total`` the whole gear; ``tooth_rigid_base`` the tooth above its root chord clamped
    on the chord (the potential-energy cantilever's problem: bending + shear + axial);
    ``body_rigid_tooth`` the whole gear with that tooth E × :data:`RIGID` (the body alone
    under the tooth's load: the fillet-foundation problem of Sainsot et al. 2004);
    ``section_body`` the rigid motion of the root chord carried to C (the split of
    :func:`tooth_compliance`); ``interaction`` = total − tooth_rigid_base − body_rigid_tooth
    (the root section does not stay plane: its warping couples tooth and body)."""

    rho: np.ndarray
    total: np.ndarray
    tooth_rigid_base: np.ndarray
    body_rigid_tooth: np.ndarray
    section_body: np.ndarray
    interaction: np.ndarray
    plane: str
    size: float


def tooth_body_split(geom: PairGeometry, gear: int, rho, plane: str = "stress", size: float = DEFAULT_SIZE,
                     neighbours: int | None = DEFAULT_NEIGHBOURS, body_plane: str | None = None,
                     ring: bool = False) -> ToothBodySplit:
    """The FE compliance of one tooth split into an independent tooth problem and body
    problem on one mesh, whose inner segment is the loaded tooth's root chord y = y_root
    of the transition cantilever (:class:`ToothBodySplit`): the FE models the potential-
    energy components are checked against. ``plane`` 'stress' by default: the cantilever
    and Sainsot's foundation use E and G. ``body_plane``: another plane for the body (the
    material below the loaded tooth's root chord and the other teeth), e.g. a tooth in
    plane strain on a body in plane stress; ``ring``: the domain of :mod:`gearmesh.fe3d`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; ``gear`` 0 pinion, 1 gear.
    rho : array_like
        (m,) roll lengths of the load points on the involute (m).
    plane, body_plane : {'strain', 'stress'}, optional
        The tooth's plane state and, if given, the body's.
    size, neighbours
        As :func:`tooth_compliance`.

    Returns
    -------
    ToothBodySplit
        Total, tooth-on-rigid-base, body-under-rigid-tooth, section-motion and interaction
        compliances (m,) (m/N per m of width).

    References
    ----------
    .. [1] Sainsot P., Velex P., Duverger O., "Contribution of gear body to tooth deflections —
       a new bidimensional analytical formula", J. Mech. Des. 126 (2004) 748–752.
    """
    from skfem import Basis, ElementTriP2, ElementVector, asm
    from skfem.models.elasticity import linear_elasticity

    lame_parameters(1.0, 0.3, plane)
    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    model = tooth_model(geom, gear, "transition")
    profile, sector = gear_sector(geom, gear, rho, size, neighbours, ring=ring, root_chord=model.theta_f)
    mesh = triangulate(sector.vertices, sector.segments, max_area=AREA_FACTOR * sector.sizes[-1] ** 2,
                       holes=sector.holes)
    mat = geom.pair.material
    lam, mu = lame_parameters(mat.youngs_modulus, mat.poisson_ratio, plane)
    pitch = 2 * math.pi / geom.pair.teeth[gear]
    chord = sector.vertices[sector.chord]
    a, b = chord[0], chord[-1]  # on the outline's polyline: y within rounding of y_root

    def above(x):  # signed distance (m) from the chord line, positive towards the tip
        return ((b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0])) / np.hypot(*(b - a))

    mid = mesh.p[:, mesh.t].mean(axis=1)
    in_tooth = (above(mid) > 0) & (np.abs(np.arctan2(mid[0], mid[1])) < 0.5 * pitch)
    elem = ElementVector(ElementTriP2())
    basis = Basis(mesh, elem, intorder=4)
    form = linear_elasticity(lam, mu)
    k_tooth = asm(form, Basis(mesh, elem, intorder=4, elements=np.flatnonzero(in_tooth))).tocsr()
    form_body = form if body_plane is None else linear_elasticity(
        *lame_parameters(mat.youngs_modulus, mat.poisson_ratio, body_plane))
    k_body = asm(form_body, Basis(mesh, elem, intorder=4, elements=np.flatnonzero(~in_tooth))).tocsr()
    bore = basis.get_dofs(lambda x: np.hypot(x[0], x[1]) <= sector.bore_radius * (1 + 1e-9)).all()
    x_p, y_p, alpha1, _ = contact_point(model, rho)
    n_right = np.column_stack([-np.cos(alpha1), -np.sin(alpha1)])
    c = np.vstack([np.zeros(rho.size), y_p - x_p * np.tan(alpha1)])

    loaded = (basis, sector.right_loads, n_right, c)
    total, solver, u = _compliance_along_load(k_tooth + k_body, bore, *loaded)
    body, _, _ = _compliance_along_load(k_body + RIGID * k_tooth, bore, *loaded)
    # the tooth alone: every dof off the tooth's elements, and the dofs on its root chord, held
    on_chord = basis.get_dofs(lambda x: (np.abs(above(x)) < 1e-9 * model.root_radius)
                              & (x[0] >= min(a[0], b[0]) - 1e-12) & (x[0] <= max(a[0], b[0]) + 1e-12)).all()
    held = np.union1d(np.setdiff1d(np.arange(basis.N), np.unique(basis.element_dofs[:, in_tooth])), on_chord)
    tooth, _, _ = _compliance_along_load(k_tooth, held, *loaded)
    t, omega = section_rigid_motion(solver, u, a, b)
    d = c - (0.5 * (a + b))[:, None]
    section = np.einsum("ik,ik->k", n_right.T, t + np.vstack([-d[1], d[0]]) * omega)
    return ToothBodySplit(rho=rho, total=total, tooth_rigid_base=tooth, body_rigid_tooth=body, section_body=section,
                          interaction=total - tooth - body, plane=plane, size=float(size))


def _compliance_along_load(k, held: np.ndarray, basis, loads: np.ndarray, directions: np.ndarray, c: np.ndarray):
    """Compliance (m,) (m/N per m of width) along ``directions`` (m, 2) at the points ``c`` (2, m)
    under unit loads at the vertices ``loads`` (m,), with stiffness matrix ``k`` and the degrees
    of freedom ``held`` fixed; and the factorised solver and the displacements (N, m)."""
    from scipy.sparse.linalg import splu

    free = np.setdiff1d(np.arange(basis.N), held)
    lu = splu(k[free][:, free].tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
              options={"SymmetricMode": True})
    solver = ElasticSolver(basis=basis, free=free, lu=lu)
    u = solver.solve(point_load_matrix(solver, loads, directions))
    cols = np.arange(len(loads))
    return np.einsum("ik,ik->k", directions.T, probe_displacements(solver, u, c)[:, cols, cols]), solver, u


@dataclass(frozen=True, eq=False)
class ContactApproach:
    """One tooth under a Hertzian pressure strip of half-width ``half_width`` (m) centred on
    the contact point of roll ``rho`` (m), unit resultant per unit width along the line of
    action, in ``plane``: ``at_c`` n·u(C) (m²/N, the tooth deflection of Weber's split),
    ``point_at_c`` the same for the point load of :func:`tooth_compliance` (same mesh),
    ``approach`` n·(u(P) − u(C)) (m²/N, the local contact part: P's approach to C),
    ``weber`` Weber's closed form of that approach (:func:`weber_approach`), ``depth`` |PC| (m)."""

    rho: float
    half_width: float
    at_c: float
    point_at_c: float
    approach: float
    weber: float
    depth: float
    plane: str


def weber_approach(depth, half_width, youngs_modulus: float, poisson_ratio: float, plane: str = "strain"):
    """Approach (m²/N, per unit load per unit width) of the surface point under the middle of
    a Hertzian strip of half-width a towards the point at ``depth`` d below it on the load
    line, the half-plane solution Weber (1949) used for the local part of a tooth's
    deflection: plane strain (2(1−ν²)/(πE))·[ln(2d/a) − ν/(2(1−ν))], plane stress
    (2/(πE))·[ln(2d/a) − ν/2]. Derivation: ∫₀ᵈ ε_z dz on the axis of the strip with
    Johnson's (Contact Mechanics, 1985, eq. 2.40/5.?) subsurface stresses σ_z = −p₀a/√(a²+z²),
    σ_x = −p₀[(a² + 2z²)/√(a²+z²) − 2z]/a, whose integrals are −p₀a·asinh(d/a) and
    −p₀·d(√(a²+d²) − d)/a → −p₀a·ln(2d/a) and −p₀a/2 for d ≫ a; p₀a = 2/π per unit load.

    Parameters
    ----------
    depth, half_width : array_like
        Depth d of the point below the surface and the strip's half-width a (m).
    youngs_modulus, poisson_ratio : float
        E (Pa) and ν (-).
    plane : {'strain', 'stress'}
        Plane state (default 'strain').
    """
    d = np.asarray(depth, dtype=float)
    a = np.asarray(half_width, dtype=float)
    e, nu = float(youngs_modulus), float(poisson_ratio)
    lam = np.arcsinh(d / a)  # exact integral of σ_z along the axis, = ln(2d/a) + O((a/d)²)
    sx = d * (np.sqrt(a * a + d * d) - d) / (a * a)  # exact integral of σ_x / (p₀a), → 1/2
    if plane == "strain":
        return 2.0 / (math.pi * e) * ((1 - nu**2) * lam - nu * (1 + nu) * sx)
    lame_parameters(1.0, 0.3, plane)
    return 2.0 / (math.pi * e) * (lam - nu * sx)


def contact_approach(geom: PairGeometry, gear: int, rho: float, half_width: float, plane: str = "strain",
                     size: float = DEFAULT_SIZE, neighbours: int | None = DEFAULT_NEIGHBOURS,
                     points: int = 12) -> ContactApproach:
    """The FE tooth under a Hertzian strip against the point load and against Weber's closed
    form (:class:`ContactApproach`). The flank carries vertices every a/``points`` of arc
    length over ±1.5 a around P (the involute's arc length from the base circle is
    ρ²/(2 r_b)); the pressure p(s) = (2/(πa))·√(1 − s²/a²) acts on them along each
    vertex's own line of action, lumped by the trapezoidal rule and scaled to a unit
    resultant.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; ``gear`` 0 pinion, 1 gear.
    rho : float
        Roll length of the contact point P (m).
    half_width : float
        Hertzian half-width a (m).
    plane : {'strain', 'stress'}
        The plane state.
    size, neighbours
        As :func:`tooth_compliance`.
    points : int
        Flank vertices per half-width.

    Returns
    -------
    ContactApproach
        The approaches under the strip and under the point load and Weber's closed form (m/N
        per m of width).

    References
    ----------
    .. [1] Weber C., "Formänderung und Profilrücknahme bei gerad- und schrägverzahnten Rädern",
       Schriftenreihe Antriebstechnik 11, Vieweg, 1949.
    .. [2] Johnson K. L., *Contact Mechanics*, Cambridge University Press, 1985, §5.
    """
    model = tooth_model(geom, gear, "transition")
    rb = model.base_radius
    s_p = rho**2 / (2 * rb)
    ds = half_width / points
    k = np.arange(-int(1.5 * points), int(1.5 * points) + 1)
    rolls = np.sqrt(2 * rb * (s_p + k * ds))
    lo, hi = geom.rho_sap[gear], float(np.nanmax(tooth_profile_rolls(geom, gear)))
    keep = (rolls >= max(lo, 0.0)) & (rolls <= hi)
    rolls, k = rolls[keep], k[keep]
    profile, sector = gear_sector(geom, gear, rolls, size, neighbours)
    mesh = triangulate(sector.vertices, sector.segments, max_area=AREA_FACTOR * sector.sizes[-1] ** 2,
                       holes=sector.holes)
    mat = geom.pair.material
    solver = elastic_solver(mesh, mat.youngs_modulus, mat.poisson_ratio, plane,
                            clamped=lambda x: np.hypot(x[0], x[1]) <= sector.bore_radius * (1 + 1e-9))
    x_p, y_p, a1, _ = contact_point(model, rolls)
    n = np.column_stack([-np.cos(a1), -np.sin(a1)])
    s = k * ds
    inside = np.abs(s) < half_width
    p = np.where(inside, np.sqrt(np.clip(1 - (s / half_width) ** 2, 0, None)), 0.0)
    p /= p.sum()
    centre = int(np.flatnonzero(k == 0)[0])
    strip = point_load_matrix(solver, sector.right_loads, n * p[:, None]).sum(axis=1)
    point = point_load_matrix(solver, sector.right_loads[[centre]], n[[centre]])[:, 0]
    u = solver.solve(np.column_stack([strip, point]))
    nc = n[centre]
    c = np.array([[0.0], [y_p[centre] - x_p[centre] * math.tan(a1[centre])]])
    uc = probe_displacements(solver, u, c)[:, 0, :]  # (2, 2 cases)
    up = u[solver.basis.nodal_dofs[:, sector.right_loads[centre]], 0]
    depth = float(np.hypot(x_p[centre] - c[0, 0], y_p[centre] - c[1, 0]))
    return ContactApproach(rho=float(rho), half_width=float(half_width), at_c=float(nc @ uc[:, 0]),
                           point_at_c=float(nc @ uc[:, 1]), approach=float(nc @ (up - uc[:, 0])),
                           weber=float(weber_approach(depth, half_width, mat.youngs_modulus, mat.poisson_ratio, plane)),
                           depth=depth, plane=plane)


def tooth_profile_rolls(geom: PairGeometry, gear: int) -> np.ndarray:
    """Roll lengths (m) of the involute of :func:`gearmesh.profile.tooth_profile` (NaN off it).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    gear : int
        0 pinion, 1 gear.

    Returns
    -------
    ndarray
        Roll length of each profile point (m), NaN on the fillet and circles.
    """
    from .profile import tooth_profile

    return tooth_profile(geom, gear, n_fillet=400, n_involute=50).roll
