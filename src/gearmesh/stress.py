"""Local stresses of the loaded contact: Hertzian pressure on the flanks and tip edges, tooth-root stress.

Everything inside is SI (m, N, Pa). Loads are those of :mod:`gearmesh.ltca`: the line load w of a
point is its normal load per unit length of contact line (N/m, = transverse load per unit face
width), its touched roll lengths ρ1, ρ2 (m) the transverse radii of curvature of the two involutes.

Contact pressure
----------------
Two elastic cylinders in line contact under a load w per unit length (Hertz 1882; Johnson,
Contact Mechanics, 1985, §4.3, eqs. 4.43–4.45):

    a = √(4 w R / (π E*)),   p0 = 2w/(π a) = √(w E* / (π R)),
    1/R = 1/R1 + 1/R2,   1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2,

a the half-width, p0 the peak pressure, R the relative radius of curvature *normal to the
contact line*. For two involute helicoids the normal radii along the line of contact are the
transverse radii ρ over cos βb (ISO 6336-2:2019, the derivation of Z_H: ρ_red,n = ρ_red,t/cos βb),
so 1/R = cos βb·(1/ρ1 + 1/ρ2). With ν and E of both gears equal (the pair file's one material)
p0 = Z_E·√(w/R) with ISO 6336-2's elasticity factor Z_E = √(1/(π((1−ν1²)/E1 + (1−ν2²)/E2))).

A tip-edge contact (LTCA regions 2 and 3, before A or after E) touches the mating flank with the
edge, not with an involute: a sharp edge makes the pressure infinite. The edge is taken as a
cylinder of radius r_e (the tip-edge rounding, pair-file key ``tip_edge_radius_mm``, default
:data:`DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT`·m_n; an assumption stated in the output: no standard
gives a value, drawings specify the edge break) against the mating flank's normal radius
ρ_mate/cos βb: 1/R = 1/r_e + cos βb/ρ_mate. Its axis lies along the edge; the inclination of the
edge to the contact line is neglected (as the LTCA neglects it for the edge's compliance).

Root stress
-----------
* ISO 6336-3:2019 method B, local form: the nominal root stress of a load F per unit face width
  applied at the outer point of single pair tooth contact is σ_F0 = F_t/(m_n)·Y_F·Y_S (F_t the
  tangential load at the reference circle); Y_F (form factor) and Y_S (stress correction factor)
  at the 30° tangent section of the virtual spur gear, :func:`root_form_factors` (clauses 6 and 7,
  eqs. for E, G, H, ϑ, s_Fn, ρ_F, h_Fe, α_Fen). Applied slice by slice to the LTCA's line loads it
  is a method-A-like evaluation of the real load distribution: a slice's root stress is its
  line load converted to ISO's tangential load per unit face width at the reference circle,
  w_t = w·cos α_t (w the transverse load per unit width along the line of action), times
  Y_F·Y_S/m_n, with Y_F evaluated for the load at the slice's own contact point
  (:func:`iso_root_stress_slices`).
* The 2-D finite-element tooth of :mod:`gearmesh.fe` (plane strain, P2 triangles): the tangential
  stress along the loaded side's fillet under a unit load per unit width at a roll length, its
  peak and where it sits (:func:`fe_fillet_stress`). The two are compared in tests and docs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry, check_tip_edge_radius, tool_tip_radius

__all__ = [
    "DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT", "contact_modulus", "hertz_line_contact", "flank_relative_radius",
    "edge_relative_radius", "pair_edge_radius", "check_edge_radius", "RootForm", "virtual_gear", "root_form_factors",
    "outer_single_contact_diameter", "gear_root_form", "virtual_load_diameter", "FilletStress", "fe_fillet_stress", "ContactStress", "contact_stress",
    "edge_pressure_reference",
    "iso_root_stress_slices",
]

#: Tip-edge rounding radius in normal modules when the pair file gives none: an assumed edge break
#: of 0.1 m_n (0.5 mm at m_n = 5 mm). No gear standard gives a value (ISO 21771 names the tip
#: rounding, drawings specify it); stated in every result that uses it.
DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT = 0.1


# --------------------------------------------------------------------------------------
# Hertzian line contact
# --------------------------------------------------------------------------------------


def contact_modulus(youngs_modulus: float, poisson_ratio: float) -> float:
    """E* (Pa) of two bodies of one material: 1/E* = 2(1 − ν²)/E (Johnson 1985, eq. 4.22 [1]_).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E, Pa.
    poisson_ratio : float
        Poisson's ratio ν.

    Returns
    -------
    float
        Contact modulus E*, Pa.

    References
    ----------
    .. [1] Johnson K.L., Contact Mechanics, Cambridge University Press, 1985, eq. 4.22.
    """
    return youngs_modulus / (2.0 * (1.0 - poisson_ratio**2))


def hertz_line_contact(line_load, radius, e_star: float):
    """Peak pressure p0 (Pa) and half-width a (m) of a Hertzian line contact [1]_: p0 = √(w E*/(π R)),
    a = √(4 w R/(π E*)) (Johnson 1985, §4.3, eqs. 4.43–4.45 [2]_).

    Parameters
    ----------
    line_load : array_like
        Load per unit length of contact line w, N/m (≥ 0; negative taken as 0).
    radius : array_like
        Relative radius of curvature R, m (> 0), broadcast against ``line_load``.
    e_star : float
        Contact modulus E*, Pa (:func:`contact_modulus`).

    Returns
    -------
    p0 : numpy.ndarray
        Peak pressure, Pa.
    a : numpy.ndarray
        Half-width of the contact band, m.

    References
    ----------
    .. [1] Hertz H., "Über die Berührung fester elastischer Körper", J. reine angew. Math. 92 (1882)
       156–171.
    .. [2] Johnson K.L., Contact Mechanics, Cambridge University Press, 1985, §4.3, eqs. 4.43–4.45.
    """
    w = np.asarray(line_load, dtype=float)
    r = np.asarray(radius, dtype=float)
    p0 = np.sqrt(np.maximum(w, 0.0) * e_star / (math.pi * r))
    a = np.sqrt(4.0 * np.maximum(w, 0.0) * r / (math.pi * e_star))
    return p0, a


def flank_relative_radius(rho_pinion, rho_gear, base_helix_angle: float):
    """Relative radius R (m) normal to the contact line of two involute helicoids touching at
    transverse roll lengths ρ1, ρ2 (m): 1/R = cos βb·(1/ρ1 + 1/ρ2) (ISO 6336-2, Z_H derivation [1]_).

    Parameters
    ----------
    rho_pinion, rho_gear : array_like
        Transverse radii of curvature (roll lengths) of pinion and gear at the point, m.
    base_helix_angle : float
        Base helix angle βb, rad.

    Returns
    -------
    numpy.ndarray
        Relative radius normal to the contact line, m.

    References
    ----------
    .. [1] ISO 6336-2:2019, Calculation of load capacity of spur and helical gears — Part 2: Calculation
       of surface durability (pitting), zone factor Z_H.
    """
    r1, r2 = np.asarray(rho_pinion, dtype=float), np.asarray(rho_gear, dtype=float)
    return 1.0 / (math.cos(base_helix_angle) * (1.0 / r1 + 1.0 / r2))


def edge_relative_radius(edge_radius: float, rho_mate, base_helix_angle: float):
    """Relative radius R (m) of a tip edge rounded to ``edge_radius`` (m) against the mating flank
    at roll length ``rho_mate`` (m): 1/R = 1/r_e + cos βb/ρ_mate (module docstring).

    Parameters
    ----------
    edge_radius : float
        Tip-edge rounding radius r_e, m.
    rho_mate : array_like
        Transverse roll length of the mating flank at the touched point, m.
    base_helix_angle : float
        Base helix angle βb, rad.

    Returns
    -------
    numpy.ndarray
        Relative radius, m, shaped like ``rho_mate``.
    """
    return 1.0 / (1.0 / edge_radius + math.cos(base_helix_angle) / np.asarray(rho_mate, dtype=float))


def pair_edge_radius(geom: PairGeometry) -> float | None:
    """The pair file's tip-edge radius (m; rating input ``tip_edge_radius_mm``), None when not given.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).

    Returns
    -------
    float or None
        Tip-edge radius, m, or None.
    """
    value = dict(geom.pair.rating_inputs).get("tip_edge_radius_mm")
    return None if value is None else value * 1e-3


def check_edge_radius(geom: PairGeometry, edge_radius: float | None) -> tuple[float, bool]:
    """The tip-edge radius (m) and whether it was given: the value, or the default
    :data:`DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT`·m_n; refuses a non-positive one or one above
    the normal tip thickness's half (GearmeshInputError on ``tip_edge_radius_mm``).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    edge_radius : float or None
        Tip-edge radius, m; None: the default.

    Returns
    -------
    radius : float
        Tip-edge radius, m.
    given : bool
        True when ``edge_radius`` was given.

    Raises
    ------
    GearmeshInputError
        ``tip_edge_radius_mm`` not positive and finite, or above half the normal tip thickness.
    """
    if edge_radius is None:
        return DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT * geom.pair.normal_module, False
    if isinstance(edge_radius, bool) or not isinstance(edge_radius, (int, float)) or not math.isfinite(edge_radius) \
            or edge_radius <= 0:
        raise GearmeshInputError("tip_edge_radius_mm", edge_radius if not isinstance(edge_radius, (int, float))
                                 else edge_radius * 1e3, "must be a positive number (mm)")
    check_tip_edge_radius(edge_radius, geom.normal_tip_thickness)
    return float(edge_radius), True


@dataclass(frozen=True)
class ContactStress:
    """Hertzian pressure of every LTCA point (arrays of the LTCA load's shape (T, P, J, N), SI).

    ``pressure`` p0 (Pa, 0 where unloaded), ``half_width`` a (m), ``radius`` the relative
    radius R used (m; NaN where no candidate), ``edge`` True at tip-edge points; ``edge_radius``
    (m) and whether it was given (``edge_radius_given``)."""

    pressure: np.ndarray
    half_width: np.ndarray
    radius: np.ndarray
    edge: np.ndarray
    edge_radius: float
    edge_radius_given: bool

    def peak(self) -> np.ndarray:
        """(T,) largest pressure (Pa) over the mesh cycle."""
        return self.pressure.max(axis=tuple(range(1, self.pressure.ndim)))

    def peak_on_edge(self) -> np.ndarray:
        """(T,) True where each torque's peak pressure sits on a tip edge."""
        flat = self.pressure.reshape(self.pressure.shape[0], -1)
        k = flat.argmax(axis=1)
        return self.edge.reshape(-1)[k % self.edge.size] if self.edge.ndim < self.pressure.ndim else \
            self.edge.reshape(self.pressure.shape[0], -1)[np.arange(flat.shape[0]), k]


def contact_stress(geom: PairGeometry, line_load, region, rho_pinion, rho_gear,
                   edge_radius: float | None = None) -> ContactStress:
    """Hertzian pressure and half-width at LTCA points (module docstring).

    Flank points (region 1) take both involutes' curvature; approach tip-edge points (region 2: the
    gear's tip edge on the pinion flank) the edge against ρ_pinion; recess ones (3: the pinion's edge
    on the gear flank) against ρ_gear. Line contact of Hertz [1]_ after Johnson [2]_, normal radii of
    the helicoids as ISO 6336-2 [3]_.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its material (:func:`gearmesh.gear.pair_geometry`).
    line_load : array_like
        (…, P, J, N) normal load per unit contact-line length, N/m (leading torque axes allowed).
    region : array_like of int
        (P, J, N) regions of :class:`gearmesh.tca.CandidateGrid`.
    rho_pinion, rho_gear : array_like
        (P, J, N) touched roll lengths, m.
    edge_radius : float, optional
        Tip-edge rounding radius, m; None: the default
        :data:`DEFAULT_TIP_EDGE_RADIUS_COEFFICIENT`·m_n.

    Returns
    -------
    ContactStress
        ``pressure`` p0 (Pa), ``half_width`` a (m), ``radius`` R (m), ``edge`` (bool), each shaped
        like ``line_load``; ``edge_radius`` (m) and ``edge_radius_given``.

    References
    ----------
    .. [1] Hertz H., "Über die Berührung fester elastischer Körper", J. reine angew. Math. 92 (1882)
       156–171.
    .. [2] Johnson K.L., Contact Mechanics, Cambridge University Press, 1985, §4.3.
    .. [3] ISO 6336-2:2019, Calculation of load capacity of spur and helical gears — Part 2: Calculation
       of surface durability (pitting).
    """
    from .separation import REGION_APPROACH_TIP, REGION_FLANK, REGION_RECESS_TIP

    r_e, given = check_edge_radius(geom, edge_radius)
    bb = geom.base_helix_angle
    mat = geom.pair.material
    e_star = contact_modulus(mat.youngs_modulus, mat.poisson_ratio)
    region = np.asarray(region)
    with np.errstate(divide="ignore", invalid="ignore"):
        r_flank = flank_relative_radius(rho_pinion, rho_gear, bb)
        radius = np.where(region == REGION_FLANK, r_flank, np.nan)
        radius = np.where(region == REGION_APPROACH_TIP, edge_relative_radius(r_e, rho_pinion, bb), radius)
        radius = np.where(region == REGION_RECESS_TIP, edge_relative_radius(r_e, rho_gear, bb), radius)
    w = np.asarray(line_load, dtype=float)
    loaded = (w > 0) & np.isfinite(radius)
    p0, a = hertz_line_contact(np.where(loaded, w, 0.0), np.where(np.isfinite(radius), radius, 1.0), e_star)
    edge = (region == REGION_APPROACH_TIP) | (region == REGION_RECESS_TIP)
    return ContactStress(pressure=np.where(loaded, p0, 0.0), half_width=np.where(loaded, a, 0.0), radius=radius,
                         edge=np.broadcast_to(edge, w.shape), edge_radius=r_e, edge_radius_given=given)


# --------------------------------------------------------------------------------------
# ISO 6336-3 method B: form factor Y_F and stress correction factor Y_S
# --------------------------------------------------------------------------------------


def edge_pressure_reference(flank_peak, edge_peak):
    """The pressure a design's tip-edge pressure is held against, like against like: the
    reference's own tip-edge peak ``edge_peak``, or its flank peak ``flank_peak`` where it has no
    edge contact (0). A reference's edge pressure (GPa with an assumed edge radius) would
    otherwise let a design's flank pressure rise at will (docs/optimisation.md).

    Parameters
    ----------
    flank_peak : array_like
        The reference's peak flank pressure, Pa.
    edge_peak : array_like
        The reference's peak tip-edge pressure, Pa (0 without edge contact).

    Returns
    -------
    numpy.ndarray
        Reference pressure, Pa, of the broadcast shape.
    """
    flank_peak, edge_peak = np.asarray(flank_peak, dtype=float), np.asarray(edge_peak, dtype=float)
    return np.where(edge_peak > 0, edge_peak, flank_peak)


def virtual_gear(geom: PairGeometry, gear: int) -> dict[str, float]:
    """The virtual spur gear of ISO 6336-3:2019 (clause 6.2 [1]_): z_n = z/(cos²βb cos β),
    d_n = m_n z_n, d_bn = d_n cos α_n, d_an = d_n + d_a − d, ε_αn = ε_α/cos²βb (SI).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.

    Returns
    -------
    dict of str to float
        ``z_n``, ``d_n`` (m), ``d_bn`` (m), ``d_an`` (m), ``eps_alpha_n``.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, clause 6.2.
    """
    p = geom.pair
    z = p.teeth[gear]
    beta, bb, an, mn = p.helix_angle, geom.base_helix_angle, p.normal_pressure_angle, p.normal_module
    zn = z / (math.cos(bb) ** 2 * math.cos(beta))
    dn = mn * zn
    return {"z_n": zn, "d_n": dn, "d_bn": dn * math.cos(an),
            "d_an": dn + 2.0 * (float(geom.tip_radius[gear]) - float(geom.reference_radius[gear])),
            "eps_alpha_n": geom.eps_alpha / math.cos(bb) ** 2}


def outer_single_contact_diameter(geom: PairGeometry, gear: int) -> float:
    """d_en (m) of the virtual gear's outer point of single pair tooth contact (ISO 6336-3:2019,
    method B [1]_): d_en = 2√((√((d_an/2)² − (d_bn/2)²) − π m_n cos α_n (ε_αn − 1))² + (d_bn/2)²);
    for ε_αn ≥ 2 the ISO formula is kept (then it is the point of the three-pair region).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.

    Returns
    -------
    float
        Diameter d_en of the virtual spur gear, m.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, method B.
    """
    v = virtual_gear(geom, gear)
    mn, an = geom.pair.normal_module, geom.pair.normal_pressure_angle
    rb, ra = 0.5 * v["d_bn"], 0.5 * v["d_an"]
    lead = math.sqrt(ra**2 - rb**2) - math.pi * mn * math.cos(an) * (v["eps_alpha_n"] - 1.0)
    return 2.0 * math.sqrt(lead**2 + rb**2)


@dataclass(frozen=True)
class RootForm:
    """ISO 6336-3 tooth-root quantities of one gear for a load at diameter ``d_en`` (SI, angles rad).

    ``Y_F``, ``Y_S``; ``s_Fn`` root chord at the 30° tangents, ``rho_F`` fillet radius there,
    ``h_Fe`` bending arm, ``alpha_Fen`` load angle, ``theta`` ϑ of the tangent point, the
    intermediate ``E``, ``G``, ``H`` of the standard, ``z_n``, ``L`` = s_Fn/h_Fe, ``q_s`` = s_Fn/(2ρ_F)."""

    Y_F: float
    Y_S: float
    s_Fn: float
    rho_F: float
    h_Fe: float
    alpha_Fen: float
    theta: float
    E: float
    G: float
    H: float
    z_n: float
    L: float
    q_s: float
    d_en: float


def root_form_factors(z_n: float, normal_module: float, pressure_angle: float, profile_shift: float,
                      rack_dedendum: float, rack_tip_radius: float, d_en: float, protuberance: float = 0.0,
                      ) -> RootForm:
    """Y_F and Y_S of a gear generated by a rack (hob), ISO 6336-3:2019 clauses 6.2 and 7.2 (method B
    [1]_; also DIN 3990-3 [2]_), for a load at diameter ``d_en`` (m) of the virtual gear of ``z_n`` teeth.

    Formulas::

        E = π m_n/4 − h_fP tan α_n + s_pr/cos α_n − (1 − sin α_n) ρ_fP/cos α_n
        G = ρ_fP/m_n − h_fP/m_n + x,   H = 2/z_n (π/2 − E/m_n) − π/3
        ϑ = 2G/z_n tan ϑ − H   (fixed point from π/6)
        s_Fn/m_n = z_n sin(π/3 − ϑ) + √3 (G/cos ϑ − ρ_fP/m_n)
        ρ_F/m_n = ρ_fP/m_n + 2G²/(cos ϑ (z_n cos²ϑ − 2G))
        α_en = arccos(d_bn/d_en),  γ_e = (π/2 + 2x tan α_n)/z_n + inv α_n − inv α_en,  α_Fen = α_en − γ_e
        h_Fe/m_n = ½[(cos γ_e − sin γ_e tan α_Fen) d_en/m_n − z_n cos(π/3 − ϑ) − G/cos ϑ + ρ_fP/m_n]
        Y_F = 6 (h_Fe/m_n) cos α_Fen / ((s_Fn/m_n)² cos α_n)
        Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)),  L = s_Fn/h_Fe,  q_s = s_Fn/(2ρ_F)

    Parameters
    ----------
    z_n : float
        Virtual number of teeth (:func:`virtual_gear`).
    normal_module, pressure_angle : float
        Normal module m_n (m) and normal pressure angle α_n (rad).
    profile_shift : float
        Profile shift coefficient x.
    rack_dedendum, rack_tip_radius : float
        Dedendum h_fP of the basic rack (the hob's addendum) and tip radius ρ_fP of the hob, m.
    d_en : float
        Diameter of the load point on the virtual gear, m (≥ d_bn).
    protuberance : float, default 0.0
        Protuberance s_pr, m.

    Returns
    -------
    RootForm
        ``Y_F``, ``Y_S``, ``s_Fn``, ``rho_F``, ``h_Fe`` (m), ``alpha_Fen``, ``theta`` (rad), the intermediates.

    Raises
    ------
    GearmeshInputError
        ``d_en`` below the virtual base diameter.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, clauses 6.2 and 7.2.
    .. [2] DIN 3990-3:1987, Tragfähigkeitsberechnung von Stirnrädern — Teil 3: Berechnung der Zahnfußtragfähigkeit.
    """
    mn, an, x = float(normal_module), float(pressure_angle), float(profile_shift)
    e = math.pi * mn / 4 - rack_dedendum * math.tan(an) + protuberance / math.cos(an) \
        - (1 - math.sin(an)) * rack_tip_radius / math.cos(an)
    g = rack_tip_radius / mn - rack_dedendum / mn + x
    h = 2.0 / z_n * (math.pi / 2 - e / mn) - math.pi / 3
    theta = math.pi / 6
    for _ in range(200):
        new = 2 * g / z_n * math.tan(theta) - h
        if abs(new - theta) < 1e-14:
            theta = new
            break
        theta = new
    s_fn = mn * (z_n * math.sin(math.pi / 3 - theta) + math.sqrt(3) * (g / math.cos(theta) - rack_tip_radius / mn))
    rho_f = mn * (rack_tip_radius / mn + 2 * g**2 / (math.cos(theta) * (z_n * math.cos(theta) ** 2 - 2 * g)))
    d_bn = mn * z_n * math.cos(an)
    if not d_en >= d_bn:
        raise GearmeshInputError("d_en", d_en, "the load point must lie on the involute (d_en ≥ d_bn)")
    a_en = math.acos(d_bn / d_en)
    inv = lambda a: math.tan(a) - a  # noqa: E731
    gamma_e = (0.5 * math.pi + 2 * x * math.tan(an)) / z_n + inv(an) - inv(a_en)
    a_fen = a_en - gamma_e
    h_fe = 0.5 * mn * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(a_fen)) * d_en / mn
                       - z_n * math.cos(math.pi / 3 - theta) - g / math.cos(theta) + rack_tip_radius / mn)
    y_f = 6 * (h_fe / mn) * math.cos(a_fen) / ((s_fn / mn) ** 2 * math.cos(an))
    ell = s_fn / h_fe
    q_s = s_fn / (2 * rho_f)
    y_s = (1.2 + 0.13 * ell) * q_s ** (1.0 / (1.21 + 2.3 / ell))
    return RootForm(Y_F=y_f, Y_S=y_s, s_Fn=s_fn, rho_F=rho_f, h_Fe=h_fe, alpha_Fen=a_fen, theta=theta, E=e, G=g,
                    H=h, z_n=z_n, L=ell, q_s=q_s, d_en=d_en)


