"""System deflection: the shafts, bearings and (described) gear bodies under the mesh force, and
what they do to the mesh — a lead mismatch in the plane of action (ISO 6336-1's f_sh) and a
translation of the gear centres along the line of action (SI units).

Industrial LTCA (ISO 6336-1:2019 method A, 7.6; the system-deflection step of KISSsoft's and
MASTA's contact analyses) takes the gearbox's elastic deformation into the contact as a
misalignment. This module does so from what the pair file states about the supports
(:mod:`gearmesh.supports`): each gear's shaft of diameter d_sh between two bearings a span L
apart, the gear's face centre ``gear_offset_mm`` s from mid-span (towards the leading face end),
each bearing half the stated radial and axial stiffness, the torque carried by the shaft on the
``torque_side`` of the face. With no shaft data there is no system deflection: the teeth alone,
ISO's solid-wheel model (stated in every result).

Model
-----
Each gear and its shaft is a straight Euler–Bernoulli beam along its axis (a frame element per
segment: axial, torsion, bending in both planes; Hermite cubics, exact nodal values for the
loads below; Przemieniecki 1968, *Theory of Matrix Structural Analysis*, §5.6), on springs at the
bearings; the face is the gear body, a solid cylinder of the reference diameter (the pinion body
of ISO 6336-1's f_sh, 7.6.2, whose 0.023·(b/d1)² term is its bending and torsion), the rest the
shaft. The mesh force acts at the operating pitch point, evenly over the face width b: the
transverse force F_bt along the transverse line of action, the axial force F_bt·tan β_b and its
moment about the gear centre (F_a·r_w, the tilt the body's web also takes), and the torque it
transmits, balanced at the torque side (the twist across the face is the torsion of ISO's f_sh).
With a described body (:mod:`gearmesh.body`: web and hub) the web's tilt under F_a
(Kirchhoff plate, harmonic 1) turns the rim further, in series with the shaft's tilt that carries
the same moment — never alone.

What the mesh sees: the flank point of each gear at the pitch point of axial position z moves by
u(z) + θ(z) × p (p the pitch point from the axis); along the common normal n of the flanks
(:func:`gearmesh.surface.plane_of_action_normal`) the two gears open the transverse separation

    Δg(z) = ((u₂ + θ₂ × p₂) − (u₁ + θ₁ × p₁))·n / cos β_b.

Its least-squares line over the face is the mismatch: its slope, as a lead mismatch over the
face in the convention of :mod:`gearmesh.deviation`, is ISO's f_sh (here with its sign); its mean,
the torsion left out (the rigid twist is the transmission error's, not the supports'), is the
supports' share of the approach along the line of action. Both are linear in F_bt (bearings at
their stated tangent stiffness): ``misalignment_per_force`` and ``approach_per_force``. The
residual of the line (the face's bending curvature) is reported, not applied.

Where the LTCA and the models take it: the lead mismatch per torque adds to the separations of the
LTCA, the contact table, the impact model and the robust optimiser's population
(:func:`mesh_misalignment`); the approach is reported beside the mesh's LTE (the dynamics model's
bearing springs carry the same translation as degrees of freedom). A ``torque_side`` that is not
stated is taken as the one that gives the larger mismatch (the unfavourable arrangement, as ISO
6336-1's K′ tables are read when the arrangement is unknown), named in the results.
Checks (tests/test_deflection.py): the beam against closed-form beam theory written independently
(simply supported shaft under a point load and a point moment, a cantilevered twist), the
translation against :meth:`gearmesh.supports.Supports.radial`, and the f_sh of a pinion body
against ISO 6336-1's formula in the docs.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from .contact import hand_sign
from .supports import TORQUE_SIDES

__all__ = ["FACE_ELEMENTS", "MeshDeflection", "ShaftDeflection", "shaft_deflection", "mesh_deflection",
           "mesh_misalignment", "describe_deflection"]

#: Beam elements over the face (the mismatch's line fit and the distributed load; the nodal values
#: are exact for the uniform loads, the fit converges as 1/n²: tested).
FACE_ELEMENTS = 16


@dataclass(frozen=True)
class ShaftDeflection:
    """One gear's beam under a unit mesh force F_bt = 1 N (m/N, rad/N): ``z`` (K,) the face nodes
    (model frame), ``u`` (K, 3) their displacements, ``theta`` (K, 3) their rotations (the web's
    tilt included), ``pitch_point`` (3,) the load point from the gear's axis at z = 0."""

    z: np.ndarray
    u: np.ndarray
    theta: np.ndarray
    pitch_point: np.ndarray


