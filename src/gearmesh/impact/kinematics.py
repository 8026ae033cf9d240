"""The mesh-in point in 3-D and the independent checks of the impact kinematics: the mesh-in
impact paper's vector velocity at the true closest points of the two modified transverse profiles
(:func:`vector_velocity`) and its reverse-rotation solution of the touch of an unmodified pair
(:func:`seed_edge_roll`).

Everything inside is SI (m, N, s, rad, kg); the event and its conventions: :mod:`gearmesh.impact`.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ..gear import PairGeometry, involute
from ..surface import body_rotation, flank_point, plane_of_action_point, relief_depth
from ..separation import REGION_APPROACH_TIP, REGION_RECESS_TIP, approach_tip_point, recess_tip_point
from .model import SCENARIO_NONE, ImpactModel
from .static import ImpactStatic


# --------------------------------------------------------------------------------------
# The mesh-in point in 3-D, and the independent checks
# --------------------------------------------------------------------------------------


def _omegas(model: ImpactModel, speed_rpm: float, approach_rate: float = 0.0) -> tuple[float, float]:
    """Signed angular velocities (rad/s, +z CCW) of pinion and gear: the pinion drives CCW, or
    the whole motion reversed when the gear drives (:mod:`gearmesh.impact`); the pinion's real speed
    adds the rate of the loaded approach, dδ/dt / r_b1 = (dδ/dτ)·Ω1 (gear held, as δ)."""
    w1 = speed_rpm * 2 * math.pi / 60.0
    w2 = w1 * model.geom.pair.teeth[0] / model.geom.pair.teeth[1]
    return (model.sigma * w1 + approach_rate * w1, -model.sigma * w2)


def mesh_in_point(model: ImpactModel, static: ImpactStatic, c: int = 0, t: int = 0) -> dict[str, np.ndarray | float]:
    """The mesh-in point M of candidate ``c`` at torque ``t`` in 3-D.

    Parameters
    ----------
    model : ImpactModel
        The prepared model (:func:`impact_model`).
    static : ImpactStatic
        Its speed-independent impact (:func:`impact_static`).
    c : int, default 0
        Row (modification parameter set) of ``static``.
    t : int, default 0
        Torque index of ``static``.

    Returns
    -------
    dict
        ``point`` (3,) the fixed-frame point at the touch (m), ``point_pinion`` (3,) the same
        point in the pinion body frame (m; :mod:`gearmesh.surface` frames), ``pinion_radius``
        and ``rho_pinion`` (roll length) (m), ``face_position`` z (m), and ``normal`` (3,) the
        unit common normal of the unmodified flanks (fixed frame, out of the pinion flank; the
        mating flank's for a pinion tip edge). NaN where the row has no mesh-in contact.
    """
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
    """The mesh-in impact paper's impact velocity v = ((ω1 − ω2) × r − E × ω2)·n, independent of the separation functions.

    The true closest points of the exact modified transverse profiles in M's slice at the touch, their common normal n.

    Parameters
    ----------
    model, static : ImpactModel, ImpactStatic
        The prepared model (:func:`impact_model`) and its static impact (:func:`impact_static`).
    speed_rpm : float
        Pinion speed (rpm); the pinion's real speed adds the rate of the loaded approach.
    c, t : int, default 0
        Row (parameter set) and torque index of ``static``.

    Returns
    -------
    dict
        ``normal_transverse`` (m/s, along the transverse common normal, + closing), ``normal_3d`` (× cos βb: the
        helicoid's 3-D normal; the axial velocity is zero), ``transverse_equivalent`` (m/s, the closing in the transverse
        line-of-action coordinate, × r_b1/arm, arm the normal's moment arm about the pinion axis; = 1 for a pinion
        involute normal), ``distance`` (m, the separation at the touch), the closest points ``pinion_point_x`` ... (m).
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
    """The mesh-in impact paper's 'reverse rotation' solution for an unmodified pair, pinion driving.

    The pinion roll (m) before the theoretical start of engagement at which the gear's tip
    corner meets the pinion flank when the pairs in mesh are compressed by ``approach`` δ (m).

    The mesh-in impact paper: arcsin(r_a2 sin(γ2 + LTE0 + Δφk2)/r_O1D) − Δφk2/i − arcsin(r_a2 sin γ2/r_O1E)
    = inv(arccos(r_b1/r_O1D)) − inv(arccos(r_b1/r_O1E')), r_O1D² = a² + r_a2² −
    2·a·r_a2·cos(γ2 + LTE0 + Δφk2), with γ2 the angle at O2 between the centre line and the
    start of engagement A (= E = E', the gear tip on the line of action) and LTE0 = δ/r_b2 the
    gear's lag. It states that the tip point D, turned back by LTE0 + Δφk2, lies on the pinion
    involute through A turned back by the pinion angle of Δφk2. That angle is Δφk2·z2/z1, so
    the printed "Δφk2/i" holds only with i = z1/z2; with the usual ratio i = z2/z1 it must read
    Δφk2·i (corrected here).

    Parameters
    ----------
    geom : PairGeometry
        The (unmodified) pair's geometry.
    approach : float
        Approach δ of the pairs in mesh (m).

    Returns
    -------
    float
        r_b2·(LTE0 + Δφk2) (m), the mesh-in impact paper's total deviation Δφ as roll, which
        :func:`impact_static` must reproduce for an unmodified pair (the same event).

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the
       mesh-in impact paper, docs/references.md): the reverse-rotation equation, corrected.
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