def gear_root_form(geom: PairGeometry, gear: int, d_en: float | None = None) -> RootForm:
    """:func:`root_form_factors` of gear ``gear`` of ``geom`` (its hob: h_fP = dedendum
    coefficient·m_n, ρ_fP of :func:`gearmesh.gear.tool_tip_radius`, no protuberance), the
    load at ``d_en`` (m; default the outer point of single pair tooth contact, method B [1]_).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.
    d_en : float, optional
        Diameter of the load point on the virtual gear, m; None:
        :func:`outer_single_contact_diameter`.

    Returns
    -------
    RootForm
        Y_F, Y_S and the root quantities (SI).

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, method B.
    """
    v = virtual_gear(geom, gear)
    p = geom.pair
    d = outer_single_contact_diameter(geom, gear) if d_en is None else d_en
    return root_form_factors(v["z_n"], p.normal_module, p.normal_pressure_angle, float(geom.profile_shift[gear]),
                             p.dedendum_coefficient[gear] * p.normal_module, tool_tip_radius(p, gear), d)


def virtual_load_diameter(geom: PairGeometry, gear: int, rho) -> np.ndarray:
    """Diameter (m) on the virtual spur gear of a load at transverse roll length ``rho`` (m) of the
    real gear: the roll length is carried over unchanged in its distance from the tip along the
    path (ISO's d_en construction [1]_: d_en from √(r_an² − r_bn²) minus the same roll distance,
    scaled by p_bn/p_bt so that one base pitch maps onto one base pitch).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.
    rho : array_like
        Transverse roll lengths of the load points on the real gear, m.

    Returns
    -------
    numpy.ndarray
        Diameters on the virtual spur gear, m, shaped like ``rho``.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, method B (d_en).
    """
    v = virtual_gear(geom, gear)
    rb, ra = 0.5 * v["d_bn"], 0.5 * v["d_an"]
    scale = geom.normal_base_pitch / geom.transverse_base_pitch
    lead = math.sqrt(ra**2 - rb**2) - (float(geom.rho_eap[gear]) - np.asarray(rho, dtype=float)) * scale
    return 2.0 * np.sqrt(np.maximum(lead, 0.0) ** 2 + rb**2)


