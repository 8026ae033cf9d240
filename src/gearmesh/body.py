"""Gear-body compliance: the axial bending of the gear's web under the axial part of the tooth load.

A helical tooth load has an axial component F_a = F_n sin β_b at the contact line. The tooth
models (:mod:`gearmesh.stiffness`, :mod:`gearmesh.fe`) hold the body's ring in its plane; the
3-D reference (:mod:`gearmesh.fe3d`, docs/validation.md) shows F_a bending the body out of its
plane (dishing and tilting), +35 % compliance for the improved potential-energy paper's gears and +58…147 % for the default
pair's thin discs. This module gives that compliance from the pair file's body geometry:

* the **web**: an annular Kirchhoff plate of thickness t (``web_thickness_mm``; a solid disc,
  t = the face width, when only ``hub_diameter_mm`` is given), clamped at the hub radius b
  (``hub_diameter_mm``/2, default the bore: the 3-D reference holds the bore) and free at the
  root radius a (the rim and teeth beyond the root circle rigid in this bending). **A pair file
  with neither key describes no body: the teeth alone**, the tooth models' bore-held ring — ISO
  6336-1's model (C_R = 1 for solid wheels; its c' is measured on real gears in real gearboxes),
  that of its worked example and of the commercial tools, where blank distortion is a switch of the
  system deflection (a solid disc held exactly at its bore is an idealisation no outside reference
  takes as its default: held at a hub of 1.5× or 2× the bore its tilt falls by a third or more).
  ``web_thickness_mm: rigid`` (one or per gear) states the same explicitly. A described body's
  bending is in series with the shafts and bearings that carry the same moment
  (:mod:`gearmesh.deflection`): the pair file must state them. A pair without a bore or a hub has
  nothing to hold the web: none, stated;
* the **load**: F_a on the edge r = a, spread evenly over the arc the contact line spans across
  the face (its transverse projection b tan β_b, as an arc at r_w: the 3-D reference loads one
  contact line evenly), carried out to the operating pitch radius r_w by a rigid tooth (so the
  edge also takes the moment F_a(r_w − a)), the deflection the mean over the arc of
  w(a) + w'(a)(r_w − a). A point load would be wrong here: under a point moment the edge's slope
  is log-singular (the harmonics of w' fall as 1/n).

The plate solution is the exact Kirchhoff one, one Fourier harmonic cos nθ at a time
(Timoshenko & Woinowsky-Krieger 1959, *Theory of Plates and Shells*, 2nd ed., §§15–18
(axisymmetric, n = 0) and §29 (unsymmetrical bending, n ≥ 1)): w_n(r) from the general solution
of ∇⁴w = 0 (A + Br² + C ln r + Dr² ln r for n = 0; Ar + Br³ + C/r + Dr ln r for n = 1;
Arⁿ + Br⁻ⁿ + Crⁿ⁺² + Dr²⁻ⁿ for n ≥ 2), four constants from w = w' = 0 at b and the free edge's
Kirchhoff conditions M_r = m_n, V_r = q_n at a (the point load's Fourier coefficients
q_0 = F/(2πa), q_n = F/(πa)). n = 0 is the dishing, n = 1 the tilt of the body, n ≥ 2 the local
bending of the rim; with the load over its arc 64 harmonics reach 10⁻⁴ (tested). Shear deformation of
the plate is left out (Kirchhoff): for thick discs it makes the compliance a lower bound.
Checks (tests/test_body.py): every harmonic of a narrow annulus against the cantilever plate strip
it becomes (edge load and edge moment, Maxwell–Betti), the series converged, thick discs → 0, and
the mesh compliance against the 3-D reference's normal-minus-transverse-load compliance (the improved
potential-energy paper's gears within 0.6 % of the stiffness, the default pair 5.7 % (the plate 97 % and 89 % of the 3-D
compliance); 11–36 % of it for the low-fluctuation paper's small thick discs, whose radial span is below their
thickness, outside a plate theory, and 53–83 % for the β ≈ 30° pairs of the meshing-line and transition-curve papers).

In the mesh, both bodies act in series with the teeth along the transverse line of action:
δ_t = w tan β_b and w = c_w F_n sin β_b = c_w F_bt tan β_b, so c_body = tan² β_b (c_w1 + c_w2)
(m/N), added to 1/K of the mesh (:func:`mesh_body_compliance`) in the TVMS
(:func:`gearmesh.stiffness.mesh_stiffness`), the LTCA (:func:`gearmesh.ltca.ltca`: the approach
gains c_body·F, the loads do not change), the contact table (:mod:`gearmesh.meshforce`) and the
entering pair's force–approach curve of the impact model. The rim's tilt (harmonic 1,
:func:`web_tilt_compliance`) also turns the flank against its mate: a lead mismatch the system
deflection adds to the shafts' tilt (:mod:`gearmesh.deflection`). Not in it: the web's effect on
the body's mass and inertia (:func:`gearmesh.gear.gear_body_mass_inertia` keeps the solid disc).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from .errors import GearmeshInputError
from .limits import LENGTH_UNITS_MM, MIN_WEB_TO_FACE, Plausible
from .supports import per_gear_length

__all__ = ["BODY_KEYS", "Body", "RIGID_WEBS", "read_body", "check_body", "describe_body", "plate_edge_compliance", "body_axial_compliance",
           "mesh_body_compliance", "web_tilt_compliance"]

#: The pair-file keys of the gear bodies: one value or [pinion, gear], mm (a web also ``rigid``).
BODY_KEYS = ("web_thickness_mm", "hub_diameter_mm")
RIGID = "rigid"
#: Fourier harmonics of the edge load summed (module docstring: 10⁻⁴ at 64 with the load over its arc).
HARMONICS = 64


@dataclass(frozen=True)
class Body:
    """The gear bodies [pinion, gear] (m): web thickness (inf: a rigid web) and hub diameter, None
    where the pair file gives none (a solid disc: the face width; the hub: the bore)."""

    web_thickness: tuple[float, float] | None = None
    hub_diameter: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        """The pair file's rules, however the body was made (a file, code or ``dataclasses.replace``):
        each web a positive length or inf (rigid), each hub a positive length, [pinion, gear];
        refused naming the pair-file key in mm. Their fit to the gear: :func:`check_body`."""
        for key, values, rigid_ok in ((BODY_KEYS[0], self.web_thickness, True), (BODY_KEYS[1], self.hub_diameter, False)):
            if values is None:
                continue
            if not isinstance(values, (list, tuple)) or len(values) != 2:
                raise GearmeshInputError(key, values, "must be a [pinion, gear] pair")
            for i, v in enumerate(values):
                if rigid_ok and isinstance(v, float) and math.isinf(v) and v > 0:
                    continue
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                    raise GearmeshInputError(f"{key}[{i}]", v * 1e3 if isinstance(v, (int, float)) else v,
                                             "must be a positive length (mm)" + (f" or '{RIGID}'" if rigid_ok else ""))

    @property
    def rigid(self) -> tuple[bool, bool]:
        """Whether each gear's web is stated rigid (no body bending)."""
        if self.web_thickness is None:
            return (False, False)
        return tuple(math.isinf(t) for t in self.web_thickness)

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {}
        if self.web_thickness is not None:
            out["web_thickness_mm"] = [RIGID if math.isinf(t) else t * 1e3 for t in self.web_thickness]
        if self.hub_diameter is not None:
            out["hub_diameter_mm"] = [d * 1e3 for d in self.hub_diameter]
        return out