@dataclass(frozen=True)
class MeshDeflection:
    """The mesh's response to the system deflection, per newton of F_bt (SI; module docstring):
    ``misalignment_per_force`` (m/N) the lead mismatch f_sh/F_bt in the convention of
    :mod:`gearmesh.deviation`, ``approach_per_force`` (m/N) the supports' translation along the
    transverse line of action, ``curvature_per_force`` (m/N) the largest residual of the line fit
    over the face, ``torque_side`` the sides used, ``torque_side_stated`` whether the pair file
    says them, ``parts`` the mismatch by part (m/N): the shafts and bearings, the webs' tilt;
    ``included`` the deflections it includes, in words."""

    misalignment_per_force: float = 0.0
    approach_per_force: float = 0.0
    curvature_per_force: float = 0.0
    torque_side: tuple[str, str] | None = None
    torque_side_stated: bool = False
    parts: dict[str, float] = field(default_factory=dict)
    included: str = "none"

    @property
    def active(self) -> bool:
        return not self.included.startswith("none")

    def misalignment(self, force) -> np.ndarray:
        """f_sh (m) at transverse forces ``force`` (N)."""
        return self.misalignment_per_force * np.asarray(force, dtype=float)


def _frame_stiffness(length: float, e: float, g: float, area: float, inertia: float, polar: float) -> np.ndarray:
    """12 × 12 stiffness of a 3-D Euler–Bernoulli frame element along z, DOFs per node
    (u_x, u_y, u_z, θ_x, θ_y, θ_z) (Przemieniecki 1968 §5.6, rotated so that the element axis is
    z: bending in x–z with slope du_x/dz = θ_y, in y–z with du_y/dz = −θ_x)."""
    k = np.zeros((12, 12))
    L = length
    ea, gj, ei = e * area / L, g * polar / L, e * inertia
    for a, b, s in ((2, 8, ea), (5, 11, gj)):  # axial, torsion
        k[np.ix_([a, b], [a, b])] += s * np.array([[1.0, -1.0], [-1.0, 1.0]])
    hermite = ei / L**3 * np.array([[12, 6 * L, -12, 6 * L], [6 * L, 4 * L * L, -6 * L, 2 * L * L],
                                    [-12, -6 * L, 12, -6 * L], [6 * L, 2 * L * L, -6 * L, 4 * L * L]])
    for w, t, sign in ((0, 4, 1.0), (1, 3, -1.0)):  # (u_x, θ_y) and (u_y, −θ_x)
        idx = [w, t, 6 + w, 6 + t]
        scale = np.array([1.0, sign, 1.0, sign])
        k[np.ix_(idx, idx)] += hermite * np.outer(scale, scale)
    return k


def _uniform_load(length: float, per_length: np.ndarray) -> np.ndarray:
    """Consistent nodal loads (12,) of a uniform load along an element of ``length``: force per
    length (f_x, f_y, f_z), moment per length (m_x, m_y, m_z) (N/m, N·m/m). Bending forces take
    the Hermite work-equivalent loads (qL/2, ±qL²/12); a distributed bending moment the end
    forces ∓m (∫ m·N′ dz); axial force and torque half to each node."""
    f = np.zeros(12)
    L = length
    fx, fy, fz, mx, my, mz = per_length
    for w, t, q, sign in ((0, 4, fx, 1.0), (1, 3, fy, -1.0)):
        f[[w, t, 6 + w, 6 + t]] += q * np.array([L / 2, sign * L * L / 12, L / 2, -sign * L * L / 12])
    # a moment per length m about y bends the x–z plane (slope θ_y): end forces −m, +m along x;
    # about x bends the y–z plane with slope −θ_x: end forces +m, −m along y
    f[[0, 6]] += my * np.array([-1.0, 1.0])
    f[[1, 7]] += mx * np.array([1.0, -1.0])
    f[[2, 8]] += fz * L / 2
    f[[5, 11]] += mz * L / 2
    return f