def iso_root_stress_slices(geom: PairGeometry, gear: int, line_load, rho, n_nodes: int = 17) -> np.ndarray:
    """Root stress (Pa) of gear ``gear`` under each point's line load by ISO 6336-3's local form [1]_.

    σ = w_t/m_n · Y_F(ρ)·Y_S(ρ), with w_t = w·cos α_t the tangential load per unit face width at the
    reference circle (F_t = F_bt cos α_t) and Y_F, Y_S for the load at the point's own roll length
    (:func:`virtual_load_diameter`, interpolated linearly from ``n_nodes`` evaluations between the
    form circle and the tip). Points with no load give 0.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.
    line_load : array_like
        The LTCA's line load w of each point, N/m (= transverse load per unit width along the line
        of action).
    rho : array_like
        The points' roll lengths on gear ``gear``, m, shaped like ``line_load``.
    n_nodes : int, default 17
        Evaluations of Y_F·Y_S between the form circle and the tip.

    Returns
    -------
    numpy.ndarray
        Nominal root stress σ_F0 of each point, Pa.

    References
    ----------
    .. [1] ISO 6336-3:2019, Calculation of load capacity of spur and helical gears — Part 3: Calculation
       of tooth bending strength, clauses 6 and 7.
    """
    p = geom.pair
    rho = np.asarray(rho, dtype=float)
    w = np.asarray(line_load, dtype=float)
    nodes = np.linspace(float(geom.rho_form[gear]), float(geom.rho_eap[gear]), n_nodes)
    d = virtual_load_diameter(geom, gear, nodes)
    v = virtual_gear(geom, gear)
    d = np.maximum(d, v["d_bn"] * (1 + 1e-12))
    yfs = np.array([(lambda f: f.Y_F * f.Y_S)(gear_root_form(geom, gear, float(dk))) for dk in d])
    factor = np.interp(np.nan_to_num(rho, nan=nodes[0]), nodes, yfs)
    wt = np.where(w > 0, w, 0.0) * math.cos(geom.transverse_pressure_angle)
    return wt / p.normal_module * factor


