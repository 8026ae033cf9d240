"""Mesh-in impact of a modified helical pair (the mesh-in impact paper): mesh-in point, impact velocity,
local stiffness and the energy-method impact force — in the TCA/LTCA framework.

Everything inside is SI (m, N, s, rad, kg). Displacements, separations and forces follow the
transverse line-of-action convention of :mod:`gearmesh.tca` and :mod:`gearmesh.ltca`
(transverse displacement r_b1·Δφ1 with the gear held, force F_bt = T1/r_b1).

The event
---------
Under load the pairs already in mesh are compressed by their approach δ(roll) (the LTE);
the entering tooth pair still has its unloaded separation g(roll, z) — flank points in the
active zone and the mating tip edge outside it (:func:`gearmesh.tca.separation_basis`),
with both gears' modifications and lead slope errors. The entering pair first touches at
the first roll where

    min_z g(roll, z) = δ_others(roll),

δ_others the approach of the other pairs alone (the entering pair carries nothing before it
touches). This is the mesh-in impact paper's TE(φ)/LTE(φ) intersection, solved in roll by a bracketing
root-finder (a grid over a window from the outer end of the tip-edge candidates to one
base pitch past the theoretical start of engagement φ1A, then Illinois regula falsi with
the exact separation and a final Newton step on the exact δ). The point of the entering pair
where it happens is the mesh-in point M; the mesh-in impact paper's two scenarios are where M lies:
``edge`` — a tip edge outside the active zone (the mesh-in impact paper scenario 1: "tip point to tooth
surface") — or ``surface`` — two (modified) flanks inside it (scenario 2). One formulation,
no separate code paths.

Driver
------
With the pinion driving the roll grows in time and pairs enter at the start of the path
of contact A (the gear's tip edge meets the pinion flank). With the gear driving (a speed
increaser), the same flanks carry the same static loads (reverse every rotation of a
pinion-driven mesh: the gear now pushes the pinion), so the LTCA is unchanged and time runs
backwards along the path: pairs enter at its end E, the pinion's tip edge meeting the gear
flank. ``tau`` below is the time-like roll σ·(roll − roll_engagement), σ = +1 / −1.

Impact velocity
---------------
The closing rate of g − δ at the touch, v_t = −d(g − δ)/dτ · r_b1·ω1, is the relative
velocity in the transverse line-of-action coordinate — the coordinate of the equivalent mass
m_eq = J1·J2/(J1·r_b2² + J2·r_b1²) (the mesh-in impact paper). Independently, :func:`vector_velocity`
evaluates the mesh-in impact paper's v = (ω1 − ω2) × r − E × ω2 at the true closest points of the two exact
(modified) transverse profiles with their common normal. In the edge case they are the same
quantity exactly (the pinion flank's normal is tangent to its base circle, so the pinion
point's normal velocity is r_b1·ω1 and the gap of the tip edge closes at v·n); in the
surface case they agree to first order in the relief slopes (the true closest points lie off
the line of action by slope/curvature). The 3-D normal velocity is v·n with the helicoid
normal, smaller by cos βb; the mesh-in impact paper puts it into E_k = ½·m_eq·v², which mixes a normal
velocity with a transverse mass: the consistent form is v_t (default,
``energy_velocity='transverse'``), the seed's literal form is kept as ``'normal'``.

Local stiffness and force
-------------------------
The mesh-in impact paper loads the entering pair alone, quasi-statically, with its points' separations
relative to M at the touch instant: here exactly that, with the LTCA's point compliances
(:func:`gearmesh.ltca.point_compliance`) and contact law, giving the F–δ curve of the
impact. The energy balance ½·m_eq·v² = ∫F dδ is solved on that curve (piecewise power-law
integration, exact for a pure power law), and F = K_s·δ^n is fitted (log-log least squares
on 24 points evenly spaced in δ over [δ_s/24, δ_s], the range the impact reaches) for seed
000's closed form F_s = ((n+1)/2·m_eq·v²)^(n/(n+1))·K_s^(1/(n+1)). Both are reported.
:func:`simulate_engagement` checks the energy method against a direct time integration of
the same event.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from .choices import DEFAULT_CONTACT_LAW, DEFAULT_CORNER_EXTENSION, DEFAULT_CYCLE_POSITIONS, DEFAULT_TOOTH_METHOD
from .errors import GearmeshInputError
from .gear import PairGeometry, involute
from .limits import check_speeds
from .ltca import _invert, check_torques, law_scales, log_universal_inverse, solve_contact
from .ltca_model import LTCAModel, ContactLaw, contact_law, ltca_model, point_compliance
from .body import mesh_body_compliance
from .deflection import mesh_misalignment
from .deviation import with_misalignment
from .surface import body_rotation, flank_point, modification_parameters, plane_of_action_point, relief_depth
from .tca import (REGION_APPROACH_TIP, REGION_RECESS_TIP, SeparationBasis, approach_tip_point, basis_gap,
                  candidate_grid, engagement_point, pair_lead_slope, point_centres, recess_tip_point, separation_basis)
from .contact import hand_sign

__all__ = [
    "SCENARIOS", "DRIVERS", "impact_paper_inertia", "equivalent_mass", "ImpactModel", "impact_model",
    "ImpactStatic", "impact_static", "ImpactResponse", "impact_response", "closed_form_force",
    "energy_balance", "fit_power_law", "vector_velocity", "seed_edge_roll", "simulate_engagement",
    "LTCACriteria", "ltca_criteria", "ltca_metrics", "load_grid", "load_window",
]

SCENARIOS = ("none", "surface", "edge")
SCENARIO_NONE, SCENARIO_SURFACE, SCENARIO_EDGE = 0, 1, 2
DRIVERS = ("pinion", "gear")
ENERGY_VELOCITIES = ("transverse", "normal")
_FIT_POINTS = 24


# --------------------------------------------------------------------------------------
# Inertia and equivalent mass (the mesh-in impact paper)
# --------------------------------------------------------------------------------------


def impact_paper_inertia(geom: PairGeometry) -> np.ndarray:
    """Polar moments (kg m²) of both gears by the mesh-in impact paper: J_i = πρB_i(r_bi⁴ − r_hi⁴)/2 — a solid
    disc of the base radius r_b over the face width B, less the hub bore r_h."""
    pair = geom.pair
    if pair.material is None or pair.bore_radius is None:
        raise GearmeshInputError("material" if pair.material is None else "bore_radius_mm", None,
                                 "is required for the gear inertias of the impact model (the mesh-in impact paper's discs)")
    rb, rh, b = geom.base_radius, np.asarray(pair.bore_radius), np.asarray(pair.face_width)
    return math.pi * pair.material.density * b * (rb**4 - rh**4) / 2.0


def equivalent_mass(geom: PairGeometry, inertia) -> float:
    """m_eq = J1·J2/(J1·r_b2² + J2·r_b1²) (kg): the mass of the relative coordinate
    r_b1·θ1 + r_b2·θ2 along the transverse line of action (the mesh-in impact paper)."""
    j1, j2 = (float(v) for v in inertia)
    rb1, rb2 = (float(v) for v in geom.base_radius)
    return j1 * j2 / (j1 * rb2**2 + j2 * rb1**2)



# --------------------------------------------------------------------------------------
# The load-, speed- and modification-independent model
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ImpactModel:
    """Everything the impact objective reuses between torques, speeds and modifications (SI).

    ``ltca`` the LTCA model (slice tables, pair table, contact law); ``driver`` 'pinion' or
    'gear' and ``sigma`` ±1 (module docstring); ``roll_engagement`` the roll at which the
    entering corner reaches the end of the active zone it enters by, ``pair_enter`` its
    tooth-pair index, ``z_corner`` that corner. The search window: ``tau`` (R,) time-like
    rolls, ``window`` the other pairs' candidate points at those rolls, flattened
    (:class:`WindowPoints`; the entering pair is column ``window_enter_column`` of the tooth
    pairs ``window_pairs``), ``enter_fine_basis`` (R, Nz) the entering pair on
    ``z_fine`` (Nz,) points over the face. ``points`` the LTCA points per line (the other
    pairs), ``local_points`` / ``local_keep`` / ``local_law`` the entering line's own slicing
    for its local stiffness; ``inertia`` (2,) kg m², ``equivalent_mass`` kg; ``lead_slope`` the
    gears' lead slope deviations (m); ``body_compliance`` the described gear bodies' compliance in
    series with the mesh (m/N, :func:`gearmesh.body.mesh_body_compliance`), in the entering pair's
    force–approach curve as in the LTCA. The mesh misalignment of each torque (the stated f_ma and
    the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`) is added where a
    torque is known (:func:`impact_static`, :func:`ltca_criteria`).
    """

    geom: PairGeometry
    ltca: LTCAModel
    driver: str
    sigma: int
    roll_engagement: float
    pair_enter: int
    z_corner: float
    extension: float
    tau: np.ndarray
    window: "WindowPoints"
    window_enter_column: int
    window_pairs: np.ndarray
    z_fine: np.ndarray
    enter_fine_basis: SeparationBasis
    points: int
    local_points: int
    local_keep: int
    local_law: ContactLaw
    inertia: np.ndarray
    equivalent_mass: float
    lead_slope: tuple[float, float]
    body_compliance: float = 0.0

    def roll(self, tau):
        """Pinion roll (m) of time-like roll ``tau`` (m)."""
        return self.roll_engagement + self.sigma * np.asarray(tau, dtype=float)

    def s_enter(self, tau, z):
        """Line-of-action position (m) of the entering pair's point at axial ``z`` (m)."""
        g = self.geom
        return (self.roll(tau) + self.pair_enter * g.transverse_base_pitch
                + hand_sign(g) * np.asarray(z, dtype=float) * math.tan(g.base_helix_angle))

    def params(self, params=None) -> np.ndarray:
        """Modification parameters as (C, 2, 6) (m); default the pair's own (C = 1)."""
        if params is None:
            return modification_parameters(self.geom)[None]
        p = np.asarray(params, dtype=float)
        if p.ndim == 2:
            p = p[None]
        if p.ndim != 3 or p.shape[1:] != (2, 6) or not np.all(np.isfinite(p)) or np.any(p < 0):
            raise GearmeshInputError("modification", p.shape, "must be finite, non-negative (C, 2, 6) parameters (m)")
        return p

    def lead_slopes(self, lead_slope, rows: int) -> np.ndarray:
        """Lead slope errors as (C, 2) (m over the face width): one [pinion, gear] pair per
        parameter set, default the model's own for every set."""
        if lead_slope is None:
            return np.broadcast_to(np.asarray(self.lead_slope, dtype=float), (rows, 2))
        f = np.asarray(lead_slope, dtype=float)
        if f.ndim == 1:
            f = f[None]
        if f.shape != (rows, 2) or not np.all(np.isfinite(f)):
            raise GearmeshInputError("lead_slope", f.shape, f"must be finite [pinion, gear] pairs, one per parameter "
                                                            f"set ({rows}, 2) (m)")
        return f


@dataclass(frozen=True)
class WindowPoints:
    """The candidate points of the pairs already in mesh at the rolls of the search window,
    flattened to K points in roll order (only real candidates kept): ``roll_index`` (K,) the
    window roll of each point, ``starts`` (R,) the first point of each roll (a roll without
    any point has none: ``counts`` 0), ``basis`` their separation basis, ``z`` (K,) their face
    positions, ``compliance`` (K,) their linear compliance (m/N, the law's linear part added).
    Everything here is independent of the modification, the lead slope and the load."""

    roll_index: np.ndarray
    starts: np.ndarray
    counts: np.ndarray
    basis: SeparationBasis
    z: np.ndarray
    compliance: np.ndarray

    def per_roll_sum(self, values: np.ndarray) -> np.ndarray:
        """Sum of ``values`` (..., K) over the points of each roll: (..., R)."""
        out = np.zeros(values.shape[:-1] + self.counts.shape)
        some = self.counts > 0
        if some.any():
            out[..., some] = np.add.reduceat(values, self.starts[some], axis=-1)
        return out


def _window_points(basis: SeparationBasis, z: np.ndarray, compliance: np.ndarray) -> WindowPoints:
    """:class:`WindowPoints` of the (R, J, N) window arrays (non-candidates dropped)."""
    keep = np.isfinite(basis.base)
    r = basis.base.shape[0]
    roll_index = np.nonzero(keep)[0]
    counts = keep.reshape(r, -1).sum(axis=1)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.intp)
    flat = SeparationBasis(*(getattr(basis, f)[keep] for f in SeparationBasis.__dataclass_fields__))
    return WindowPoints(roll_index=roll_index, starts=starts, counts=counts, basis=flat, z=np.asarray(z)[keep],
                        compliance=compliance[keep])


def _engagement(geom: PairGeometry, driver: str) -> tuple[float, int, float]:
    """(roll, pair index, corner z) at which the entering pair's leading corner reaches the end
    of the active zone it enters by: A (s = 0) with the pinion driving, E (s = g_α) with the
    gear driving (roll in [0, p_bt))."""
    if driver == "pinion":
        return engagement_point(geom)
    pbt = geom.transverse_base_pitch
    half_axial = 0.5 * geom.face_width * math.tan(geom.base_helix_angle)
    # the corner with the smallest s, z = −h·b/2, reaches s = g_α
    roll_e = (geom.path_of_contact + half_axial) % pbt
    if roll_e >= pbt * (1 - 1e-12):
        roll_e = 0.0
    j_e = int(round((geom.path_of_contact + half_axial - roll_e) / pbt))
    z_e = -hand_sign(geom) * 0.5 * geom.face_width if half_axial > 0 else 0.0
    return float(roll_e), j_e, float(z_e)


def impact_model(geom: PairGeometry, points: int = 50, lead_slope=None, contact_law_name: str = DEFAULT_CONTACT_LAW,
                 method: str = DEFAULT_TOOTH_METHOD, extension: float = DEFAULT_CORNER_EXTENSION, driver: str = "pinion",
                 added_inertia_kg_m2=(0.0, 0.0), window_positions: int = 32, face_samples: int = 257,
                 cycle_positions: int = DEFAULT_CYCLE_POSITIONS, local_points: int = 400, local_keep: int = 400,
                 ltca: LTCAModel | None = None) -> ImpactModel:
    """Prepare the impact objective of ``geom`` (its modification is only the default).

    Parameters
    ----------
    points : LTCA points per contact line (the other pairs and the local stiffness).
    lead_slope : lead slope deviations [pinion, gear] (m over the face width); None: the pair's own.
    contact_law_name, method : local contact law and cantilever model (:mod:`gearmesh.ltca`).
    extension : reach of the tip-edge candidates beyond the active zone (fraction of p_bt).
    driver : 'pinion' or 'gear' (module docstring).
    added_inertia_kg_m2 : inertia (kg m²) of what hangs on each shaft, added to the mesh-in impact paper's discs.
    window_positions : grid rolls over the search window (−extension … +1 base pitch).
    face_samples : samples of the entering line over the face for min_z (refined by a parabola).
    cycle_positions : rolls per mesh cycle of the LTCA grid kept for :func:`ltca_criteria`.
    local_points, local_keep : slices of the entering line for its local stiffness, and how
        many of them (those closest to contact) are loaded. The F–δ curve of an edge contact
        spreads along the line (separations growing like |z − z_M|), and converges only when a
        slice's separation step is small against the impact's approach: hundreds of slices,
        more than the LTCA's ``points`` (test ``test_convergence_in_local_slices``).
    ltca : a prepared LTCA model (its grid is the one :func:`ltca_criteria` uses).
    """
    if driver not in DRIVERS:
        raise GearmeshInputError("driver", driver, f"must be one of {list(DRIVERS)}")
    added = np.asarray(added_inertia_kg_m2, dtype=float)
    if added.shape != (2,) or not np.all(np.isfinite(added)) or np.any(added < 0):
        raise GearmeshInputError("added_inertia_kg_m2", list(np.atleast_1d(added)),
                                 "must be two finite, non-negative inertias [pinion, gear] (kg m²)")
    for name, value, low, high in (("window_positions", window_positions, 8, 10000),
                                   ("face_samples", face_samples, 9, 100000), ("local_points", local_points, 2, 100000),
                                   ("local_keep", local_keep, 2, 100000)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not low <= value <= high:
            raise GearmeshInputError(name, value, f"must be an integer in [{low}, {high}]")
    lead_slope = pair_lead_slope(geom, lead_slope)
    if ltca is None:
        ltca = ltca_model(geom, positions=cycle_positions, points=points, lead_slope=lead_slope, contact_law_name=contact_law_name,
                          method=method, extension=extension)
    inertia = impact_paper_inertia(geom) + added
    pbt = geom.transverse_base_pitch
    ext = float(extension) * pbt
    sigma = 1 if driver == "pinion" else -1
    roll_e, j_e, z_c = _engagement(geom, driver)
    # window: from the outer end of the entering corner's tip-edge candidates to one base pitch in
    tau = np.linspace(-ext, pbt, int(window_positions))
    tau = np.unique(np.append(tau, 0.0))
    roll = roll_e + sigma * tau
    grid = candidate_grid(geom, roll, points, tuple(lead_slope), extension)
    col = np.flatnonzero(grid.pairs == j_e)
    if col.size == 0:
        raise RuntimeError("the entering tooth pair is not among the candidate pairs of the window")
    col = int(col[0])
    compliance = point_compliance(geom, ltca.pair_table, ltca.tables, grid.s, grid.region, grid.rho_pinion,
                                  grid.rho_gear, with_hertz=ltca.law.name == "linear") / grid.dz + ltca.law.linear
    # the pairs already in mesh, flattened to their candidate points
    window = _window_points(_without_column(grid.basis, col), np.broadcast_to(grid.z, grid.s.shape), compliance)
    z_fine = np.linspace(-0.5 * geom.face_width, 0.5 * geom.face_width, int(face_samples))
    s_fine = (roll[:, None] + j_e * pbt + hand_sign(geom) * z_fine[None, :] * math.tan(geom.base_helix_angle))
    fine = separation_basis(geom, s_fine, np.inf)
    return ImpactModel(geom=geom, ltca=ltca, driver=driver, sigma=sigma, roll_engagement=roll_e, pair_enter=j_e,
                       z_corner=z_c, extension=ext, tau=tau, window=window, window_enter_column=col, window_pairs=np.asarray(grid.pairs),
                       z_fine=z_fine, enter_fine_basis=fine, points=int(points), local_points=int(local_points),
                       local_keep=int(local_keep),
                       local_law=contact_law(geom, geom.face_width / local_points, ltca.law.name) if ltca.law.name != "linear"
                       else ContactLaw("linear", 0.0, 1.0, 0.0, geom.face_width / local_points), inertia=inertia,
                       equivalent_mass=equivalent_mass(geom, inertia), lead_slope=lead_slope,
                       body_compliance=mesh_body_compliance(geom))


# --------------------------------------------------------------------------------------
# The entering pair: separation against roll, refined minimum over the face
# --------------------------------------------------------------------------------------


def _parabolic_min(values: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Minimum over the last axis of samples ``values`` at equally spaced ``x``, refined by the
    parabola through the three samples centred on the smallest one (the end triple at either
    end, so the refined minimum does not jump when the smallest sample reaches an end); the
    vertex is used when it lies within that triple, else the smallest sample. Returns
    (minimum, its x); NaN where every sample is NaN."""
    v = np.where(np.isfinite(values), values, np.inf)
    n = v.shape[-1]
    k = np.argmin(v, axis=-1)
    vk = np.take_along_axis(v, k[..., None], -1)[..., 0]
    kc = np.clip(k, 1, n - 2)

    def at(i):
        return np.take_along_axis(v, i[..., None], -1)[..., 0]

    vm, v0, vp = at(kc - 1), at(kc), at(kc + 1)
    h = x[1] - x[0]
    with np.errstate(invalid="ignore", divide="ignore"):
        curv = vm - 2 * v0 + vp
        off = 0.5 * (vm - vp) / np.where(curv > 0, curv, 1.0)
        inside = np.isfinite(vm + v0 + vp) & (curv > 0) & (np.abs(off) <= 1.0)
        vertex = v0 - 0.25 * (vm - vp) * off
    use = inside & (vertex < vk)
    vmin = np.where(use, vertex, vk)
    xmin = np.where(use, x[kc] + off * h, x[k])
    return np.where(np.isinf(vk), np.nan, vmin), xmin


def _rows(a: np.ndarray, ndim: int) -> np.ndarray:
    """Per-row arrays (C, ...) with ``ndim`` unit axes inserted after the row axis (to broadcast
    one parameter set or lead-slope pair per row against points)."""
    return a.reshape(a.shape[:1] + (1,) * ndim + a.shape[1:])


#: Face samples either side of the previous minimum that :func:`_enter_gap` searches when told
#: where the minimum was (a touch iteration moves the roll by micrometres).
_NEAR_SAMPLES = 6


def _enter_gap(model: ImpactModel, params: np.ndarray, tau: np.ndarray, lead: np.ndarray, near=None):
    """Smallest separation of the entering pair over the face (m) and where (z), at time-like
    rolls ``tau`` (N,), one parameter set ``params`` (N, 2, 6) and lead-slope pair ``lead`` (N, 2)
    per roll. With ``near`` (N,) face positions of a minimum found at a neighbouring roll, only the
    :data:`_NEAR_SAMPLES` face samples either side of it are searched; a row whose minimum falls on
    the edge of that block (and not at a face end) is searched over the whole face."""
    g = model.geom
    tau = np.asarray(tau, dtype=float)
    z = model.z_fine
    if near is None:
        s = model.s_enter(tau[:, None], z)
        gap = basis_gap(g, separation_basis(g, s, np.inf), z, _rows(lead, 1), _rows(params, 1))
        return _parabolic_min(gap, z)
    h, n = z[1] - z[0], 2 * _NEAR_SAMPLES + 1
    first = np.clip(np.rint((np.asarray(near) - z[0]) / h).astype(np.intp) - _NEAR_SAMPLES, 0, z.size - n)
    zz = z[first[:, None] + np.arange(n)]
    s = model.s_enter(tau[:, None], zz)
    gap = basis_gap(g, separation_basis(g, s, np.inf), zz, _rows(lead, 1), _rows(params, 1))
    local = np.arange(n) * h
    gmin, x = _parabolic_min(gap, local)
    k = np.argmin(np.where(np.isfinite(gap), gap, np.inf), axis=1)
    inside = ((k > 0) | (first == 0)) & ((k < n - 1) | (first == z.size - n)) & np.isfinite(gmin)
    zmin = zz[:, 0] + x
    if not inside.all():
        gmin[~inside], zmin[~inside] = _enter_gap(model, params[~inside], tau[~inside], lead[~inside])
    return gmin, zmin


def _enter_gap_window(model: ImpactModel, params: np.ndarray, lead: np.ndarray):
    """The same on the window grid (C, R), reusing the window's entering-line basis."""
    gap = basis_gap(model.geom, model.enter_fine_basis, model.z_fine, _rows(lead, 2), _rows(params, 2))
    return _parabolic_min(gap, model.z_fine)


def _solve_rows(gap: np.ndarray, compliance: np.ndarray, force: np.ndarray, law: ContactLaw,
                rtol: float = 1e-12, delta_start=None) -> np.ndarray:
    """Approach δ (m) of each row (NaN for a row without any candidate point); ``rtol`` of the
    load sum (and 100× finer for each point's inversion)."""
    ok = np.isfinite(gap).any(axis=1)
    delta = np.full(gap.shape[0], np.nan)
    if ok.any():
        start = None if delta_start is None else np.asarray(delta_start, dtype=float).reshape(-1)[ok]
        _, d, _, _ = solve_contact(gap[ok], compliance[ok], force[ok], law, rtol=rtol, inner_tol=min(1e-14, rtol / 100),
                                   delta_start=start)
        delta[ok] = d
    return delta


def _point_loads(model: ImpactModel, approach: np.ndarray, gap: np.ndarray, compliance: np.ndarray):
    """Loads q (N) and tangent stiffnesses dq/dδ (N/m) of points of separation ``gap`` at the
    approach ``approach`` (broadcast): each point's law inverted directly (NaN gap: no point)."""
    law = model.ltca.law
    d = approach - gap
    return _invert(np.where(np.isfinite(d), d, -1.0), compliance, law.coefficient, law.exponent)


def _others_at(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray):
    """Separations (N, M) and compliances (N, M) (m/N, law's linear part added) of the pairs
    already in mesh at time-like rolls ``tau`` (N,), one parameter set and lead pair per roll:
    the exact candidate points of the window's tooth pairs at those rolls (no interpolation)."""
    g = model.geom
    z, dz = point_centres(g, model.points)
    s = (model.roll(tau)[:, None, None] + model.window_pairs[None, :, None] * g.transverse_base_pitch
         + hand_sign(g) * z[None, None, :] * math.tan(g.base_helix_angle))
    basis = _without_column(separation_basis(g, s, model.extension), model.window_enter_column)
    gap = basis_gap(g, basis, z, _rows(lead, 2), _rows(params, 2))
    comp = point_compliance(g, model.ltca.pair_table, model.ltca.tables, s, basis.region, basis.rho_pinion,
                            basis.rho_gear, with_hertz=model.ltca.law.name == "linear") / dz + model.ltca.law.linear
    n = gap.shape[0]
    return gap.reshape(n, -1), comp.reshape(n, -1)


def _touch_force(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray, near=None):
    """The force F*(τ) at which the entering pair touches at time-like roll τ, exactly, for rows
    (N,): the force the pairs already in mesh carry when they are compressed to the entering
    pair's smallest separation g(τ), F* = Σ_i q_i(g(τ) − g_i(τ)). Returns F* (N), the tangent
    stiffness ΣdF/dδ there (N/m), g (m) and its face position z (m); ``near`` as :func:`_enter_gap`;
    and the other pairs' points there (:class:`_Others`)."""
    gap_e, z_e = _enter_gap(model, params, tau, lead, near)
    gap_o, comp = _others_at(model, params, lead, tau)
    q, dq = _point_loads(model, gap_e[:, None], gap_o, comp)
    return q.sum(axis=1), dq.sum(axis=1), gap_e, z_e, _Others(gap_o, comp, q, dq)


@dataclass
class _Others:
    """The points of the pairs already in mesh at a touch roll, rows (N, M): separations (m),
    compliances (m/N), loads q (N) and dq/dδ (N/m) at the entering pair's separation."""

    gap: np.ndarray
    comp: np.ndarray
    q: np.ndarray
    dq: np.ndarray

    def put(self, rows: np.ndarray, other: "_Others") -> "_Others":
        """``other`` written into ``rows`` (allocated at the first write, NaN elsewhere)."""
        for name in ("gap", "comp", "q", "dq"):
            here, there = getattr(self, name), getattr(other, name)
            if here is None:
                here = np.full((self.gap_rows, there.shape[1]), np.nan)
                setattr(self, name, here)
            here[rows] = there
        return self

    gap_rows: int = 0


# --------------------------------------------------------------------------------------
# The static (speed-independent) part: mesh-in point, slope, F–δ curve
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ImpactStatic:
    """Speed-independent impact quantities for C modifications × T torques (SI).

    ``torque`` (T,) pinion torque, ``force`` (T,) F_bt; per (C, T): ``scenario`` 0 none /
    1 surface / 2 edge; ``tau`` time-like roll of the touch (m, negative = before the
    theoretical engagement), ``roll`` the pinion roll there; ``approach`` δ_others at the
    touch (m); ``gap_rate`` −dg/dτ and ``approach_rate`` dδ/dτ there (-): the closing rate of
    g − δ per unit roll is their sum (:attr:`slope`);
    ``s``, ``z``, ``rho_pinion``, ``rho_gear`` where M lies (m); ``region`` its candidate
    region; ``te_engagement`` the entering pair's separation at the theoretical engagement
    (m; the mesh-in impact paper's TE(φ1A)), ``lte_engagement`` the approach of all pairs there (LTE(φ1A);
    NaN unless asked for); ``curve_force`` / ``curve_approach`` (C, T, K) the F–δ curve of the
    entering pair alone from M (N, m; F = 0 at δ = 0 implied), from the separations and
    compliances of its slices ``curve_separation`` / ``curve_compliance`` (C, T, L);
    ``params`` (C, 2, 6) and ``lead_slope`` (C, 2) the micro-geometry of each row (m).
    """

    torque: np.ndarray
    force: np.ndarray
    scenario: np.ndarray
    tau: np.ndarray
    roll: np.ndarray
    approach: np.ndarray
    gap_rate: np.ndarray
    approach_rate: np.ndarray
    s: np.ndarray
    z: np.ndarray
    rho_pinion: np.ndarray
    rho_gear: np.ndarray
    region: np.ndarray
    te_engagement: np.ndarray
    lte_engagement: np.ndarray
    curve_force: np.ndarray
    curve_approach: np.ndarray
    params: np.ndarray
    curve_separation: np.ndarray
    curve_compliance: np.ndarray
    lead_slope: np.ndarray

    @property
    def slope(self) -> np.ndarray:
        """−d(g − δ)/dτ at the touch (-): the closing rate of the entering pair per unit roll."""
        return self.gap_rate + self.approach_rate


#: Illinois iterations of the touch roll within its window cell (each an exact evaluation).
_MAX_TOUCH_ITERATIONS = 60
#: The touch is pinned down when the entering pair's separation and the loaded approach differ
#: by at most this (m) — the criterion of an "impact found".
_TOUCH_TOLERANCE = 1e-12


def _crossing(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force: np.ndarray):
    """Touch roll τ*, the entering pair's smallest separation there and its face position for
    every (C, T) of transverse forces ``force`` (C, T) N (module docstring; NaN where the touch fell
    on a window roll), whether found and whether at the window start, and the entering pair's
    separation at the theoretical engagement (C,).

    The touch condition g(τ) = δ_others(τ) is solved as F*(τ) = F_bt (:func:`_touch_force`):
    since the other pairs' force grows with their approach, g > δ_others exactly where
    F*(τ) > F_bt. F* needs one inversion per point and no load iteration, and does not depend
    on the torque: one pass over the window grid brackets every torque's touch (the first
    roll with F* ≤ F_bt; :func:`_window_touch_force`), then a secant iteration with exact
    evaluations of F* pins it down inside its cell."""
    nc, nt = force.shape
    k0 = int(np.flatnonzero(model.tau == 0.0)[0])
    f_win, g_win = _window_touch_force(model, params, lead, force.min(axis=1), k0)
    below = f_win[:, None, :] <= force[:, :, None]  # NaN: not below
    found = below.any(axis=-1)
    k = np.argmax(below, axis=-1)  # first roll at or past the touch
    at_start = found & (k == 0)
    t_star, g_star, z_star = (np.full((nc, nt), np.nan) for _ in range(3))
    cc, tt = np.nonzero(found & ~at_start)
    if cc.size:
        kk = k[cc, tt]
        a, b = model.tau[kk - 1], model.tau[kk]
        target = force[cc, tt]
        fa, fb = f_win[cc, kk - 1] - target, f_win[cc, kk] - target  # fa > 0 ≥ fb: the bracket
        # secant iteration from the cubic estimate (its slope for the first step), kept inside the
        # bracket (bisection when a step would leave it); every evaluation exact
        x_last, slope = _inverse_cubic(model.tau, f_win[cc], kk, target, a, b, fa, fb)
        f_last, g_last, z_last = (np.full(cc.size, np.nan) for _ in range(3))
        last_others = _Others(None, None, None, None, cc.size)
        active = np.flatnonzero(fb != 0.0)
        x_next = x_last.copy()
        for _ in range(_MAX_TOUCH_ITERATIONS):
            if not active.size:
                break
            c = x_next[active]
            f_c, k_c, g_c, z_c, o_c = _touch_force(model, params[cc[active]], lead[cc[active]], c)
            g_last[active], z_last[active] = g_c, z_c
            last_others.put(active, o_c)
            fc = f_c - target[active]
            up = fc > 0
            a[active] = np.where(up, c, a[active])
            fa[active] = np.where(up, fc, fa[active])
            b[active] = np.where(up, b[active], c)
            fb[active] = np.where(up, fb[active], fc)
            with np.errstate(invalid="ignore", divide="ignore"):
                prev_x, prev_f = x_last[active], f_last[active]
                step = np.where(np.isfinite(prev_f), fc * (c - prev_x) / (fc - prev_f), fc / slope[active])
                nxt = c - step
            ai, bi = a[active], b[active]
            nxt = np.where(np.isfinite(nxt) & (nxt > ai) & (nxt < bi), nxt, 0.5 * (ai + bi))
            x_last[active], f_last[active] = c, fc
            x_next[active] = nxt
            # pinned down: |g − δ| ≈ |F* − F_bt|/K below the touch tolerance, or the cell collapsed
            stop = (np.abs(fc) <= 0.5 * _TOUCH_TOLERANCE * k_c) | (bi - ai <= 1e-15)
            active = active[~stop]
        t_star[cc, tt] = np.where(np.isfinite(f_last), x_last, b)
        g_star[cc, tt], z_star[cc, tt] = g_last, z_last
        if last_others.gap is not None:  # the other pairs at each touch roll, as last evaluated
            evaluated = np.isfinite(f_last)
            at_touch = _Others(None, None, None, None, nc * nt).put(cc[evaluated] * nt + tt[evaluated],
                                                                    _Others(*(getattr(last_others, f)[evaluated] for f in
                                                                              ("gap", "comp", "q", "dq"))))
            return t_star, g_star, z_star, found & ~at_start, at_start, g_win[:, k0], at_touch
    return t_star, g_star, z_star, found & ~at_start, at_start, g_win[:, k0], None


#: Window rolls evaluated per pass of :func:`_window_touch_force`.
_WINDOW_CHUNK = 8


def _window_touch_force(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force_min: np.ndarray, k0: int):
    """F*(c, τ_k) and the entering pair's smallest separation g(c, τ_k) on the window rolls (C, R).

    The rolls are taken in passes of :data:`_WINDOW_CHUNK` from the window's start: a row is done
    once its F* has fallen to its smallest force ``force_min`` (C,) and the roll after that
    crossing is known (the first crossing of every larger force comes no later, since
    F* ≤ F_bt,min implies F* ≤ F_bt), so the rolls after it are left NaN. Roll ``k0`` (the
    theoretical engagement) is always evaluated."""
    w, g = model.window, model.geom
    nc, r = params.shape[0], model.tau.size
    f_win, g_win = np.full((nc, r), np.nan), np.full((nc, r), np.nan)
    ends = np.append(w.starts, w.roll_index.size)
    ends[:-1][w.counts == 0] = w.starts[w.counts == 0]
    active, lo = np.arange(nc), 0
    while active.size and lo < r:
        hi = min(r, lo + _WINDOW_CHUNK)
        pr, lr = params[active], lead[active]
        basis = SeparationBasis(*(getattr(model.enter_fine_basis, f)[lo:hi] for f in SeparationBasis.__dataclass_fields__))
        gap_e, _ = _parabolic_min(basis_gap(g, basis, model.z_fine, _rows(lr, 2), _rows(pr, 2)), model.z_fine)
        pts = slice(int(w.starts[lo]), int(ends[hi]) if hi < r else w.roll_index.size)
        sub = SeparationBasis(*(getattr(w.basis, f)[pts] for f in SeparationBasis.__dataclass_fields__))
        gap_o = basis_gap(g, sub, w.z[pts], _rows(lr, 1), _rows(pr, 1))
        q, _ = _point_loads(model, gap_e[:, w.roll_index[pts] - lo], gap_o, w.compliance[pts])
        f = np.zeros((active.size, hi - lo))
        some = w.counts[lo:hi] > 0
        if some.any():
            f[:, some] = np.add.reduceat(q, w.starts[lo:hi][some] - w.starts[lo], axis=-1)
        f_win[active, lo:hi] = np.where(np.isfinite(gap_e), f, np.nan)
        g_win[active, lo:hi] = gap_e
        below = f_win[active, :hi] <= force_min[active, None]
        k = np.argmax(below, axis=1)
        done = (below.any(axis=1) & (k + 1 < hi)) | (hi == r)
        active, lo = active[~done], hi
    missing = np.isnan(g_win[:, k0])
    if missing.any():  # rows done before the engagement roll: its separation still
        basis = SeparationBasis(*(getattr(model.enter_fine_basis, f)[k0:k0 + 1]
                                  for f in SeparationBasis.__dataclass_fields__))
        g_win[missing, k0] = _parabolic_min(basis_gap(g, basis, model.z_fine, _rows(lead[missing], 2),
                                                      _rows(params[missing], 2)), model.z_fine)[0][:, 0]
    return f_win, g_win


def _lagrange_cubic(x: np.ndarray, y: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Value and derivative at ``t`` (R,) of the cubic through the four points (``x``, ``y``) (R, 4)
    of each row (Lagrange basis and its derivative)."""
    val, der = np.zeros_like(t), np.zeros_like(t)
    for i in range(4):
        li, dli = np.ones_like(t), np.zeros_like(t)
        for j in range(4):
            if j != i:
                w = 1.0 / (x[:, i] - x[:, j])
                dli = dli * (t - x[:, j]) * w + li * w
                li = li * (t - x[:, j]) * w
        val += y[:, i] * li
        der += y[:, i] * dli
    return val, der


def _inverse_cubic(tau: np.ndarray, f: np.ndarray, k: np.ndarray, target: np.ndarray, a, b, fa, fb) -> np.ndarray:
    """A first estimate of the roll where F* = ``target`` inside window cell [τ_(k−1), τ_k] and the
    slope dF*/dτ there: the cubic through F* at the four nodes k−2 … k+1 as a function of τ, solved
    by two Newton steps from the linear estimate; the linear estimate and the chord's slope where
    the cubic leaves the cell or does not fall (rows (N,), ``f`` (N, R) F* on the window)."""
    r = tau.size
    lin = b - fb * (b - a) / (fb - fa)
    kk = np.clip(k, 2, r - 2)
    nodes = kk[:, None] + np.arange(-2, 2)[None, :]
    x = tau[nodes]
    y = np.take_along_axis(f, nodes, 1) - target[:, None]
    t = lin.copy()
    with np.errstate(invalid="ignore", divide="ignore"):
        for _ in range(2):
            val, der = _lagrange_cubic(x, y, t)
            t = t - val / der
        _, der = _lagrange_cubic(x, y, t)  # the cubic's slope at the estimate (for the first secant step)
    ok = np.isfinite(t) & (t > a) & (t < b) & (der < 0)
    return np.where(ok, t, lin), np.where(ok, der, (fb - fa) / (b - a))


def _enter_points(model: ImpactModel, params: np.ndarray, lead: np.ndarray, tau: np.ndarray):
    """The entering pair's line at the touch ``tau`` (C, T), discretised for its local stiffness:
    ``local_points`` equal slices over the face, of which the ``local_keep`` with the smallest
    separation from the first to touch are kept (the others cannot load within the curve,
    checked by :func:`impact_response`). Returns separations relative to the first point to touch
    (C, T, K) and compliances (m/N) of those slices."""
    g = model.geom
    z, dz = point_centres(g, model.local_points)
    s = model.s_enter(tau[..., None], z)
    basis = separation_basis(g, s, np.inf)
    gap = basis_gap(g, basis, z, _rows(lead, 2), _rows(params, 2))
    comp = point_compliance(g, model.ltca.pair_table, model.ltca.tables, s, basis.region, basis.rho_pinion,
                            basis.rho_gear, with_hertz=model.ltca.law.name == "linear") / dz
    gap = np.where(np.isfinite(gap), gap, np.inf)
    keep = min(model.local_keep, gap.shape[-1])
    if keep < gap.shape[-1]:
        idx = np.argpartition(gap, keep - 1, axis=-1)[..., :keep]
        gap = np.take_along_axis(gap, idx, -1)
        comp = np.take_along_axis(comp, idx, -1)
    with np.errstate(invalid="ignore"):
        rel = gap - gap.min(axis=-1, keepdims=True)
    return rel, comp


def impact_static(model: ImpactModel, torques, params=None, curve_levels: int = 48,
                  curve_force_min=None, lead_slope=None, engagement: bool = True) -> ImpactStatic:
    """The speed-independent part of the impact for pinion torques ``torques`` (N m) and
    modification parameter sets ``params`` ((C, 2, 6) m; default the pair's own).

    ``lead_slope`` (C, 2) the lead slope deviations [pinion, gear] of each set (m over the face
    width; default the model's for all): additive to the separations
    (:func:`gearmesh.deviation.lead_gap`), so a tolerance sample costs no new geometry; each
    torque adds its mesh misalignment (:func:`gearmesh.deflection.mesh_misalignment`: torques
    of different misalignment are solved as one batch of a row per set and torque, each row
    with its own lead slopes and force — what each torque alone gives, to round-off).
    ``curve_levels`` approaches of the entering pair's F–δ curve, geometric up to one at which
    it carries at least ``curve_force_min`` (N, (C, T) or scalar; default 4·F_bt) —
    :func:`impact_response` extends it where an impact needs more. ``engagement``: also the
    loaded TE of all pairs at the theoretical engagement (``lte_engagement``, one more load
    solve per row; NaN without).
    """

    g = model.geom
    params = model.params(params)
    lead = model.lead_slopes(lead_slope, params.shape[0])
    t1 = check_torques(torques)
    force = t1 / float(g.base_radius[0])
    mis = mesh_misalignment(g, force)
    if np.all(mis == mis[0]):
        return _static(model, t1, params, with_misalignment(lead, mis[0]), lead, curve_levels, curve_force_min,
                       engagement)
    # each torque at its own misalignment: one row per (set, torque), each with its own lead rows and
    # force (the rows of a batch are solved independently, so this is each torque solved alone)
    nc, nt = params.shape[0], t1.size
    c, t = np.repeat(np.arange(nc), nt), np.tile(np.arange(nt), nc)
    cfm = None if curve_force_min is None else \
        np.broadcast_to(np.asarray(curve_force_min, dtype=float), (nc, nt)).reshape(-1, 1)
    rows = _static(model, t1[:1], params[c], with_misalignment(lead[c], mis[t]), lead[c], curve_levels, cfm,
                   engagement, force=force[t][:, None])
    return _unstack_rows(rows, t1, force, params, lead)


def _unstack_rows(rows: "ImpactStatic", t1: np.ndarray, force: np.ndarray, params: np.ndarray,
                  lead: np.ndarray) -> "ImpactStatic":
    """The :class:`ImpactStatic` of C sets at T torques from one solved with a row per (set, torque)
    (rows (C·T, 1, ...), set-major): pinion torques ``t1`` (T,) N m, forces ``force`` (T,) N, the
    sets' ``params`` (C, 2, 6) and own lead slopes ``lead`` (C, 2) m."""
    nc, nt = params.shape[0], t1.size
    out = {"torque": t1, "force": force, "params": params, "lead_slope": np.array(lead)}
    for name in ImpactStatic.__dataclass_fields__:
        if name not in out:
            a = getattr(rows, name)
            out[name] = a.reshape((nc, nt) + a.shape[2:])
    return ImpactStatic(**out)


def _static(model: ImpactModel, t1: np.ndarray, params: np.ndarray, lead: np.ndarray, lead_rows: np.ndarray,
            curve_levels: int, curve_force_min, engagement: bool, force: np.ndarray | None = None) -> "ImpactStatic":
    """:func:`impact_static` at pinion torques ``t1`` (N m) whose separations share the lead rows
    ``lead`` (C, 2) (m, the mesh misalignment of these torques included); ``lead_rows`` the rows'
    own slopes, stored in the result. ``force`` (C, T) N: each row's own transverse forces instead
    of those of ``t1`` (a row per set and torque, :func:`impact_static`; ``torque``, ``force`` of the
    result are then those of ``t1``)."""
    g = model.geom
    nc = params.shape[0]
    f_t = t1 / float(g.base_radius[0])
    force = np.broadcast_to(f_t if force is None else np.asarray(force, dtype=float), (nc, f_t.size))
    nt = force.shape[1]
    t_star, g_star, z_star, found, at_start, te0, at_touch = _crossing(model, params, lead, force)
    if np.any(at_start):
        warnings.warn("impact: the entering pair touches at the outer end of the tip-edge candidates; "
                      "raise corner_extension", RuntimeWarning, stacklevel=2)
    tt = np.where(found, t_star, 0.0)
    # at the touch, the rates from one stacked exact evaluation at τ − 2ε, τ − ε, τ: the one-sided
    # (second-order) difference from the approach side is the closing rate just before the touch,
    # positive at any crossing from above even where min_z g or a point's separation has a kink
    # (a point of the pairs in mesh unloading, the minimum jumping along the face or following a kink)
    eps = 1e-6 * g.transverse_base_pitch
    offsets = np.array([-2 * eps, -eps, 0.0])
    rows_c = np.broadcast_to(np.arange(nc)[:, None], (nc, nt)).reshape(-1)
    stack = (tt.reshape(-1)[None, :] + offsets[:, None]).reshape(-1)
    p3, l3 = np.tile(params[rows_c], (3, 1, 1)), np.tile(lead[rows_c], (3, 1))
    # the smallest separation at τ* from the touch iteration (the whole face; searched anew where the
    # touch fell on a window roll), the two earlier rolls near its face position
    gap_min, z_min = g_star.reshape(-1).copy(), z_star.reshape(-1).copy()
    redo = ~np.isfinite(gap_min)
    if redo.any():
        gap_min[redo], z_min[redo] = _enter_gap(model, params[rows_c[redo]], tt.reshape(-1)[redo], lead[rows_c[redo]])
    n2 = 2 * nc * nt
    gap2, _ = (v.reshape(2, nc * nt) for v in _enter_gap(model, p3[:n2], stack[:n2], l3[:n2], np.tile(z_min, 2)))
    gap3 = np.concatenate([gap2, gap_min[None]])
    # the other pairs at τ − 2ε, τ − ε, and at τ itself where the touch iteration left them
    kept = np.zeros(nc * nt, dtype=bool) if at_touch is None else np.isfinite(at_touch.gap).any(axis=1) & found.reshape(-1)
    anew = np.concatenate([np.ones(n2, dtype=bool), ~kept])
    gap_n, comp_n = _others_at(model, p3[anew], l3[anew], stack[anew])
    m = gap_n.shape[-1]
    gap_o, comp = np.empty((3 * nc * nt, m)), np.empty((3 * nc * nt, m))
    gap_o[anew], comp[anew] = gap_n, comp_n
    gap_o, comp = gap_o.reshape(3, nc * nt, m), comp.reshape(3, nc * nt, m)
    q, dq = np.empty((nc * nt, m)), np.empty((nc * nt, m))
    if kept.any():
        gap_o[2, kept], comp[2, kept], q[kept], dq[kept] = (at_touch.gap[kept], at_touch.comp[kept], at_touch.q[kept],
                                                            at_touch.dq[kept])
    q[~kept], dq[~kept] = _point_loads(model, gap_min[~kept, None], gap_o[2, ~kept], comp[2, ~kept])
    stiff = dq.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        resid = (q.sum(axis=1) - force.reshape(-1)) / stiff  # g − δ_others at τ* (one Newton step)
        # δ − g_i = c_i(τ)·q_i + δ_c(q_i) at fixed Σq_i = F_bt: dδ/dτ = Σk_i·(g_i' + c_i'·q_i)/Σk_i
        # (k_i = dq_i/dδ; the compliance changes as the points move along the profile)
        rate_o = (3 * (gap_o[2] + comp[2] * q) - 4 * (gap_o[1] + comp[1] * q) + gap_o[0] + comp[0] * q) / (2 * eps)
        approach_rate = np.sum(np.where(dq > 0, dq * rate_o, 0.0), axis=1) / stiff
    gap_rate = -(3 * gap3[2] - 4 * gap3[1] + gap3[0]) / (2 * eps)
    delta = gap_min - resid
    found = found & (np.abs(resid).reshape(nc, nt) <= _TOUCH_TOLERANCE)  # a crossing not pinned down is no impact
    delta, gap_rate, approach_rate, z_m = (v.reshape(nc, nt) for v in (delta, gap_rate, approach_rate, z_min))
    s_m = model.s_enter(tt, z_m)
    bm = separation_basis(g, s_m, np.inf)
    region = np.where(found, bm.region, 0).astype(np.int8)
    scenario = np.where(~found, SCENARIO_NONE,
                        np.where((region == REGION_APPROACH_TIP) | (region == REGION_RECESS_TIP), SCENARIO_EDGE,
                                 SCENARIO_SURFACE)).astype(np.int8)
    # TE and LTE at the theoretical engagement (τ = 0, a window roll): all pairs at φ1A
    lte0 = (_approach_at(model, params, lead, force[None], np.zeros((1, nc, nt)), others=False)[0]
            if engagement else np.full((nc, nt), np.nan))
    # F–δ curve of the entering pair alone from M
    # separations from the first slice to touch (→ M as local_points → ∞)
    rel, comp = _enter_points(model, params, lead, tt)
    fmin = 4.0 * force * np.ones((nc, 1)) if curve_force_min is None else \
        np.broadcast_to(np.asarray(curve_force_min, dtype=float), (nc, nt))
    cf, ca = _force_curve(model, rel, comp, _curve_reach(model, rel, comp, fmin), curve_levels)
    nan = ~found
    for arr in (delta, gap_rate, approach_rate, s_m, z_m):
        arr[nan] = np.nan
    cf[nan], ca[nan] = np.nan, np.nan
    return ImpactStatic(torque=t1, force=f_t, scenario=scenario, tau=np.where(found, tt, np.nan),
                        roll=np.where(found, model.roll(tt), np.nan), approach=delta, gap_rate=gap_rate,
                        approach_rate=approach_rate, s=s_m, z=z_m,
                        rho_pinion=np.where(found, bm.rho_pinion, np.nan), rho_gear=np.where(found, bm.rho_gear, np.nan),
                        region=region, te_engagement=np.broadcast_to(te0[:, None], (nc, nt)).copy(),
                        lte_engagement=lte0, curve_force=cf, curve_approach=ca, params=params,
                        curve_separation=rel, curve_compliance=comp, lead_slope=np.array(lead_rows))


def _without_column(basis: SeparationBasis, column: int) -> SeparationBasis:
    """``basis`` (..., J, N) with tooth pair ``column`` made a non-candidate (the entering pair)."""
    base = np.array(basis.base)
    base[..., column, :] = np.nan
    return replace(basis, base=base)


def _approach_at(model: ImpactModel, params: np.ndarray, lead: np.ndarray, force: np.ndarray, tau: np.ndarray,
                 others: bool, delta_start=None) -> np.ndarray:
    """Approach δ of the other pairs (``others``) or of all pairs at time-like rolls ``tau``
    (..., C, T) — leading axes stack several rolls per (C, T) — by one exact solve on a
    candidate grid at those rolls; ``lead`` (C, 2) the lead slopes of each parameter set."""
    g, law = model.geom, model.ltca.law
    shape = tau.shape
    roll = model.roll(tau).reshape(-1)
    grid = candidate_grid(g, roll, model.points, (0.0, 0.0), model.extension / g.transverse_base_pitch,
                          pairs=model.window_pairs)
    b = _without_column(grid.basis, model.window_enter_column) if others else grid.basis
    p = np.broadcast_to(params[:, None], shape + (2, 6)).reshape(-1, 1, 1, 2, 6)
    f = np.broadcast_to(lead[:, None], shape + (2,)).reshape(-1, 1, 1, 2)
    gap = basis_gap(g, b, np.broadcast_to(grid.z, grid.s.shape), f, p).reshape(roll.size, -1)
    comp = (point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid.s, grid.region, grid.rho_pinion,
                             grid.rho_gear, with_hertz=law.name == "linear") / grid.dz).reshape(roll.size, -1)
    f = np.broadcast_to(force, shape).reshape(-1)
    start = None if delta_start is None else np.broadcast_to(delta_start, shape)
    return _solve_rows(gap, comp, f, law, delta_start=start).reshape(shape)


def _sorted_slices(model: ImpactModel, rel: np.ndarray, comp: np.ndarray):
    """The entering line's slices of every row (R, L), in order of separation from the first to
    touch: separations (non-candidates at 1 m, out of reach) and compliances (m/N, the local
    law's linear part added)."""
    law = model.local_law
    length = rel.shape[-1]
    e = np.where(np.isfinite(rel), rel, 1.0).reshape(-1, length)
    c = (np.where(np.isfinite(comp), comp, 1.0) + law.linear).reshape(-1, length)
    order = np.argsort(e, axis=1, kind="stable")
    return np.take_along_axis(e, order, 1), np.take_along_axis(c, order, 1)


def _force_curve(model: ImpactModel, rel: np.ndarray, comp: np.ndarray, dmax: np.ndarray, levels: int):
    """F–δ of the entering pair alone: approaches (C, T, K) geometric from 1e-5·dmax to dmax and
    the force each causes, F(δ) = Σ q_i(δ − e_i) with every slice's own law inverted directly
    (separations ``rel`` e_i from the first slice to touch; no load solve needed this way round).

    Only the loaded (slice, level) pairs are formed: with the slices in order of separation, the
    slices loaded at level k are the first n_k of them (e_i < δ_k)."""
    law = model.local_law
    e, c = _sorted_slices(model, rel, comp)
    rows, length = e.shape
    frac = np.geomspace(1e-5, 1.0, int(levels))
    dm = np.broadcast_to(np.asarray(dmax, dtype=float), rel.shape[:-1]).reshape(-1)
    d = dm[:, None] * frac  # (R, K)
    with np.errstate(invalid="ignore", divide="ignore"):
        first = np.searchsorted(frac, e / dm[:, None], side="right")  # first level with δ_k > e_i
    # the ratio test can differ from δ_k > e_i by one ulp: settle it on δ_k itself
    lower = np.maximum(first - 1, 0)
    first = np.where((first > 0) & (np.take_along_axis(d, np.minimum(lower, levels - 1), 1) > e), lower, first)
    hist = np.zeros((rows, levels + 1), dtype=np.intp)
    np.add.at(hist, (np.arange(rows)[:, None], first), 1)
    n = np.cumsum(hist[:, :levels], axis=1).reshape(-1)  # slices loaded at each (row, level)
    rk = np.repeat(np.arange(rows * levels), n)
    j = np.arange(rk.size) - np.repeat(np.cumsum(n) - n, n)
    flat = (rk // levels) * length + j
    x = d.reshape(-1)[rk] - e.reshape(-1)[flat]  # > 0 by construction
    if law.coefficient:
        # the universal inverse of :func:`gearmesh.ltca.invert_tabulated`, with each slice's
        # scales taken once per slice rather than once per (slice, level)
        log_q, log_cq = law_scales(c, law.coefficient, law.exponent)
        v = log_universal_inverse(np.log(x) - log_cq.reshape(-1)[flat], law.exponent)
        q = np.exp(log_q.reshape(-1)[flat] + v)
        outside = np.isnan(v)
        if outside.any():
            q[outside] = _invert(x[outside], c.reshape(-1)[flat[outside]], law.coefficient, law.exponent)[0]
    else:
        q = x / c.reshape(-1)[flat]
    force = np.bincount(rk, weights=q, minlength=rows * levels).reshape(rel.shape[:-1] + (levels,))
    # the described bodies in series: they bend under the entering pair's force too (gearmesh.body)
    return force, d.reshape(rel.shape[:-1] + (levels,)) + model.body_compliance * force


def _curve_reach(model: ImpactModel, rel: np.ndarray, comp: np.ndarray, force: np.ndarray) -> np.ndarray:
    """An approach (m) at which the entering pair carries at least ``force`` (N), close to the
    least one: δ_lin + coef·q_max^m, δ_lin the approach of the slices with their linear
    compliances alone (exact, from prefix sums over the slices in order of separation) and q_max
    the largest slice load there. An upper bound: at it every loaded slice's law gives at least
    its linear load, since q_i ≤ q_max adds at most coef·q_max^m to its approach."""
    law = model.local_law
    e, c = _sorted_slices(model, rel, comp)
    f = np.broadcast_to(np.asarray(force, dtype=float), rel.shape[:-1]).reshape(-1, 1)
    k = 1.0 / c
    s, t = np.cumsum(k, axis=1), np.cumsum(e * k, axis=1)
    carried = e[:, 1:] * s[:, :-1] - t[:, :-1]  # force when the approach reaches the next slice
    j = np.sum(carried < f, axis=1, keepdims=True)
    delta = (f + np.take_along_axis(t, j, 1)) / np.take_along_axis(s, j, 1)
    q_max = np.max(np.where(np.arange(e.shape[1]) <= j, (delta - e) * k, 0.0), axis=1, keepdims=True)
    reach = delta + (law.coefficient * q_max**law.exponent if law.coefficient else 0.0)
    return reach.reshape(rel.shape[:-1])


# --------------------------------------------------------------------------------------
# Energy method
# --------------------------------------------------------------------------------------


def closed_form_force(mass, velocity, k_s, n):
    """The mesh-in impact paper's energy-method peak force F_s = ((n+1)/2·m·v²)^(n/(n+1))·K_s^(1/(n+1)) (N),
    from ½·m·v² = ∫₀^δs K_s·δ^n dδ; m (kg), v (m/s), K_s (N/m^n), n (-)."""
    n = np.asarray(n, dtype=float)
    return ((n + 1) / 2 * mass * np.asarray(velocity) ** 2) ** (n / (n + 1)) * np.asarray(k_s) ** (1 / (n + 1))


def energy_balance(curve_approach, curve_force, energy):
    """Peak force and approach where ∫₀^δ F dδ = ``energy`` on a tabulated F–δ curve.

    ``curve_approach``, ``curve_force`` (..., K) increasing, with (0, 0) implied before the
    first node; between nodes F is the power law through them (exact for a pure power law,
    so the closed form and this agree to round-off on F = K·δ^n). ``energy`` (...,) or
    broadcastable with an extra speed axis last: (..., S). Returns (force, approach), NaN
    where the curve does not reach the energy (extend it).
    """
    d = np.asarray(curve_approach, dtype=float)
    f = np.asarray(curve_force, dtype=float)
    e = np.asarray(energy, dtype=float)
    # segment exponents p_i = ln(F_i+1/F_i)/ln(δ_i+1/δ_i); the first segment continues to 0
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.log(f[..., 1:] / f[..., :-1]) / np.log(d[..., 1:] / d[..., :-1])
    p = np.concatenate([p[..., :1], p], axis=-1)  # segment k ends at node k
    d_prev = np.concatenate([np.zeros_like(d[..., :1]), d[..., :-1]], axis=-1)
    f_prev = np.concatenate([np.zeros_like(f[..., :1]), f[..., :-1]], axis=-1)
    seg = (d * f - d_prev * f_prev) / (p + 1)
    cum = np.cumsum(seg, axis=-1)  # energy at node k
    # locate the segment for every energy (last axis of e is extra)
    cum_e = cum[..., None, :]
    k = np.sum(cum_e < e[..., None], axis=-1)  # first node with cum ≥ e
    kk = np.clip(k, 0, d.shape[-1] - 1)
    take = lambda a: np.take_along_axis(np.broadcast_to(a[..., None, :], e.shape + a.shape[-1:]), kk[..., None], -1)[..., 0]  # noqa: E731
    ck, pk, dk, fk = take(cum), take(p), take(d), take(f)
    # within segment k: E(δ) = E_k − (δ_k F_k − δ F(δ))/(p+1), F(δ) = F_k (δ/δ_k)^p
    rest = (ck - e) * (pk + 1)  # = δ_k F_k − δ F(δ) ≥ 0
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = ((dk * fk - rest) / (dk * fk)) ** (1.0 / (pk + 1))  # (δ/δ_k)
        approach = dk * ratio
        force = fk * ratio**pk
    bad = (k >= d.shape[-1]) | ~np.isfinite(force)
    return np.where(bad, np.nan, force), np.where(bad, np.nan, approach)


def fit_power_law(curve_approach, curve_force, approach_max, n_points: int = _FIT_POINTS):
    """Least-squares fit F = K_s·δ^n (log-log) to the F–δ curve over [δ_s/n_points, δ_s] at
    ``n_points`` approaches evenly spaced in δ (the range an impact of peak approach δ_s
    reaches). ``approach_max`` (..., S). Returns (K_s in N/m^n, n, RMS relative error of F)."""
    d = np.asarray(curve_approach, dtype=float)
    f = np.asarray(curve_force, dtype=float)
    dm = np.asarray(approach_max, dtype=float)
    x = dm[..., None] * (np.arange(1, n_points + 1) / n_points)  # (..., S, P)
    # log-log interpolation of the curve (consistent with the energy balance), (0,0) implied
    ld, lf = np.log(d), np.log(f)
    lx = np.log(x)
    idx = np.clip(np.sum(ld[..., None, None, :] < lx[..., None], axis=-1), 1, d.shape[-1] - 1)

    def at(a, i):
        return np.take_along_axis(np.broadcast_to(a[..., None, None, :], lx.shape + a.shape[-1:]), i[..., None], -1)[..., 0]

    d0, d1, f0, f1 = at(ld, idx - 1), at(ld, idx), at(lf, idx - 1), at(lf, idx)
    with np.errstate(invalid="ignore", divide="ignore"):
        ly = f0 + (lx - d0) * (f1 - f0) / (d1 - d0)
    ok = np.isfinite(lx).all(axis=-1, keepdims=True)
    lx, ly = np.where(ok, lx, 0.0), np.where(ok, ly, 0.0)  # no impact: no fit (NaN below)
    xm, ym = lx.mean(axis=-1), ly.mean(axis=-1)
    n = ((lx - xm[..., None]) * (ly - ym[..., None])).sum(-1) / ((lx - xm[..., None]) ** 2).sum(-1)
    logk = ym - n * xm
    k_s = np.exp(logk)
    pred = np.exp(logk[..., None] + n[..., None] * lx)
    err = np.sqrt(np.mean((pred / np.exp(ly) - 1.0) ** 2, axis=-1))
    bad = ~ok[..., 0]
    return np.where(bad, np.nan, k_s), np.where(bad, np.nan, n), np.where(bad, np.nan, err)


@dataclass(frozen=True)
class ImpactResponse:
    """Speed-dependent impact quantities (C, T, S) for the speeds ``speed_rpm`` (S,) (SI).

    ``velocity_transverse`` v_t (m/s, the closing rate of g − δ); ``velocity_normal`` v_t·cos βb
    (the 3-D normal velocity of the helicoid normal); ``kinetic_energy`` ½·m_eq·v² of the
    velocity selected by ``energy_velocity``; ``force_energy_balance`` and
    ``approach_energy_balance`` from the computed F–δ curve; ``stiffness_coefficient`` K_s
    (N/m^n), ``stiffness_exponent`` n and ``fit_error`` of F = K_s·δ^n over that range;
    ``force`` the mesh-in impact paper's closed form with them (N).
    """

    speed_rpm: np.ndarray
    velocity_transverse: np.ndarray
    velocity_normal: np.ndarray
    kinetic_energy: np.ndarray
    force: np.ndarray
    force_energy_balance: np.ndarray
    approach_energy_balance: np.ndarray
    stiffness_coefficient: np.ndarray
    stiffness_exponent: np.ndarray
    fit_error: np.ndarray
    energy_velocity: str


def impact_response(model: ImpactModel, static: ImpactStatic, speeds_rpm,
                    energy_velocity: str = "transverse") -> tuple[ImpactStatic, ImpactResponse]:
    """Impact velocity, energy, peak force and fitted local stiffness at pinion speeds
    ``speeds_rpm`` for every (C, T) of ``static``; the F–δ curve is extended (and the static
    part returned anew) where an impact reaches beyond it; a RuntimeWarning says when the
    impact's approach reaches slices that ``local_keep`` left out."""
    if energy_velocity not in ENERGY_VELOCITIES:
        raise GearmeshInputError("energy_velocity", energy_velocity, f"must be one of {list(ENERGY_VELOCITIES)}")
    speeds = check_speeds(None, speeds_rpm)
    omega1 = speeds * (2 * math.pi / 60.0)
    rb1 = float(model.geom.base_radius[0])
    vt = np.maximum(static.slope, 0.0)[..., None] * rb1 * omega1  # (C, T, S)
    vn = vt * math.cos(model.geom.base_helix_angle)
    m = model.equivalent_mass
    ek = 0.5 * m * (vt if energy_velocity == "transverse" else vn) ** 2
    for _ in range(8):
        f_eb, d_eb = energy_balance(static.curve_approach, static.curve_force, ek)
        short = (np.isnan(f_eb) & (ek > 0) & np.isfinite(static.slope)[..., None]).any(axis=-1)
        if not short.any():
            break
        # extend the F–δ curve of the rows that do not reach the impact's energy (4× the approach)
        cf, ca = np.array(static.curve_force), np.array(static.curve_approach)
        f_new, d_new = _force_curve(model, static.curve_separation[short][None], static.curve_compliance[short][None],
                                    4.0 * ca[short][None, :, -1], cf.shape[-1])
        cf[short], ca[short] = f_new[0], d_new[0]
        static = replace(static, curve_force=cf, curve_approach=ca)
    reach = np.nanmax(np.where(np.isfinite(static.curve_separation), static.curve_separation, np.nan), axis=-1)
    if static.curve_separation.shape[-1] < model.local_points and np.any(d_eb > reach[..., None]):
        warnings.warn("impact: the impact's approach reaches beyond the slices kept for the local stiffness; "
                      "raise local_keep", RuntimeWarning, stacklevel=2)
    zero = ek <= 0
    f_eb = np.where(zero, 0.0, f_eb)
    d_eb = np.where(zero, 0.0, d_eb)
    with np.errstate(invalid="ignore", divide="ignore"):
        k_s, n, err = fit_power_law(static.curve_approach, static.curve_force, np.where(zero, np.nan, d_eb))
        force = np.where(zero, 0.0, closed_form_force(m, vt if energy_velocity == "transverse" else vn, k_s, n))
    return static, ImpactResponse(speed_rpm=speeds, velocity_transverse=vt, velocity_normal=vn, kinetic_energy=ek,
                                  force=force, force_energy_balance=f_eb, approach_energy_balance=d_eb,
                                  stiffness_coefficient=k_s, stiffness_exponent=n, fit_error=err,
                                  energy_velocity=energy_velocity)


# --------------------------------------------------------------------------------------
# Load window: F_s against torque beside a reference
# --------------------------------------------------------------------------------------


def load_grid(torques, step: float, top: float | None = None) -> np.ndarray:
    """Torques (N m) of the load window: every multiple of ``step`` up to ``top`` (default 1.25 ×
    the largest of ``torques``), and the ``torques`` themselves (sorted, unique)."""
    top = 1.25 * max(torques) if top is None else top
    grid = step * np.arange(1, int(math.floor(top / step + 1e-9)) + 1)
    return np.unique(np.concatenate([grid, np.asarray(torques, dtype=float)]))


def load_window(grid: np.ndarray, force: np.ndarray, standard: np.ndarray, design: float) -> tuple[float, float]:
    """[low, high] (N m) of the contiguous run of ``grid`` torques around ``design`` where
    ``force`` is below ``standard`` (NaN, NaN when it is not at the design torque; the ends are
    grid torques, so a window reaching a grid end may extend further)."""
    beats = np.asarray(force) < np.asarray(standard)
    k = int(np.argmin(np.abs(grid - design)))
    if not beats[k]:
        return math.nan, math.nan
    lo = k
    while lo > 0 and beats[lo - 1]:
        lo -= 1
    hi = k
    while hi < grid.size - 1 and beats[hi + 1]:
        hi += 1
    return float(grid[lo]), float(grid[hi])


# --------------------------------------------------------------------------------------
# What else a modification changes: LTE and line load over the mesh cycle
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LTCACriteria:
    """What an engineer signs off, from the loaded contact over one mesh cycle, per (C, T) row
    (SI): ``lte_peak_to_peak`` (m), ``te_harmonics`` (C, T, 3) amplitudes of mesh orders 1–3 (m,
    :func:`gearmesh.ltca.lte_harmonics`), ``max_line_load`` (N/m), ``flank_pressure`` and
    ``edge_pressure`` the largest Hertzian pressure on the flanks (region 1) and on the tip edges
    (regions 2, 3; the pair's tip-edge radius, :mod:`gearmesh.stress`) (Pa, 0 where none is
    loaded), ``root_stress`` the largest ISO 6336-3 local root stress of either gear (Pa);
    ``load`` (C, T, P, J, N) the point loads (N), for ISO 6336's load factors from the LTCA
    (:func:`gearmesh.rating.ltca_load_factors`)."""

    lte_peak_to_peak: np.ndarray
    te_harmonics: np.ndarray
    max_line_load: np.ndarray
    flank_pressure: np.ndarray
    edge_pressure: np.ndarray
    root_stress: np.ndarray
    load: np.ndarray

    @property
    def peak_pressure(self) -> np.ndarray:
        """(C, T) largest pressure wherever it sits (ltca.nc's peak_contact_pressure)."""
        return np.maximum(self.flank_pressure, self.edge_pressure)


def ltca_criteria(model: ImpactModel, torques, params=None, lead_slope=None, stresses: bool = True,
                  samples: int = 1) -> LTCACriteria:
    """The loaded contact of modification parameter sets ``params`` ((C, 2, 6) m) with lead slopes
    ``lead_slope`` ((C, 2) m; None: the model's) at pinion ``torques`` (N m), over one mesh cycle:
    the LTCA of :mod:`gearmesh.ltca` on the model's mesh-cycle grid, gaps re-evaluated from its
    separation basis (no new geometry), and from its loads the sign-off quantities of
    :class:`LTCACriteria` (``stresses`` False: pressure and root stress left NaN). ``samples``: the
    rows come in runs of that many manufactured gears of one design, the first the nominal
    (:func:`_cycle_loads` starts the others from it).

    Each (row, torque, position) is one contact problem on the position's candidate points,
    solved with the tabulated contact law (:func:`gearmesh.ltca.solve_contact_tabulated`: the
    loads of :func:`gearmesh.ltca.solve_contact` to its tolerance). The stresses are per point
    of the grid a fixed function of its line load w — the Hertzian peak p0 = √(w E*/(π R))
    (:func:`gearmesh.stress.contact_stress`) and ISO 6336-3's local root stress
    σ = w cos α_t Y_F Y_S / m_n (:func:`gearmesh.stress.iso_root_stress_slices`), R and Y_F Y_S
    those of the point's roll lengths — so each is evaluated once at w = 1 and scaled:
    p0(w) = √w · p0(1), σ(w) = w · σ(1) (the same quantities, not an approximation)."""
    from .ltca import lte_harmonics

    g, lt = model.geom, model.ltca
    params = model.params(params)
    nc = params.shape[0]
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 1 or nc % samples:
        raise GearmeshInputError("samples", samples, f"must be a positive integer dividing the {nc} parameter sets")
    lead = np.broadcast_to(np.asarray(lt.lead_slope if lead_slope is None else lead_slope, dtype=float), (nc, 2))
    force = check_torques(torques) / float(g.base_radius[0])
    mis = mesh_misalignment(g, force)
    grid = lt.grid
    p = grid.gap.shape[0] - 1  # the last row is φ1A
    basis = SeparationBasis(*(getattr(grid.basis, f)[:p] for f in SeparationBasis.__dataclass_fields__))
    z = np.broadcast_to(grid.z, basis.base.shape)
    nt = force.size
    # each position's candidate points first (the grid's, the same for every gear), the rest dropped
    candidate = np.isfinite(basis.base).reshape(p, -1)  # (P, M)
    cols = np.argsort(~candidate, axis=1, kind="stable")[:, :int(candidate.sum(axis=1).max())]  # (P, M')
    comp = np.take_along_axis(lt.compliance[:p].reshape(p, -1), cols, axis=1)

    # (C, P, M') at one misalignment, or (C, T, P, M') at each torque's own (the system deflection
    # grows with the load): every row of _cycle_loads is its own contact problem, so the torques
    # solve together as they would one at a time
    one = bool(np.all(mis == mis[0]))
    m = np.asarray(mis[:1] if one else mis, dtype=float)
    lead_t = with_misalignment(np.broadcast_to(lead[:, None], (nc, m.size, 2)), m[None, :])  # (C, T or 1, 2)
    gp = basis_gap(g, basis, z, lead_t[:, :, None, None, None, :],
                   params[:, None, None, None, None, :, :])  # (C, T or 1, P, J, N)
    gp = np.take_along_axis(gp.reshape(nc, m.size, p, -1), cols[None, None], axis=3)
    q, delta = _cycle_loads(lt.law, gp[:, 0] if one else gp, comp, force, samples)
    w = q / grid.dz  # line loads (N/m), (C, T, P, M')
    nan = np.full((nc, nt), np.nan)
    flank = edge = root = nan
    if stresses:
        pressure, edge_point, root_stress = (np.take_along_axis(a.reshape(p, -1), cols, axis=1)
                                             for a in _unit_load_stresses(model))
        p0 = np.sqrt(w) * pressure
        flank = np.where(edge_point, 0.0, p0).max(axis=(2, 3))
        edge = np.where(edge_point, p0, 0.0).max(axis=(2, 3))
        root = (w * root_stress).max(axis=(2, 3))
    load = np.zeros((nc, nt, p, candidate.shape[1]))
    np.put_along_axis(load, np.broadcast_to(cols, q.shape), q, axis=3)
    return LTCACriteria(lte_peak_to_peak=np.ptp(delta, axis=-1), te_harmonics=lte_harmonics(delta),
                        max_line_load=w.max(axis=(2, 3)), flank_pressure=flank, edge_pressure=edge,
                        root_stress=root, load=load.reshape(nc, nt, p, *basis.base.shape[1:]))


def _cycle_loads(law: ContactLaw, gap: np.ndarray, compliance: np.ndarray, force: np.ndarray,
                 samples: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Loads (C, T, P, M) N and approach (C, T, P) m of C gears with separations ``gap`` (C, P, M),
    or (C, T, P, M) each torque's own, at the points of P positions (compliance (P, M) m/N) under
    the transverse forces ``force`` (T,) N: every row one contact problem of
    :func:`gearmesh.ltca.solve_contact_tabulated`.

    With ``samples`` S > 1 the gears come in runs of S manufactured gears of one design, the
    first the nominal. A sample's separations differ from its nominal's by its deviations
    (Δg_i, µm), so its approach starts at the nominal's tangent estimate
    δ_n + Σ k_i Δg_i / Σ k_i (k_i = dq_i/dδ at the nominal's solution). It is an upper bound of
    the sample's: each q_i(d) is convex, so q_i(δ − g_i − Δg_i) ≥ q_i,n + k_i (δ − δ_n − Δg_i) and
    the loads at that δ carry at least F; Newton descends from it in a few steps."""
    from .ltca import solve_contact_tabulated

    nt = force.size
    if gap.ndim == 3:  # one set of separations for every torque
        gap = gap[:, None]
    nc, _, p, m = gap.shape

    def solve(gp: np.ndarray, start=None):
        k = gp.shape[0]
        rows = (k, nt, p, m)
        q, d, dq = solve_contact_tabulated(np.broadcast_to(gp, rows).reshape(-1, m),
                                           np.broadcast_to(compliance, rows).reshape(-1, m),
                                           np.broadcast_to(force[:, None], rows[:3]).reshape(-1), law, start)
        return q.reshape(rows), d.reshape(rows[:3]), dq.reshape(rows)

    if samples == 1:
        return solve(gap)[:2]
    g = gap.reshape(nc // samples, samples, *gap.shape[1:])
    qn, dn, kn = solve(g[:, 0])
    qs, ds, _ = solve(g[:, 1:].reshape(-1, *gap.shape[1:]), _tangent_start(g[:, 1:] - g[:, :1], dn, kn).reshape(-1))
    q = np.concatenate([qn[:, None], qs.reshape(-1, samples - 1, nt, p, m)], axis=1).reshape(nc, nt, p, m)
    d = np.concatenate([dn[:, None], ds.reshape(-1, samples - 1, nt, p)], axis=1).reshape(nc, nt, p)
    return q, d


def _tangent_start(change: np.ndarray, delta: np.ndarray, tangent: np.ndarray) -> np.ndarray:
    """Upper bound (C, S, T, P) m of the approach of gears whose separations differ from a solved
    one's by ``change`` (C, S, T, P, M) m, or (C, S, P, M) the same at every torque (inf/NaN where
    no point): δ + Σ k_i Δg_i / Σ k_i
    with the solved gear's approach ``delta`` (C, T, P) and point tangents ``tangent``
    k_i = dq_i/dδ (C, T, P, M) (:func:`_cycle_loads`)."""
    if change.ndim == tangent.ndim:  # (C, S, P, M): the same change at every torque
        change = change[:, :, None]
    with np.errstate(invalid="ignore"):  # inf − inf at points that are no candidates (k = 0 there)
        dg = np.where(tangent[:, None] > 0, change, 0.0)  # (C, S, T, P, M)
    return delta[:, None] + (tangent[:, None] * dg).sum(axis=-1) / tangent.sum(axis=-1)[:, None]


def _unit_load_stresses(model: ImpactModel) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per point of the mesh-cycle grid (P, J, N) under a line load of 1 N/m: the Hertzian
    peak pressure (Pa, 0 where no point), whether it is a tip-edge point, and the larger ISO 6336-3
    local root stress of the two gears (Pa) (:func:`ltca_criteria`)."""
    from .stress import contact_stress, iso_root_stress_slices, pair_edge_radius

    g, grid = model.geom, model.ltca.grid
    p = grid.gap.shape[0] - 1
    region, r1, r2 = grid.region[:p], grid.rho_pinion[:p], grid.rho_gear[:p]
    unit = np.ones(region.shape)
    c = contact_stress(g, unit, region, r1, r2, pair_edge_radius(g))
    root = np.maximum(iso_root_stress_slices(g, 0, unit, r1), iso_root_stress_slices(g, 1, unit, r2))
    return c.pressure, np.asarray(c.edge), root


def ltca_metrics(model: ImpactModel, torques, params=None) -> tuple[np.ndarray, np.ndarray]:
    """Peak-to-peak LTE (m) and largest line load (N/m) over one mesh cycle, (C, T), of
    :func:`ltca_criteria`."""
    c = ltca_criteria(model, torques, params, stresses=False)
    return c.lte_peak_to_peak, c.max_line_load


# --------------------------------------------------------------------------------------
# The mesh-in point in 3-D, and the independent checks
# --------------------------------------------------------------------------------------


def _omegas(model: ImpactModel, speed_rpm: float, approach_rate: float = 0.0) -> tuple[float, float]:
    """Signed angular velocities (rad/s, +z CCW) of pinion and gear: the pinion drives CCW, or
    the whole motion reversed when the gear drives (module docstring); the pinion's real speed
    adds the rate of the loaded approach, dδ/dt / r_b1 = (dδ/dτ)·Ω1 (gear held, as δ)."""
    w1 = speed_rpm * 2 * math.pi / 60.0
    w2 = w1 * model.geom.pair.teeth[0] / model.geom.pair.teeth[1]
    return (model.sigma * w1 + approach_rate * w1, -model.sigma * w2)


def mesh_in_point(model: ImpactModel, static: ImpactStatic, c: int = 0, t: int = 0) -> dict[str, np.ndarray | float]:
    """M of candidate ``c`` at torque ``t`` in 3-D: fixed-frame point at the touch (m), the same
    point in the pinion body frame (m; :mod:`gearmesh.surface` frames), pinion radius and roll
    length, face position, and the unit common normal of the unmodified flanks (fixed frame,
    out of the pinion flank; the mating flank's for a pinion tip edge)."""
    g = model.geom
    if static.scenario[c, t] == SCENARIO_NONE:
        nan3 = np.full(3, np.nan)
        return {"point": nan3, "point_pinion": nan3, "normal": nan3, "pinion_radius": np.nan,
                "rho_pinion": np.nan, "face_position": np.nan}
    s, z, region = float(static.s[c, t]), float(static.z[c, t]), int(static.region[c, t])
    phi1 = float(static.roll[c, t]) / float(g.base_radius[0])
    j = model.pair_enter
    if region == REGION_APPROACH_TIP:
        x, y = approach_tip_point(g, s)
        p = np.array([float(x), float(y), z])
    elif region == REGION_RECESS_TIP:
        x, y = recess_tip_point(g, s)
        p = np.array([float(x), float(y), z])
    else:
        p = plane_of_action_point(g, g.rho_sap[0] + s, z)
    rot1 = float(body_rotation(g, 0, phi1))
    if region == REGION_RECESS_TIP:  # the gear flank's normal, turned to point into the pinion's side
        _, n_body = flank_point(g, 1, float(static.rho_gear[c, t]), z, tooth=-j)
        normal = -_rotate(n_body, float(body_rotation(g, 1, phi1)))
    else:
        _, n_body = flank_point(g, 0, float(static.rho_pinion[c, t]), z, tooth=j)
        normal = _rotate(n_body, rot1)
    rho1 = float(static.rho_pinion[c, t])
    return {"point": p, "point_pinion": _rotate(p, -rot1), "normal": normal,
            "pinion_radius": math.hypot(float(g.base_radius[0]), rho1), "rho_pinion": rho1, "face_position": z}


def _rotate(v: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    v = np.asarray(v, dtype=float)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]])


def _profile(model: ImpactModel, params: np.ndarray, gear: int, rho, z: float, phi1: float) -> np.ndarray:
    """Fixed-frame transverse points (…, 2) of the modified flank of the entering pair's tooth of
    ``gear`` in slice z at pinion rotation φ1 (conjugate, unloaded): the helicoid section moved
    inward by δ/cos βb along its transverse normal (the section of a surface offset by δ
    along its normal; :mod:`gearmesh.tca`)."""
    g = model.geom
    tooth = model.pair_enter if gear == 0 else -model.pair_enter
    rho = np.asarray(rho, dtype=float)
    pts, nrm = flank_point(g, gear, rho, z, tooth=tooth)
    nt = nrm[..., :2] / np.linalg.norm(nrm[..., :2], axis=-1, keepdims=True)
    depth = relief_depth(params[gear], float(g.rho_sap[gear]), float(g.rho_eap[gear]), g.face_width, rho, z)
    xy = pts[..., :2] - (depth / math.cos(g.base_helix_angle))[..., None] * nt
    ang = float(body_rotation(g, gear, phi1))
    c, s = math.cos(ang), math.sin(ang)
    out = np.stack([c * xy[..., 0] - s * xy[..., 1], s * xy[..., 0] + c * xy[..., 1]], axis=-1)
    if gear == 1:
        out[..., 0] += g.center_distance
    return out


def vector_velocity(model: ImpactModel, static: ImpactStatic, speed_rpm: float, c: int = 0,
                    t: int = 0) -> dict[str, float]:
    """The mesh-in impact paper's impact velocity v = ((ω1 − ω2) × r − E × ω2)·n, computed independently of the
    separation functions: the true closest points of the two exact modified transverse profiles
    in the slice of M at the touch roll (a tip edge against a flank, or flank against flank),
    their common normal n, and the relative velocity of the two material points along it.

    Returns ``normal_transverse`` (m/s, along the transverse common normal, + closing),
    ``normal_3d`` (× cos βb: the helicoid's 3-D normal; the axial velocity is zero),
    ``transverse_equivalent`` (the same closing expressed in the transverse line-of-action
    coordinate, × r_b1/arm, arm the normal's moment arm about the pinion axis; = 1 for a
    pinion involute normal), ``distance`` the closest distance (m; = the separation at the
    touch) and the closest points.
    """
    from scipy.optimize import brentq, fsolve

    g = model.geom
    params = static.params[c]
    region = int(static.region[c, t])
    z = float(static.z[c, t])
    phi1 = float(static.roll[c, t]) / float(g.base_radius[0])
    r1, r2 = float(static.rho_pinion[c, t]), float(static.rho_gear[c, t])
    eps = 1e-7 * g.pair.normal_module

    def p1(r):
        return _profile(model, params, 0, r, z, phi1)

    def p2(r):
        return _profile(model, params, 1, r, z, phi1)

    def tangent(f, r):
        return (f(r + eps) - f(r - eps)) / (2 * eps)

    def along(f_move, r_fixed_point, r):
        return float(np.dot(f_move(r) - r_fixed_point, tangent(f_move, r)))

    def foot(curve, point, r0, gear):
        """The point of ``curve`` (a flank of ``gear``) whose tangent is normal to point − curve(r)."""
        span = 0.05 * g.transverse_base_pitch
        r = brentq(lambda x: along(curve, point, x), max(g.rho_form[gear], r0 - span),
                   min(g.rho_eap[gear], r0 + span), xtol=1e-15)
        return r, curve(r)

    if region == REGION_APPROACH_TIP:  # the gear tip edge against the pinion flank
        q2 = p2(g.rho_eap[1])
        r1, q1 = foot(p1, q2, r1, 0)
    elif region == REGION_RECESS_TIP:  # the pinion tip edge against the gear flank
        q1 = p1(g.rho_eap[0])
        r2, q2 = foot(p2, q1, r2, 1)
    else:  # flank against flank: the difference is normal to both tangents
        def stationary(x):
            d = p1(x[0] * 1e-3) - p2(x[1] * 1e-3)
            return [np.dot(d, tangent(p1, x[0] * 1e-3)) * 1e6, np.dot(d, tangent(p2, x[1] * 1e-3)) * 1e6]

        with warnings.catch_warnings():  # fsolve reports slow progress once at the round-off floor
            warnings.simplefilter("ignore", RuntimeWarning)
            sol = fsolve(stationary, [r1 * 1e3, r2 * 1e3], xtol=1e-10)
        r1, r2 = sol[0] * 1e-3, sol[1] * 1e-3
        q1, q2 = p1(r1), p2(r2)
    d = q2 - q1
    dist = float(np.linalg.norm(d))
    n = d / dist  # from the pinion flank to the gear flank
    w1, w2 = _omegas(model, speed_rpm, float(static.approach_rate[c, t]))
    v1 = w1 * np.array([-q1[1], q1[0]])
    v2 = w2 * np.array([-q2[1], q2[0] - g.center_distance])
    vn = float(np.dot(v1 - v2, n))
    arm = abs(q1[0] * n[1] - q1[1] * n[0])
    return {"normal_transverse": vn, "normal_3d": vn * math.cos(g.base_helix_angle),
            "transverse_equivalent": vn * float(g.base_radius[0]) / arm, "distance": dist,
            "pinion_point_x": float(q1[0]), "pinion_point_y": float(q1[1]), "gear_point_x": float(q2[0]),
            "gear_point_y": float(q2[1])}


def seed_edge_roll(geom: PairGeometry, approach: float) -> float:
    """The mesh-in impact paper's 'reverse rotation' solution for an unmodified pair, pinion driving: the pinion
    roll (m) before the theoretical start of engagement at which the gear's tip corner meets the
    pinion flank when the pairs in mesh are compressed by ``approach`` δ (m).

    The mesh-in impact paper: arcsin(r_a2 sin(γ2 + LTE0 + Δφk2)/r_O1D) − Δφk2/i − arcsin(r_a2 sin γ2/r_O1E)
    = inv(arccos(r_b1/r_O1D)) − inv(arccos(r_b1/r_O1E')), r_O1D² = a² + r_a2² −
    2·a·r_a2·cos(γ2 + LTE0 + Δφk2), with γ2 the angle at O2 between the centre line and the
    start of engagement A (= E = E', the gear tip on the line of action) and LTE0 = δ/r_b2 the
    gear's lag. It states that the tip point D, turned back by LTE0 + Δφk2, lies on the pinion
    involute through A turned back by the pinion angle of Δφk2. That angle is Δφk2·z2/z1, so
    the printed "Δφk2/i" holds only with i = z1/z2; with the usual ratio i = z2/z1 it must read
    Δφk2·i (corrected here). Returns r_b2·(LTE0 + Δφk2), the mesh-in impact paper's total deviation Δφ as
    roll, which :func:`impact_static` must reproduce for an unmodified pair (the same event).
    """
    from scipy.optimize import brentq

    a = geom.center_distance
    rb1, rb2 = (float(r) for r in geom.base_radius)
    ra2 = float(geom.tip_radius[1])
    awt = geom.operating_pressure_angle
    ax = rb1 * math.cos(awt) + geom.rho_sap[0] * math.sin(awt)
    ay = -rb1 * math.sin(awt) + geom.rho_sap[0] * math.cos(awt)
    gamma2 = math.atan2(-ay, a - ax)
    r_o1e = math.hypot(ax, ay)
    lte0 = approach / rb2
    ratio = geom.pair.teeth[1] / geom.pair.teeth[0]

    def residual(dphi):
        gd = gamma2 + lte0 + dphi
        r_o1d = math.sqrt(a * a + ra2 * ra2 - 2 * a * ra2 * math.cos(gd))
        lhs = (math.asin(ra2 * math.sin(gd) / r_o1d) - dphi * ratio - math.asin(ra2 * math.sin(gamma2) / r_o1e))
        return lhs - (involute(math.acos(rb1 / r_o1d)) - involute(math.acos(rb1 / r_o1e)))

    hi = 0.5 * geom.transverse_base_pitch / rb2
    dphi = brentq(residual, -lte0, hi, xtol=1e-16, rtol=1e-15)
    return rb2 * (lte0 + dphi)


def simulate_engagement(model: ImpactModel, torque: float, speed_rpm: float, params=None, samples: int = 600,
                        cycles_after: float = 2.5) -> dict[str, np.ndarray | float]:
    """Direct time integration of the mesh-in event, to check the energy method.

    The two-inertia torsional system in its relative coordinate x (transverse approach along
    the line of action, gear held): m_eq·ẍ = F_bt − F_mesh(x, τ(t)), τ advancing at r_b1·Ω1,
    F_mesh the LTCA contact force of every point of every pair (the entering one included) at
    approach x (:func:`gearmesh.ltca.solve_contact`'s point laws, inverted directly). No
    damping: the energy method is conservative. It starts in static equilibrium a little before
    the touch (x = δ, ẋ = dδ/dt), integrates (scipy solve_ivp, RK45) through the touch for
    ``cycles_after`` periods of the mesh's natural frequency √(k/m_eq), and reports over the
    impact window — from the touch to one natural period after it (compression and rebound of
    the impact; later the undamped mesh keeps ringing under its own stiffness fluctuation, which
    is not the impact) — the entering pair's largest force (``entering_peak``), its largest
    excess over its quasi-static force at the same mesh position (``entering_excess``: the
    dynamic impact, the quantity the dynamics reports), and the largest mesh force above the
    static force F_bt (``peak_above_static``). (A window that closed at the entering pair's first
    local maximum could close a few µs after a grazing touch, on a wiggle of a few newtons.)
    The energy method's premise — all of ½·m_eq·v² goes into the entering pair — ignores the
    pairs already in mesh, which unload as x rebounds; the ratio measures that.
    """
    from scipy.integrate import solve_ivp

    g, law = model.geom, model.ltca.law
    params = model.params(params)[:1]
    st = impact_static(model, [torque], params)
    if st.scenario[0, 0] == SCENARIO_NONE:
        raise GearmeshInputError("torque_Nm", torque, "gives no mesh-in contact in the search window")
    speed = float(check_speeds(None, [speed_rpm], "speed_rpm")[0])
    f_bt = float(st.force[0])
    t_star = float(st.tau[0, 0])
    m = model.equivalent_mass
    # tangent mesh stiffness at the touch (all pairs) for the time scale
    lead = with_misalignment(model.lead_slope, float(mesh_misalignment(g, f_bt)))  # this torque's mesh
    grid0 = candidate_grid(g, np.array([float(st.roll[0, 0])]), model.points, lead,
                           model.extension / g.transverse_base_pitch, pairs=model.window_pairs)
    gap0 = basis_gap(g, grid0.basis, np.broadcast_to(grid0.z, grid0.s.shape), lead, params[0])
    comp0 = point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid0.s, grid0.region, grid0.rho_pinion,
                             grid0.rho_gear, with_hertz=law.name == "linear") / grid0.dz
    _, _, k0, _ = solve_contact(gap0.reshape(1, -1), comp0.reshape(1, -1), np.array([f_bt]), law)
    period = 2 * math.pi * math.sqrt(m / float(k0[0]))
    rate = float(g.base_radius[0]) * speed * 2 * math.pi / 60.0  # dτ/dt (m/s)
    tau0 = t_star - max(0.02 * g.transverse_base_pitch, 0.5 * period * rate)
    tau1 = t_star + cycles_after * period * rate
    taus = np.linspace(tau0, tau1, int(samples))
    grid = candidate_grid(g, model.roll(taus), model.points, lead, model.extension / g.transverse_base_pitch,
                          pairs=model.window_pairs)
    gaps = basis_gap(g, grid.basis, np.broadcast_to(grid.z, grid.s.shape), lead, params[0])
    comps = point_compliance(g, model.ltca.pair_table, model.ltca.tables, grid.s, grid.region, grid.rho_pinion,
                             grid.rho_gear, with_hertz=law.name == "linear") / grid.dz
    nr = taus.size
    gaps = np.where(np.isfinite(gaps), gaps, np.inf).reshape(nr, -1)
    comps = np.where(np.isfinite(comps), comps, 1.0).reshape(nr, -1)
    enter = np.zeros(gaps.shape[1], dtype=bool).reshape(grid.s.shape[1:])
    enter[model.window_enter_column] = True
    enter = enter.reshape(-1)
    c_eff = comps + law.linear

    def at(tau):
        u = (tau - tau0) / (taus[1] - taus[0])
        i = int(min(max(math.floor(u), 0), nr - 2))
        w = u - i
        with np.errstate(invalid="ignore"):
            gg = gaps[i] + w * (gaps[i + 1] - gaps[i])
        return np.where(np.isfinite(gg), gg, np.inf), c_eff[i] + w * (c_eff[i + 1] - c_eff[i])

    def loads(x, tau):
        gg, cc = at(tau)
        d = x - gg
        q, _ = _invert(np.where(np.isfinite(d), d, -1.0)[None], cc[None], law.coefficient, law.exponent)
        return q[0]

    def rhs(t, y):
        return [y[1], (f_bt - loads(y[0], tau0 + rate * t).sum()) / m]

    # static start: approach of all pairs at τ0 and its rate
    h = 1e-7 * g.transverse_base_pitch
    d_lo, d0, d_hi = _approach_at(model, params, lead[None], st.force, np.array([tau0 - h, tau0, tau0 + h])[:, None, None],
                                  others=False)[:, 0, 0]
    v0 = (d_hi - d_lo) / (2 * h) * rate
    t_end = (tau1 - tau0) / rate
    sol = solve_ivp(rhs, (0.0, t_end), [d0, v0], method="RK45", rtol=1e-7, atol=1e-12, max_step=period / 40,
                    dense_output=True)
    t = np.linspace(0.0, t_end, int(samples))
    x = sol.sol(t)[0]
    q = np.array([loads(xi, tau0 + rate * ti) for xi, ti in zip(x, t)])
    total = q.sum(axis=1)
    entering = q[:, enter].sum(axis=1)
    t_touch = (t_star - tau0) / rate
    # the entering pair's quasi-static load at every sampled mesh position (the LTCA at F_bt)
    q_static, _, _, _ = solve_contact(gaps, comps, np.full(nr, f_bt), law)
    entering_static = np.interp(tau0 + rate * t, taus, q_static[:, enter].sum(axis=1))
    window = (t >= t_touch) & (t <= t_touch + period)
    excess = entering - entering_static
    i_peak = int(np.flatnonzero(window)[np.argmax(excess[window])]) if window.any() else t.size - 1
    return {"time": t, "tau": tau0 + rate * t, "approach": x, "mesh_force": total, "entering_force": entering,
            "entering_static": entering_static, "static_force": f_bt,
            "peak_above_static": float(total[window].max() - f_bt) if window.any() else np.nan,
            "entering_peak": float(entering[window].max()) if window.any() else np.nan,
            "entering_excess": float(excess[i_peak]), "peak_time": float(t[i_peak]), "period": period,
            "touch_time": t_touch}
