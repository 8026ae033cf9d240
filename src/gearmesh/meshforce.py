"""The mesh force of the real tooth contact as a function of the bodies' approach and the
mesh position: F(x, τ), tabulated once per pair and micro-geometry for the dynamics.

Everything inside is SI. The convention is the LTCA's (:mod:`gearmesh.ltca`): x is the
transverse approach of the gear bodies along the line of action (r_b1·Δφ1 with the gear held),
the force the transverse load F_bt it transmits (the moment about the pinion axis over r_b1).

Model
-----
At a pinion roll r the candidate contact points i of every tooth pair in and around the active
zone — flank points and the tip edges before A and after E, both gears' modifications and lead
slope errors — have unloaded separations g_i(r) (:func:`gearmesh.tca.candidate_grid`, the
separation basis shared with the LTCA and the impact model) and linear compliances c_i
(:func:`gearmesh.ltca_model.point_compliance`: bending, shear, axial compression and fillet
foundation of both teeth) in series with the local contact law δ_c(q) (Palmgren's line contact
or linear Hertz, :func:`gearmesh.ltca_model.contact_law`). With independent slices each point's load
at an approach x is its own law inverted,

    q_i(x, r) = f_i⁻¹((x − g_i(r))₊),   f_i(q) = c_i·q + δ_c(q),

and the mesh force is their sum F(x, r) = Σ_i q_i. For a given force its inverse is the LTCA
(:func:`gearmesh.ltca_solve.solve_contact` solves Σ q_i(x) = F for x), so the quasi-static limit of
a simulation driven by F(x, r) is the LTCA's loaded TE, and its tangent dF/dx at the static
approach is the LTCA's loaded mesh stiffness. What the table adds is everything away from the
static state: an entering tooth pair whose tip edge touches *before* A when the pairs in mesh
are deflected further than their static approach (the mesh-in impact of the mesh-in impact paper), a pair that
lets go earlier when the approach drops, and contact loss when x falls below every separation.
This is the "mesh force from the instantaneous contact of all tooth pairs" formulation of the
gear-dynamics literature (Velex & Maatar 1996, J. Sound Vib. 191:629 — the time-varying
contact of discretised contact lines inside the equations of motion; Eritenel & Parker 2012,
Mech. Mach. Theory 56:28 for helical gears; Parker, Vijayakar & Imajo 2000, J. Sound Vib.
237:435 with an FE contact model), here with the project's own slice model of the contact.

What it leaves out: the slices are independent (no plate coupling of a tooth along the face,
so a face-end corner is too stiff locally); every load acts along the transverse line of action
(an edge load's normal lies off it by a small angle, taken to first order in the separations
of :mod:`gearmesh.tca`); the mesh position advances with the nominal speed (the vibration does
not shift the contact lines, the usual assumption); friction is absent.

The table
---------
Rows are the position within the *engagement window* w ∈ [0, p_bt], the pinion roll
r = r_A − p_bt/2 + w with r_A the theoretical start of engagement of the entering pair
(:func:`gearmesh.tca.engagement_point`): the entering pair reaches A at w = p_bt/2. The total
force is periodic in w (row P repeats row 0); the *entering pair* — the tooth pair that reaches
A during the window — is followed over the whole window by its own index, so its load, its
first touch before A and its dynamic impact are read from the same table (``enter_force``,
``enter_gap``). Columns are the approach beyond the first touch, u = x − g_min(r) ≥ 0, on a
uniform grid up to the approach at which every row carries at least ``force_max``; F is
interpolated bilinearly in (w, u) and extrapolated linearly in u (its tangent) above the grid.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .contact_model import TABLE_CONTACT, ContactModel
from .errors import GearmeshInputError
from .gear import PairGeometry
from .body import mesh_body_compliance
from .deflection import mesh_misalignment
from .deviation import with_misalignment
from .ltca_solve import load_sums, solve_contact
from .ltca_model import ContactLaw, ltca_model, point_compliance
from .tooth import SliceComplianceTable
from .separation import REGION_APPROACH_TIP, REGION_RECESS_TIP, basis_gap
from .tca import candidate_grid, check_count, engagement_point, pair_lead_slope

__all__ = ["MeshForceTable", "mesh_force_table", "TableLayout", "table_layout", "tabulate", "DEFAULT_TABLE_POSITIONS", "DEFAULT_TABLE_APPROACHES"]

#: Rows (window positions per mesh cycle) and columns (approaches) of the default table; the
#: convergence of the dynamics in both is tested (tests/test_meshforce.py, test_dynamics_contact.py).
DEFAULT_TABLE_POSITIONS = 256
DEFAULT_TABLE_APPROACHES = 96


@dataclass(frozen=True)
class MeshForceTable:
    """F(x, w) of one pair and micro-geometry over one mesh cycle (module docstring), SI.

    ``pitch`` p_bt (m); ``roll_engagement`` r_A (m, in [0, p_bt)); ``window`` (P+1,) window
    positions w (m, 0 … p_bt); ``roll`` (P+1,) the pinion rolls r = r_A − p_bt/2 + w;
    ``approach`` (U,) u (m, 0 … u_max); ``gap_min`` (P+1,) the smallest separation of all
    candidates (m: the first touch, contact lost below it); ``force`` / ``stiffness`` (P+1, U)
    F (N) and dF/dx (N/m) at x = g_min + u; ``enter_gap`` (P+1,) the entering pair's smallest
    separation (m, inf without candidates); ``enter_force`` (P+1, U) its load (N) at the same
    approaches; ``force_max`` the force (N) every row reaches within the grid.
    """

    pitch: float
    roll_engagement: float
    window: np.ndarray
    roll: np.ndarray
    approach: np.ndarray
    gap_min: np.ndarray
    force: np.ndarray
    stiffness: np.ndarray
    enter_gap: np.ndarray
    enter_force: np.ndarray
    force_max: float

    @property
    def positions(self) -> int:
        """P, rows per mesh cycle."""
        return self.window.size - 1

    def window_position(self, roll) -> np.ndarray:
        """w (m) of pinion rolls ``roll`` (m): (r − r_A + p_bt/2) mod p_bt."""
        return np.mod(np.asarray(roll, dtype=float) - self.roll_engagement + 0.5 * self.pitch, self.pitch)

    def _cell(self, w, u):
        """Row index, row weight, column index and column offset (m) of (w, u), both arrays."""
        dw = self.pitch / self.positions
        t = np.asarray(w, dtype=float) / dw
        i = np.clip(t.astype(np.intp), 0, self.positions - 1)
        du = self.approach[1] - self.approach[0]
        j = np.clip((np.asarray(u, dtype=float) / du).astype(np.intp), 0, self.approach.size - 2)
        return i, t - i, j, u - self.approach[j]

    def _bilinear(self, table, i, a, j, du_off):
        """Bilinear in (w, u), linear extrapolation in u beyond the grid (from the last cell)."""
        du = self.approach[1] - self.approach[0]
        b = du_off / du

        def row(k):
            f0, f1 = table[k, j], table[k, j + 1]
            return f0 + b * (f1 - f0)

        return (1 - a) * row(i) + a * row(i + 1)

    def gap(self, w) -> np.ndarray:
        """g_min (m) at window positions ``w`` (m), linear between rows."""
        return np.interp(w, self.window, self.gap_min)

    def evaluate(self, x, w):
        """Mesh force F (N) and its tangent dF/dx (N/m) at approach ``x`` (m) and window position
        ``w`` (m) (arrays of one shape); zero where x ≤ g_min(w)."""
        x, w = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(w, dtype=float))
        u = x - self.gap(w)
        i, a, j, off = self._cell(w, np.maximum(u, 0.0))
        f = self._bilinear(self.force, i, a, j, off)
        k = self._bilinear(self.stiffness, i, a, j, off)
        touch = u > 0
        return np.where(touch, np.maximum(f, 0.0), 0.0), np.where(touch, k, 0.0)

    def entering(self, x, w) -> np.ndarray:
        """Load (N) of the entering pair at approach ``x`` (m) and window position ``w`` (m)."""
        x, w = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(w, dtype=float))
        u = x - self.gap(w)
        i, a, j, off = self._cell(w, np.maximum(u, 0.0))
        f = self._bilinear(self.enter_force, i, a, j, off)
        return np.where(u > 0, np.maximum(f, 0.0), 0.0)

    def static_approach(self, force: float) -> tuple[np.ndarray, np.ndarray]:
        """Approach x (m) and tangent stiffness dF/dx (N/m) at every row where F(x) = ``force``
        (N): the table's own quasi-static solution (rows monotone in u; linear between columns,
        linear extrapolation above the grid)."""
        f = self.force
        i = np.arange(f.shape[0])
        j = np.clip(np.sum(f < force, axis=1), 1, f.shape[1] - 1)  # searchsorted (left) of each monotone row
        u = self.approach[j - 1] + (force - f[i, j - 1]) * (self.approach[j] - self.approach[j - 1]) \
            / (f[i, j] - f[i, j - 1])
        du = self.approach[1] - self.approach[0]
        j = np.clip((u / du).astype(np.intp), 0, self.approach.size - 2)
        b = (u - self.approach[j]) / du
        k = self.stiffness[i, j] + b * (self.stiffness[i, j + 1] - self.stiffness[i, j])
        return self.gap_min + u, k

    def static_touch(self, force: float) -> float:
        """The roll (m) before A at which the entering pair first touches in the quasi-static
        mesh under ``force`` (N): the first window position where the static approach reaches its
        separation, between rows by linear interpolation of x_s − g_enter; 0 at or after A."""
        x_s, _ = self.static_approach(force)
        h = np.where(np.isfinite(self.enter_gap), x_s - self.enter_gap, -np.inf)
        hit = np.flatnonzero(h > 0)
        if not hit.size:
            return 0.0
        k = int(hit[0])
        if k == 0:
            w = 0.0
        else:
            h0 = h[k - 1] if np.isfinite(h[k - 1]) else -1.0
            w = self.window[k - 1] + (self.window[k] - self.window[k - 1]) * (-h0) / (h[k] - h0) \
                if np.isfinite(h[k - 1]) else self.window[k]
        return float(max(0.5 * self.pitch - w, 0.0))


def _enter_columns(pairs: np.ndarray, j_enter: int, roll: np.ndarray, window: np.ndarray, roll_a: float,
                   pitch: float) -> np.ndarray:
    """Column of the entering pair in each row (−1 where it has no candidate column): the pair
    with index j_A at r_A keeps its identity over the window, so at a roll k pitches earlier it
    is pair j_A + k (:func:`gearmesh.tca.candidate_grid`: s = r + j·p_bt + …)."""
    unwrapped = roll_a - 0.5 * pitch + window
    shift = np.rint((unwrapped - roll) / pitch).astype(int)
    want = j_enter + shift
    col = np.full(roll.size, -1)
    for k, j in enumerate(want):
        hit = np.flatnonzero(pairs == j)
        if hit.size:
            col[k] = int(hit[0])
    return col


@dataclass(frozen=True)
class TableLayout:
    """What the table of a pair needs that no micro-geometry changes (SI): the contact ``law``,
    the window positions ``window`` (P+1,) and pinion rolls ``roll`` (P+1,), the candidate
    ``grid`` (its separation basis gives the gaps of any modification), the points' compliances
    ``compliance`` (P+1, M) (m/N per unit face width, the contact law's linear part included),
    the entering pair's points ``enter_mask`` (P+1, M), and r_A ``roll_engagement``."""

    geom: PairGeometry
    law: ContactLaw
    pitch: float
    roll_engagement: float
    window: np.ndarray
    roll: np.ndarray
    grid: object
    compliance: np.ndarray
    enter_mask: np.ndarray

    def gaps(self, params=None, lead_slope=(0.0, 0.0)) -> np.ndarray:
        """Unloaded separations (m) of every point, (..., P+1, M), inf where no candidate, for
        modification parameters ``params`` (..., 2, 6) m (default the pair's own) and lead slopes
        ``lead_slope`` (..., 2) m (:func:`gearmesh.separation.basis_gap`: no new geometry)."""
        grid = self.grid
        rows = self.roll.size
        if params is None:
            gap = basis_gap(self.geom, grid.basis, np.broadcast_to(grid.z, grid.s.shape), lead_slope)
            lead_shape = np.shape(lead_slope)[:-1]
            gap = gap.reshape(lead_shape + (rows, -1))
        else:
            params = np.asarray(params, dtype=float)
            lead = np.broadcast_to(np.asarray(lead_slope, dtype=float), params.shape[:-2] + (2,))
            lead_ax = lead[..., None, None, None, :]
            gap = basis_gap(self.geom, grid.basis, grid.z, lead_ax, params[..., None, None, None, :, :])
            gap = gap.reshape(params.shape[:-2] + (rows, -1))
        return np.where(np.isfinite(gap), gap, np.inf)


def table_layout(geom: PairGeometry, positions: int = DEFAULT_TABLE_POSITIONS, contact: ContactModel = TABLE_CONTACT,
                 tables: tuple[SliceComplianceTable, SliceComplianceTable] | None = None) -> TableLayout:
    """The micro-geometry-independent part of :func:`mesh_force_table` (its parameters).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    positions : int, default :data:`DEFAULT_TABLE_POSITIONS`
        Rows (window positions) per mesh cycle (≥ 16).
    contact : ContactModel, default :data:`gearmesh.contact_model.TABLE_CONTACT`
        Candidate points (slices) per contact line, local contact law
        (:func:`gearmesh.ltca_model.contact_law`), tooth model of the slice compliance, and reach of
        the tip-edge candidates beyond the active zone, fraction of p_bt, in (0, 0.5]
        (:class:`gearmesh.contact_model.ContactModel`).
    tables : tuple of SliceComplianceTable, optional
        Per-gear slice compliance tables to reuse (same tooth model).

    Returns
    -------
    TableLayout
        ``law``, ``pitch`` p_bt (m), ``roll_engagement`` r_A (m), ``window`` and ``roll`` (P+1,) m,
        candidate ``grid``, ``compliance`` (P+1, M) m/N, ``enter_mask`` (P+1, M).

    Raises
    ------
    GearmeshInputError
        ``table_positions`` or ``table_extension`` out of range.
    """
    positions = check_count("table_positions", positions, 16, 100000)
    points, extension = contact.points, contact.extension
    if not 0 < extension <= 0.5:
        raise GearmeshInputError("table_extension", extension, "must lie in (0, 0.5] (fraction of the base pitch)")
    # the load-independent LTCA model: slice tables, pair table, contact law (its own grid unused)
    base = ltca_model(geom, positions=1, contact=contact, tables=tables)
    law: ContactLaw = base.law
    pitch = geom.transverse_base_pitch
    roll_a, j_a, _ = engagement_point(geom)
    window = np.arange(positions + 1) * (pitch / positions)
    roll = np.mod(roll_a - 0.5 * pitch + window, pitch)
    grid = candidate_grid(geom, roll, points, (0.0, 0.0), extension)
    comp = point_compliance(geom, base.pair_table, base.tables, grid.s, grid.region, grid.rho_pinion,
                            grid.rho_gear, with_hertz=law.name == "linear") / grid.dz
    rows = roll.size
    comp = np.where(np.isfinite(grid.gap), comp, 1.0).reshape(rows, -1) + law.linear
    col = _enter_columns(np.asarray(grid.pairs), j_a, roll, window, roll_a, pitch)
    n_line = grid.gap.shape[2]
    enter_mask = np.zeros(comp.shape, dtype=bool)
    for k, c in enumerate(col):
        if c >= 0:
            enter_mask[k, c * n_line:(c + 1) * n_line] = True
    return TableLayout(geom=geom, law=law, pitch=pitch, roll_engagement=float(roll_a), window=window, roll=roll,
                       grid=grid, compliance=comp, enter_mask=enter_mask)


def tabulate(layout: TableLayout, gap: np.ndarray, force_max: float,
             approaches: int = DEFAULT_TABLE_APPROACHES) -> MeshForceTable:
    """The :class:`MeshForceTable` of one micro-geometry with separations ``gap`` (P+1, M) m
    (:meth:`TableLayout.gaps`) up to ``force_max`` (N).

    Parameters
    ----------
    layout : TableLayout
        The pair's micro-geometry-independent layout (:func:`table_layout`).
    gap : numpy.ndarray
        Unloaded separations of every candidate point, (P+1, M) m, inf where no candidate.
    force_max : float
        Transverse force every row reaches on the grid, N (positive, finite).
    approaches : int, default :data:`DEFAULT_TABLE_APPROACHES`
        Columns (approaches) of the table (≥ 8).

    Returns
    -------
    MeshForceTable
        ``approach`` (U,) m, ``gap_min`` (P+1,) m, ``force`` (P+1, U) N, ``stiffness`` (P+1, U) N/m,
        ``enter_gap`` (P+1,) m, ``enter_force`` (P+1, U) N, with the bodies' compliance in series.

    Raises
    ------
    GearmeshInputError
        ``table_approaches`` or ``force_max`` out of range, or a row without a candidate point.
    """
    approaches = check_count("table_approaches", approaches, 8, 100000)
    if not (isinstance(force_max, (int, float)) and math.isfinite(force_max) and force_max > 0):
        raise GearmeshInputError("force_max", force_max, "must be a positive finite force (N)")
    law, comp, enter_mask = layout.law, layout.compliance, layout.enter_mask
    rows, m = gap.shape
    gap_min = gap.min(axis=1)
    if not np.all(np.isfinite(gap_min)):
        raise GearmeshInputError("positions", int(np.sum(~np.isfinite(gap_min))), "rows without a candidate point")
    enter_gap = np.where(enter_mask, gap, np.inf).min(axis=1)
    # the approach range: every row carries force_max
    _, delta_max, _, _ = solve_contact(gap, comp - law.linear, np.full(rows, float(force_max)), law)
    u_max = float(np.max(delta_max - gap_min))
    geom = layout.geom
    c_body = mesh_body_compliance(geom)
    u = np.linspace(0.0, u_max, approaches)
    force, stiff, enter = load_sums(gap, comp, gap_min[:, None] + u[None, :], law, enter_mask)
    if c_body:
        u, force, stiff, enter = _with_body(u, force, stiff, enter, c_body, float(force_max))
    _warn_reach(layout.grid, gap, gap_min[:, None] + u_max, layout.grid.extension, geom.path_of_contact)
    return MeshForceTable(pitch=layout.pitch, roll_engagement=layout.roll_engagement, window=layout.window,
                          roll=layout.roll, approach=u, gap_min=gap_min, force=force, stiffness=stiff,
                          enter_gap=enter_gap, enter_force=enter, force_max=float(force_max))


def _with_body(u, force, stiff, enter, c_body: float, force_max: float):
    """The table of the teeth (approach u (U,), force, tangent, entering pair's load (R, U)) with the
    bodies' compliance ``c_body`` (m/N, :mod:`gearmesh.body`) in series: the bodies' approach is
    u + c_body·F(u) (they bend under the total force), each row interpolated back onto a uniform grid
    that still reaches ``force_max`` in every row; tangent 1/(1/k + c_body)."""
    u_new = np.linspace(0.0, float(u[-1]) + c_body * force_max, u.size)
    out = [np.empty((force.shape[0], u.size)) for _ in range(3)]
    for r in range(force.shape[0]):
        x = u + c_body * force[r]
        out[0][r] = np.interp(u_new, x, force[r])
        out[1][r] = np.interp(u_new, x, 1.0 / (1.0 / np.maximum(stiff[r], 1e-300) + c_body))
        out[2][r] = np.interp(u_new, x, enter[r])
    return u_new, out[0], out[1], out[2]


def mesh_force_table(geom: PairGeometry, force_max: float, positions: int = DEFAULT_TABLE_POSITIONS,
                     approaches: int = DEFAULT_TABLE_APPROACHES, contact: ContactModel = TABLE_CONTACT,
                     lead_slope=None, tables: tuple[SliceComplianceTable, SliceComplianceTable] | None = None,
                     static_force: float | None = None) -> MeshForceTable:
    """Tabulate the mesh force F(x, w) of ``geom`` (its modifications) over one mesh cycle.

    The model and the table's layout are the module docstring's: each candidate point's load is its
    own contact law inverted at the approach, the mesh force their sum, after the "mesh force from the
    instantaneous contact of all tooth pairs" formulation of [1]_, [2]_, [3]_ with the project's own
    slice model, for the mesh-in impact of [4]_.

    Several micro-geometries of one pair: :func:`table_layout` once, then :func:`tabulate` of
    :meth:`TableLayout.gaps` for each.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its modifications (:func:`gearmesh.gear.pair_geometry`).
    force_max : float
        Every row reaches at least this transverse force (N) on the grid (give a few times the
        largest static force F_bt a simulation will see; above it F is extrapolated with its tangent).
    positions : int, default :data:`DEFAULT_TABLE_POSITIONS`
        Rows per mesh cycle (module docstring).
    approaches : int, default :data:`DEFAULT_TABLE_APPROACHES`
        Columns (approaches) of the table.
    contact : ContactModel, default :data:`gearmesh.contact_model.TABLE_CONTACT`
        Candidate points (slices) per contact line, as the LTCA's, local contact law, tooth model, and
        reach of the tip-edge candidates beyond the active zone (fraction of p_bt, at most 0.5: the
        entering pair is followed over half a pitch before A) (:class:`gearmesh.contact_model.ContactModel`).
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width; None: the pair's own.
    tables : tuple of SliceComplianceTable, optional
        Per-gear slice compliance tables to reuse (same tooth model).
    static_force : float, optional
        The static transverse force (N) whose mesh misalignment the separations carry (the stated
        f_ma and the system deflection's f_sh at it, :func:`gearmesh.deflection.mesh_misalignment`:
        the gearbox deflects with the mean load); None: the stated f_ma alone.

    Returns
    -------
    MeshForceTable
        F (N) and dF/dx (N/m) over window position w (m) and approach u (m) beyond the first touch,
        with the entering pair's separation (m) and load (N) (:class:`MeshForceTable`).

    References
    ----------
    .. [1] Velex P., Maatar M., "A mathematical model for analyzing the influence of shape
       deviations and mounting errors on gear dynamic behaviour", J. Sound Vib. 191 (1996) 629–660.
    .. [2] Eritenel T., Parker R.G., "An investigation of tooth mesh nonlinearity and partial
       contacts of a helical gear pair using a lumped-parameter model", Mech. Mach. Theory 56
       (2012) 28–51.
    .. [3] Parker R.G., Vijayakar S.M., Imajo T., "Non-linear dynamic response of a spur gear pair:
       modelling and experimental comparisons", J. Sound Vib. 237 (2000) 435–455.
    .. [4] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears,
       docs/references.md.
    """
    layout = table_layout(geom, positions, contact, tables)
    lead = with_misalignment(pair_lead_slope(geom, lead_slope),
                             float(mesh_misalignment(geom, 0.0 if static_force is None else static_force)))
    return tabulate(layout, layout.gaps(lead_slope=lead), force_max, approaches)


def _warn_reach(grid, gap: np.ndarray, x_max: np.ndarray, ext: float, path: float) -> None:
    """Warn when tip-edge candidates in the outer fifth of the candidate zone carry load at the
    largest approach of the table (the zone would be too short for that approach)."""
    s = grid.s.reshape(gap.shape)
    region = grid.region.reshape(gap.shape)
    far = (((region == REGION_APPROACH_TIP) & (s < -0.8 * ext)) | ((region == REGION_RECESS_TIP)
                                                                   & (s > path + 0.8 * ext)))
    if np.any(far & (gap < x_max)):
        warnings.warn("mesh force table: tip edges reach the end of the candidate zone at the largest approach "
                      "of the table; lower force_max or widen the extension", RuntimeWarning, stacklevel=3)
