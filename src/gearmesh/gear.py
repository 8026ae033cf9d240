"""Gear pair data, the pair-file format, validation and basic cylindrical-gear geometry.

Everything inside is SI (m, rad, kg, Pa). The pair file (``config/pairs/*.yaml``) uses
engineering units with the unit in the key name; :func:`load_pair` converts once, here.

Geometry follows ISO 21771:2007 (cylindrical involute gears and gear pairs, concepts and
geometry) and DIN 3960; the equation of each quantity is given where it is computed.
Index 0 is the pinion (the driver), index 1 the gear.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import yaml

from .choices import FZG_LOAD_STAGES, IDLER_GEARS, LIFE_FACTOR_CONDITIONS
from .errors import GearmeshInputError, unknown_key_rule
from .limits import (DENSITY, MAX_FACE_WIDTH_TO_DIAMETER, MAX_INPUT_BYTES, MAX_INPUT_DEPTH,  # noqa: F401
                     MAX_INPUT_NODES, MAX_MODIFICATION_TO_MODULE, MAX_TEETH, MIN_FACE_WIDTH_TO_MODULE, MODULE_RANGE,
                     RATING_INPUT_RANGES, YOUNGS_MODULUS)
from .rack import form_roll, involute, rack_from  # the rack and the form point live below gear
from .body import BODY_KEYS, Body, check_body, read_body
from .deviation import DEVIATION_KEYS, Deviations, read_deviations
from .supports import SUPPORT_KEYS, Supports, check_supports, read_supports

GEARS = ("pinion", "gear")


def inverse_involute(value: float) -> float:
    """The pressure angle α in [0, π/2) (rad) with inv(α) = ``value`` (value ≥ 0)."""
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
    defaults: tuple[str, ...] = ()  # pair-file keys not given, filled by defaults (e.g. DEFAULT_MATERIAL)
    supports: Supports = field(default_factory=lambda: read_supports({}))  # bearings and shafts (dynamics)
    body: Body = field(default_factory=Body)  # gear-body webs and hubs (gearmesh.body)
    deviations: Deviations = field(default_factory=Deviations)  # manufacturing deviations (gearmesh.deviation)
    rating_inputs: tuple[tuple[str, Any], ...] = ()  # load-capacity inputs given ((name, value), ...), RATING_KEYS

    def with_changes(self, **changes: Any) -> "GearPair":
        """A copy with some fields replaced (e.g. a helix-angle sweep)."""
        return replace(self, **changes)


# --------------------------------------------------------------------------------------
# The pair file: engineering units -> SI, with schema-level checks
# --------------------------------------------------------------------------------------

_PAIR_KEYS = {
    "name", "teeth", "normal_module_mm", "normal_pressure_angle_deg", "helix_angle_deg",
    "face_width_mm", "profile_shift", "center_distance_mm", "addendum_coefficient",
    "dedendum_coefficient", "tool_tip_radius_coefficient", "bore_radius_mm", "material",
    "modification", "helix_hand", "source",
    "tip_diameter_mm", "root_diameter_mm", "bore_diameter_mm", "basic_rack_profile",  # datasheet alternatives
    *SUPPORT_KEYS,  # the gearbox: bearings and shafts (gearmesh.supports)
    *BODY_KEYS,  # the gear bodies' webs and hubs (gearmesh.body)
    *DEVIATION_KEYS,  # the manufactured gear's deviations (gearmesh.deviation)
    "accuracy_grade", "roughness_um", "lubricant", "tip_edge_radius_mm",  # load capacity (gearmesh.rating)
    "life_factor_conditions", "idler_gear",
}
#: Keys that say the same thing: at most one of each group may be given (_one_of).
_ALTERNATIVE_KEYS = (
    ("addendum_coefficient", "tip_diameter_mm"),
    ("dedendum_coefficient", "root_diameter_mm", "basic_rack_profile"),
    ("tool_tip_radius_coefficient", "basic_rack_profile"),
    ("bore_radius_mm", "bore_diameter_mm"),
)
#: What a valid pair file may leave out that some computations need, and which commands need it:
#: {key: (what needs it, the commands that do)}. ``gearmesh validate`` names them for a pair that
#: lacks the key; a command that needs it refuses with :func:`missing_key` (the key to add).
#: Without a bore: the geometry and the ISO 6336 rating by the standard's factors run.
OPTIONAL_NEEDS = {
    "bore_radius_mm": ("the fillet foundation of the tooth stiffness (Sainsot, Velex & Duverger 2004, J. Mech. "
                       "Design 126) and the gear bodies' masses",
                       ("stiffness", "ltca", "impact", "rating", "dynamics", "optimise")),
}
#: The pair-file keys that give a value of :data:`OPTIONAL_NEEDS` in other words (datasheet dimensions).
_GIVEN_AS = {"bore_radius_mm": "bore_diameter_mm, a datasheet's inner diameter"}


def missing_key(key: str, what: str | None = None) -> GearmeshInputError:
    """The refusal of a computation that needs pair-file key ``key`` (:data:`OPTIONAL_NEEDS`), saying
    what needs it and which key to add."""
    need = what or OPTIONAL_NEEDS[key][0]
    other = f" (or {_GIVEN_AS[key]})" if key in _GIVEN_AS else ""
    return GearmeshInputError(key, None, f"is required for {need}: add {key}{other} to the pair file")


def missing_needs(pair: "GearPair") -> dict[str, str]:
    """{key: what a command needs it for and which commands} for each key of :data:`OPTIONAL_NEEDS`
    that ``pair`` leaves out (what ``gearmesh validate`` reports beside "valid")."""
    given = {"bore_radius_mm": pair.bore_radius is not None}
    return {key: f"add {key}{f' (or {_GIVEN_AS[key]})' if key in _GIVEN_AS else ''} for {what}: needed by "
                 f"{', '.join(commands)}" for key, (what, commands) in OPTIONAL_NEEDS.items() if not given[key]}


#: ISO 53:1998 basic rack profiles (α_P = 20°, h_aP = 1.0 m): the dedendum h_fP and root fillet
#: radius ρ_fP of the rack, in modules — the addendum and tip radius of the hob that generates
#: the gear (``dedendum_coefficient``, ``tool_tip_radius_coefficient``). A for high torque, B and
#: C for normal service (smaller fillets), D for gears finished by grinding or shaving.
ISO53_PROFILES = {"ISO 53 A": (1.25, 0.38), "ISO 53 B": (1.25, 0.30), "ISO 53 C": (1.25, 0.25),
                  "ISO 53 D": (1.40, 0.39)}
_REQUIRED_KEYS = ("teeth", "normal_module_mm", "normal_pressure_angle_deg", "helix_angle_deg", "face_width_mm")
_MATERIAL_KEYS = {"youngs_modulus_GPa", "poisson_ratio", "density_kg_m3", "contact_fatigue_limit_MPa",
                  "bending_fatigue_limit_MPa"}
#: Pair-file keys of the load-capacity rating (path in the file → input name of gearmesh.rating, which
#: fills and names the defaults of those not given). Checked here, on reading, by :func:`check_rating_input`.
RATING_KEYS = {
    ("material", "contact_fatigue_limit_MPa"): "contact_fatigue_limit_MPa",
    ("material", "bending_fatigue_limit_MPa"): "bending_fatigue_limit_MPa",
    ("accuracy_grade",): "accuracy_grade",
    ("roughness_um", "flank_Ra"): "flank_Ra_um", ("roughness_um", "flank_Rz"): "flank_Rz_um",
    ("roughness_um", "root_Rz"): "root_Rz_um",
    ("lubricant", "viscosity_40C_mm2_s"): "viscosity_40C_mm2_s",
    ("lubricant", "viscosity_100C_mm2_s"): "viscosity_100C_mm2_s",
    ("lubricant", "oil_temperature_C"): "oil_temperature_C",
    ("lubricant", "fzg_load_stage"): "fzg_load_stage",
    ("tip_edge_radius_mm",): "tip_edge_radius_mm",
    ("life_factor_conditions",): "life_factor_conditions",
    ("idler_gear",): "idler_gear",
}
#: Steel, for a pair file without ``material`` or without one of its keys (given keys override):
#: E = 206 GPa and ν = 0.3 are the steel of the gear standards, ISO 6336-1:2019 (the single
#: stiffness c' refers to E_st = 206 000 N/mm²) and ISO 6336-2:2019 (Z_E = √(E/(2π(1 − ν²))) =
#: 189.8 √(N/mm²) for steel on steel); ρ = 7850 kg/m³ is EN 1993-1-1:2005 §3.2.6 (which gives
#: E = 210 GPa for structural steel: the gear standards' 206 GPa is taken because the stiffness
#: and load limits here refer to it). Which keys were filled is stated (:func:`pair_notes`).
DEFAULT_MATERIAL = {"youngs_modulus_GPa": 206.0, "poisson_ratio": 0.3, "density_kg_m3": 7850.0}
_MODIFICATION_KEYS = {  # file key -> (field, factor to SI)
    "root_relief_um": ("root_relief", 1e-6),
    "tip_relief_um": ("tip_relief", 1e-6),
    "root_relief_length_mm": ("root_relief_length", 1e-3),
    "tip_relief_length_mm": ("tip_relief_length", 1e-3),
    "crowning_um": ("crowning", 1e-6),
    "unmodified_lead_length_mm": ("unmodified_lead_length", 1e-3),
}
#: Each modification parameter's engineering unit, as its pair-file key names it ("um" or "mm").
MODIFICATION_UNITS = {attr: key.rsplit("_", 1)[1] for key, (attr, _) in _MODIFICATION_KEYS.items()}


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


def _positive(field_name: str, value: Any) -> float:
    v = _number(field_name, value)
    if v <= 0:
        raise GearmeshInputError(field_name, value, "must be positive")
    return v


def _per_gear(field_name: str, value: Any, check) -> tuple[float, float]:
    """One number for both gears, or a [pinion, gear] list of two."""
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise GearmeshInputError(field_name, value, "must be one number or a [pinion, gear] pair")
        return (check(f"{field_name}[0]", value[0]), check(f"{field_name}[1]", value[1]))
    v = check(field_name, value)
    return (v, v)


def _mapping(field_name: str, value: Any, allowed: set[str]) -> Mapping[str, Any]:
    if not isinstance(value, Mapping):
        raise GearmeshInputError(field_name, value, "must be a mapping")
    unknown = sorted(set(value) - allowed)
    if unknown:
        raise GearmeshInputError(f"{field_name}.{unknown[0]}", value[unknown[0]],
                                 unknown_key_rule(unknown[0], allowed, "gearmesh schema pair --format markdown"))
    return value


def _teeth(value: Any) -> tuple[int, int]:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise GearmeshInputError("teeth", value, "must be a [pinion, gear] list of two integers")
    out = []
    for i, z in enumerate(value):
        if isinstance(z, bool) or not isinstance(z, int):
            raise GearmeshInputError(f"teeth[{i}]", z, "must be an integer")
        check_teeth(f"teeth[{i}]", z)
        out.append(z)
    return (out[0], out[1])




def check_teeth(field_name: str, z: int) -> None:
    """Refuse a tooth count outside [5, :data:`MAX_TEETH`] (compared as integers: no overflow)."""
    if z < 5:
        raise GearmeshInputError(field_name, z, "must be at least 5 (external gears)")
    if z > MAX_TEETH:
        raise GearmeshInputError(field_name, z, f"must be at most {MAX_TEETH} (ISO 1328-1 scope)")


def _pair_name(given: Any, default_name: str | None) -> str:
    """The pair's name: as given, else ``default_name`` (the file stem); either must be a
    :data:`NAME_PATTERN` name."""
    rule = "1 to 160 letters, digits, '_', '-' or '.' (not first): a file name, no path characters"
    if given is None:
        if default_name is None:
            raise GearmeshInputError("name", None, "is required")
        if not NAME_PATTERN.fullmatch(default_name):
            raise GearmeshInputError("name", None, f"is required: the file name {default_name!r} cannot be one ({rule})")
        return default_name
    if not isinstance(given, str) or not NAME_PATTERN.fullmatch(given):
        raise GearmeshInputError("name", given, f"must be {rule}")
    return given


def _modification(field_name: str, value: Any) -> Modification:
    if value is None:
        return Modification()
    spec = _mapping(field_name, value, set(_MODIFICATION_KEYS))
    kwargs = {}
    for key, (attr, factor) in _MODIFICATION_KEYS.items():
        if key in spec:
            v = _number(f"{field_name}.{key}", spec[key])
            if v < 0:
                raise GearmeshInputError(f"{field_name}.{key}", spec[key], "must not be negative")
            kwargs[attr] = v * factor
    return Modification(**kwargs)


def pair_from_dict(data: Mapping[str, Any], source: str = "", default_name: str | None = None) -> GearPair:
    """Build a :class:`GearPair` (SI) from a pair-file mapping in engineering units.

    Checks the form of the data (keys, types, signs, ranges); the physics of the pair
    (contact ratio, interference, centre distance) is checked by :func:`pair_geometry`.
    ``name`` may be left out when ``default_name`` is given (a file's stem, :func:`load_pair`).
    """
    spec = _mapping("pair", data, _PAIR_KEYS)
    for key in _REQUIRED_KEYS:
        if key not in spec:
            raise GearmeshInputError(key, None, "is required")
    name = _pair_name(spec.get("name"), default_name)
    for group in _ALTERNATIVE_KEYS:
        _one_of(spec, group)
    alpha_n = _number("normal_pressure_angle_deg", spec["normal_pressure_angle_deg"])
    if not 0 < alpha_n < 45:
        raise GearmeshInputError("normal_pressure_angle_deg", alpha_n, "must lie in (0, 45) degrees")
    beta = _number("helix_angle_deg", spec["helix_angle_deg"])
    if not 0 <= beta < 60:
        raise GearmeshInputError("helix_angle_deg", beta,
                                 "must lie in [0, 60) degrees; give the hand with helix_hand")
    hand = spec.get("helix_hand", "right")
    if hand not in ("right", "left"):
        raise GearmeshInputError("helix_hand", hand, "must be 'right' or 'left' (of the pinion)")

    shift = None
    if spec.get("profile_shift") is not None:
        shift = _per_gear("profile_shift", spec["profile_shift"], _number)
        for i, x in enumerate(shift):
            if not -3 < x < 3:
                raise GearmeshInputError(f"profile_shift[{i}]", x, "must lie in (-3, 3)")
    center = None
    if spec.get("center_distance_mm") is not None:
        center = _positive("center_distance_mm", spec["center_distance_mm"]) * 1e-3

    def nonneg(f, v):
        x = _number(f, v)
        if x < 0:
            raise GearmeshInputError(f, v, "must not be negative")
        return x

    bore = None
    if spec.get("bore_radius_mm") is not None:
        bore = tuple(b * 1e-3 for b in _per_gear("bore_radius_mm", spec["bore_radius_mm"], nonneg))
    elif spec.get("bore_diameter_mm") is not None:  # a datasheet's inner (bore) diameter: r = d/2
        bore = tuple(d / 2 * 1e-3 for d in _per_gear("bore_diameter_mm", spec["bore_diameter_mm"], nonneg))
    rack = _basic_rack(spec.get("basic_rack_profile"), alpha_n)

    given_material = {} if spec.get("material") is None else _mapping("material", spec["material"], _MATERIAL_KEYS)
    m = {**DEFAULT_MATERIAL, **{k: v for k, v in given_material.items() if k in DEFAULT_MATERIAL}}
    defaults = tuple(f"material.{key}" for key in DEFAULT_MATERIAL if key not in given_material)
    rating = _rating_inputs(spec, given_material)
    material = Material(  # its own checks: the rules of the file's keys
        youngs_modulus=_number("material.youngs_modulus_GPa", m["youngs_modulus_GPa"]) * 1e9,
        poisson_ratio=_number("material.poisson_ratio", m["poisson_ratio"]),
        density=_number("material.density_kg_m3", m["density_kg_m3"]),
    )

    mods = (Modification(), Modification())
    if spec.get("modification") is not None:
        mm = _mapping("modification", spec["modification"], set(GEARS))
        mods = (_modification("modification.pinion", mm.get("pinion")),
                _modification("modification.gear", mm.get("gear")))

    pair = GearPair(
        name=name,
        teeth=_teeth(spec["teeth"]),
        normal_module=_positive("normal_module_mm", spec["normal_module_mm"]) * 1e-3,
        normal_pressure_angle=math.radians(alpha_n),
        helix_angle=math.radians(beta),
        face_width=tuple(b * 1e-3 for b in _per_gear("face_width_mm", spec["face_width_mm"], _positive)),
        profile_shift=shift,
        center_distance=center,
        addendum_coefficient=_per_gear("addendum_coefficient", spec.get("addendum_coefficient", 1.0), _positive),
        dedendum_coefficient=(_per_gear("dedendum_coefficient", spec.get("dedendum_coefficient", 1.25), _positive)
                              if rack is None else (rack[0], rack[0])),
        tool_tip_radius_coefficient=(
            _per_gear("tool_tip_radius_coefficient", spec["tool_tip_radius_coefficient"], nonneg)
            if spec.get("tool_tip_radius_coefficient") is not None
            else (rack[1], rack[1]) if rack is not None else (None, None)),
        bore_radius=bore,
        material=material,
        modification=mods,
        helix_hand=hand,
        source=str(spec.get("source", source)),
        defaults=defaults,
        supports=read_supports(spec),
        body=read_body(spec),
        deviations=read_deviations(spec),
        rating_inputs=rating,
    )
    return _datasheet_diameters(pair, spec)


def check_rating_input(name: str, value: Any, field_name: str | None = None) -> float | int | str:
    """One load-capacity input (a name of :data:`RATING_KEYS`' values) checked: the accuracy grade
    an integer 1..12 (ISO 1328-1), the FZG load stage an integer 1..12 (ISO 14635-1), the oil
    temperature in (−40, 200) °C, the life-factor conditions and the idler gear one of their words
    (:mod:`gearmesh.choices`), every other a positive number within its plausible range
    (:data:`gearmesh.limits.RATING_INPUT_RANGES`: fatigue limits of ISO 6336-5's materials,
    roughness, viscosities); GearmeshInputError naming ``field_name`` (default ``name``)."""
    key = field_name or name
    words = {"life_factor_conditions": LIFE_FACTOR_CONDITIONS, "idler_gear": IDLER_GEARS}
    if name in words:
        if not isinstance(value, str) or value not in words[name]:
            raise GearmeshInputError(key, value, f"must be one of {list(words[name])}")
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise GearmeshInputError(key, value, "must be a finite number")
    if name == "accuracy_grade":
        if not float(value).is_integer() or not 1 <= value <= 12:
            raise GearmeshInputError(key, value, "must be an ISO 1328-1 accuracy grade, an integer in 1..12")
        return int(value)
    if name == "fzg_load_stage":
        if not float(value).is_integer() or int(value) not in FZG_LOAD_STAGES:
            raise GearmeshInputError(key, value, f"must be an FZG load stage (ISO 14635-1), an integer in "
                                                 f"{FZG_LOAD_STAGES[0]}..{FZG_LOAD_STAGES[-1]}")
        return int(value)
    if name == "oil_temperature_C":
        if not -40 < value < 200:
            raise GearmeshInputError(key, value, "must lie in (-40, 200) °C")
        return float(value)
    if value <= 0:
        raise GearmeshInputError(key, value, "must be positive")
    if name in RATING_INPUT_RANGES:  # within what materials, surfaces and oils have
        RATING_INPUT_RANGES[name].check(value, key)
    return float(value)


def _rating_inputs(spec: Mapping[str, Any], material: Mapping[str, Any]) -> tuple[tuple[str, Any], ...]:
    """The load-capacity inputs given in a pair file, checked (:data:`RATING_KEYS`)."""
    sections = {"roughness_um": {"flank_Ra", "flank_Rz", "root_Rz"},
                "lubricant": {"viscosity_40C_mm2_s", "viscosity_100C_mm2_s", "oil_temperature_C", "fzg_load_stage"}}
    given = {"material": material}
    for sec, keys in sections.items():
        if spec.get(sec) is not None:
            given[sec] = _mapping(sec, spec[sec], keys)
    out = []
    for path, name in RATING_KEYS.items():
        value = spec.get(path[0]) if len(path) == 1 else given.get(path[0], {}).get(path[1])
        if value is not None:
            out.append((name, check_rating_input(name, value, ".".join(path))))
    values = dict(out)
    if values.get("viscosity_100C_mm2_s", 0) >= values.get("viscosity_40C_mm2_s", math.inf):
        raise GearmeshInputError("lubricant.viscosity_100C_mm2_s", values["viscosity_100C_mm2_s"],
                                 "must be below lubricant.viscosity_40C_mm2_s")
    return tuple(out)


def _one_of(spec: Mapping[str, Any], keys: tuple[str, ...]) -> None:
    """Refuse two keys of one group of :data:`_ALTERNATIVE_KEYS` given together."""
    given = [k for k in keys if spec.get(k) is not None]
    if len(given) > 1:
        raise GearmeshInputError(given[1], spec[given[1]], f"conflicts with {given[0]} = {spec[given[0]]!r}: "
                                 "both set the same dimension, give one of them")


def _basic_rack(value: Any, alpha_n_deg: float) -> tuple[float, float] | None:
    """(dedendum, tool tip radius) coefficients of an :data:`ISO53_PROFILES` name, or None."""
    if value is None:
        return None
    if value not in ISO53_PROFILES:
        raise GearmeshInputError("basic_rack_profile", value, f"must be one of {list(ISO53_PROFILES)}")
    if not math.isclose(alpha_n_deg, 20.0, abs_tol=1e-9):
        raise GearmeshInputError("basic_rack_profile", value, f"is a 20° profile (ISO 53:1998), the pair has "
                                 f"normal_pressure_angle_deg = {alpha_n_deg:g}: give dedendum_coefficient and "
                                 "tool_tip_radius_coefficient instead")
    return ISO53_PROFILES[value]


def _datasheet_diameters(pair: GearPair, spec: Mapping[str, Any]) -> GearPair:
    """``pair`` with the coefficients that the datasheet diameters ``tip_diameter_mm`` and
    ``root_diameter_mm`` (one number or [pinion, gear]) give, exactly (ISO 21771 eqs. 45, 47):

        h_a* = (d_a − d)/(2 m_n) − x,    h_f* = (d − d_f)/(2 m_n) + x,

    d = z m_n/cos β the reference diameter and x the profile shift as :func:`pair_geometry`
    resolves it (given, inferred from the centre distance, or zero). A tip diameter thus
    includes any tip shortening; a root diameter is that of the generating hob's addendum
    h_f*·m_n (a tooth-thickness allowance cut by a deeper infeed is not modelled).
    """
    if spec.get("tip_diameter_mm") is None and spec.get("root_diameter_mm") is None:
        return pair
    mn = pair.normal_module
    d = np.array(pair.teeth) * mn / math.cos(pair.helix_angle)
    shift = _resolve_shift_and_center(pair, *_transverse_angle_and_radius_sum(pair))[0]
    changes = {}
    if spec.get("tip_diameter_mm") is not None:
        tip = np.array(_per_gear("tip_diameter_mm", spec["tip_diameter_mm"], _positive)) * 1e-3
        changes["addendum_coefficient"] = _coefficient("tip_diameter_mm", tip, (tip - d) / (2 * mn) - shift,
                                                       "addendum coefficient", "tip at or below")
    if spec.get("root_diameter_mm") is not None:
        root = np.array(_per_gear("root_diameter_mm", spec["root_diameter_mm"], _positive)) * 1e-3
        changes["dedendum_coefficient"] = _coefficient("root_diameter_mm", root, (d - root) / (2 * mn) + shift,
                                                       "dedendum coefficient", "root at or above")
    return pair.with_changes(**changes)


def _transverse_angle_and_radius_sum(pair: GearPair) -> tuple[float, float]:
    """αt = atan(tan αn/cos β) (rad) and r1 + r2 = (z1 + z2) m_n/(2 cos β) (m), ISO 21771 eqs. 9, 11:
    what :func:`_resolve_shift_and_center` needs, for a pair not yet through :func:`pair_geometry`."""
    beta = pair.helix_angle
    return (math.atan(math.tan(pair.normal_pressure_angle) / math.cos(beta)),
            sum(pair.teeth) * pair.normal_module / (2 * math.cos(beta)))


def _coefficient(key: str, diameters: np.ndarray, values: np.ndarray, what: str, where: str) -> tuple[float, float]:
    """The per-gear ``values`` converted from ``diameters`` (m) of pair-file ``key``, each > 0."""
    for i, v in enumerate(values):
        if not v > 0:
            raise GearmeshInputError(f"{key}[{i}]", float(diameters[i]) * 1e3,
                                     f"puts the {GEARS[i]} {where} its reference circle shifted by the profile "
                                     f"shift ({what} {v:.4f} <= 0)")
    return (float(values[0]), float(values[1]))


#: Name of a pair: usable as a file name (letters, digits, '_', '-' and '.', not first; no
#: path characters), short enough to stay far below the 255-byte limit of one path component
#: (Linux NAME_MAX) with any suffix. Study configs restrict the names they use further (schema).
NAME_PATTERN = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9_.-]{0,159}")


def validate_pair(pair: GearPair) -> None:
    """Range checks on a :class:`GearPair` in SI, also for pairs built in code (sweeps,
    designs); field names are the pair-file keys. The ranges are :data:`MODULE_RANGE`,
    :data:`MIN_FACE_WIDTH_TO_MODULE` and :data:`MAX_FACE_WIDTH_TO_DIAMETER`."""
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




class _InputRefused(yaml.YAMLError):
    """Raised by the loader for a document that cannot be a gearmesh input (reason as text)."""


class _UniqueKeyLoader(yaml.SafeLoader):
    """A safe YAML loader for small input documents: refuses a mapping with the same key twice
    (PyYAML keeps the last), aliases (``*name``: a "billion laughs" document expands
    exponentially when walked), more than :data:`MAX_INPUT_NODES` nodes and nesting deeper
    than :data:`MAX_INPUT_DEPTH`."""

    _nodes = 0
    _depth = 0

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            mark = self.peek_event().start_mark
            raise _InputRefused(f"uses a YAML alias (line {mark.line + 1}); write the value out")
        self._nodes += 1
        if self._nodes > MAX_INPUT_NODES:
            raise _InputRefused(f"has more than {MAX_INPUT_NODES} YAML nodes")
        self._depth += 1
        try:
            if self._depth > MAX_INPUT_DEPTH:
                raise _InputRefused(f"nests deeper than {MAX_INPUT_DEPTH} levels")
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1


def _unique_mapping(loader: _UniqueKeyLoader, node: yaml.MappingNode, deep: bool = False):
    keys = [loader.construct_object(k, deep=deep) for k, _ in node.value]
    seen, duplicates = set(), set()
    for key in keys:
        try:
            (duplicates if key in seen else seen).add(key)
        except TypeError:  # an unhashable key: construct_mapping refuses it below
            pass
    if duplicates:
        raise GearmeshInputError(min(map(str, duplicates)), None,
                                 f"is given twice in one mapping (line {node.start_mark.line + 1})")
    return loader.construct_mapping(node, deep=deep)


_UniqueKeyLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _unique_mapping)


def read_input_text(path: str | Path, what: str) -> str:
    """The text of a small input file, read bounded: refuses anything but a regular file (a
    directory, FIFO or device such as /dev/zero, checked before opening), more than
    :data:`MAX_INPUT_BYTES` and non-UTF-8 bytes, each as one :class:`GearmeshInputError`."""
    import stat

    path = Path(path)
    try:
        mode = path.stat().st_mode
        if not stat.S_ISREG(mode):
            raise GearmeshInputError(what, str(path), "is not a regular file")
        with path.open("rb") as f:
            data = f.read(MAX_INPUT_BYTES + 1)
    except OSError as exc:
        raise GearmeshInputError(what, str(path), f"cannot be read ({exc.strerror})") from None
    if len(data) > MAX_INPUT_BYTES:
        raise GearmeshInputError(what, str(path), f"is larger than {MAX_INPUT_BYTES // 1024} kB: not a gearmesh input")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise GearmeshInputError(what, str(path), "is not UTF-8 text") from None


def read_yaml(path: str | Path, what: str) -> Any:
    """Parse a small YAML input file (:func:`read_input_text`); a malformed file, a key given
    twice, an alias or an oversized document is a one-line :class:`GearmeshInputError`."""
    text = read_input_text(path, what)
    try:
        return yaml.load(text, Loader=_UniqueKeyLoader)
    except _InputRefused as exc:
        raise GearmeshInputError(what, str(path), str(exc)) from None
    except yaml.YAMLError as exc:
        raise GearmeshInputError(what, str(path), "is not valid YAML: " + " ".join(str(exc).split())) from None
    except RecursionError:  # pragma: no cover - MAX_INPUT_DEPTH refuses first
        raise GearmeshInputError(what, str(path), "nests too deep") from None


def load_pair(path_or_data: str | Path | Mapping[str, Any]) -> GearPair:
    """Read a pair file (YAML, engineering units) or mapping into a :class:`GearPair`; a file
    without ``name`` is named after its stem (``my_pair.yaml``: ``my_pair``), a different
    ``name`` is kept as given."""
    if isinstance(path_or_data, Mapping):
        return pair_from_dict(path_or_data)
    data = read_yaml(path_or_data, "pair file")
    if not isinstance(data, Mapping):
        what = "is empty" if data is None else f"holds a {type(data).__name__}, not a mapping of keys"
        raise GearmeshInputError("pair file", str(path_or_data), f"{what}: a pair file maps keys such as teeth and "
                                 "normal_module_mm to values; `gearmesh example low_fluctuation_pair1` prints one to start from")
    try:
        return pair_from_dict(data, source=str(path_or_data), default_name=Path(path_or_data).stem)
    except GearmeshInputError as exc:  # the field and rule as they were, and the file they are in
        raise GearmeshInputError(exc.field, exc.value, f"{exc.rule} (in pair file {path_or_data})") from None


def pair_notes(pair: GearPair) -> list[str]:
    """What the results of ``pair`` rest on that its file did not say: a centre distance taken
    as the zero-backlash one (:func:`shift_rounding_center_distance`) and the material values
    filled by :data:`DEFAULT_MATERIAL`. One sentence each, for the output (JSON, dataset attrs)."""
    notes = []
    if pair.center_distance is not None and pair.profile_shift is not None:
        a0 = _resolve_shift_and_center(pair, *_transverse_angle_and_radius_sum(pair))[3]
        if pair.center_distance < a0:
            notes.append(f"center_distance_mm = {pair.center_distance * 1e3:.6g} lies {(a0 - pair.center_distance) * 1e6:.2g}"
                         f" µm below the zero-backlash distance {a0 * 1e3:.6f} mm of the shifts as printed, within "
                         "their rounding to four decimals: zero backlash, computed at that distance")
    filled = _defaulted_material(pair)
    if filled:
        values = ", ".join(f"{key} = {DEFAULT_MATERIAL[key]:g}" for key in filled)
        notes.append(f"material not given: steel {values} (ISO 6336-1/-2 steel, EN 1993-1-1 density)")
    return notes


def material_values(material: Material) -> dict[str, float]:
    """``material`` as the pair file's ``material`` mapping (GPa, -, kg/m³)."""
    return {"youngs_modulus_GPa": material.youngs_modulus * 1e-9, "poisson_ratio": material.poisson_ratio,
            "density_kg_m3": material.density}


def _defaulted_material(pair: GearPair) -> list[str]:
    """The material keys of ``pair`` filled by :data:`DEFAULT_MATERIAL` and still at that value
    (a material set in code since replaces them)."""
    if pair.material is None:
        return []
    values = material_values(pair.material)
    return [key for key, default in DEFAULT_MATERIAL.items()
            if f"material.{key}" in pair.defaults and math.isclose(values[key], default, rel_tol=1e-12)]


#: The example pairs shipped with the package, one file each: every pair of the source documents
#: (docs/references.md), also the workflow's pair library (the repository's config/pairs links here).
EXAMPLES_DIR = Path(__file__).parent / "pairs"


def example_pairs() -> dict[str, Path]:
    """{name: file} of the example pairs shipped with the package (:data:`EXAMPLES_DIR`)."""
    return {f.stem: f for f in sorted(EXAMPLES_DIR.glob("*.yaml"))}


def example_pair(name: str) -> Path:
    """The file of the shipped example pair ``name`` (e.g. ``helical_z29_71_m5``), for :func:`load_pair`."""
    pairs = example_pairs()
    if name not in pairs:
        raise GearmeshInputError("example", name, f"must be one of {sorted(pairs)}")
    return pairs[name]


def check_pair_name(pair: GearPair, path: str | Path) -> GearPair:
    """Refuse a pair whose ``name`` differs from the name of its file ``path``: the rule of
    a study's pair library (``pairs_dir/NAME.yaml``), whose results are filed under the name.
    The command line has no such rule (:func:`load_pair`)."""
    if pair.name != Path(path).stem:
        raise GearmeshInputError("name", pair.name, f"must equal the file name {Path(path).stem!r} of {path}")
    return pair


def load_named_pair(path: str | Path) -> GearPair:
    """Read a pair file whose ``name`` equals its file name (:func:`check_pair_name`)."""
    return check_pair_name(load_pair(path), path)


def pair_to_dict(pair: GearPair) -> dict[str, Any]:
    """The inverse of :func:`pair_from_dict`: a pair-file mapping in engineering units."""
    out: dict[str, Any] = {
        "name": pair.name,
        "teeth": list(pair.teeth),
        "normal_module_mm": pair.normal_module * 1e3,
        "normal_pressure_angle_deg": math.degrees(pair.normal_pressure_angle),
        "helix_angle_deg": math.degrees(pair.helix_angle),
        "face_width_mm": [b * 1e3 for b in pair.face_width],
        "addendum_coefficient": list(pair.addendum_coefficient),
        "dedendum_coefficient": list(pair.dedendum_coefficient),
        "helix_hand": pair.helix_hand,
    }
    if any(c is not None for c in pair.tool_tip_radius_coefficient):
        out["tool_tip_radius_coefficient"] = list(pair.tool_tip_radius_coefficient)
    if pair.profile_shift is not None:
        out["profile_shift"] = list(pair.profile_shift)
    if pair.center_distance is not None:
        out["center_distance_mm"] = pair.center_distance * 1e3
    if pair.bore_radius is not None:
        out["bore_radius_mm"] = [r * 1e3 for r in pair.bore_radius]
    if pair.material is not None:  # the keys given; defaulted ones are filled again on reading
        defaulted = _defaulted_material(pair)
        material = {k: v for k, v in material_values(pair.material).items() if k not in defaulted}
        if material:
            out["material"] = material
    for (*path, last), name in RATING_KEYS.items():
        value = dict(pair.rating_inputs).get(name)
        if value is not None:
            (out.setdefault(path[0], {}) if path else out)[last] = value
    if any(not m.is_zero for m in pair.modification):
        out["modification"] = {
            gear: {key: getattr(mod, attr) / factor for key, (attr, factor) in _MODIFICATION_KEYS.items()}
            for gear, mod in zip(GEARS, pair.modification)
        }
    out.update(pair.supports.to_dict())
    out.update(pair.body.to_dict())
    out.update(pair.deviations.to_dict())
    return out


#: The keys of a variant (gearmesh.settings.Variant).
_VARIANT_KEYS = {"modification", "from"}


def variant_pair(pair: GearPair, variant: str, spec: Mapping[str, Any]) -> GearPair:
    """``pair`` carrying the modification of micro-geometry ``variant`` (none for 'standard'
    or a variant without one); the variant's modification replaces the pair file's. A variant
    ``{from: optimise.NAME}`` is ``pair`` as given: the optimisation's pair file, its optimum
    (the workflow hands that file to the variant's stages). A key other than ``modification`` and
    ``from``, or both, is refused naming it (a misspelt key must not give the unmodified pair)."""
    spec = _mapping(f"variants.{variant}", spec, _VARIANT_KEYS)
    if spec.get("from") and spec.get("modification"):
        raise GearmeshInputError(f"variants.{variant}.from", spec["from"], "and modification are exclusive: a variant "
                                 "is the optimum of a run or a modification of its own; keep one")
    if spec.get("from"):
        return pair
    data = pair_to_dict(pair)
    data.pop("modification", None)
    if spec.get("modification"):
        data["modification"] = spec["modification"]
    return pair_from_dict(data, source=pair.source)


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
    if a < a0:  # within the shifts' rounding: zero backlash at a0 (pair_notes says so); beyond: refused
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

    Parameters: ``normal_module`` m_n (m), ``tool_addendum`` h_aP0 (m), ``alpha_n`` (rad).
    """
    land = math.pi * normal_module / 4 - tool_addendum * math.tan(alpha_n)
    return land * math.cos(alpha_n) / (1 - math.sin(alpha_n))


def tool_tip_radius(pair: GearPair, gear: int) -> float:
    """Tip rounding ρ_aP0 (m) of the rack (hob) that generates gear ``gear`` (0 pinion, 1 gear).

    Given: ρ*·m_n, refused when it does not fit (> :func:`max_tool_tip_radius`). Not given:
    the ISO 53 value 0.38 m_n, or the full-radius tip where 0.38 m_n does not fit (e.g. αn =
    25° with h_aP0 = 1.25 m_n, the low-fluctuation paper: ρ_max = 0.318 m_n). A rack tooth pointed before
    its tip line (π/4 ≤ h_f*·tan αn) is refused on ``dedendum_coefficient``.
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
    Works on scalars and arrays; ``on`` is 'pinion' or 'gear'."""
    if on not in GEARS:
        raise GearmeshInputError("on", on, "must be 'pinion' or 'gear' (where the torque acts)")
    return torque if on == "pinion" else torque * (pair.teeth[0] / pair.teeth[1])


def gear_body_mass_inertia(reference_radius, bore_radius, face_width, density):
    """Mass (kg) and polar moment (kg m²) of a solid disc of the reference (pitch) radius
    minus the bore over the face width: m = ρπ(r² − r_i²)b, J = m(r² + r_i²)/2.

    This is the body convention of the low-fluctuation paper (Table 1: pair 1 gives 0.2165/0.6266 kg and
    0.96/7.90 ·10⁻⁴ kg m²).
    """
    r, ri, b = np.asarray(reference_radius), np.asarray(bore_radius), np.asarray(face_width)
    mass = density * np.pi * (r**2 - ri**2) * b
    return mass, 0.5 * mass * (r**2 + ri**2)


def pair_geometry(pair: GearPair) -> PairGeometry:
    """Derived geometry of ``pair``, refusing any pair that cannot work.

    When the profile shifts were inferred from the centre distance, a refusal caused by
    them (shift or tip geometry) names ``center_distance_mm`` (the value the user gave) and
    says which inferred shift failed; other refusals keep their own field.
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

    gear_names = GEARS
    for i in range(2):
        if pair.bore_radius is not None and rf[i] <= pair.bore_radius[i]:
            raise GearmeshInputError(f"bore_radius_mm[{i}]", pair.bore_radius[i] * 1e3,
                                     f"must be below the {gear_names[i]} root radius {rf[i] * 1e3:.3f} mm")
        if rf[i] <= 0:
            raise GearmeshInputError(f"dedendum_coefficient[{i}]", float(hf[i]),
                                     f"puts the {gear_names[i]} root circle at or below its axis")
        if ra[i] <= rb[i]:
            raise GearmeshInputError(f"addendum_coefficient[{i}]", float(ha[i]),
                                     f"puts the {gear_names[i]} tip circle ({ra[i] * 1e3:.3f} mm) inside its base "
                                     f"circle ({rb[i] * 1e3:.3f} mm): no involute flank")

    # Tooth thickness on the reference circle and at the tip (ISO 21771 eqs. 64, 70).
    st = mt * (np.pi / 2 + 2 * shift * math.tan(an))
    sn = st * math.cos(beta)
    alpha_at = np.arccos(rb / ra)
    sat = 2 * ra * (st / (2 * r) + involute(alpha_t) - involute(alpha_at))
    beta_a = np.arctan(np.tan(beta) * ra / r)
    san = sat * np.cos(beta_a)
    for i in range(2):
        if san[i] <= 0:
            raise GearmeshInputError(f"profile_shift[{i}]", float(shift[i]),
                                     f"makes the {gear_names[i]} tooth pointed (normal tip thickness "
                                     f"{san[i] * 1e3:.3f} mm <= 0); reduce the shift or the addendum")

    # Roll lengths along the transverse line of action (ISO 21771 §5.4.1).
    rho_a = np.sqrt(ra**2 - rb**2)
    line_of_action = a * math.sin(alpha_wt)  # T1T2
    rho_sap = line_of_action - rho_a[::-1]
    racks = [rack_from(z[i], mn, an, beta, pair.dedendum_coefficient[i] * mn, tool_tip_radius(pair, i), shift[i])
             for i in range(2)]
    rho_form, undercut = (np.array(v) for v in zip(*(form_roll(rack) for rack in racks)))
    r_form = np.sqrt(rb**2 + rho_form**2)
    for i in range(2):
        other = 1 - i
        if rho_sap[i] < 0:
            raise GearmeshInputError(f"addendum_coefficient[{other}]", float(ha[other]),
                                     f"the {gear_names[other]} tip reaches past the {gear_names[i]} base tangent "
                                     "point of the line of action (involute interference)")
        if rho_sap[i] < rho_form[i] - 1e-12:
            raise GearmeshInputError(f"profile_shift[{i}]", float(shift[i]),
                                     f"the {gear_names[other]} tip (start of active profile at roll length "
                                     f"{rho_sap[i] * 1e3:.3f} mm) reaches below the {gear_names[i]} form circle "
                                     f"(involute starts at {rho_form[i] * 1e3:.3f} mm{', undercut' if undercut[i] else ''}): "
                                     "fillet interference")
    clearance = a - ra[::-1] - rf
    for i in range(2):
        if clearance[i] < 0:
            raise GearmeshInputError(f"addendum_coefficient[{1 - i}]", float(ha[1 - i]),
                                     f"the {gear_names[1 - i]} tip circle cuts the {gear_names[i]} root circle "
                                     f"(tip clearance {clearance[i] * 1e3:.3f} mm < 0)")

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

    # Backlash: thicknesses on the operating pitch circles (ISO 21771 §5.5; j = 0 at a0).
    swt = 2 * rw * (st / (2 * r) + involute(alpha_t) - involute(alpha_wt))
    j_wt = 2 * math.pi * rw[0] / z[0] - swt.sum() if a != a0 else 0.0  # at a0 zero by construction, not ±1e-17
    j_bn = j_wt * math.cos(alpha_wt) * math.cos(beta_b)

    if pair.bore_radius is not None and pair.material is not None:
        mass, inertia = gear_body_mass_inertia(r, np.array(pair.bore_radius), np.array(pair.face_width),
                                               pair.material.density)
    else:
        mass = inertia = np.full(2, np.nan)

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




def check_tip_edge_radius(edge_radius: float, normal_tip_thickness) -> None:
    """Refuse a tip-edge rounding radius (m) above half the thinner normal tip thickness (m, per
    gear): the rounding would take the whole tip (GearmeshInputError on ``tip_edge_radius_mm``).
    The pair's own radius is checked with its geometry (:func:`pair_geometry`, so ``validate``
    refuses what the rating would), one given to a stress function by it too."""
    limit = 0.5 * float(np.min(normal_tip_thickness))
    if edge_radius > limit:
        raise GearmeshInputError("tip_edge_radius_mm", edge_radius * 1e3,
                                 f"must not exceed half the normal tip thickness ({limit * 1e3:.3g} mm)")


def validate_modifications(geom: PairGeometry) -> None:
    """Refuse relief lengths longer than the active flank, lead lengths beyond the face and
    depths beyond :data:`MAX_MODIFICATION_TO_MODULE` normal modules."""
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