# --------------------------------------------------------------------------------------
# The finite-element tooth's fillet stress
# --------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class FilletStress:
    """Tangential stress along the loaded side's fillet of the FE tooth under a unit load (1 N per
    m of face width) along the line of action at roll lengths ``rho`` (m).

    ``arc`` (n,) fillet points' distance from the root-space middle along the fillet (m);
    ``stress`` (m_loads, n) σ_tt per unit load (Pa per N/m = 1/m); ``peak`` (m_loads,) its
    maximum (tension); ``peak_radius`` (m_loads,) the radius of the peak point from the gear
    centre (m); ``peak_angle`` angle (rad) between the fillet's tangent at the peak and the
    tooth centre line (ISO's 30° tangent is at π/6)."""

    rho: np.ndarray
    arc: np.ndarray
    stress: np.ndarray
    peak: np.ndarray
    peak_radius: np.ndarray
    peak_angle: np.ndarray
    n_elements: int


def fe_fillet_stress(geom: PairGeometry, gear: int, rho, plane: str = "strain", size: float = 0.05,
                     neighbours: int | None = 3) -> FilletStress:
    """FE fillet stress per unit load of gear ``gear`` (0, 1) for loads at roll lengths ``rho`` (m).

    The sector, mesh, load and solver are those of :func:`gearmesh.fe.tooth_compliance` (P2
    triangles, edge ``size``·m_n on the loaded tooth, ``neighbours`` teeth each side, the bore
    clamped). The stress σ = λ tr(ε) I + 2μ ε is L2-projected onto continuous P2 fields and read
    2e-4·m_n inside the loaded (right, x > 0) flank's fillet; σ_tt = t·σ·t with t the fillet's
    tangent — at a free surface the only non-zero stress, the largest principal one.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with material and bore (:func:`gearmesh.gear.pair_geometry`).
    gear : int
        0 the pinion, 1 the gear.
    rho : float or array_like
        (m_loads,) roll lengths of the unit loads (1 N per m of face width along the line of
        action), m.
    plane : {'strain', 'stress'}, default 'strain'
        Plane strain or plane stress.
    size : float, default 0.05
        Element edge on the loaded tooth, in normal modules.
    neighbours : int or None, default 3
        Teeth modelled on each side of the loaded one.

    Returns
    -------
    FilletStress
        ``arc`` (n,) m, ``stress`` (m_loads, n) σ_tt per unit load (1/m), ``peak`` (m_loads,) 1/m,
        ``peak_radius`` (m), ``peak_angle`` (rad).
    """
    from skfem import ElementTriP2

    from .fe import loaded_tooth
    from .fe_elastic import lame_parameters, point_load_matrix
    from .tooth import contact_point

    rho = np.atleast_1d(np.asarray(rho, dtype=float))
    profile, sector, model, mesh, solver = loaded_tooth(geom, gear, rho, plane, size, neighbours)
    mat = geom.pair.material
    _, _, alpha1, _ = contact_point(model, rho)
    n_right = np.column_stack([-np.cos(alpha1), -np.sin(alpha1)])
    u = solver.solve(point_load_matrix(solver, sector.right_loads, n_right))
    lam, mu = lame_parameters(mat.youngs_modulus, mat.poisson_ratio, plane)
    basis = solver.basis
    scalar = basis.with_element(ElementTriP2())
    fil = profile.segment == 0
    pts = np.column_stack([profile.x[fil], profile.y[fil]])
    tang = np.column_stack([profile.tangent_x[fil], profile.tangent_y[fil]])
    inward = np.column_stack([-tang[:, 1], tang[:, 0]])  # left of root→tip on the right flank: into the tooth
    # 2e-4 m_n inside: beyond the chords of the meshed outline (sagitta < 1e-4 m_n at the default
    # spacing on the root circle), where σ_tt differs from the surface's by ~2e-4 m_n/ρ_F (< 0.1 %)
    probe = (pts + 2e-4 * geom.pair.normal_module * inward).T
    probes = scalar.probes(probe)
    out = np.empty((rho.size, pts.shape[0]))
    for k in range(rho.size):
        grad = basis.interpolate(u[:, k]).grad  # (2, 2, elements, quadrature points)
        exx, eyy, exy = grad[0, 0], grad[1, 1], 0.5 * (grad[0, 1] + grad[1, 0])
        tr = exx + eyy
        sxx = scalar.project(lam * tr + 2 * mu * exx)
        syy = scalar.project(lam * tr + 2 * mu * eyy)
        sxy = scalar.project(2 * mu * exy)
        vx, vy, vxy = probes @ sxx, probes @ syy, probes @ sxy
        out[k] = tang[:, 0] ** 2 * vx + tang[:, 1] ** 2 * vy + 2 * tang[:, 0] * tang[:, 1] * vxy
    seg = np.hypot(*np.diff(pts, axis=0).T)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    i = out.argmax(axis=1)
    peak_angle = np.abs(np.arctan2(tang[i, 0], tang[i, 1]))
    return FilletStress(rho=rho, arc=arc, stress=out, peak=out[np.arange(rho.size), i],
                        peak_radius=np.hypot(pts[i, 0], pts[i, 1]), peak_angle=peak_angle,
                        n_elements=int(mesh.t.shape[1]))