def shaft_deflection(youngs_modulus: float, poisson_ratio: float, shaft_diameter: float, span: float, offset: float,
                     body_diameter: float, body_length: float, face_width: float, bearing_radial: float,
                     bearing_axial: float, load: np.ndarray, pitch_point: np.ndarray, torque_end: float,
                     web_tilt: np.ndarray | None = None, face_elements: int = FACE_ELEMENTS) -> ShaftDeflection:
    """Displacements and rotations of a gear's face under a load spread evenly over it.

    Parameters
    ----------
    youngs_modulus, poisson_ratio : float
        E (Pa) and ν (-).
    shaft_diameter, body_diameter : float
        Diameter (m) of the shaft, and of the segments within ±``body_length``/2 (the gear body).
    span, offset, body_length, face_width : float
        (m) The beam on the z axis (model frame), face centre z = 0: bearings at z = ∓L/2 − offset,
        the body over ±body_length/2, the load spread evenly over z ∈ ±face_width/2.
    bearing_radial, bearing_axial : float
        Stiffness of both bearings together (N/m; inf: rigid): each bearing half of it, radial in x and y.
    load, pitch_point : ndarray
        (3,) the force (N) and its point of action from the axis (m).
    torque_end, face_elements : int
        ±1: the load's torque about the axis is reacted at the bearing of the +z or −z end, which holds
        the twist; beam elements over the face (default :data:`FACE_ELEMENTS`).
    web_tilt : ndarray, optional
        (3,) a rotation (rad) of the rim relative to the shaft, added over the face.

    Returns
    -------
    ShaftDeflection
        Face nodes ``z`` (K,) m, their displacements ``u`` (K, 3) m and rotations ``theta`` (K, 3) rad.

    References
    ----------
    .. [1] Przemieniecki J.S., *Theory of Matrix Structural Analysis*, McGraw-Hill, 1968, §5.6.
    """
    e, nu = youngs_modulus, poisson_ratio
    g = e / (2.0 * (1.0 + nu))
    b = face_width
    face = np.linspace(-0.5 * b, 0.5 * b, face_elements + 1)
    bearings = np.array([-0.5 * span - offset, 0.5 * span - offset])
    nodes = np.unique(np.round(np.concatenate([face, bearings, [-0.5 * body_length, 0.5 * body_length]]), 15))
    n = nodes.size
    K = np.zeros((6 * n, 6 * n))
    F = np.zeros(6 * n)
    per_length = np.concatenate([load, np.cross(pitch_point, load)]) / b
    for i in range(n - 1):
        z0, z1 = nodes[i], nodes[i + 1]
        mid = 0.5 * (z0 + z1)
        d = body_diameter if abs(mid) < 0.5 * body_length else shaft_diameter
        area, inertia = math.pi * d * d / 4.0, math.pi * d**4 / 64.0
        dofs = np.arange(6 * i, 6 * i + 12)
        K[np.ix_(dofs, dofs)] += _frame_stiffness(z1 - z0, e, g, area, inertia, 2.0 * inertia)
        if abs(mid) < 0.5 * b:
            F[dofs] += _uniform_load(z1 - z0, per_length)
    fixed = []
    for zb in bearings:
        k = int(np.argmin(np.abs(nodes - zb)))
        for dof, stiff in ((0, 0.5 * bearing_radial), (1, 0.5 * bearing_radial), (2, 0.5 * bearing_axial)):
            if math.isinf(stiff):
                fixed.append(6 * k + dof)
            else:
                K[6 * k + dof, 6 * k + dof] += stiff
    k_torque = int(np.argmin(np.abs(nodes - bearings[1 if torque_end > 0 else 0])))
    fixed.append(6 * k_torque + 5)
    free = np.setdiff1d(np.arange(6 * n), fixed)
    x = np.zeros(6 * n)
    x[free] = np.linalg.solve(K[np.ix_(free, free)], F[free])
    at_face = np.searchsorted(nodes, face - 1e-15)
    x = x.reshape(n, 6)
    theta = x[at_face, 3:] + (0.0 if web_tilt is None else np.asarray(web_tilt)[None, :])
    return ShaftDeflection(z=face, u=x[at_face, :3], theta=theta, pitch_point=np.asarray(pitch_point, dtype=float))


