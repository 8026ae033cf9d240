"""Loaded tooth contact analysis (LTCA) of a modified helical pair.

Everything inside is SI (m, N, rad). Displacements, separations and loads follow the
transverse line-of-action convention of :mod:`gearmesh.tca` and :mod:`gearmesh.stiffness`:
a point's load q is the transverse force it carries (its moment about the pinion axis over
r_b1), the applied force is F_bt = T1/r_b1, and the approach δ is the transverse rigid
displacement r_b1·Δφ1 (gear held). The normal load per unit length of contact line of a
point of width Δz is q/Δz (a slice carries a line Δz/cos βb long under the normal load
q/cos βb), which is also its transverse load per unit face width.

Model
-----
At every roll position the candidate points of :func:`gearmesh.tca.candidate_grid` (the
slice centres of every tooth pair in or near the active zone, with their unloaded
separations g_i) are loaded through independent transverse slices (Smith's slice theory,
as :mod:`gearmesh.stiffness`): point i of width Δz deflects

    δ − g_i = f_i(q_i) = c_i·q_i + δ_c(q_i),   c_i = (c_1(ρ1) + c_2(ρ2))/Δz,

with c_1, c_2 the per-unit-width bending + shear + axial + fillet-foundation compliances of
both teeth from :func:`gearmesh.slice_compliance.slice_compliance_table` resampled by
:func:`gearmesh.slice_compliance.pair_slice_table` (Yang & Lin 1987, Tian 2004, Sainsot et al.
2004; the tip-edge points of regions 2/3 take each tooth's compliance at its own touched
roll length — the tip of one, ρ_P of the other — for a load along the line of action: the
small inclination of an edge load off the line of action is neglected) and δ_c the local
contact approach. The contact problem is

    q_i ≥ 0,   Σ q_i = F,   δ − g_i = f_i(q_i) where q_i > 0,   q_i = 0 where g_i ≥ δ.

Independent slices make the compliance matrix diagonal, so the complementarity problem is
solved *exactly*, by one monotone scalar equation per position (:mod:`gearmesh.ltca_solve`).

Why independent slices: it is the model whose unloaded, linearised limit *is* the
stiffness stage (K = Σ slices in parallel), so LTE = F/K(φ) holds to round-off and the
two stages cannot drift apart; neighbouring-slice coupling (the tooth as a plate, e.g.
Schmidt's/Seager's influence coefficients) spreads load across the face and softens
edge peaks — left out, see the report.

The local contact law and the load-independent model (points, separations, compliances) are
:mod:`gearmesh.ltca_model`'s, the solve of the contact problem :mod:`gearmesh.ltca_solve`'s; this
module is the LTCA at each load, its stiffness terms and the harmonics of its LTE.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry, pinion_torque
from .limits import positive_values
from .loads import check_loads
from .body import mesh_body_compliance
from .deflection import mesh_deflection, mesh_misalignment
from .deviation import lead_gap
from .contact_model import LTCA_CONTACT, ContactModel
from .ltca_model import LTCAModel, contact_law, ltca_model
from .ltca_solve import solve_contact
from .tooth import require_stiffness_data
from .separation import REGION_APPROACH_TIP, REGION_RECESS_TIP
from .tca import (CandidateGrid, TCAResult, first_contact, nanmin, engagement_point,
                  engagement_separation, pair_lead_slope)

__all__ = [
    "check_torques", "pinion_torques", "LTCAResult", "ltca", "contact_tangent_compliance",
    "edge_tangent_stiffness", "with_loaded_extension", "MESH_ORDERS", "lte_harmonics", "torque_gaps",
]

#: Mesh orders of the loaded-TE harmonics (ltca.nc, the optimiser's TE criteria).
MESH_ORDERS = (1, 2, 3)


def contact_tangent_compliance(geom: PairGeometry, pinion_torque: float) -> float:
    """The linear mesh stiffness's contact compliance (m²/N per unit transverse width).

    The role of :func:`gearmesh.slice_compliance.hertz_compliance_transverse`: the tangent of the LTCA's
    Palmgren law [1]_, [2]_ (:func:`~gearmesh.ltca_model.contact_law`) at the mean line load of
    ``pinion_torque``, c = 0.9 δ_t(f)/f with f = F_bt/(b εα) the transverse force per unit of contact
    width (the contact lines' transverse widths sum to b εα on average, l_mean = b εα/cos βb). So the
    stiffness stage's TVMS, the LTCA's loaded stiffness and the contact table's tangent are one
    stiffness at one load (issue 28; Palmgren's law is of the size of Weber's contact part,
    docs/validation.md). The tangent falls as f^-0.1: ±10 % of the contact compliance for a load 2.5× off.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its material (:func:`gearmesh.gear.pair_geometry`).
    pinion_torque : float
        Pinion torque T1, N·m (positive, finite).

    Returns
    -------
    float
        Tangent contact compliance per unit transverse width, m²/N.

    Raises
    ------
    GearmeshInputError
        ``torque_Nm`` not positive and finite, or the pair lacks the stiffness data.

    References
    ----------
    .. [1] Palmgren A., Ball and Roller Bearing Engineering, 3rd ed., SKF Industries, Philadelphia,
       1959.
    .. [2] Harris T.A., Kotzalas M.N., Rolling Bearing Analysis, 5th ed., CRC Press, Boca Raton, 2007,
       eq. 6.41.
    """
    require_stiffness_data(geom, need_bore=False)
    if not (math.isfinite(pinion_torque) and pinion_torque > 0):
        raise GearmeshInputError("torque_Nm", pinion_torque, "must be a positive finite number")
    f = pinion_torque / float(geom.base_radius[0]) / (geom.face_width * geom.eps_alpha)
    law = contact_law(geom, 1.0)  # width 1 m: δ_t = coefficient · f^0.9
    return law.exponent * law.coefficient * f ** law.exponent / f


def edge_tangent_stiffness(result: "LTCAResult") -> np.ndarray:
    """Tangent stiffness (T, P) in N/m of the loaded tip-edge points beyond the active zone.

    The loaded extension of contact (the unrelieved tips that touch under load before the start and
    after the end of the active profile; Munro 1990, Velex & Maatar 1996 [1]_). Each loaded point i of
    :func:`~gearmesh.ltca_solve.solve_contact` has δ − g_i = c_i q_i + coef·q_i^m, so its tangent is
    1/(c_i + coef·m·q_i^(m−1)); the LTCA's tangent ``stiffness`` is the sum over all loaded points,
    this the sum over the tip-edge ones alone (teeth only: the bodies' series compliance,
    :mod:`gearmesh.body`, is not in it).

    Parameters
    ----------
    result : LTCAResult
        An LTCA (:func:`ltca`) with its ``model`` and ``load`` (T, P, J, N) N.

    Returns
    -------
    numpy.ndarray
        (T, P) tangent stiffness of the tip-edge points (regions 2 and 3), N/m.

    References
    ----------
    .. [1] Velex P., Maatar M., "A mathematical model for analyzing the influence of shape
       deviations and mounting errors on gear dynamic behaviour", J. Sound Vib. 191 (1996) 629–660.
    """
    model = result.model
    law, g = model.law, model.grid
    corner = (g.region == REGION_APPROACH_TIP) | (g.region == REGION_RECESS_TIP)
    p = result.load.shape[1]
    q = result.load
    c = model.compliance[None, :p] + law.linear
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = c + (law.coefficient * law.exponent * q ** (law.exponent - 1.0) if law.coefficient else 0.0)
        k = np.where(corner[None, :p] & (q > 0), 1.0 / slope, 0.0)
    return k.sum(axis=(2, 3))


def with_loaded_extension(geom: PairGeometry, K: np.ndarray, pinion_torque: float,
                          contact: ContactModel = LTCA_CONTACT) -> np.ndarray:
    """The linear TVMS ``K`` with the loaded extension of contact added in parallel with the teeth.

    Added inside the bodies' series compliance: the tip-edge tangent stiffness
    (:func:`edge_tangent_stiffness`) of the LTCA at ``pinion_torque`` on the same rolls. The linear
    TVMS counts the active zone only; under load the unrelieved tips also touch beyond it, and that
    contact is what the LTCA's tangent has and the TVMS lacks (issue 28: for the default pair at
    1000 N·m 77 of its 767 N/µm). So ``tvms``, ``ltca`` and ``contact`` are one mesh stiffness at
    one load.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    K : array_like
        (P,) linear mesh stiffness, N/m, evenly over one mesh cycle from roll 0, as
        :func:`gearmesh.stiffness.mesh_stiffness`.
    pinion_torque : float
        Pinion torque T1 of the LTCA, N·m.
    contact : ContactModel, default :data:`gearmesh.contact_model.LTCA_CONTACT`
        The LTCA's contact model (:class:`gearmesh.contact_model.ContactModel`).

    Returns
    -------
    numpy.ndarray
        (P,) mesh stiffness with the loaded tip-edge contact, N/m (``K`` itself when no tip edge
        carries load).

    References
    ----------
    .. [1] Velex P., Maatar M., "A mathematical model for analyzing the influence of shape
       deviations and mounting errors on gear dynamic behaviour", J. Sound Vib. 191 (1996) 629–660.
    """
    K = np.asarray(K, dtype=float)
    res = ltca(geom, [pinion_torque], positions=K.size, contact=contact)
    k_edge = edge_tangent_stiffness(res)[0]
    if not np.any(k_edge):
        return K
    c = mesh_body_compliance(geom)
    if c:
        return 1.0 / (1.0 / (1.0 / (1.0 / K - c) + k_edge) + c)
    return K + k_edge


# --------------------------------------------------------------------------------------
# Torques
# --------------------------------------------------------------------------------------


def check_torques(torques, field: str = "torques_Nm") -> np.ndarray:
    """Torques (N·m) as a 1-d float array; refuses empty, non-numeric, non-finite, non-positive.

    Parameters
    ----------
    torques : float or array_like
        Torque(s), N·m.
    field : str, default 'torques_Nm'
        Field named in the error.

    Returns
    -------
    numpy.ndarray
        (T,) torques, N·m.

    Raises
    ------
    GearmeshInputError
        Empty, non-numeric, non-finite or non-positive torques.
    """
    return positive_values(torques, field, "N m", note="; the pinion drives")


def pinion_torques(geom: PairGeometry, torques, on: str = "pinion", field: str = "torques_Nm") -> np.ndarray:
    """Pinion torques T1 (N·m): as given, or from gear torques T2 by T1 = T2·z1/z2.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    torques : float or array_like
        Torque(s), N·m.
    on : {'pinion', 'gear'}, default 'pinion'
        The member the torques act on.
    field : str, default 'torques_Nm'
        Field named in an error.

    Returns
    -------
    numpy.ndarray
        (T,) pinion torques T1, N·m.
    """
    return pinion_torque(geom.pair, check_torques(torques, field), on)


def loaded_pinion_torques(geom: PairGeometry, torques, on: str = "pinion",
                          field: str = "torques_Nm") -> tuple[np.ndarray, np.ndarray]:
    """The torques as given and as pinion torques T1 (N·m), each refused (GearmeshInputError
    naming ``field``) above the contact-stress and deflection limits of
    :func:`gearmesh.loads.check_load`: the entry check of every stage that loads the mesh.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    torques : float or array_like
        Torque(s), N·m.
    on : {'pinion', 'gear'}, default 'pinion'
        The member the torques act on.
    field : str, default 'torques_Nm'
        Field named in an error.

    Returns
    -------
    given : numpy.ndarray
        (T,) the torques as given, N·m.
    pinion : numpy.ndarray
        (T,) pinion torques T1, N·m.

    Raises
    ------
    GearmeshInputError
        Torques not positive and finite, or beyond the load limits.
    """
    given = check_torques(torques, field)
    t1 = pinion_torque(geom.pair, given, on)
    check_loads(geom, t1, field, given)
    return given, t1


# --------------------------------------------------------------------------------------
# LTCA
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class LTCAResult:
    """LTCA over one mesh cycle at several torques (SI; transverse convention).

    torque (T,) pinion torque T1 (N·m); force (T,) F_bt = T1/r_b1 (N);
    load (T, P, J, N) transverse load of every point (N) — line load q/Δz (N/m);
    lte (T, P) loaded transmission error = approach δ (m); stiffness (T, P) tangent mesh
    stiffness dF/dδ (N/m); pairs_in_contact (T, P); corner_load (T, P) load on tip edges
    (regions 2, 3) (N); lte_at_engagement, stiffness_at_engagement,
    corner_load_at_engagement (T,) at φ1A; tca the unloaded :class:`~gearmesh.tca.TCAResult`
    on the same grid; model the :class:`~gearmesh.ltca_model.LTCAModel`; iterations the Newton steps used;
    misalignment (T,) the mesh's lead mismatch beyond the gears' lead slopes (m: the stated f_ma
    and the system deflection's f_sh, :func:`gearmesh.deflection.mesh_misalignment`);
    system_approach (T,) the supports' translation of the gear centres along the transverse line
    of action (m, not in ``lte``: :mod:`gearmesh.deflection`).
    """

    torque: np.ndarray
    force: np.ndarray
    load: np.ndarray
    lte: np.ndarray
    stiffness: np.ndarray
    pairs_in_contact: np.ndarray
    corner_load: np.ndarray
    lte_at_engagement: np.ndarray
    stiffness_at_engagement: np.ndarray
    corner_load_at_engagement: np.ndarray
    tca: TCAResult
    model: LTCAModel
    iterations: int
    misalignment: np.ndarray | None = None
    system_approach: np.ndarray | None = None

    @property
    def grid(self) -> CandidateGrid:
        return self.tca.grid

    @property
    def line_load(self) -> np.ndarray:
        """Normal load per unit contact-line length (N/m) = transverse load per unit width."""
        return self.load / self.model.grid.dz

    @property
    def max_line_load(self) -> np.ndarray:
        """(T, P) largest line load (N/m) at each position."""
        return self.line_load.max(axis=(2, 3))


def _tca_from_grid(model: LTCAModel, te_pair_full: np.ndarray, tol: float = 1e-9) -> TCAResult:
    geom, g = model.geom, model.grid
    p = g.roll.size - 1
    grid = CandidateGrid(roll=g.roll[:p], pairs=g.pairs, z=g.z, dz=g.dz, s=g.s[:p], region=g.region[:p],
                         rho_pinion=g.rho_pinion[:p], rho_gear=g.rho_gear[:p], gap=g.gap[:p], extension=g.extension)
    te_pair = te_pair_full[:p]
    cs, cz, c1, c2 = first_contact(grid, te_pair, tol)
    roll_a, j_a, z_a = engagement_point(geom)
    te_a, next_a = engagement_separation(geom, g.z.size, model.lead_slope, g.extension / geom.transverse_base_pitch,
                                         model.misalignment)
    return TCAResult(grid=grid, te=nanmin(te_pair, axis=-1), te_pair=te_pair, contact_s=cs, contact_z=cz,
                     contact_rho_pinion=c1, contact_rho_gear=c2, roll_engagement=roll_a, pair_engagement=j_a,
                     z_engagement=z_a, te_at_engagement=te_a, te_next_pair_at_engagement=next_a,
                     lead_slope=model.lead_slope, misalignment=model.misalignment)


def torque_gaps(model: LTCAModel, misalignment: np.ndarray) -> np.ndarray:
    """The grid's separations (T, P+1, J, N) (m) at each torque's mesh misalignment ``misalignment``
    (T,) m (the stated f_ma and the load's f_sh; the grid carries the stated one alone).

    Parameters
    ----------
    model : LTCAModel
        The load-independent LTCA model (:func:`gearmesh.ltca_model.ltca_model`).
    misalignment : numpy.ndarray
        (T,) mesh misalignment of each torque, m.

    Returns
    -------
    numpy.ndarray
        (T, P+1, J, N) unloaded separations, m.
    """
    g, geom = model.grid, model.geom
    mis = np.asarray(misalignment, dtype=float)
    if np.all(mis == model.misalignment):
        return np.broadcast_to(g.gap[None], (mis.size,) + g.gap.shape)
    z = np.broadcast_to(g.z, g.gap.shape)
    lead = np.asarray(model.lead_slope)
    return (g.gap[None] - lead_gap(geom, lead, z, model.misalignment)[None]
            + lead_gap(geom, lead, z[None], mis[:, None, None, None]))


def _solve(model: LTCAModel, force: np.ndarray, misalignment: np.ndarray | None = None):
    """All torques and positions of ``model`` in one vectorised solve: loads (T, P+1, J, N),
    approach (T, P+1), tangent stiffness (T, P+1), Newton iterations; ``misalignment`` (T,) m the
    mesh misalignment per torque (None: the grid's)."""
    g = model.grid
    pp, jj, nn = g.gap.shape
    nt = force.size
    if misalignment is None:
        misalignment = np.full(nt, model.misalignment)
    gap = torque_gaps(model, misalignment).reshape(nt * pp, jj * nn)
    comp = np.broadcast_to(model.compliance.reshape(1, pp, jj * nn), (nt, pp, jj * nn)).reshape(nt * pp, jj * nn)
    q, delta, k, it = solve_contact(gap, comp, np.repeat(force, pp), model.law)
    return q.reshape(nt, pp, jj, nn), delta.reshape(nt, pp), k.reshape(nt, pp), it


def _reach_exceeded(model: LTCAModel, q: np.ndarray) -> bool:
    """True when a loaded tip-edge point lies in the outer fifth of the candidate zone."""
    g = model.grid
    if g.extension <= 0:
        return False
    far = (((g.region == REGION_APPROACH_TIP) & (g.s < -0.8 * g.extension))
           | ((g.region == REGION_RECESS_TIP) & (g.s > model.geom.path_of_contact + 0.8 * g.extension)))
    return bool(np.any((q > 0) & far[None]))


def ltca(geom: PairGeometry, torques, positions: int = 64, contact: ContactModel = LTCA_CONTACT, lead_slope=None,
         on: str = "pinion", model: LTCAModel | None = None, misalignment=None, tables=None) -> LTCAResult:
    """Loaded TCA at each torque over one mesh cycle (and at the start of engagement φ1A).

    When loaded tip edges reach the outer fifth of the candidate zone beyond the active profile, the
    zone is doubled (up to one base pitch) and the LTCA repeated; with a given ``model`` a RuntimeWarning
    is issued instead. Each torque's mesh misalignment — the stated f_ma and the system deflection's f_sh
    under its force (:func:`gearmesh.deflection.mesh_misalignment`) — adds to the separations as a lead
    mismatch (:func:`torque_gaps`); the supports' translation along the line of action is reported
    beside the LTE (``system_approach``), not in it.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius; carries the modifications).
    torques : float or array_like
        Torque(s), N·m, on the pinion or, with ``on='gear'``, on the gear.
    positions : int, default 64
        Roll positions per mesh cycle.
    contact : ContactModel, default :data:`gearmesh.contact_model.LTCA_CONTACT`
        Candidate points per contact line, local contact law (:func:`gearmesh.ltca_model.contact_law`),
        tooth model of the slice compliance and reach of the tip-edge candidates beyond the active zone
        (:class:`gearmesh.contact_model.ContactModel`).
    lead_slope : sequence of 2 float, optional
        Lead slope deviations [pinion, gear], m over the face width; None: the pair's own (:mod:`gearmesh.deviation`).
    on : {'pinion', 'gear'}, default 'pinion'
        The member ``torques`` act on.
    model : LTCAModel, optional
        A prepared :class:`~gearmesh.ltca_model.LTCAModel` to reuse (``positions`` and ``contact`` then ignored).
    misalignment : float or array_like, optional
        The mesh misalignment of each torque, m, instead of the pair's own (e.g. the rating's with ISO's f_ma).
    tables : optional
        The slice-compliance tables of another pair's teeth to build the model on
        (:func:`gearmesh.ltca_model.ltca_model`; e.g. the modified pair's for its unmodified reference).

    Returns
    -------
    LTCAResult
        ``torque`` (T,) N·m, ``force`` F_bt (T,) N, ``load`` (T, P, J, N) N, ``lte`` (T, P) m, ``stiffness``
        (T, P) N/m, ``corner_load`` (T, P) N, the values at φ1A, the unloaded ``tca`` and the ``model``.

    Raises
    ------
    GearmeshInputError
        Torques, ``positions`` or modifications out of range.
    """
    t1 = pinion_torques(geom, torques, on)
    lead_slope = pair_lead_slope(geom, lead_slope)
    force = t1 / geom.base_radius[0]
    misalignment = (mesh_misalignment(geom, force) if misalignment is None
                    else np.broadcast_to(np.asarray(misalignment, dtype=float), force.shape).copy())
    own = model is None
    while True:
        if own:
            model = ltca_model(geom, positions, contact, lead_slope, tables=tables)
        q, delta, k, it = _solve(model, force, misalignment)
        if not _reach_exceeded(model, q):
            break
        if not own or contact.extension >= 1.0:
            warnings.warn("LTCA: tip-edge contact reaches the end of the candidate zone beyond the active "
                          "profile; raise corner_extension", RuntimeWarning, stacklevel=2)
            break
        contact = contact.with_(extension=min(1.0, 2.0 * contact.extension))  # the load reaches further: widen
    c_body = mesh_body_compliance(geom)
    if c_body:  # the bodies bend under the total force, in series (gearmesh.body)
        delta, k = delta + c_body * force[:, None], 1.0 / (1.0 / k + c_body)
    g = model.grid
    pp = g.gap.shape[0]
    pair_load = q.sum(axis=3)
    in_contact = (pair_load > 1e-9 * force[:, None, None]).sum(axis=2)
    corner = ((g.region == REGION_APPROACH_TIP) | (g.region == REGION_RECESS_TIP))
    corner_load = np.where(corner[None], q, 0.0).sum(axis=(2, 3))
    te_pair = nanmin(g.gap, axis=-1)
    tca_res = _tca_from_grid(model, te_pair)
    p = pp - 1
    return LTCAResult(torque=t1, force=force, load=q[:, :p], lte=delta[:, :p], stiffness=k[:, :p],
                      pairs_in_contact=in_contact[:, :p], corner_load=corner_load[:, :p],
                      lte_at_engagement=delta[:, p], stiffness_at_engagement=k[:, p],
                      corner_load_at_engagement=corner_load[:, p], tca=tca_res, model=model, iterations=it,
                      misalignment=misalignment, system_approach=mesh_deflection(geom).approach_per_force * force)


def lte_harmonics(lte, orders=MESH_ORDERS) -> np.ndarray:
    """Amplitudes (m) of mesh orders ``orders`` of a loaded TE sampled at P evenly spaced rolls over
    one mesh cycle, end excluded (last axis; :func:`gearmesh.contact.mesh_cycle_rolls`): the
    one-sided discrete Fourier amplitude 2·|X_k|/P of order k (exact for a band-limited signal of
    orders below P/2).

    Parameters
    ----------
    lte : array_like
        (..., P) loaded transmission error, m.
    orders : sequence of int, default :data:`MESH_ORDERS`
        Mesh orders, each below P/2.

    Returns
    -------
    numpy.ndarray
        (..., len(orders)) amplitudes, m.

    Raises
    ------
    ValueError
        An order at or above P/2.
    """
    lte = np.asarray(lte, dtype=float)
    n = lte.shape[-1]
    if max(orders) >= n / 2:
        raise ValueError(f"mesh order {max(orders)} needs more than {2 * max(orders)} positions per cycle")
    return 2.0 * np.abs(np.fft.rfft(lte, axis=-1)[..., list(orders)]) / n