#: Rigid webs on both gears (``web_thickness_mm: rigid``): the teeth alone, ISO's c' and the source documents' model.
RIGID_WEBS = Body(web_thickness=(math.inf, math.inf))


def _web(key: str, value: Any) -> tuple[float, float]:
    """A web thickness (mm), [pinion, gear] or ``rigid`` (each) → (m, m), inf for rigid."""
    items = list(value) if isinstance(value, (list, tuple)) else [value, value]
    if len(items) == 2 and RIGID in items:
        return tuple(math.inf if v == RIGID else per_gear_length(f"{key}[{i}]", v, RIGID)[0]
                     for i, v in enumerate(items))
    return per_gear_length(key, value, RIGID)


def read_body(spec: Mapping[str, Any]) -> Body:
    """The body keys of a pair-file mapping (others ignored): the web one positive length, ``rigid``
    or a [pinion, gear] pair of either, the hub one positive length or a pair; their agreement with
    the gear (web ≤ face, bore ≤ hub < root circle) is checked by :func:`check_body` once the
    geometry is known.

    Parameters
    ----------
    spec : mapping
        A pair file's keys; ``web_thickness_mm`` and ``hub_diameter_mm`` (mm) are read.

    Returns
    -------
    Body
        ``web_thickness`` and ``hub_diameter`` [pinion, gear] in m (inf: a rigid web), None where not given.
    """
    web, hub = (spec.get(k) for k in BODY_KEYS)
    return Body(None if web is None else _web(BODY_KEYS[0], web),
                None if hub is None else per_gear_length(BODY_KEYS[1], hub))