def _gear_loads(geom) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Forces (N) on pinion and gear per unit F_bt at the pitch point, and the pitch points from
    each gear's axis (m): the gear takes +n F_bt/cos β_b, the pinion the reaction (module docstring)."""
    from .surface import plane_of_action_normal

    n = plane_of_action_normal(geom) / math.cos(geom.base_helix_angle)  # per unit F_bt
    r1, r2 = (float(r) for r in geom.operating_pitch_radius)
    return [-n, n], [np.array([r1, 0.0, 0.0]), np.array([-r2, 0.0, 0.0])]


def _web_tilt(geom, gear: int, axial: float, pitch_point: np.ndarray) -> np.ndarray | None:
    """The rim's rotation (rad) relative to the hub under the axial force ``axial`` (N) at the pitch
    point, where the pair file describes the body (:func:`gearmesh.body.web_tilt_compliance`)."""
    from .body import web_tilt_compliance

    c = web_tilt_compliance(geom, gear)
    if not c:
        return None
    radial = pitch_point / np.linalg.norm(pitch_point)
    # the rim at the load point moves along the axial force: Θ × (r r̂)·e_z = w  ⇒  Θ ∥ r̂ × e_z
    return c * axial * np.cross(radial, np.array([0.0, 0.0, 1.0]))


