"""Supports of the gear bodies: bearing and shaft stiffness at the gear centre (SI units).

The dynamics (:mod:`gearmesh.dynamics`) hold each gear body on a radial spring (x, y) and an
axial spring (z). The pair file says what they are (:class:`Supports`, keys
``bearing_radial_stiffness_N_per_um``, ``bearing_axial_stiffness_N_per_um`` and optionally
``shaft_diameter_mm``, ``bearing_span_mm``); left out, the low-fluctuation paper §4's values (stated as a
default in every result). ``rigid`` removes the direction from the model: both directions
rigid is the torsional model of ISO 6336-1's resonance speed n_E1.

Closed forms (each checked in ``tests/test_supports.py``):

* Shaft bending, the gear at mid-span of a simply supported shaft of span L and diameter d:
  k_s = 48 E I / L³, I = π d⁴/64 (Roark's Formulas for Stress and Strain, 7th ed., Table 8.1
  case 1e; Timoshenko & Gere, Mechanics of Materials). The gear's slope is zero at mid-span,
  so the shaft adds no tilt to the 8-DOF model. It acts in series with the bearings:
  1/k = 1/k_bearings + 1/k_s (radial). The shaft's axial compliance L/(2EA) is left out (for
  the default pair 3 % and 1 % of the bearings').
* Rolling bearing (line contact): Palmgren's roller–raceway approach δ = 3.84·10⁻⁵ Q^0.9 /
  l^0.8 (mm, N, mm; Palmgren 1959, Ball and Roller Bearing Engineering; Harris & Kotzalas
  2007, Rolling Bearing Analysis, 5th ed., Vol. 1 §6.5) at the inner and the outer raceway,
  the most loaded roller's Q_max = 4.08 F_r/(Z cos α) for zero clearance (half the rollers
  loaded, Sjövall's integral J_r(0.5) = 0.2453 for line contact; Harris & Kotzalas §7.2), the
  axial load shared by all Z rollers, Q = F_a/(Z sin α). The stiffness is the tangent at the
  load, F/(0.9 δ) (δ ∝ F^0.9), the same law as the LTCA's tooth contact.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from .errors import GearmeshInputError
from .limits import BEARING_STIFFNESS

#: Palmgren's line-contact constant: δ (mm) = PALMGREN_LINE · Q^0.9 (N) / l^0.8 (mm), one raceway.
PALMGREN_LINE = 3.84e-5
PALMGREN_LINE_EXPONENT = 0.9
#: Most loaded roller of a line-contact bearing with zero clearance: Q_max = 4.08 F_r / (Z cos α).
STRIBECK_LINE = 4.08


def shaft_bending_stiffness(youngs_modulus: float, diameter: float, span: float) -> float:
    """Radial stiffness (N/m) at mid-span of a simply supported solid round shaft: 48 E I / L³,
    I = π d⁴/64 (Roark, Table 8.1 case 1e).

    Parameters
    ----------
    youngs_modulus : float
        E (Pa).
    diameter : float
        Shaft diameter d (m).
    span : float
        Bearing span L (m).

    Returns
    -------
    float
        k_s (N/m).

    References
    ----------
    .. [1] Young W.C., Budynas R.G., *Roark's Formulas for Stress and Strain*, 7th ed.,
       McGraw-Hill, 2002, Table 8.1 case 1e.
    """
    inertia = math.pi * diameter**4 / 64.0
    return 48.0 * youngs_modulus * inertia / span**3


def in_series(*stiffness: float) -> float:
    """Springs in series: 1/Σ(1/k_i) (N/m); an infinite k (rigid) adds nothing.

    Parameters
    ----------
    *stiffness : float
        The springs' stiffnesses k_i (N/m; inf: rigid).

    Returns
    -------
    float
        The series stiffness (N/m); inf when all are rigid.
    """
    return 1.0 / sum(1.0 / k for k in stiffness if math.isfinite(k))


def roller_bearing_stiffness(radial_load: float, axial_load: float, rollers: int, roller_length: float,
                             contact_angle: float) -> tuple[float, float]:
    """Tangent radial and axial stiffness (N/m) of one line-contact rolling bearing (module
    docstring: Palmgren's approach at both raceways, Q_max = 4.08 F_r/(Z cos α), the axial load
    on all rollers).

    Parameters
    ----------
    radial_load, axial_load : float
        F_r and F_a on the bearing (N, > 0).
    rollers : int
        Number of rollers Z.
    roller_length : float
        Effective roller length l (m).
    contact_angle : float
        Contact angle α (rad; 0 < α < π/2 for the axial value).

    Returns
    -------
    k_r, k_a : float
        Tangent radial and axial stiffness (N/m).

    References
    ----------
    .. [1] Palmgren A., *Ball and Roller Bearing Engineering*, 3rd ed., 1959 (line-contact
       approach δ = 3.84·10⁻⁵ Q^0.9/l^0.8).
    .. [2] Harris T.A., Kotzalas M.N., *Rolling Bearing Analysis*, 5th ed., Vol. 1, CRC Press,
       2007, §6.5 (contact deformation) and §7.2 (load distribution, Q_max = 4.08 F_r/(Z cos α)).
    """
    l_mm = roller_length * 1e3

    def approach(q):  # both raceways, m
        return 2.0 * PALMGREN_LINE * q**PALMGREN_LINE_EXPONENT / l_mm**0.8 * 1e-3

    q_r = STRIBECK_LINE * radial_load / (rollers * math.cos(contact_angle))
    k_r = radial_load / (PALMGREN_LINE_EXPONENT * approach(q_r) / math.cos(contact_angle))
    q_a = axial_load / (rollers * math.sin(contact_angle))
    k_a = axial_load / (PALMGREN_LINE_EXPONENT * approach(q_a) / math.sin(contact_angle))
    return k_r, k_a


# --------------------------------------------------------------------------------------
# The pair file's supports
# --------------------------------------------------------------------------------------

#: Pair-file keys of the supports (engineering units), each one value, [pinion, gear] or (the
#: stiffnesses) ``rigid``.
SUPPORT_KEYS = ("bearing_radial_stiffness_N_per_um", "bearing_axial_stiffness_N_per_um", "shaft_diameter_mm",
                "bearing_span_mm", "gear_offset_mm", "torque_side")
#: The shaft end (of the face) on whose side each gear's shaft carries the torque: the face end
#: where a tooth pair's contact line enters first (pinion driving) is the leading one
#: (:mod:`gearmesh.deviation`).
TORQUE_SIDES = ("leading", "trailing")
RIGID = "rigid"
#: Supports of a pair file that says none: the low-fluctuation paper §4's bearings (k_x = k_y = 1.5·10⁸ N/m,
#: k_z = 10⁷ N/m, both gears), the only bearing values of the source documents. They belong to
#: the low-fluctuation paper's small pair (d ≈ 50/130 mm), not to every gearbox: a pair file should say its own
#: (the default study's does); which applied is stated in every dynamics result.
DEFAULT_SUPPORTS_N_PER_UM = {"bearing_radial_stiffness_N_per_um": 150.0, "bearing_axial_stiffness_N_per_um": 10.0}


@dataclass(frozen=True)
class Supports:
    """Stiffness (N/m) of each gear's support at the gear centre, [pinion, gear]: ``bearing_radial``
    and ``bearing_axial`` of the bearings of its shaft together (``inf``: rigid), the shaft
    ``shaft_diameter`` and ``bearing_span`` (m, or None: no shaft bending). ``defaulted``: the
    pair file said nothing (:data:`DEFAULT_SUPPORTS_N_PER_UM`)."""

    bearing_radial: tuple[float, float]
    bearing_axial: tuple[float, float]
    shaft_diameter: tuple[float, float] | None = None
    bearing_span: tuple[float, float] | None = None
    defaulted: bool = False
    gear_offset: tuple[float, float] = (0.0, 0.0)
    torque_side: tuple[str, str] | None = None

    def __post_init__(self) -> None:
        """The pair file's rules, however the supports were made (a file, code or
        ``dataclasses.replace``): each bearing stiffness positive and within what bearings have
        (:data:`gearmesh.limits.BEARING_STIFFNESS`, N/µm; inf: rigid), the shaft's diameter and span
        positive lengths, given together; refused naming the pair-file key in its units."""
        for key, values in ((SUPPORT_KEYS[0], self.bearing_radial), (SUPPORT_KEYS[1], self.bearing_axial)):
            for i, k in enumerate(_two(key, values)):
                if math.isinf(k) and k > 0:
                    continue
                if isinstance(k, bool) or not isinstance(k, (int, float)) or not math.isfinite(k) or k <= 0:
                    raise GearmeshInputError(f"{key}[{i}]", k if not isinstance(k, (int, float)) else k * 1e-6,
                                             f"must be a positive number (N/um) or '{RIGID}'")
                BEARING_STIFFNESS.check(k * 1e-6, f"{key}[{i}]")
        if (self.shaft_diameter is None) != (self.bearing_span is None):
            given, missing = (SUPPORT_KEYS[2], SUPPORT_KEYS[3]) if self.bearing_span is None else SUPPORT_KEYS[3:1:-1]
            raise GearmeshInputError(missing, None, f"is required with {given} (the shaft's bending needs both)")
        for key, values in ((SUPPORT_KEYS[2], self.shaft_diameter), (SUPPORT_KEYS[3], self.bearing_span)):
            for i, v in enumerate(_two(key, values) if values is not None else ()):
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
                    raise GearmeshInputError(f"{key}[{i}]", v if not isinstance(v, (int, float)) else v * 1e3,
                                             "must be a positive length (mm)")

    def radial(self, youngs_modulus: float) -> tuple[float, float]:
        """Radial stiffness (N/m) at each gear centre: bearings in series with the shaft's bending
        (E of the pair's material); inf where both are rigid. With the gear at distances a and c
        from its two bearings (a + c = L, ``gear_offset`` s from mid-span: a, c = L/2 ± s) the
        shaft deflects F a²c²/(3EIL) under the load (Roark, Table 8.1 case 1e) and the two
        bearings, each half the stated stiffness k, carry F c/L and F a/L: their deflections put
        the gear at F (a² + c²)/(L² k/2) (at mid-span F/k and 48EI/L³: :func:`shaft_bending_stiffness`)."""
        if self.shaft_diameter is None:
            return self.bearing_radial
        out = []
        for kb, d, span, s in zip(self.bearing_radial, self.shaft_diameter, self.bearing_span, self.gear_offset):
            a, c = 0.5 * span + s, 0.5 * span - s
            shaft = 3.0 * youngs_modulus * math.pi * d**4 / 64.0 * span / (a * a * c * c)
            bearings = kb * span * span / (2.0 * (a * a + c * c))
            out.append(in_series(bearings, shaft) if math.isfinite(kb) else shaft)
        return tuple(out)

    def axial(self) -> tuple[float, float]:
        """Axial stiffness (N/m) at each gear centre (the bearings'; inf: rigid)."""
        return self.bearing_axial

    def to_dict(self) -> dict[str, Any]:
        """The pair-file keys (engineering units; ``rigid`` for inf); empty when defaulted."""
        if self.defaulted:
            return {}
        out: dict[str, Any] = {
            "bearing_radial_stiffness_N_per_um": [RIGID if math.isinf(k) else k * 1e-6 for k in self.bearing_radial],
            "bearing_axial_stiffness_N_per_um": [RIGID if math.isinf(k) else k * 1e-6 for k in self.bearing_axial]}
        if self.shaft_diameter is not None:
            out["shaft_diameter_mm"] = [d * 1e3 for d in self.shaft_diameter]
            out["bearing_span_mm"] = [s * 1e3 for s in self.bearing_span]
        if any(self.gear_offset):
            out["gear_offset_mm"] = [s * 1e3 for s in self.gear_offset]
        if self.torque_side is not None:
            out["torque_side"] = list(self.torque_side)
        return out

    def describe(self, youngs_modulus: float) -> str:
        """One sentence for the output: the stiffnesses the dynamics uses and where they come from."""
        def n(k):
            return RIGID if math.isinf(k) else f"{k * 1e-6:.4g}"
        r, a = self.radial(youngs_modulus), self.axial()
        where = ("not given in the pair file: the low-fluctuation paper §4's bearings (gearmesh.supports.DEFAULT_SUPPORTS_N_PER_UM)"
                 if self.defaulted else "from the pair file")
        shaft = "" if self.shaft_diameter is None else " (bearings in series with the shaft's bending)"
        return (f"supports radial [{n(r[0])}, {n(r[1])}] N/um{shaft}, axial [{n(a[0])}, {n(a[1])}] N/um "
                f"[pinion, gear], {where}")


def _two(key: str, values: Any) -> tuple[Any, Any]:
    """A [pinion, gear] pair of a :class:`Supports` field, refused naming ``key`` otherwise."""
    if not isinstance(values, (list, tuple)) or len(values) != 2:
        raise GearmeshInputError(key, values, "must be a [pinion, gear] pair")
    return tuple(values)


def check_supports(supports: Supports, face_width, bore_radius) -> None:
    """One :class:`GearmeshInputError` naming the key when a shaft does not fit its gear: thicker
    than the bore it passes through, or its bearings closer together than the gear is wide (they
    sit either side of it).

    Parameters
    ----------
    supports : Supports
        The pair's supports (m, N/m).
    face_width : sequence of float
        [pinion, gear] face widths (m).
    bore_radius : sequence of float or None
        [pinion, gear] bore radii (m), None when the pair gives none.

    Returns
    -------
    None
        Raises :class:`gearmesh.errors.GearmeshInputError` naming the pair-file key.
    """
    if supports.shaft_diameter is None:
        return
    for i in range(2):
        d, span = supports.shaft_diameter[i], supports.bearing_span[i]
        if bore_radius is not None and d > 2 * bore_radius[i] * (1 + 1e-12):
            raise GearmeshInputError(f"shaft_diameter_mm[{i}]", d * 1e3, "must not exceed the bore diameter "
                                     f"{2e3 * bore_radius[i]:.6g} mm (2 x bore_radius_mm): the shaft passes through the "
                                     "gear's bore")
        if span < face_width[i] * (1 - 1e-12):
            raise GearmeshInputError(f"bearing_span_mm[{i}]", span * 1e3, f"must be at least the face width "
                                     f"{face_width[i] * 1e3:.6g} mm: the bearings sit either side of the gear")


def _stiffness(key: str, value: Any) -> tuple[float, float]:
    """One stiffness (N/µm), [pinion, gear] or ``rigid`` → (N/m, N/m), inf for rigid."""
    def one(name, v):
        if v == RIGID:
            return math.inf
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise GearmeshInputError(name, v, f"must be a positive number (N/um) or '{RIGID}'")
        return float(v) * 1e6
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise GearmeshInputError(key, value, f"must be one value, a [pinion, gear] pair or '{RIGID}'")
        return one(f"{key}[0]", value[0]), one(f"{key}[1]", value[1])
    v = one(key, value)
    return v, v


def per_gear_length(key: str, value: Any, alternative: str = "") -> tuple[float, float]:
    """One positive length (mm) or a [pinion, gear] pair of a pair-file key → (m, m); one
    :class:`GearmeshInputError` naming the key (and index) otherwise (shafts here, gear bodies in
    :mod:`gearmesh.body`, whose web may also be the word ``alternative``, named in the rule).

    Parameters
    ----------
    key : str
        The pair-file key, for the error message.
    value : float or sequence of float
        One length or a [pinion, gear] pair (mm).
    alternative : str
        A word the caller accepts instead (e.g. ``rigid``), named in the rule (default none).

    Returns
    -------
    tuple of float
        (pinion, gear) lengths (m).
    """
    rule = "must be a positive length (mm)" + (f" or '{alternative}'" if alternative else "")

    def one(name, v):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
            raise GearmeshInputError(name, v, rule)
        return float(v) * 1e-3
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise GearmeshInputError(key, value, "must be one value or a [pinion, gear] pair")
        return one(f"{key}[0]", value[0]), one(f"{key}[1]", value[1])
    v = one(key, value)
    return v, v


def read_supports(spec: Mapping[str, Any]) -> Supports:
    """The supports of a pair-file mapping (its other keys ignored): both stiffnesses or neither
    (then :data:`DEFAULT_SUPPORTS_N_PER_UM`), shaft diameter and bearing span together or not at
    all. One :class:`~gearmesh.errors.GearmeshInputError` naming the key otherwise.

    Parameters
    ----------
    spec : mapping
        A pair file's keys; :data:`SUPPORT_KEYS` are read (N/µm, mm, ``rigid``).

    Returns
    -------
    Supports
        Bearing stiffnesses (N/m, inf: rigid), shaft diameter, bearing span and gear offset (m),
        torque sides; ``defaulted`` when the pair file gives no stiffness.
    """
    given = {k: spec[k] for k in SUPPORT_KEYS if spec.get(k) is not None}
    stiff = [k for k in SUPPORT_KEYS[:2] if k in given]
    if len(stiff) == 1:
        other = SUPPORT_KEYS[1] if stiff[0] == SUPPORT_KEYS[0] else SUPPORT_KEYS[0]
        raise GearmeshInputError(other, None, f"is required with {stiff[0]} (both directions of the supports)")
    shaft = [k for k in SUPPORT_KEYS[2:4] if k in given]
    if len(shaft) == 1:
        other = SUPPORT_KEYS[3] if shaft[0] == SUPPORT_KEYS[2] else SUPPORT_KEYS[2]
        raise GearmeshInputError(other, None, f"is required with {shaft[0]} (the shaft's bending needs both)")
    if shaft and not stiff:
        raise GearmeshInputError(SUPPORT_KEYS[0], None, f"is required with {shaft[0]} (the bearings the shaft "
                                 "sits in)")
    placed = [k for k in SUPPORT_KEYS[4:] if k in given]
    if placed and not shaft:
        raise GearmeshInputError(placed[0], given[placed[0]], "needs shaft_diameter_mm and bearing_span_mm (the shaft "
                                 "it places the gear on)")
    if not stiff:
        d = DEFAULT_SUPPORTS_N_PER_UM
        return Supports(_stiffness(SUPPORT_KEYS[0], d[SUPPORT_KEYS[0]]),
                        _stiffness(SUPPORT_KEYS[1], d[SUPPORT_KEYS[1]]), defaulted=True)
    span = per_gear_length(SUPPORT_KEYS[3], given[SUPPORT_KEYS[3]]) if shaft else None
    offset = _offsets(given.get(SUPPORT_KEYS[4]), span) if shaft else (0.0, 0.0)
    return Supports(_stiffness(SUPPORT_KEYS[0], given[SUPPORT_KEYS[0]]),
                    _stiffness(SUPPORT_KEYS[1], given[SUPPORT_KEYS[1]]),
                    per_gear_length(SUPPORT_KEYS[2], given[SUPPORT_KEYS[2]]) if shaft else None,
                    span, gear_offset=offset, torque_side=_torque_sides(given.get(SUPPORT_KEYS[5])))


def _offsets(value: Any, span: tuple[float, float]) -> tuple[float, float]:
    """``gear_offset_mm`` (one or [pinion, gear], signed towards the leading face end) → (m, m), each
    gear centre strictly between its bearings (an overhung gear is outside this beam model)."""
    key = SUPPORT_KEYS[4]
    if value is None:
        return 0.0, 0.0
    items = list(value) if isinstance(value, (list, tuple)) else [value, value]
    if len(items) != 2:
        raise GearmeshInputError(key, value, "must be one value or a [pinion, gear] pair (mm)")
    out = []
    for i, v in enumerate(items):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise GearmeshInputError(f"{key}[{i}]", v, "must be a finite length (mm, signed)")
        if abs(v) * 1e-3 >= 0.5 * span[i]:
            raise GearmeshInputError(f"{key}[{i}]", v, f"must place the gear between its bearings: |offset| < half "
                                     f"the bearing span, {0.5e3 * span[i]:.6g} mm")
        out.append(float(v) * 1e-3)
    return out[0], out[1]


def _torque_sides(value: Any) -> tuple[str, str] | None:
    """``torque_side`` [pinion, gear] of :data:`TORQUE_SIDES` (None: not stated)."""
    key = SUPPORT_KEYS[5]
    if value is None:
        return None
    if not isinstance(value, (list, tuple)) or len(value) != 2 or any(v not in TORQUE_SIDES for v in value):
        raise GearmeshInputError(key, value, f"must be a [pinion, gear] pair of {list(TORQUE_SIDES)}: the face end on "
                                 "whose side each shaft carries the torque")
    return str(value[0]), str(value[1])