def check_body(body: Body, face_width, bore_radius, root_radius, supports=None) -> None:
    """One :class:`GearmeshInputError` naming the key when a web is thicker than its face or thinner
    than :data:`gearmesh.limits.MIN_WEB_TO_FACE` of it (naming a likely unit slip), a hub is not
    between the bore and the root circle (all in m, [pinion, gear]; bore may be None), or when a
    body is described without the shafts and bearings (``supports``,
    :class:`gearmesh.supports.Supports`) that carry the same moment (module docstring).

    Parameters
    ----------
    body : Body
        The gear bodies (m).
    face_width : sequence of float
        [pinion, gear] face widths (m).
    bore_radius : sequence of float or None
        [pinion, gear] bore radii (m), None when the pair gives none.
    root_radius : sequence of float
        [pinion, gear] root radii (m).
    supports : Supports, optional
        The pair's shafts and bearings; a described body with defaulted supports is refused.

    Returns
    -------
    None
        Raises :class:`gearmesh.errors.GearmeshInputError` naming the pair-file key.
    """
    described = (body.web_thickness is not None and not all(body.rigid)) or body.hub_diameter is not None
    if described and supports is not None and supports.defaulted:
        key = "web_thickness_mm" if body.web_thickness is not None else "hub_diameter_mm"
        raise GearmeshInputError(key, body.to_dict()[key], "describes a gear body, whose tilt comes in series with the "
                                 "shafts and bearings that carry the same moment: state the bearing stiffnesses "
                                 "(rigid, or with shaft_diameter_mm and bearing_span_mm) too, or web_thickness_mm: "
                                 "rigid")
    for i in range(2):
        if body.web_thickness is not None and math.isfinite(body.web_thickness[i]):
            b = face_width[i] * 1e3
            Plausible(MIN_WEB_TO_FACE * b, b * (1 + 1e-12), LENGTH_UNITS_MM,
                      f"from {MIN_WEB_TO_FACE:g} x the face width (thinner: no plate, gearmesh.limits.MIN_WEB_TO_FACE) "
                      "to the face width").check(body.web_thickness[i] * 1e3, f"web_thickness_mm[{i}]")
        if body.hub_diameter is not None:
            d = body.hub_diameter[i]
            if d >= 2 * root_radius[i]:
                raise GearmeshInputError(f"hub_diameter_mm[{i}]", d * 1e3, "must be smaller than the root "
                                         f"diameter {2e3 * root_radius[i]:.6g} mm")
            if bore_radius is not None and d < 2 * bore_radius[i] * (1 - 1e-12):
                raise GearmeshInputError(f"hub_diameter_mm[{i}]", d * 1e3, "must not be smaller than the bore "
                                         f"diameter {2e3 * bore_radius[i]:.6g} mm")


def _basis(n: int, r: float) -> np.ndarray:
    """Rows f, f', f'', f''' (4 × 4) of the four biharmonic solutions of harmonic ``n`` at ``r``."""
    L = math.log(r)
    if n == 0:
        return np.array([[1, r * r, L, r * r * L],
                         [0, 2 * r, 1 / r, 2 * r * L + r],
                         [0, 2, -1 / r**2, 2 * L + 3],
                         [0, 0, 2 / r**3, 2 / r]], dtype=float)
    if n == 1:
        return np.array([[r, r**3, 1 / r, r * L],
                         [1, 3 * r * r, -1 / r**2, L + 1],
                         [0, 6 * r, 2 / r**3, 1 / r],
                         [0, 6, -6 / r**4, -1 / r**2]], dtype=float)
    rows = []
    for p in (n, -n, n + 2, 2 - n):
        rows.append([r**p, p * r ** (p - 1), p * (p - 1) * r ** (p - 2), p * (p - 1) * (p - 2) * r ** (p - 3)])
    return np.array(rows, dtype=float).T


