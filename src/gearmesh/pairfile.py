"""The pair file (``config/pairs/*.yaml``, engineering units, the unit in each key's name): its
keys, the reader into a :class:`~gearmesh.gear.GearPair` (SI, converted once, here) with the
checks of the file's form, the writer back, the variants' pairs and the shipped example pairs.

The physics of a pair (contact ratio, interference, centre distance) is checked by
:func:`gearmesh.gear.pair_geometry`; the datasheet diameters are converted with the profile shifts
it resolves (ISO 21771:2007 eqs. 45, 47).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from .body import read_body
from .choices import FZG_LOAD_STAGES, IDLER_GEARS, LIFE_FACTOR_CONDITIONS
from .deviation import read_deviations
from .errors import GearmeshInputError, unknown_key_rule
from .gear import (GEARS, GearPair, Material, Modification, _number, _resolve_shift_and_center,
                   _transverse_angle_and_radius_sum, check_teeth, material_values)
from .inputfile import read_yaml
from .limits import RATING_INPUT_RANGES
from .pair_keys import (DEFAULT_MATERIAL, ISO53_PROFILES, NAME_PATTERN, GearModification, PairFile,
                        PairMaterial)
from .schema import has_default, key_of, section_keys, settings_fields
from .supports import read_supports

# --------------------------------------------------------------------------------------
# The keys of a pair file
# --------------------------------------------------------------------------------------

#: The keys of a pair file, of its material and of a gear's modification, and those a pair file must give:
#: from their declaration (:mod:`gearmesh.pair_keys`), read here, never restated.
_PAIR_KEYS = frozenset(section_keys(PairFile))
_REQUIRED_KEYS = tuple(key_of(f) for f in settings_fields(PairFile) if not has_default(f))
_MATERIAL_KEYS = frozenset(section_keys(PairMaterial))
_ALTERNATIVE_KEYS = PairFile.ALTERNATIVES
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
    what needs it and which key to add.

    Parameters
    ----------
    key : str
        The pair-file key (a key of :data:`OPTIONAL_NEEDS`, or any key when ``what`` is given).
    what : str, optional
        What needs it; default :data:`OPTIONAL_NEEDS`' own words.

    Returns
    -------
    GearmeshInputError
        Naming ``key``, for the caller to raise.
    """
    need = what or OPTIONAL_NEEDS[key][0]
    other = f" (or {_GIVEN_AS[key]})" if key in _GIVEN_AS else ""
    return GearmeshInputError(key, None, f"is required for {need}: add {key}{other} to the pair file")


def missing_needs(pair: "GearPair") -> dict[str, str]:
    """{key: what a command needs it for and which commands} for each key of :data:`OPTIONAL_NEEDS`
    that ``pair`` leaves out (what ``gearmesh validate`` reports beside "valid").

    Parameters
    ----------
    pair : GearPair
        A pair as read.

    Returns
    -------
    dict of str to str
        One sentence per key left out; empty when the pair has them all.
    """
    given = {"bore_radius_mm": pair.bore_radius is not None}
    return {key: f"add {key}{f' (or {_GIVEN_AS[key]})' if key in _GIVEN_AS else ''} for {what}: needed by "
                 f"{', '.join(commands)}" for key, (what, commands) in OPTIONAL_NEEDS.items() if not given[key]}


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
#: A gear's modification keys (:class:`gearmesh.pair_keys.GearModification`) → (the Modification field, the factor
#: of the key's unit to SI): the unit is the key's suffix.
_UNIT_TO_SI = {"um": 1e-6, "mm": 1e-3}
_MODIFICATION_KEYS = {key: (key.rsplit("_", 1)[0], _UNIT_TO_SI[key.rsplit("_", 1)[1]])
                      for key in section_keys(GearModification)}
#: Each modification parameter's engineering unit, as its pair-file key names it ("um" or "mm").
MODIFICATION_UNITS = {attr: key.rsplit("_", 1)[1] for key, (attr, _) in _MODIFICATION_KEYS.items()}


