"""The keys of a pair file, declared once (typed).

Every key of a pair file is a field of one of the frozen dataclasses below, declared with
:func:`gearmesh.schema.setting` (type, default, bounds, description), as the study's settings
are in :mod:`gearmesh.settings`. From them come the pair-file schema for editors
(:func:`pair_schema`, published as ``schemas/pair.schema.json`` by :mod:`gearmesh.published`)
and the reference of every key (``gearmesh schema pair --format markdown``). The physics of a
pair is the reader's (:mod:`gearmesh.pairfile`, :mod:`gearmesh.gear`), which takes its keys and
defaults from here; this module imports no physics.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any, ClassVar, Literal

from .choices import FZG_LOAD_STAGES, IDLER_GEARS, LIFE_FACTOR_CONDITIONS
from .limits import (BEARING_STIFFNESS, BENDING_FATIGUE_LIMIT, CONTACT_FATIGUE_LIMIT, DENSITY, MAX_LEAD_SLOPE_UM,
                     MODULE_RANGE, ROUGHNESS_RA, ROUGHNESS_RZ, VISCOSITY_40C, VISCOSITY_100C, YOUNGS_MODULUS, Plausible)
from .schema import REQUIRED, object_schema, setting


#: ISO 53:1998 basic rack profiles (α_P = 20°, h_aP = 1.0 m): the dedendum h_fP and root fillet
#: radius ρ_fP of the rack, in modules — the addendum and tip radius of the hob that generates
#: the gear (``dedendum_coefficient``, ``tool_tip_radius_coefficient``). A for high torque, B and
#: C for normal service (smaller fillets), D for gears finished by grinding or shaving.
ISO53_PROFILES = {"ISO 53 A": (1.25, 0.38), "ISO 53 B": (1.25, 0.30), "ISO 53 C": (1.25, 0.25),
                  "ISO 53 D": (1.40, 0.39)}
#: Steel, for a pair file without ``material`` or without one of its keys (given keys override):
#: E = 206 GPa and ν = 0.3 are the steel of the gear standards, ISO 6336-1:2019 (the single
#: stiffness c' refers to E_st = 206 000 N/mm²) and ISO 6336-2:2019 (Z_E = √(E/(2π(1 − ν²))) =
#: 189.8 √(N/mm²) for steel on steel); ρ = 7850 kg/m³ is EN 1993-1-1:2005 §3.2.6 (which gives
#: E = 210 GPa for structural steel: the gear standards' 206 GPa is taken because the stiffness
#: and load limits here refer to it). Which keys were filled is stated (:func:`gearmesh.pairfile.pair_notes`).
DEFAULT_MATERIAL = {"youngs_modulus_GPa": 206.0, "poisson_ratio": 0.3, "density_kg_m3": 7850.0}
#: Name of a pair: usable as a file name (letters, digits, '_', '-' and '.', not first; no
#: path characters), short enough to stay far below the 255-byte limit of one path component
#: (Linux NAME_MAX) with any suffix. Study configs restrict the names they use further (schema).
NAME_PATTERN = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9_.-]{0,159}")
#: Keys that say the same thing: at most one of each group may be given (the reader refuses two).
ALTERNATIVE_KEYS = (
    ("addendum_coefficient", "tip_diameter_mm"),
    ("dedendum_coefficient", "root_diameter_mm", "basic_rack_profile"),
    ("tool_tip_radius_coefficient", "basic_rack_profile"),
    ("bore_radius_mm", "bore_diameter_mm"),
)


def _within(plausible: Plausible) -> dict[str, float]:
    """The schema bounds of a pair-file key checked against a plausible range (in the key's unit,
    the first of the range's units: :class:`gearmesh.limits.Plausible`)."""
    return {"minimum": plausible.low, "maximum": plausible.high}


@dataclass(frozen=True, kw_only=True)
class PairMaterial:
    """Isotropic elastic material of both gears; a key left out is steel's (the reader's
    ``DEFAULT_MATERIAL``, stated in every result)."""

    youngs_modulus_GPa: float = setting(DEFAULT_MATERIAL["youngs_modulus_GPa"], "Young's modulus",
                                        **_within(YOUNGS_MODULUS))
    poisson_ratio: float = setting(DEFAULT_MATERIAL["poisson_ratio"], "Poisson's ratio", minimum=0,
                                   exclusive_maximum=0.5)
    density_kg_m3: float = setting(DEFAULT_MATERIAL["density_kg_m3"], "density", **_within(DENSITY))
    contact_fatigue_limit_MPa: float | None = setting(
        None, "contact fatigue limit σ_Hlim of the rating (null: 1500, case-hardened steel MQ, ISO 6336-5)",
        **_within(CONTACT_FATIGUE_LIMIT))
    bending_fatigue_limit_MPa: float | None = setting(
        None, "bending fatigue limit σ_Flim of the rating (null: 500, case-hardened steel MQ, ISO 6336-5)",
        **_within(BENDING_FATIGUE_LIMIT))


@dataclass(frozen=True, kw_only=True)
class PairRoughness:
    """Surface roughness of the rating (ISO 6336-2/-3), the same on both gears."""

    flank_Ra: float | None = setting(None, "flank arithmetic mean roughness Ra (null: 0.4, ground)",
                                     **_within(ROUGHNESS_RA))
    flank_Rz: float | None = setting(None, "flank mean peak-to-valley roughness Rz (null: 2.5, ground)",
                                     **_within(ROUGHNESS_RZ))
    root_Rz: float | None = setting(None, "tooth-root roughness Rz (null: 10, hobbed)", **_within(ROUGHNESS_RZ))


@dataclass(frozen=True, kw_only=True)
class PairLubricant:
    """The oil of the rating (ISO 6336-2 Z_L; the scuffing rating's friction, bulk and scuffing temperatures)."""

    viscosity_40C_mm2_s: float | None = setting(None, "kinematic viscosity at 40 °C (null: 220, ISO VG 220)",
                                                **_within(VISCOSITY_40C))
    viscosity_100C_mm2_s: float | None = setting(None, "kinematic viscosity at 100 °C (null: 19, ISO VG 220)",
                                                 **_within(VISCOSITY_100C))
    oil_temperature_C: float | None = setting(None, "oil temperature (null: 70)", exclusive_minimum=-40,
                                              exclusive_maximum=200)
    fzg_load_stage: int | None = setting(None, "FZG load stage of the oil (ISO 14635-1 test A/8.3/90) for the "
                                               "scuffing rating (null: 12, the least of a CLP oil by DIN 51517-3)",
                                         minimum=FZG_LOAD_STAGES[0], maximum=FZG_LOAD_STAGES[-1])


@dataclass(frozen=True, kw_only=True)
class GearModification:
    """The six micro-geometry parameters of one gear (all zero when left out)."""

    root_relief_um: float = setting(0.0, "root relief depth y1 at the start of active profile", minimum=0)
    tip_relief_um: float = setting(0.0, "tip relief depth y2 at the tip", minimum=0)
    root_relief_length_mm: float = setting(0.0, "root relief length y3, roll length from the start of active "
                                                "profile", minimum=0)
    tip_relief_length_mm: float = setting(0.0, "tip relief length y4, roll length from the tip", minimum=0)
    crowning_um: float = setting(0.0, "lead crowning depth y5 at each face end", minimum=0)
    unmodified_lead_length_mm: float = setting(0.0, "central unmodified lead length y6", minimum=0)


@dataclass(frozen=True, kw_only=True)
class PairModification:
    """Micro-geometry of the pinion and of the gear."""

    pinion: GearModification | None = setting(None, "the pinion's six parameters (null: none)")
    gear: GearModification | None = setting(None, "the gear's six parameters (null: none)")


@dataclass(frozen=True, kw_only=True)
class PairFile:
    """A helical gear pair as designed: engineering units in the key names; index 0 (or the first
    of a [pinion, gear] list) is the pinion, the driver. A datasheet's diameters may stand for the
    coefficients (tip_diameter_mm for addendum_coefficient, root_diameter_mm or
    basic_rack_profile for dedendum_coefficient, bore_diameter_mm for bore_radius_mm)."""

    #: Keys that give one quantity: at most one of each group (the reader's own list).
    ALTERNATIVES: ClassVar = ALTERNATIVE_KEYS
    name: str | None = setting(None, "the pair's name (null or left out: the file name without .yaml; a study's "
                                     "pair library needs the two equal)", pattern=f"^{NAME_PATTERN.pattern}$")
    teeth: tuple[int, int] = setting(REQUIRED, "numbers of teeth [pinion, gear] (external gears)", minimum=5)
    normal_module_mm: float = setting(REQUIRED, "normal module m_n (ISO 54 modules with margins)",
                                      minimum=round(MODULE_RANGE[0] * 1e3, 9), maximum=round(MODULE_RANGE[1] * 1e3, 9))
    normal_pressure_angle_deg: float = setting(REQUIRED, "normal pressure angle α_n", exclusive_minimum=0,
                                               exclusive_maximum=45)
    helix_angle_deg: float = setting(REQUIRED, "helix angle β (the hand in helix_hand)", minimum=0,
                                     exclusive_maximum=60)
    helix_hand: Literal["right", "left"] = setting("right", "hand of the pinion's helix (the gear's is the other)")
    face_width_mm: float | tuple[float, float] = setting(REQUIRED, "face width, one or [pinion, gear]; the mesh uses "
                                                                   "the overlap", exclusive_minimum=0)
    profile_shift: float | tuple[float, float] | None = setting(
        None, "profile shift coefficients x, one or [pinion, gear] (null: none, or inferred from the centre "
        "distance)", exclusive_minimum=-3, exclusive_maximum=3)
    center_distance_mm: float | None = setting(None, "operating centre distance (null: the zero-backlash distance "
                                                     "of the shifts)", exclusive_minimum=0)
    addendum_coefficient: float | tuple[float, float] = setting(1.0, "tip height over the reference circle in "
                                                                     "normal modules (before the shift)",
                                                                exclusive_minimum=0)
    tip_diameter_mm: float | tuple[float, float] | None = setting(
        None, "tip diameter d_a, one or [pinion, gear], instead of addendum_coefficient (exact with the shifts)",
        exclusive_minimum=0)
    dedendum_coefficient: float | tuple[float, float] = setting(1.25, "the generating hob's addendum in normal "
                                                                      "modules", exclusive_minimum=0)
    root_diameter_mm: float | tuple[float, float] | None = setting(
        None, "root diameter d_f, one or [pinion, gear], instead of dedendum_coefficient (exact with the shifts)",
        exclusive_minimum=0)
    basic_rack_profile: Literal[tuple(ISO53_PROFILES)] | None = setting(
        None, "an ISO 53:1998 basic rack profile (20° pairs): its dedendum and root fillet radius instead of "
        "dedendum_coefficient and tool_tip_radius_coefficient")
    tool_tip_radius_coefficient: float | tuple[float, float] | None = setting(
        None, "the hob's tip radius in normal modules (null: 0.38, ISO 53, or the largest that fits)", minimum=0)
    bore_radius_mm: float | tuple[float, float] | None = setting(
        None, "bore radius, one or [pinion, gear]: needed for masses, inertias and the fillet foundation", minimum=0)
    bore_diameter_mm: float | tuple[float, float] | None = setting(
        None, "bore (inner) diameter, one or [pinion, gear], instead of bore_radius_mm", minimum=0)
    material: PairMaterial | None = setting(None, "elastic material of both gears (null or left out: steel)")
    bearing_radial_stiffness_N_per_um: float | Literal["rigid"] | tuple[float | Literal["rigid"], float | Literal["rigid"]] | None = setting(
        None, "radial stiffness of each gear's bearings together at the gear centre, one, [pinion, gear] or rigid "
        "(dynamics; null: the low-fluctuation paper's 150, stated in the results)", **_within(BEARING_STIFFNESS))
    bearing_axial_stiffness_N_per_um: float | Literal["rigid"] | tuple[float | Literal["rigid"], float | Literal["rigid"]] | None = setting(
        None, "axial stiffness of each gear's bearings at the gear centre, one, [pinion, gear] or rigid (dynamics; "
        "null: the low-fluctuation paper's 10)", **_within(BEARING_STIFFNESS))
    shaft_diameter_mm: float | tuple[float, float] | None = setting(
        None, "shaft diameter, one or [pinion, gear]: shaft bending 48EI/L³ in series with the radial bearing "
        "stiffness (with bearing_span_mm; the gear at mid-span)", exclusive_minimum=0)
    bearing_span_mm: float | tuple[float, float] | None = setting(
        None, "distance between the two bearings of each shaft, one or [pinion, gear] (with shaft_diameter_mm)",
        exclusive_minimum=0)
    web_thickness_mm: float | Literal["rigid"] | tuple[float | Literal["rigid"], float | Literal["rigid"]] | None = setting(
        None, "thickness of each gear body's web, one, [pinion, gear] or rigid, at most the face width: the body's "
        "axial bending under the helical load in series with the mesh and its tilt with the shafts' (gearmesh.body; "
        "needs the shafts and bearings; null with no hub_diameter_mm: no body described, the teeth alone, ISO "
        "6336-1's model; null with a hub: a solid disc, the face width; rigid: no body bending)",
        exclusive_minimum=0)
    hub_diameter_mm: float | tuple[float, float] | None = setting(
        None, "diameter where each web meets its hub (held), one or [pinion, gear], from the bore up to below the "
        "root circle (gearmesh.body; null: the bore)", exclusive_minimum=0)
    gear_offset_mm: float | tuple[float, float] | None = setting(
        None, "offset of each gear's face centre from the middle of its bearing span, signed towards the leading "
        "face end (the end where a tooth pair's contact line enters first), one or [pinion, gear] (null: mid-span; "
        "with shaft_diameter_mm)")
    torque_side: tuple[Literal["leading", "trailing"], Literal["leading", "trailing"]] | None = setting(
        None, "the face end on whose side each shaft carries the torque, [pinion, gear] (null: the side that gives "
        "the larger mesh misalignment, stated in the results; with shaft_diameter_mm)")
    lead_slope_deviation_um: tuple[float, float] | None = setting(
        None, "helix slope deviation f_Hβ of each gear over its face, [pinion, gear] (ISO 1328-1), positive where "
        "the flank stands proud at the leading face end: the mesh sees the sum (null: none)",
        minimum=-MAX_LEAD_SLOPE_UM, maximum=MAX_LEAD_SLOPE_UM)
    profile_slope_deviation_um: tuple[float, float] | None = setting(
        None, "profile slope deviation f_Hα of each gear over its active profile, [pinion, gear] (ISO 1328-1), "
        "positive where the flank stands proud at the tip (null: none)",
        minimum=-MAX_LEAD_SLOPE_UM, maximum=MAX_LEAD_SLOPE_UM)
    mesh_misalignment_um: float | None = setting(
        None, "mesh misalignment f_ma in the plane of action (ISO 6336-1), signed as the lead slope deviations "
        "(null: none in the analyses; the rating takes ISO's f_ma of the accuracy grade)",
        minimum=-MAX_LEAD_SLOPE_UM, maximum=MAX_LEAD_SLOPE_UM)
    modification: PairModification | None = setting(None, "micro-geometry of each gear")
    accuracy_grade: int | None = setting(None, "ISO 1328-1 accuracy grade of the rating (null: 6)", minimum=1,
                                         maximum=12)
    roughness_um: PairRoughness | None = setting(None, "surface roughness of the rating")
    lubricant: PairLubricant | None = setting(None, "the oil of the rating")
    tip_edge_radius_mm: float | None = setting(None, "tip-edge rounding radius of the edge-contact pressure (null: "
                                                     "0.1 m_n, an assumed edge break)", exclusive_minimum=0)
    life_factor_conditions: Literal[LIFE_FACTOR_CONDITIONS] | None = setting(
        None, "long-life conditions of the life factors Z_NT, Y_NT (ISO 6336-2/-3:2019): normal, the line to 0.85 at "
        "1e10 cycles; optimum, 1.0 beyond the knee (null: normal)")
    idler_gear: Literal[IDLER_GEARS] | None = setting(
        None, "the gear that is an idler, meshing with a third gear on its other flank: bending both ways, "
        "Y_M = 0.7 (ISO 6336-3; null: neither)")
    source: str = setting("", "where the data come from")


def pair_schema() -> dict[str, Any]:
    """The JSON schema of a pair file (:class:`PairFile`): what an editor completes and checks.
    The physics of a pair (contact ratio, interference, centre distance) is the reader's
    (:func:`gearmesh.gear.pair_geometry`), beyond any schema.

    Returns
    -------
    dict
        JSON schema (draft 2020-12) of :class:`PairFile`: every key with its type, default, bounds
        and description (units in the key names).

    References
    ----------
    .. [1] JSON Schema, draft 2020-12, Core and Validation specifications.
       https://json-schema.org/draft/2020-12
    """
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "gearmesh gear pair file",
            **object_schema(PairFile)}