def _harmonic_edge(n: int, b: float, a: float, nu: float, D: float, q: float, m: float) -> tuple[float, float]:
    """f(a), f'(a) (m, -) of harmonic ``n`` for the plate clamped at b, free at a with the edge
    line load ``q`` (N/m, along w) and edge moment ``m`` (N·m/m, turning the edge's slope up)."""
    scale = np.array([1.0, 1 / a, 1 / a**2, 1 / a**3])[:, None]  # in ρ = r/a: f⁽ᵏ⁾(r) = a⁻ᵏ g⁽ᵏ⁾(ρ)
    fb, fa = scale * _basis(n, b / a), scale * _basis(n, 1.0)
    f, f1, f2, f3 = fa
    n2 = n * n
    # Kirchhoff free edge (Timoshenko & Woinowsky-Krieger §29): M_r = -D[f'' + ν(f'/a − n² f/a²)],
    # V_r = Q_r + (1/a)∂M_rθ/∂θ = -D[(f''' + f''/a − f'/a² − n² f'/a² + 2n² f/a³) + (1−ν)n²(f/a³ − f'/a²)]
    Mr = -D * (f2 + nu * (f1 / a - n2 * f / a**2))
    Vr = -D * (f3 + f2 / a - f1 / a**2 - n2 * f1 / a**2 + 2 * n2 * f / a**3 + (1 - nu) * n2 * (f / a**3 - f1 / a**2))
    A = np.vstack([fb[0], fb[1], Mr, Vr])
    c = np.linalg.solve(A, np.array([0.0, 0.0, -m, q]))
    return float(fa[0] @ c), float(fa[1] @ c)


def plate_edge_compliance(youngs_modulus: float, poisson_ratio: float, hub_radius: float, edge_radius: float,
                          thickness: float, load_radius: float | None = None, spread: float = 0.0,
                          harmonics: int = HARMONICS, point: bool = True) -> float:
    """Axial deflection (m) per unit axial force (N) at ``load_radius`` (default the edge) of an
    annular Kirchhoff plate clamped at ``hub_radius`` and free at ``edge_radius`` (m), thickness
    ``thickness`` (m), loaded on the edge, evenly over an arc of ``spread`` rad (0: a point), and
    carried out to ``load_radius`` by a rigid arm; the deflection is the mean over the arc (module
    docstring).

    Parameters
    ----------
    youngs_modulus : float
        E (Pa).
    poisson_ratio : float
        ν (-).
    hub_radius, edge_radius : float
        Clamped inner radius b and free outer radius a (m), 0 < b < a.
    thickness : float
        Plate thickness t (m).
    load_radius : float, optional
        Radius (m) the rigid arm carries the force out to (default the edge a).
    spread : float
        Arc (rad) the edge load is spread over (default 0: a point).
    harmonics : int
        Fourier harmonics summed (default :data:`HARMONICS`, 64).
    point : bool
        False: the force spread evenly around the edge (harmonic 0 alone). Default True.

    Returns
    -------
    float
        Axial compliance (m/N).

    References
    ----------
    .. [1] Timoshenko S., Woinowsky-Krieger S., *Theory of Plates and Shells*, 2nd ed.,
       McGraw-Hill, 1959, §§15–18 (axisymmetric bending) and §29 (unsymmetrical bending).
    """
    b, a, t = float(hub_radius), float(edge_radius), float(thickness)
    if not (0 < b < a and t > 0):
        raise ValueError("need 0 < hub radius < edge radius and a positive thickness")
    r = a if load_radius is None else float(load_radius)
    D = youngs_modulus * t**3 / (12.0 * (1.0 - poisson_ratio**2))
    w = 0.0
    for n in range(harmonics if point else 1):
        x = 0.5 * n * spread
        sinc = math.sin(x) / x if x else 1.0  # the arc's harmonic n, and the mean over it, each × sinc
        q = (1.0 if n == 0 else 2.0) / (2 * math.pi * a) * sinc
        f, f1 = _harmonic_edge(n, b, a, poisson_ratio, D, q, q * (r - a))
        w += (f + f1 * (r - a)) * sinc
    return w


def _described_web(geom, gear: int) -> tuple[float, float, float] | None:
    """(hub radius, edge radius, web thickness) (m) of a described body's web, None without one."""
    pair = geom.pair
    body = pair.body
    t = body.web_thickness[gear] if body.web_thickness is not None else pair.face_width[gear]
    if math.isinf(t):
        return None
    hub = body.hub_diameter[gear] / 2 if body.hub_diameter is not None else pair.bore_radius[gear]
    return hub, float(geom.root_radius[gear]), t