# --------------------------------------------------------------------------------------
# Reading: engineering units -> SI, with schema-level checks
# --------------------------------------------------------------------------------------

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
    (contact ratio, interference, centre distance) is checked by :func:`gearmesh.gear.pair_geometry`.
    ``name`` may be left out when ``default_name`` is given (a file's stem, :func:`load_pair`).

    Parameters
    ----------
    data : mapping
        A pair file's keys, engineering units (mm, deg, GPa, ...) as their names say.
    source : str, default ""
        Where the data come from (the file's path), kept on the pair.
    default_name : str, optional
        The name when ``data`` has none.

    Returns
    -------
    GearPair
        The pair in SI units (m, rad, Pa, kg/m³, N/m).

    Raises
    ------
    GearmeshInputError
        Naming the first bad key (``modification.pinion.tip_relief_um`` …): unknown, required and
        missing, two alternatives given together, wrong type, sign or range.

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and
       geometry, eqs. 45, 47 (tip and root diameters from the datasheet).
    """
    spec = _mapping("pair", data, _PAIR_KEYS)
    for key in _REQUIRED_KEYS:
        if key not in spec:
            raise GearmeshInputError(key, None, "is required")
    name = _pair_name(spec.get("name"), default_name)
    for group in _ALTERNATIVE_KEYS:
        _one_of(spec, group)
    alpha_n, beta, hand = _angles_and_hand(spec)
    shift, center = _shift_and_center(spec)
    bore = _bore_radius(spec)
    rack = _basic_rack(spec.get("basic_rack_profile"), alpha_n)
    material, defaults, rating = _material_and_rating(spec)
    mods = _modifications(spec)
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
            _per_gear("tool_tip_radius_coefficient", spec["tool_tip_radius_coefficient"], _non_negative)
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


def _angles_and_hand(spec: Mapping[str, Any]) -> tuple[float, float, str]:
    """The normal pressure angle αn in (0, 45)° and the helix angle β in [0, 60)° (both in
    degrees, as given) and the pinion's helix hand."""
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
    return alpha_n, beta, hand


def _shift_and_center(spec: Mapping[str, Any]) -> tuple[tuple[float, float] | None, float | None]:
    """The profile shifts (each in (-3, 3)) and the centre distance (m), None where not given."""
    shift = None
    if spec.get("profile_shift") is not None:
        shift = _per_gear("profile_shift", spec["profile_shift"], _number)
        for i, x in enumerate(shift):
            if not -3 < x < 3:
                raise GearmeshInputError(f"profile_shift[{i}]", x, "must lie in (-3, 3)")
    center = None
    if spec.get("center_distance_mm") is not None:
        center = _positive("center_distance_mm", spec["center_distance_mm"]) * 1e-3
    return shift, center


def _non_negative(field_name: str, value: Any) -> float:
    x = _number(field_name, value)
    if x < 0:
        raise GearmeshInputError(field_name, value, "must not be negative")
    return x


def _bore_radius(spec: Mapping[str, Any]) -> tuple[float, float] | None:
    """The bore radii (m) from ``bore_radius_mm`` or a datasheet's ``bore_diameter_mm``, None
    when neither is given."""
    if spec.get("bore_radius_mm") is not None:
        return tuple(b * 1e-3 for b in _per_gear("bore_radius_mm", spec["bore_radius_mm"], _non_negative))
    if spec.get("bore_diameter_mm") is not None:  # a datasheet's inner (bore) diameter: r = d/2
        return tuple(d / 2 * 1e-3 for d in _per_gear("bore_diameter_mm", spec["bore_diameter_mm"], _non_negative))
    return None


def _material_and_rating(spec: Mapping[str, Any]) -> tuple[Material, tuple[str, ...], tuple[tuple[str, Any], ...]]:
    """The material (the keys not given filled by :data:`DEFAULT_MATERIAL`), the pair-file keys so
    filled, and the load-capacity inputs given (:func:`_rating_inputs`)."""
    given_material = {} if spec.get("material") is None else _mapping("material", spec["material"], _MATERIAL_KEYS)
    m = {**DEFAULT_MATERIAL, **{k: v for k, v in given_material.items() if k in DEFAULT_MATERIAL}}
    defaults = tuple(f"material.{key}" for key in DEFAULT_MATERIAL if key not in given_material)
    rating = _rating_inputs(spec, given_material)
    material = Material(  # its own checks: the rules of the file's keys
        youngs_modulus=_number("material.youngs_modulus_GPa", m["youngs_modulus_GPa"]) * 1e9,
        poisson_ratio=_number("material.poisson_ratio", m["poisson_ratio"]),
        density=_number("material.density_kg_m3", m["density_kg_m3"]),
    )
    return material, defaults, rating


def _modifications(spec: Mapping[str, Any]) -> tuple[Modification, Modification]:
    """The (pinion, gear) micro-geometry of the ``modification`` mapping; none when not given."""
    if spec.get("modification") is None:
        return (Modification(), Modification())
    mm = _mapping("modification", spec["modification"], set(GEARS))
    return (_modification("modification.pinion", mm.get("pinion")),
            _modification("modification.gear", mm.get("gear")))


def check_rating_input(name: str, value: Any, field_name: str | None = None) -> float | int | str:
    """One load-capacity input (a name of :data:`RATING_KEYS`' values) checked: the accuracy grade
    an integer 1..12 (ISO 1328-1), the FZG load stage an integer 1..12 (ISO 14635-1), the oil
    temperature in (−40, 200) °C, the life-factor conditions and the idler gear one of their words
    (:mod:`gearmesh.choices`), every other a positive number within its plausible range
    (:data:`gearmesh.limits.RATING_INPUT_RANGES`: fatigue limits of ISO 6336-5's materials,
    roughness, viscosities); GearmeshInputError naming ``field_name`` (default ``name``).

    Parameters
    ----------
    name : str
        The rating input's name (a value of :data:`RATING_KEYS`).
    value : object
        The value as given (units as the pair-file key says: MPa, µm, mm²/s, °C).
    field_name : str, optional
        The field an error names; default ``name``.

    Returns
    -------
    float or int or str
        The value checked (an int for the grade and the FZG stage, a word for the choices).

    Raises
    ------
    GearmeshInputError
        Naming ``field_name`` for a value outside its range or set.

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1
       (accuracy grades 1–12).
    .. [2] ISO 14635-1, Gears — FZG test procedures — Part 1: FZG test method A/8,3/90 (load stages 1–12).
    .. [3] ISO 6336-5:2016, Calculation of load capacity of spur and helical gears — Part 5: Strength
       and quality of materials (the fatigue limits' span).
    """
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

    d = z m_n/cos β the reference diameter and x the profile shift as :func:`gearmesh.gear.pair_geometry`
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


def _coefficient(key: str, diameters: np.ndarray, values: np.ndarray, what: str, where: str) -> tuple[float, float]:
    """The per-gear ``values`` converted from ``diameters`` (m) of pair-file ``key``, each > 0."""
    for i, v in enumerate(values):
        if not v > 0:
            raise GearmeshInputError(f"{key}[{i}]", float(diameters[i]) * 1e3,
                                     f"puts the {GEARS[i]} {where} its reference circle shifted by the profile "
                                     f"shift ({what} {v:.4f} <= 0)")
    return (float(values[0]), float(values[1]))


def load_pair(path_or_data: str | Path | Mapping[str, Any]) -> GearPair:
    """Read a pair file (YAML, engineering units) or mapping into a :class:`GearPair`; a file
    without ``name`` is named after its stem (``my_pair.yaml``: ``my_pair``), a different
    ``name`` is kept as given.

    Parameters
    ----------
    path_or_data : str, pathlib.Path or mapping
        A pair file (YAML) or its keys.

    Returns
    -------
    GearPair
        The pair in SI units.

    Raises
    ------
    GearmeshInputError
        Naming "pair file" for a file that cannot be read or is not a mapping, else the first bad
        key (the rule names the file).
    """
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
    as the zero-backlash one (:func:`gearmesh.gear.shift_rounding_center_distance`) and the material values
    filled by :data:`DEFAULT_MATERIAL`. One sentence each, for the output (JSON, dataset attrs).

    Parameters
    ----------
    pair : GearPair
        A pair as read.

    Returns
    -------
    list of str
        The notes, empty when the file said everything.
    """
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
    """{name: file} of the example pairs shipped with the package (:data:`EXAMPLES_DIR`).

    Returns
    -------
    dict of str to pathlib.Path
        Name to pair file, sorted by name.
    """
    return {f.stem: f for f in sorted(EXAMPLES_DIR.glob("*.yaml"))}


def example_pair(name: str) -> Path:
    """The file of the shipped example pair ``name`` (e.g. ``helical_z29_71_m5``), for :func:`load_pair`.

    Parameters
    ----------
    name : str
        An example pair's name.

    Returns
    -------
    pathlib.Path
        Its pair file.

    Raises
    ------
    GearmeshInputError
        Naming "example" for an unknown name, listing the known ones.
    """
    pairs = example_pairs()
    if name not in pairs:
        raise GearmeshInputError("example", name, f"must be one of {sorted(pairs)}")
    return pairs[name]


def check_pair_name(pair: GearPair, path: str | Path) -> GearPair:
    """Refuse a pair whose ``name`` differs from the name of its file ``path``: the rule of
    a study's pair library (``pairs_dir/NAME.yaml``), whose results are filed under the name.
    The command line has no such rule (:func:`load_pair`).

    Parameters
    ----------
    pair : GearPair
        The pair read from ``path``.
    path : str or pathlib.Path
        Its file.

    Returns
    -------
    GearPair
        ``pair`` unchanged.

    Raises
    ------
    GearmeshInputError
        Naming "name" when it is not the file's stem.
    """
    if pair.name != Path(path).stem:
        raise GearmeshInputError("name", pair.name, f"must equal the file name {Path(path).stem!r} of {path}")
    return pair


def load_named_pair(path: str | Path) -> GearPair:
    """Read a pair file whose ``name`` equals its file name (:func:`check_pair_name`).

    Parameters
    ----------
    path : str or pathlib.Path
        A pair file of a study's pair library.

    Returns
    -------
    GearPair
        The pair in SI units.

    Raises
    ------
    GearmeshInputError
        What :func:`load_pair` and :func:`check_pair_name` raise.
    """
    return check_pair_name(load_pair(path), path)


# --------------------------------------------------------------------------------------
# Writing, and the pairs of the variants
# --------------------------------------------------------------------------------------


def pair_to_dict(pair: GearPair) -> dict[str, Any]:
    """The inverse of :func:`pair_from_dict`: a pair-file mapping in engineering units.

    Parameters
    ----------
    pair : GearPair
        A pair (SI units).

    Returns
    -------
    dict
        Pair-file keys and values in engineering units (mm, deg, µm, GPa); defaulted material values
        left out.
    """
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
    ``from``, or both, is refused naming it (a misspelt key must not give the unmodified pair).

    Parameters
    ----------
    pair : GearPair
        The study's pair (or an optimisation's optimum for a ``from`` variant).
    variant : str
        The variant's name, as an error names it (``variants.NAME``).
    spec : mapping
        The variant's settings: ``modification`` (the pair-file block) or ``from``, or neither.

    Returns
    -------
    GearPair
        The pair with the variant's modification (SI).

    Raises
    ------
    GearmeshInputError
        Naming ``variants.NAME.KEY`` for an unknown key, both keys, or a bad modification value.
    """
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
