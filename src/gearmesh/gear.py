"""Gear pair data, its validation and basic cylindrical-gear geometry.

Everything here is SI (m, rad, kg, Pa). The pair file (``config/pairs/*.yaml``, engineering
units) is read and written by :mod:`gearmesh.pairfile`.

Geometry follows ISO 21771:2007 (cylindrical involute gears and gear pairs, concepts and
geometry) and DIN 3960; the equation of each quantity is given where it is computed.
Index 0 is the pinion (the driver), index 1 the gear.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .errors import GearmeshInputError
from .limits import (DENSITY, MAX_FACE_WIDTH_TO_DIAMETER, MAX_MODIFICATION_TO_MODULE, MAX_TEETH,
                     MIN_FACE_WIDTH_TO_MODULE, MODULE_RANGE, YOUNGS_MODULUS)
from .rack import form_roll, involute, rack_from  # the rack and the form point live below gear
from .body import Body, check_body
from .deviation import Deviations
from .supports import Supports, check_supports, read_supports

GEARS = ("pinion", "gear")


def inverse_involute(value: float) -> float:
    """The pressure angle α in [0, π/2) (rad) with inv(α) = ``value`` (value ≥ 0).

    Parameters
    ----------
    value : float
        inv α = tan α − α (rad), ≥ 0; a negative value raises ValueError.
    """
    if value < 0:
        raise ValueError(f"inverse involute of a negative value {value}")
    if value == 0:
        return 0.0
    from scipy.optimize import brentq  # imported here: scipy.optimize costs ~0.7 s of start-up
    return brentq(lambda a: involute(a) - value, 0.0, math.pi / 2 - 1e-12, xtol=1e-15, rtol=1e-15)


# --------------------------------------------------------------------------------------
# Data classes (SI)
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Material:
    """Isotropic elastic material: Young's modulus (Pa), Poisson ratio (-), density (kg/m³)."""

    youngs_modulus: float
    poisson_ratio: float
    density: float

    def __post_init__(self) -> None:
        """The pair file's material rules, however the material was made (a file, code or
        ``dataclasses.replace``): E > 0, 0 <= ν < 0.5 (a positive bulk modulus, E/(3(1 − 2ν))),
        density > 0, all finite, E and density within what gear materials have
        (:data:`gearmesh.limits.YOUNGS_MODULUS`, :data:`gearmesh.limits.DENSITY`); refused naming the
        pair-file key in its units."""
        for key, value, scale, plausible in (("youngs_modulus_GPa", self.youngs_modulus, 1e-9, YOUNGS_MODULUS),
                                             ("density_kg_m3", self.density, 1.0, DENSITY)):
            if _number(f"material.{key}", value * scale if _is_number(value) else value) <= 0:
                raise GearmeshInputError(f"material.{key}", value * scale, "must be positive")
            plausible.check(value * scale, f"material.{key}")
        nu = _number("material.poisson_ratio", self.poisson_ratio)
        if not 0 <= nu < 0.5:
            raise GearmeshInputError("material.poisson_ratio", nu, "must lie in [0, 0.5)")

    @property
    def shear_modulus(self) -> float:
        """G = E / (2(1 + ν)) in Pa."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


@dataclass(frozen=True)
class Modification:
    """The six micro-geometry parameters of the mesh-in impact paper for one gear (all in m).

    ``root_relief`` y1 and ``tip_relief`` y2 are the maximum profile reliefs; the relief
    lengths y3, y4 are roll lengths along the transverse path of contact, measured from the
    start of active profile (root relief) and from the tip (tip relief); ``crowning`` y5 is
    the lead relief at each face end outside the central ``unmodified_lead_length`` y6.
    The depth function is :func:`gearmesh.surface.modification_depth`.
    """

    root_relief: float = 0.0
    tip_relief: float = 0.0
    root_relief_length: float = 0.0
    tip_relief_length: float = 0.0
    crowning: float = 0.0
    unmodified_lead_length: float = 0.0

    @property
    def is_zero(self) -> bool:
        return self.root_relief == 0 and self.tip_relief == 0 and self.crowning == 0


@dataclass(frozen=True)
class GearPair:
    """A helical gear pair as designed (SI units; index 0 pinion, 1 gear).

    ``profile_shift`` and ``center_distance`` may be None (not given); see
    :func:`pair_geometry` for how the operating centre distance is resolved.
    """

    name: str
    teeth: tuple[int, int]
    normal_module: float
    normal_pressure_angle: float
    helix_angle: float
    face_width: tuple[float, float]
    profile_shift: tuple[float, float] | None = None
    center_distance: float | None = None
    addendum_coefficient: tuple[float, float] = (1.0, 1.0)
    dedendum_coefficient: tuple[float, float] = (1.25, 1.25)
    tool_tip_radius_coefficient: tuple[float | None, float | None] = (None, None)
    bore_radius: tuple[float, float] | None = None
    material: Material | None = None
    modification: tuple[Modification, Modification] = (Modification(), Modification())
    helix_hand: str = "right"
    source: str = ""
    defaults: tuple[str, ...] = ()  # pair-file keys not given, filled by defaults (e.g. pair_keys.DEFAULT_MATERIAL)
    supports: Supports = field(default_factory=lambda: read_supports({}))  # bearings and shafts (dynamics)
    body: Body = field(default_factory=Body)  # gear-body webs and hubs (gearmesh.body)
    deviations: Deviations = field(default_factory=Deviations)  # manufacturing deviations (gearmesh.deviation)
    rating_inputs: tuple[tuple[str, Any], ...] = ()  # load-capacity inputs given ((name, value), ...), pairfile.RATING_KEYS

    def with_changes(self, **changes: Any) -> "GearPair":
        """A copy with some fields replaced (e.g. a helix-angle sweep)."""
        return replace(self, **changes)


# --------------------------------------------------------------------------------------
# Checks of a pair's data (field names are the pair-file keys)
# --------------------------------------------------------------------------------------


def _number(field_name: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        rule = "must be a finite number"
        try:
            float(value)
            if isinstance(value, str):  # YAML 1.1 reads 1e6 (no dot, no sign) as text
                rule += " (YAML reads it as text: write e.g. 1.0e+6)"
        except (TypeError, ValueError):
            pass
        raise GearmeshInputError(field_name, value, rule)
    return float(value)


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float, np.number)) and not isinstance(value, bool)


def check_teeth(field_name: str, z: int) -> None:
    """Refuse a tooth count outside [5, :data:`MAX_TEETH`] (compared as integers: no overflow).

    Parameters
    ----------
    field_name : str
        The pair-file key named in the refusal (e.g. ``teeth[0]``).
    z : int
        Number of teeth (-).
    """
    if z < 5:
        raise GearmeshInputError(field_name, z, "must be at least 5 (external gears)")
    if z > MAX_TEETH:
        raise GearmeshInputError(field_name, z, f"must be at most {MAX_TEETH} (ISO 1328-1 scope)")


def validate_pair(pair: GearPair) -> None:
    """Range checks on a :class:`GearPair` in SI, also for pairs built in code (sweeps,
    designs); field names are the pair-file keys. The ranges are :data:`MODULE_RANGE`,
    :data:`MIN_FACE_WIDTH_TO_MODULE` and :data:`MAX_FACE_WIDTH_TO_DIAMETER`.

    Parameters
    ----------
    pair : GearPair
        The pair (SI); a GearmeshInputError names the first key out of range.

    References
    ----------
    .. [1] ISO 54:1996, Cylindrical gears for general engineering and for heavy engineering — Modules.
    .. [2] ANSI/AGMA 2001-D04, Fundamental rating factors and calculation methods for involute spur and
       helical gear teeth (face width b ≤ 2 d1).
    """
    for i, z in enumerate(pair.teeth):
        if isinstance(z, bool) or not isinstance(z, (int, np.integer)):
            raise GearmeshInputError(f"teeth[{i}]", z, "must be an integer")
        check_teeth(f"teeth[{i}]", z)
    mn, (m_lo, m_hi) = pair.normal_module, MODULE_RANGE
    checks = [
        ("normal_module_mm", mn * 1e3, m_lo <= mn <= m_hi,
         f"must lie in [{m_lo * 1e3:g}, {m_hi * 1e3:g}] mm (ISO 54 modules, with margins)"),
        ("normal_pressure_angle_deg", math.degrees(pair.normal_pressure_angle),
         0 < pair.normal_pressure_angle < math.radians(45), "must lie in (0, 45) degrees"),
        ("helix_angle_deg", math.degrees(pair.helix_angle), 0 <= pair.helix_angle < math.radians(60),
         "must lie in [0, 60) degrees; give the hand with helix_hand"),
        ("helix_hand", pair.helix_hand, pair.helix_hand in ("right", "left"), "must be 'right' or 'left'"),
    ]
    checks += [(f"face_width_mm[{i}]", b * 1e3, b > 0, "must be positive") for i, b in enumerate(pair.face_width)]
    d1 = pair.teeth[0] * mn / math.cos(pair.helix_angle)
    checks += [(f"face_width_mm[{i}]", b * 1e3, b >= MIN_FACE_WIDTH_TO_MODULE * mn,
                f"must be at least {MIN_FACE_WIDTH_TO_MODULE:g} normal module ({mn * 1e3:g} mm): "
                "narrower, the tooth is a plate in plane stress") for i, b in enumerate(pair.face_width)]
    checks += [(f"face_width_mm[{i}]", b * 1e3, b <= MAX_FACE_WIDTH_TO_DIAMETER * d1,
                f"must be at most {MAX_FACE_WIDTH_TO_DIAMETER:g} pinion reference diameters ({d1 * 1e3:.4g} mm; "
                "AGMA 2001 / ISO 6336-1 load distribution)") for i, b in enumerate(pair.face_width)]
    if pair.profile_shift is not None:
        checks += [(f"profile_shift[{i}]", x, -3 < x < 3, "must lie in (-3, 3)")
                   for i, x in enumerate(pair.profile_shift)]
    if pair.center_distance is not None:
        checks.append(("center_distance_mm", pair.center_distance * 1e3, pair.center_distance > 0, "must be positive"))
    for name, value, ok, rule in checks:
        if not ok:
            raise GearmeshInputError(name, value, rule)


def material_values(material: Material) -> dict[str, float]:
    """``material`` as the pair file's ``material`` mapping (GPa, -, kg/m³).

    Parameters
    ----------
    material : Material
        The material (SI: Pa, -, kg/m³).
    """
    return {"youngs_modulus_GPa": material.youngs_modulus * 1e-9, "poisson_ratio": material.poisson_ratio,
            "density_kg_m3": material.density}


# --------------------------------------------------------------------------------------
# Derived geometry
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class PairGeometry:
    """Derived geometry of a working gear pair (SI; per-gear values as length-2 arrays).

    Roll lengths ``rho`` are distances along the transverse line of action from each gear's
    base-circle tangent point (ρ = √(r² − r_b²)); they are the common abscissa of the
    contact lines, stiffness and transmission error (docs/modelling.md).
    """

    pair: GearPair
    profile_shift: np.ndarray  # (-) as used, given or inferred
    shift_inferred: bool
    transverse_module: float
    transverse_pressure_angle: float  # αt
    operating_pressure_angle: float  # αwt
    base_helix_angle: float  # βb
    center_distance: float  # a (operating)
    zero_backlash_center_distance: float
    reference_radius: np.ndarray
    base_radius: np.ndarray
    tip_radius: np.ndarray
    root_radius: np.ndarray
    operating_pitch_radius: np.ndarray
    form_radius: np.ndarray  # true start of the involute (generated)
    undercut: np.ndarray  # bool per gear
    sap_radius: np.ndarray  # start of active profile
    eap_radius: np.ndarray  # end of active profile (= tip radius)
    rho_form: np.ndarray
    rho_sap: np.ndarray
    rho_eap: np.ndarray
    face_width: float  # meshing face width (overlap)
    transverse_base_pitch: float  # p_bt
    normal_base_pitch: float  # p_bn
    path_of_contact: float  # g_α
    eps_alpha: float
    eps_beta: float
    transverse_thickness: np.ndarray  # s_t on the reference circle
    normal_thickness: np.ndarray  # s_n on the reference circle
    normal_tip_thickness: np.ndarray  # s_an
    tip_clearance: np.ndarray  # c = a − r_a(other) − r_f
    backlash_circumferential: float  # j_wt on the operating pitch circle
    backlash_normal: float  # j_bn
    mass: np.ndarray  # kg, nan without bore/material
    inertia: np.ndarray  # kg m², nan without bore/material

    @property
    def eps_gamma(self) -> float:
        return self.eps_alpha + self.eps_beta

    @property
    def gear_ratio(self) -> float:
        return self.pair.teeth[1] / self.pair.teeth[0]

    def scalars(self) -> dict[str, float | list[float]]:
        """The headline numbers in engineering units (the CLI's ``geometry --json``)."""
        mm = lambda v: [float(x) * 1e3 for x in v]  # noqa: E731
        return {
            "name": self.pair.name,
            "eps_alpha": self.eps_alpha,
            "eps_beta": self.eps_beta,
            "eps_gamma": self.eps_gamma,
            "transverse_pressure_angle_deg": math.degrees(self.transverse_pressure_angle),
            "operating_pressure_angle_deg": math.degrees(self.operating_pressure_angle),
            "base_helix_angle_deg": math.degrees(self.base_helix_angle),
            "center_distance_mm": self.center_distance * 1e3,
            "zero_backlash_center_distance_mm": self.zero_backlash_center_distance * 1e3,
            "backlash_mm": self.backlash_normal * 1e3,
            "circumferential_backlash_mm": self.backlash_circumferential * 1e3,
            "profile_shift": [float(x) for x in self.profile_shift],
            "profile_shift_inferred": self.shift_inferred,
            "addendum_coefficient": [float(x) for x in self.pair.addendum_coefficient],  # as used (tip diameter)
            "dedendum_coefficient": [float(x) for x in self.pair.dedendum_coefficient],
            "reference_radius_mm": mm(self.reference_radius),
            "base_radius_mm": mm(self.base_radius),
            "tip_radius_mm": mm(self.tip_radius),
            "root_radius_mm": mm(self.root_radius),
            "form_radius_mm": mm(self.form_radius),
            "sap_radius_mm": mm(self.sap_radius),
            "eap_radius_mm": mm(self.eap_radius),
            "undercut": [bool(u) for u in self.undercut],
            "normal_tip_thickness_mm": mm(self.normal_tip_thickness),
            "transverse_base_pitch_mm": self.transverse_base_pitch * 1e3,
            "face_width_mm": self.face_width * 1e3,
            "mass_kg": [float(x) for x in self.mass],
            "inertia_kg_m2": [float(x) for x in self.inertia],
            "material": material_values(self.pair.material) if self.pair.material is not None else None,
        }


def _transverse_angle_and_radius_sum(pair: GearPair) -> tuple[float, float]:
    """αt = atan(tan αn/cos β) (rad) and r1 + r2 = (z1 + z2) m_n/(2 cos β) (m), ISO 21771 eqs. 9, 11:
    what :func:`_resolve_shift_and_center` needs, for a pair not yet through :func:`pair_geometry`."""
    beta = pair.helix_angle
    return (math.atan(math.tan(pair.normal_pressure_angle) / math.cos(beta)),
            sum(pair.teeth) * pair.normal_module / (2 * math.cos(beta)))


def _resolve_shift_and_center(pair: GearPair, alpha_t: float, r_sum: float):
    """Profile shifts, operating centre distance and αwt (ISO 21771 §5.3, eqs. 57–59).

    inv αwt = inv αt + 2 tan αn (x1 + x2)/(z1 + z2) is the zero-backlash condition, and
    a cos αwt = (r1 + r2) cos αt ties αwt to the centre distance.
    """
    z_sum = sum(pair.teeth)
    tan_an = math.tan(pair.normal_pressure_angle)
    inferred = False
    if pair.profile_shift is None and pair.center_distance is not None:
        # Without shifts: the total shift that closes the backlash at this distance, split equally.
        cos_awt = r_sum * math.cos(alpha_t) / pair.center_distance
        if not 0 < cos_awt < 1:
            raise GearmeshInputError("center_distance_mm", pair.center_distance * 1e3,
                                     "is too small for any working pair of these teeth "
                                     f"(the base circles need more than {r_sum * math.cos(alpha_t) * 1e3:.3f} mm)")
        alpha_wt = math.acos(cos_awt)
        x_sum = (involute(alpha_wt) - involute(alpha_t)) * z_sum / (2 * tan_an)
        shift = np.array([x_sum / 2, x_sum / 2])
        inferred = True
    else:
        shift = np.array(pair.profile_shift if pair.profile_shift is not None else (0.0, 0.0))
    if inferred:
        return shift, True, pair.center_distance, pair.center_distance, alpha_wt
    inv_wt0 = involute(alpha_t) + 2 * tan_an * shift.sum() / z_sum
    if inv_wt0 <= 0:
        raise GearmeshInputError("profile_shift", [float(x) for x in shift],
                                 "the sum of the shifts is so negative that no operating pressure angle exists")
    alpha_wt0 = inverse_involute(inv_wt0)
    a0 = r_sum * math.cos(alpha_t) / math.cos(alpha_wt0)
    if pair.center_distance is None:
        return shift, False, a0, a0, alpha_wt0
    a = pair.center_distance
    if a < a0:  # within the shifts' rounding: zero backlash at a0 (pairfile.pair_notes says so); beyond: refused
        allowed = shift_rounding_center_distance(pair, alpha_t, alpha_wt0)
        if a0 - a > allowed:
            raise GearmeshInputError("center_distance_mm", a * 1e3,
                                     f"is {(a0 - a) * 1e6:.3g} µm below the zero-backlash distance {a0 * 1e3:.4f} mm "
                                     f"of these profile shifts, more than the {allowed * 1e6:.2g} µm their rounding to "
                                     "four decimals explains (the teeth would interpenetrate)")
        return shift, inferred, a0, a0, alpha_wt0
    alpha_wt = math.acos(min(1.0, r_sum * math.cos(alpha_t) / a))
    return shift, inferred, a, a0, alpha_wt


#: Half a unit of the fourth decimal: datasheets and the source documents print profile shifts
#: to four decimals, so each printed shift is the designed one within ±0.5·10⁻⁴.
SHIFT_ROUNDING = 0.5e-4


def shift_rounding_center_distance(pair: GearPair, alpha_t: float, alpha_wt0: float) -> float:
    """How far (m) below the zero-backlash centre distance a0 of the printed shifts a given
    centre distance may lie and still be the zero-backlash design: the change of a0 when both
    shifts are off by :data:`SHIFT_ROUNDING` in the same direction.

    From inv αwt = inv αt + 2 tan αn Σx/Σz and a0 = (r1 + r2) cos αt / cos αwt (ISO 21771
    eqs. 57–59), with d inv α/dα = tan²α:  ∂a0/∂Σx = 2 a0 tan αn/(Σz tan αwt) =
    m_n tan αn cos αt/(cos β sin αwt), so the tolerance is 2·0.5·10⁻⁴·∂a0/∂Σx, about 10⁻⁴ m_n
    (1.25 µm for z 24/95, m_n 14 mm, αn 20°, β 10°, x 0.48/0.6691). Against manufacturing it is
    nothing: the finest centre-distance allowance of DIN 3964 (ISO 286 field js5) is ±6.5 µm
    for a = 50–80 mm and ±20 µm for a = 800–1000 mm. A centre distance printed 0.1–0.3 µm
    below a0 (that pair at 861.000 mm, a0 = 861.00015 mm) is therefore the zero-backlash design
    whose shifts were rounded, not interpenetrating teeth.

    Parameters
    ----------
    pair : GearPair
        The pair (SI).
    alpha_t, alpha_wt0 : float
        Transverse pressure angle αt and operating pressure angle αwt at a0 (rad).

    Returns
    -------
    float
        The accepted shortfall a0 − a (m).

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry, eqs. 57–59.
    """
    mn, an, beta = pair.normal_module, pair.normal_pressure_angle, pair.helix_angle
    da0_dxsum = mn * math.tan(an) * math.cos(alpha_t) / (math.cos(beta) * math.sin(alpha_wt0))
    return 2 * SHIFT_ROUNDING * da0_dxsum


DEFAULT_TOOL_TIP_RADIUS_COEFFICIENT = 0.38  # ISO 53:1998 basic rack profile A: ρ_fP = 0.38 m_n


def max_tool_tip_radius(normal_module: float, tool_addendum: float, alpha_n: float) -> float:
    """Largest tip rounding (m) of a basic rack that fits tangent to flank and tip line.

    ρ_max = (π m_n/4 − h_aP0 tan αn)·cos αn/(1 − sin αn): the two roundings of one rack tooth
    meet on its centreline (full-radius tip; ISO 53:1998, ρ_fP,max = 0.472 m_n for αn = 20°,
    h_fP = 1.25 m_n). Negative when the rack tooth is pointed before its tip line.

    Parameters
    ----------
    normal_module : float
        Normal module m_n (m).
    tool_addendum : float
        Tool addendum h_aP0 (m), the gear's dedendum.
    alpha_n : float
        Normal pressure angle αn (rad).

    Returns
    -------
    float
        ρ_max (m).

    References
    ----------
    .. [1] ISO 53:1998, Cylindrical gears for general and heavy engineering — Standard basic rack tooth profile.
    """
    land = math.pi * normal_module / 4 - tool_addendum * math.tan(alpha_n)
    return land * math.cos(alpha_n) / (1 - math.sin(alpha_n))


def tool_tip_radius(pair: GearPair, gear: int) -> float:
    """Tip rounding ρ_aP0 (m) of the rack (hob) that generates gear ``gear`` (0 pinion, 1 gear).

    Given: ρ*·m_n, refused when it does not fit (> :func:`max_tool_tip_radius`). Not given:
    the ISO 53 value 0.38 m_n, or the full-radius tip where 0.38 m_n does not fit (e.g. αn =
    25° with h_aP0 = 1.25 m_n, the low-fluctuation paper: ρ_max = 0.318 m_n). A rack tooth pointed before
    its tip line (π/4 ≤ h_f*·tan αn) is refused on ``dedendum_coefficient``.

    Parameters
    ----------
    pair : GearPair
        The pair (SI); its ``tool_tip_radius_coefficient`` ρ* (-) or None per gear.
    gear : int
        0 for the pinion, 1 for the gear.

    References
    ----------
    .. [1] ISO 53:1998, Cylindrical gears for general and heavy engineering — Standard basic rack tooth
       profile (profile A, ρ_fP = 0.38 m_n).
    .. [2] [untitled] Low mesh-stiffness fluctuation design of helical gears, Table 1.
    """
    mn, an = pair.normal_module, pair.normal_pressure_angle
    rho_max = max_tool_tip_radius(mn, pair.dedendum_coefficient[gear] * mn, an)
    if rho_max < 0:
        raise GearmeshInputError(
            f"dedendum_coefficient[{gear}]", pair.dedendum_coefficient[gear],
            f"the {GEARS[gear]} generating rack tooth is pointed before its tip line "
            f"(needs h_f* < π/(4 tan αn) = {math.pi / (4 * math.tan(an)):.4f})")
    given = pair.tool_tip_radius_coefficient[gear]
    if given is None:
        return min(DEFAULT_TOOL_TIP_RADIUS_COEFFICIENT * mn, rho_max)
    if given * mn > rho_max * (1 + 1e-9):
        raise GearmeshInputError(
            f"tool_tip_radius_coefficient[{gear}]", given,
            f"the {GEARS[gear]} hob tip rounding does not fit its tooth: at most {rho_max / mn:.4f} "
            "(full-radius tip) for this pressure angle and dedendum")
    return given * mn


def pinion_torque(pair: GearPair, torque, on: str):
    """Pinion torque T1 (N m) of a torque given on the pinion or on the gear: T1 = T2·z1/z2
    (torque balance of a lossless mesh, the base radii being proportional to the teeth).

    Parameters
    ----------
    pair : GearPair
        The pair (its tooth counts z1, z2).
    torque : float or ndarray
        The torque (N m), any shape.
    on : {'pinion', 'gear'}
        The member it acts on.

    Returns
    -------
    float or ndarray
        T1 (N m), the shape of ``torque``.
    """
    if on not in GEARS:
        raise GearmeshInputError("on", on, "must be 'pinion' or 'gear' (where the torque acts)")
    return torque if on == "pinion" else torque * (pair.teeth[0] / pair.teeth[1])


def gear_body_mass_inertia(reference_radius, bore_radius, face_width, density):
    """Mass (kg) and polar moment (kg m²) of a solid disc of the reference (pitch) radius
    minus the bore over the face width: m = ρπ(r² − r_i²)b, J = m(r² + r_i²)/2.

    This is the body convention of the low-fluctuation paper (Table 1: pair 1 gives 0.2165/0.6266 kg and
    0.96/7.90 ·10⁻⁴ kg m²).

    Parameters
    ----------
    reference_radius, bore_radius, face_width : array_like
        r, r_i and b (m), broadcast together (per gear: shape (2,)).
    density : float
        ρ (kg/m³).

    Returns
    -------
    mass, inertia : ndarray
        m (kg) and J about the axis (kg m²).

    References
    ----------
    .. [1] [untitled] Low mesh-stiffness fluctuation design of helical gears, Table 1.
    """
    r, ri, b = np.asarray(reference_radius), np.asarray(bore_radius), np.asarray(face_width)
    mass = density * np.pi * (r**2 - ri**2) * b
    return mass, 0.5 * mass * (r**2 + ri**2)


def pair_geometry(pair: GearPair) -> PairGeometry:
    """Derived geometry of ``pair``, refusing any pair that cannot work.

    When the profile shifts were inferred from the centre distance, a refusal caused by
    them (shift or tip geometry) names ``center_distance_mm`` (the value the user gave) and
    says which inferred shift failed; other refusals keep their own field.

    Parameters
    ----------
    pair : GearPair
        The pair as designed (SI); no shifts but a centre distance: those closing the backlash, split equally.

    Returns
    -------
    PairGeometry
        Radii (m, (2,)), roll lengths ``rho_*`` (m), pressure angles (rad), centre distance (m),
        ``eps_alpha``, ``eps_beta`` (-), thicknesses and backlash (m), masses (kg), inertias (kg m²).

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and geometry
       (eqs. 9, 11, 13, 21, 45, 47, 57–59, 64, 70, 87, 91; §5.4.1, §5.5).
    """
    try:
        return _pair_geometry(pair)
    except GearmeshInputError as exc:
        caused_by_shift = exc.field.startswith(("profile_shift", "addendum_coefficient"))
        if pair.profile_shift is None and pair.center_distance is not None and caused_by_shift:
            raise GearmeshInputError(
                "center_distance_mm", pair.center_distance * 1e3,
                f"needs profile shifts for zero backlash that make no working pair: {exc}") from None
        raise


def _pair_geometry(pair: GearPair) -> PairGeometry:
    """:func:`pair_geometry` without the re-labelling of refusals.

    Refusals (:class:`GearmeshInputError`, naming the field): centre distance below zero
    backlash or below the base circles; non-positive dedendum space (root below bore);
    pointed teeth (normal tip thickness ≤ 0); tip below the base circle; the mating tip
    reaching below the form circle (interference with the fillet or the undercut);
    negative tip clearance; transverse contact ratio εα < 1.
    """
    validate_pair(pair)
    z = np.array(pair.teeth, dtype=float)
    mn, an, beta = pair.normal_module, pair.normal_pressure_angle, pair.helix_angle
    mt = mn / math.cos(beta)
    alpha_t = math.atan(math.tan(an) / math.cos(beta))  # ISO 21771 eq. 9
    beta_b = math.atan(math.tan(beta) * math.cos(alpha_t))  # eq. 21
    r = z * mt / 2  # eq. 11
    rb = r * math.cos(alpha_t)  # eq. 13
    shift, inferred, a, a0, alpha_wt = _resolve_shift_and_center(pair, alpha_t, r.sum())
    ha = np.array(pair.addendum_coefficient)
    hf = np.array(pair.dedendum_coefficient)
    ra = r + (ha + shift) * mn  # eq. 45, no tip shortening
    rf = r - (hf - shift) * mn  # eq. 47
    rw = rb / math.cos(alpha_wt)
    _check_circles(pair, rb, ra, rf, ha, hf)
    st, sn, san = _tooth_thicknesses(pair, mt, alpha_t, r, rb, ra, shift)

    # Roll lengths along the transverse line of action (ISO 21771 §5.4.1).
    rho_a = np.sqrt(ra**2 - rb**2)
    line_of_action = a * math.sin(alpha_wt)  # T1T2
    rho_sap = line_of_action - rho_a[::-1]
    rho_form, undercut = _form_rolls(pair, z, shift)
    r_form = np.sqrt(rb**2 + rho_form**2)
    _check_active_profiles(ha, shift, rho_sap, rho_form, undercut)
    clearance = _tip_clearance(a, ra, rf, ha)

    pbt = math.pi * mt * math.cos(alpha_t)
    path = rho_a.sum() - line_of_action  # g_α, eq. 87
    eps_alpha = path / pbt
    if eps_alpha < 1:
        raise GearmeshInputError("addendum_coefficient", [float(x) for x in ha],
                                 f"gives a transverse contact ratio eps_alpha = {eps_alpha:.4f} < 1: "
                                 "the mesh is not continuous")
    check_body(pair.body, pair.face_width, pair.bore_radius, rf, pair.supports)
    check_supports(pair.supports, pair.face_width, pair.bore_radius)
    edge_radius = dict(pair.rating_inputs).get("tip_edge_radius_mm")
    if edge_radius is not None:
        check_tip_edge_radius(edge_radius * 1e-3, san)
    b = min(pair.face_width)
    eps_beta = b * math.sin(beta) / (math.pi * mn)  # eq. 91
    j_wt, j_bn = _backlash(z, r, rw, st, alpha_t, alpha_wt, beta_b, a, a0)
    mass, inertia = _body_mass_inertia(pair, r)

    geom = PairGeometry(
        pair=pair, profile_shift=shift, shift_inferred=inferred, transverse_module=mt,
        transverse_pressure_angle=alpha_t, operating_pressure_angle=alpha_wt, base_helix_angle=beta_b,
        center_distance=a, zero_backlash_center_distance=a0, reference_radius=r, base_radius=rb,
        tip_radius=ra, root_radius=rf, operating_pitch_radius=rw, form_radius=r_form, undercut=undercut,
        sap_radius=np.sqrt(rb**2 + rho_sap**2), eap_radius=ra, rho_form=rho_form, rho_sap=rho_sap,
        rho_eap=rho_a, face_width=b, transverse_base_pitch=pbt, normal_base_pitch=math.pi * mn * math.cos(an),
        path_of_contact=path, eps_alpha=eps_alpha, eps_beta=eps_beta, transverse_thickness=st,
        normal_thickness=sn, normal_tip_thickness=san, tip_clearance=clearance,
        backlash_circumferential=j_wt, backlash_normal=j_bn, mass=mass, inertia=inertia,
    )
    validate_modifications(geom)
    return geom


def _check_circles(pair: GearPair, rb: np.ndarray, ra: np.ndarray, rf: np.ndarray, ha: np.ndarray,
                   hf: np.ndarray) -> None:
    """Refuse a root circle (radius ``rf``, m) at or inside the bore or the axis, and a tip circle
    (``ra``) inside the base circle (``rb``): no involute flank. ``ha``, ``hf``: the addendum and
    dedendum coefficients."""
    for i in range(2):
        if pair.bore_radius is not None and rf[i] <= pair.bore_radius[i]:
            raise GearmeshInputError(f"bore_radius_mm[{i}]", pair.bore_radius[i] * 1e3,
                                     f"must be below the {GEARS[i]} root radius {rf[i] * 1e3:.3f} mm")
        if rf[i] <= 0:
            raise GearmeshInputError(f"dedendum_coefficient[{i}]", float(hf[i]),
                                     f"puts the {GEARS[i]} root circle at or below its axis")
        if ra[i] <= rb[i]:
            raise GearmeshInputError(f"addendum_coefficient[{i}]", float(ha[i]),
                                     f"puts the {GEARS[i]} tip circle ({ra[i] * 1e3:.3f} mm) inside its base "
                                     f"circle ({rb[i] * 1e3:.3f} mm): no involute flank")


def _tooth_thicknesses(pair: GearPair, mt: float, alpha_t: float, r: np.ndarray, rb: np.ndarray, ra: np.ndarray,
                       shift: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tooth thickness on the reference circle, transverse s_t and normal s_n, and the normal tip
    thickness s_an (m) (ISO 21771 eqs. 64, 70); a pointed tooth (s_an ≤ 0) is refused."""
    beta = pair.helix_angle
    st = mt * (np.pi / 2 + 2 * shift * math.tan(pair.normal_pressure_angle))
    sn = st * math.cos(beta)
    alpha_at = np.arccos(rb / ra)
    sat = 2 * ra * (st / (2 * r) + involute(alpha_t) - involute(alpha_at))
    beta_a = np.arctan(np.tan(beta) * ra / r)
    san = sat * np.cos(beta_a)
    for i in range(2):
        if san[i] <= 0:
            raise GearmeshInputError(f"profile_shift[{i}]", float(shift[i]),
                                     f"makes the {GEARS[i]} tooth pointed (normal tip thickness "
                                     f"{san[i] * 1e3:.3f} mm <= 0); reduce the shift or the addendum")
    return st, sn, san


def _form_rolls(pair: GearPair, z: np.ndarray, shift: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roll length (m) of the true form point of each gear, where its generated involute starts,
    and whether the gear is undercut (:func:`gearmesh.rack.form_roll` of its generating rack)."""
    mn, an, beta = pair.normal_module, pair.normal_pressure_angle, pair.helix_angle
    racks = [rack_from(z[i], mn, an, beta, pair.dedendum_coefficient[i] * mn, tool_tip_radius(pair, i), shift[i])
             for i in range(2)]
    rho_form, undercut = (np.array(v) for v in zip(*(form_roll(rack) for rack in racks)))
    return rho_form, undercut


def _check_active_profiles(ha: np.ndarray, shift: np.ndarray, rho_sap: np.ndarray, rho_form: np.ndarray,
                           undercut: np.ndarray) -> None:
    """Refuse a mate's tip that reaches past the base tangent point of the line of action
    (involute interference) or below the form circle (fillet interference): the start of active
    profile ``rho_sap`` (roll length, m) must lie on the involute, at or above ``rho_form``."""
    for i in range(2):
        other = 1 - i
        if rho_sap[i] < 0:
            raise GearmeshInputError(f"addendum_coefficient[{other}]", float(ha[other]),
                                     f"the {GEARS[other]} tip reaches past the {GEARS[i]} base tangent "
                                     "point of the line of action (involute interference)")
        if rho_sap[i] < rho_form[i] - 1e-12:
            raise GearmeshInputError(f"profile_shift[{i}]", float(shift[i]),
                                     f"the {GEARS[other]} tip (start of active profile at roll length "
                                     f"{rho_sap[i] * 1e3:.3f} mm) reaches below the {GEARS[i]} form circle "
                                     f"(involute starts at {rho_form[i] * 1e3:.3f} mm{', undercut' if undercut[i] else ''}): "
                                     "fillet interference")


def _tip_clearance(a: float, ra: np.ndarray, rf: np.ndarray, ha: np.ndarray) -> np.ndarray:
    """Tip clearance c = a − r_a(other) − r_f (m) of each gear's root circle; negative refused."""
    clearance = a - ra[::-1] - rf
    for i in range(2):
        if clearance[i] < 0:
            raise GearmeshInputError(f"addendum_coefficient[{1 - i}]", float(ha[1 - i]),
                                     f"the {GEARS[1 - i]} tip circle cuts the {GEARS[i]} root circle "
                                     f"(tip clearance {clearance[i] * 1e3:.3f} mm < 0)")
    return clearance


def _backlash(z: np.ndarray, r: np.ndarray, rw: np.ndarray, st: np.ndarray, alpha_t: float, alpha_wt: float,
              beta_b: float, a: float, a0: float) -> tuple[float, float]:
    """Circumferential backlash j_wt on the operating pitch circle and normal backlash j_bn (m),
    from the thicknesses on the operating pitch circles (ISO 21771 §5.5; j = 0 at a0)."""
    swt = 2 * rw * (st / (2 * r) + involute(alpha_t) - involute(alpha_wt))
    j_wt = 2 * math.pi * rw[0] / z[0] - swt.sum() if a != a0 else 0.0  # at a0 zero by construction, not ±1e-17
    j_bn = j_wt * math.cos(alpha_wt) * math.cos(beta_b)
    return j_wt, j_bn


def _body_mass_inertia(pair: GearPair, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The gear bodies' masses (kg) and inertias (kg m²) (:func:`gear_body_mass_inertia`); NaN
    without a bore or a material."""
    if pair.bore_radius is not None and pair.material is not None:
        return gear_body_mass_inertia(r, np.array(pair.bore_radius), np.array(pair.face_width),
                                      pair.material.density)
    mass = inertia = np.full(2, np.nan)
    return mass, inertia


def check_tip_edge_radius(edge_radius: float, normal_tip_thickness) -> None:
    """Refuse a tip-edge rounding radius (m) above half the thinner normal tip thickness (m, per
    gear): the rounding would take the whole tip (GearmeshInputError on ``tip_edge_radius_mm``).
    The pair's own radius is checked with its geometry (:func:`pair_geometry`, so ``validate``
    refuses what the rating would), one given to a stress function by it too.

    Parameters
    ----------
    edge_radius : float
        Tip-edge rounding radius (m).
    normal_tip_thickness : array_like
        Normal tip thickness s_an of each gear (m), shape (2,).
    """
    limit = 0.5 * float(np.min(normal_tip_thickness))
    if edge_radius > limit:
        raise GearmeshInputError("tip_edge_radius_mm", edge_radius * 1e3,
                                 f"must not exceed half the normal tip thickness ({limit * 1e3:.3g} mm)")


def validate_modifications(geom: PairGeometry) -> None:
    """Refuse relief lengths longer than the active flank, lead lengths beyond the face and
    depths beyond :data:`MAX_MODIFICATION_TO_MODULE` normal modules.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry with its two :class:`Modification` (m); refusals name ``modification.<gear>.*``.
    """
    depth_limit = MAX_MODIFICATION_TO_MODULE * geom.pair.normal_module
    for i, (gear, mod) in enumerate(zip(GEARS, geom.pair.modification)):
        active = geom.rho_eap[i] - geom.rho_sap[i]
        field_base = f"modification.{gear}"
        for attr in ("root_relief", "tip_relief", "crowning"):
            if getattr(mod, attr) > depth_limit:
                raise GearmeshInputError(f"{field_base}.{attr}_um", getattr(mod, attr) * 1e6,
                                         f"must be at most {MAX_MODIFICATION_TO_MODULE:g} normal module "
                                         f"({depth_limit * 1e6:.4g} µm): deeper reshapes the tooth")
        if mod.root_relief_length + mod.tip_relief_length > active * (1 + 1e-9):
            raise GearmeshInputError(
                f"{field_base}.root_relief_length_mm + tip_relief_length_mm",
                (mod.root_relief_length + mod.tip_relief_length) * 1e3,
                f"exceeds the active roll length of the {gear} flank ({active * 1e3:.3f} mm)")
        if (mod.root_relief > 0) != (mod.root_relief_length > 0):
            raise GearmeshInputError(f"{field_base}.root_relief_length_mm", mod.root_relief_length * 1e3,
                                     "root relief amount and length must both be zero or both positive")
        if (mod.tip_relief > 0) != (mod.tip_relief_length > 0):
            raise GearmeshInputError(f"{field_base}.tip_relief_length_mm", mod.tip_relief_length * 1e3,
                                     "tip relief amount and length must both be zero or both positive")
        if mod.unmodified_lead_length > geom.face_width * (1 + 1e-9):
            raise GearmeshInputError(f"{field_base}.unmodified_lead_length_mm", mod.unmodified_lead_length * 1e3,
                                     f"exceeds the face width {geom.face_width * 1e3:.3f} mm")
        if mod.crowning > 0 and mod.unmodified_lead_length >= geom.face_width:
            raise GearmeshInputError(f"{field_base}.unmodified_lead_length_mm", mod.unmodified_lead_length * 1e3,
                                     "leaves no face width for the lead crowning")