def body_axial_compliance(geom, gear: int) -> float:
    """c_w (m/N) of one gear of ``geom`` (:class:`gearmesh.gear.PairGeometry`): the web of the pair
    file's body (a solid disc of the face width held at the bore when only a hub is stated; 0 for a
    rigid web), the load at the operating pitch radius.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (material, body, bore, root and operating pitch radii in m).
    gear : int
        0 pinion, 1 gear.

    Returns
    -------
    float
        c_w (m/N).
    """
    web = _described_web(geom, gear)
    if web is None:
        return 0.0
    mat = geom.pair.material
    r_w = float(geom.operating_pitch_radius[gear])
    return plate_edge_compliance(mat.youngs_modulus, mat.poisson_ratio, web[0], web[1], web[2], r_w,
                                 spread=geom.face_width * math.tan(geom.base_helix_angle) / r_w)


def web_tilt_compliance(geom, gear: int) -> float:
    """The rim's tilt (rad per N of axial force at the operating pitch radius) of a described body:
    the plate's harmonic 1 at the edge, f₁(a)/a — the rigid tilt of the rim about the diameter
    normal to the load's radius (module docstring; Timoshenko & Woinowsky-Krieger §29). 0 where the
    bodies add nothing (:func:`describe_body`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (material, body, root and operating pitch radii in m).
    gear : int
        0 pinion, 1 gear.

    Returns
    -------
    float
        Rim tilt per axial force (rad/N).

    References
    ----------
    .. [1] Timoshenko S., Woinowsky-Krieger S., *Theory of Plates and Shells*, 2nd ed.,
       McGraw-Hill, 1959, §29.
    """
    if _why_none(geom.pair) is not None:
        return 0.0
    web = _described_web(geom, gear)
    if web is None:
        return 0.0
    hub, a, t = web
    mat = geom.pair.material
    r_w = float(geom.operating_pitch_radius[gear])
    D = mat.youngs_modulus * t**3 / (12.0 * (1.0 - mat.poisson_ratio**2))
    x = 0.5 * geom.face_width * math.tan(geom.base_helix_angle) / r_w  # half the load's arc
    sinc = math.sin(x) / x if x else 1.0
    q = 2.0 / (2 * math.pi * a) * sinc
    f, _ = _harmonic_edge(1, hub, a, mat.poisson_ratio, D, q, q * (r_w - a))
    return f / a


def _why_none(pair) -> str | None:
    """Why the pair's bodies add no compliance (None: they do)."""
    if pair.body.web_thickness is None and pair.body.hub_diameter is None:
        return "the pair file describes no gear body (web_thickness_mm, hub_diameter_mm): the teeth alone"
    if all(pair.body.rigid):
        return "the pair file states rigid webs (web_thickness_mm: rigid)"
    if pair.material is None:
        return "the pair file gives no material"
    if pair.body.hub_diameter is None and pair.bore_radius is None:
        return "the pair file gives no bore or hub to hold the web (bore_radius_mm, hub_diameter_mm)"
    return None


def mesh_body_compliance(geom) -> float:
    """Both bodies' compliance in series with the mesh along the transverse line of action (m/N):
    tan² β_b (c_w1 + c_w2) (module docstring); 0 where the bodies add none (no body described,
    rigid webs, or no material, or neither bore nor hub: :func:`describe_body` says which).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (base helix angle β_b in rad, the pair file's bodies).

    Returns
    -------
    float
        c_body (m/N).
    """
    if _why_none(geom.pair) is not None:
        return 0.0
    return math.tan(geom.base_helix_angle) ** 2 * (body_axial_compliance(geom, 0) + body_axial_compliance(geom, 1))


def describe_body(geom) -> str:
    """One sentence for a result's attributes: the gear-body compliance in its mesh stiffness.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (the pair file's bodies).

    Returns
    -------
    str
        Why there is none, or the compliance in µm/kN along the transverse line of action.
    """
    why = _why_none(geom.pair)
    if why is not None:
        return f"none: {why}; the tooth model's ring held at the bore"
    where = f"pair file {geom.pair.body.to_dict()}"
    return (f"the webs' axial bending in series with the teeth (gearmesh.body, {where}): "
            f"{mesh_body_compliance(geom) * 1e9:.4g} um/kN along the transverse line of action")