def _separation(geom, shafts: list[ShaftDeflection]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Δg(z) (m per N of F_bt) over the face, its translation part, and z (model frame)."""
    from .surface import plane_of_action_normal

    n = plane_of_action_normal(geom) / math.cos(geom.base_helix_angle)
    total, translation = 0.0, 0.0
    for sign, sd in zip((-1.0, 1.0), shafts):
        move = sd.u + np.cross(sd.theta, sd.pitch_point)
        total = total + sign * move @ n
        no_twist = sd.u + np.cross(sd.theta * np.array([1.0, 1.0, 0.0]), sd.pitch_point)
        translation = translation + sign * no_twist @ n
    return total, translation, shafts[0].z


def _fit(geom, total: np.ndarray, translation: np.ndarray, z: np.ndarray) -> tuple[float, float, float]:
    """(misalignment, approach, curvature) per N from Δg(z): the least-squares line's slope as a lead
    mismatch (:func:`gearmesh.deviation.lead_gap`: slope −F·h/b), the translation's mean, and the
    largest residual from the line."""
    slope, intercept = np.polyfit(z, total, 1)
    mis = -hand_sign(geom) * geom.face_width * slope
    return float(mis), float(np.mean(translation)), float(np.max(np.abs(total - (slope * z + intercept))))


def _why_none(geom) -> str | None:
    """Why the pair has no system deflection (None: it has one)."""
    from .body import web_tilt_compliance

    pair = geom.pair
    sup = pair.supports
    if pair.material is None:
        return "the pair file gives no material"
    if sup.defaulted:
        return "the pair file states no supports"
    if sup.shaft_diameter is None and not any(web_tilt_compliance(geom, i) for i in (0, 1)):
        return "the pair file states no shafts (shaft_diameter_mm, bearing_span_mm) and no gear body"
    return None


def _rigid_shaft(geom, tilt: np.ndarray | None, pitch_point: np.ndarray) -> ShaftDeflection:
    """A gear on a shaft the pair file does not describe (rigid): only its web tilts."""
    z = np.linspace(-0.5 * geom.face_width, 0.5 * geom.face_width, FACE_ELEMENTS + 1)
    theta = np.zeros((z.size, 3)) + (0.0 if tilt is None else tilt[None, :])
    return ShaftDeflection(z=z, u=np.zeros((z.size, 3)), theta=theta, pitch_point=pitch_point)


def mesh_deflection(geom) -> MeshDeflection:
    """The system deflection of ``geom``'s pair per newton of F_bt (module docstring); zero, with
    the reason in ``included``, when the pair file states no shafts. Computed once per pair (the
    pair, a frozen dataclass, is the key: its geometry follows from it).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; its pair's supports, bodies and material.

    Returns
    -------
    MeshDeflection
        ``misalignment_per_force``, ``approach_per_force``, ``curvature_per_force`` (m/N of F_bt),
        ``parts`` (m/N), the torque sides and ``included`` (words).

    References
    ----------
    .. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1,
       7.6 (the mesh misalignment f_sh from the deformation of shafts and gear bodies).
    .. [2] Przemieniecki J.S., *Theory of Matrix Structural Analysis*, McGraw-Hill, 1968, §5.6.
    """
    known = _DEFLECTIONS.get(geom.pair)
    if known is None:
        if len(_DEFLECTIONS) >= 256:
            _DEFLECTIONS.clear()
        known = _DEFLECTIONS[geom.pair] = _deflection(geom)
    return known


#: Deflections computed, by pair (bounded: cleared when full).
_DEFLECTIONS: dict = {}


def _deflection(geom) -> MeshDeflection:
    pair = geom.pair
    why = _why_none(geom)
    if why is not None:
        return MeshDeflection(included=f"none: {why}; the teeth alone (ISO 6336-1's solid-wheel model)")
    sup, mat = pair.supports, pair.material
    h = hand_sign(geom)
    loads, points = _gear_loads(geom)
    b = geom.face_width
    shafted = sup.shaft_diameter is not None
    sides = ([sup.torque_side] if sup.torque_side is not None or not shafted
             else list(itertools.product(TORQUE_SIDES, repeat=2)))
    sides = [s if s is not None else ("leading", "leading") for s in sides]
    best = None
    for side in sides:
        shafts, tilts = [], []
        for i in range(2):
            tilt = _web_tilt(geom, i, float(loads[i][2]), points[i])
            tilts.append(tilt)
            end = h * (1.0 if side[i] == "leading" else -1.0)
            if sup.shaft_diameter is None:
                shafts.append(_rigid_shaft(geom, tilt, points[i]))
                continue
            shafts.append(shaft_deflection(
                mat.youngs_modulus, mat.poisson_ratio, sup.shaft_diameter[i], sup.bearing_span[i],
                h * sup.gear_offset[i], 2.0 * float(geom.reference_radius[i]), float(pair.face_width[i]), b,
                sup.bearing_radial[i], sup.bearing_axial[i], loads[i], points[i], end, tilt))
        total, translation, z = _separation(geom, shafts)
        mis, approach, curve = _fit(geom, total, translation, z)
        if best is None or abs(mis) > abs(best[0]) * (1 + 1e-12):
            web = 0.0
            if any(t is not None for t in tilts):
                bare = [ShaftDeflection(sd.z, sd.u, sd.theta - (0.0 if t is None else t[None, :]), sd.pitch_point)
                        for sd, t in zip(shafts, tilts)]
                web = mis - _fit(geom, *_separation(geom, bare))[0]
            best = (mis, approach, curve, side, web)
    mis, approach, curve, side, web = best
    parts = {"shafts_and_bearings": mis - web, "webs": web}
    stated = sup.torque_side is not None
    what = ("shafts and bearings" if shafted else "rigid shafts") + (" and the webs' tilt" if web else "")
    sides_note = "stated" if stated else "not stated: the unfavourable one"
    return MeshDeflection(misalignment_per_force=mis, approach_per_force=approach, curvature_per_force=curve,
                          torque_side=tuple(side), torque_side_stated=stated, parts=parts,
                          included=f"{what} under the mesh force (gearmesh.deflection; torque side {list(side)}, "
                                   f"{sides_note})")


def mesh_misalignment(geom, force) -> np.ndarray:
    """The mesh's lead mismatch beyond the gears' own lead slopes (m) at transverse forces ``force``
    (N): the stated mesh misalignment f_ma plus the system deflection's f_sh
    (:func:`mesh_deflection`), in the convention of :mod:`gearmesh.deviation`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (its stated misalignment f_ma in m, supports and bodies).
    force : array_like
        Transverse forces F_bt (N).

    Returns
    -------
    ndarray
        Lead mismatch (m), shaped like ``force``.
    """
    return geom.pair.deviations.misalignment + mesh_deflection(geom).misalignment(force)


def describe_deflection(geom) -> str:
    """One sentence for a result's attributes: the deflections the mesh includes.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.

    Returns
    -------
    str
        What is included, with f_sh and the supports' approach in µm/kN of F_bt.
    """
    d = mesh_deflection(geom)
    if not d.active:
        return d.included
    return (f"{d.included}: f_sh {d.misalignment_per_force * 1e9:.4g} um/kN of F_bt, supports' approach "
            f"{d.approach_per_force * 1e9:.4g} um/kN along the transverse line of action")
