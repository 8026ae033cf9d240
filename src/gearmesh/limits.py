"""Every limit of the package, in one module, each with where it comes from.

Input documents (size, nodes, nesting), pair data (teeth, face width, modification depth,
helix angle), the plausible range of every physical input with its units (:class:`Plausible`:
material data, fatigue limits, bearings, roughness, oil, the ISO 6336 factors a user may give;
a value outside it is refused naming the unit slip that would bring it inside), list lengths,
loads, speeds and work sizes. The limits that need a pair's
geometry and a load, a speed or a stage's grid are checked here too: the nominal contact
stress and deflection of a torque, the rim speed of a rotational speed, and the size of the
grids and sweeps a stage would allocate. The functions that compute (``gearmesh.datasets.*``)
call these checks at their entry, so the Python API, the command line and the workflow refuse
the same values with the same one line (GearmeshInputError), in bounded time and memory: a
list is measured by its length (O(1)) before any of its items is read.

This module imports no other gearmesh module but :mod:`gearmesh.errors`, not even for its
annotations (a ``geom`` below is a :class:`gearmesh.gear.PairGeometry`, which takes its
limits from here), so every module can take its limits from here without an import circle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .errors import GearmeshInputError

# --------------------------------------------------------------------------------------
# Input documents and lists
# --------------------------------------------------------------------------------------

#: Largest input document read (bytes). The largest shipped study config is about 3 kB and a
#: pair file under 2 kB; 256 kB leaves a factor of ~100 for comments, yet keeps the pure-Python
#: YAML parse of the worst such file under about a second and ~100 MB.
MAX_INPUT_BYTES = 256 * 1024
#: Most YAML nodes (scalars, lists, mappings) and deepest nesting of an input document: a study
#: has a few hundred nodes nested at most ~6 deep; more is not a pair or a study.
MAX_INPUT_NODES = 20_000
MAX_INPUT_DEPTH = 20
#: Most items of any list setting that declares no smaller bound (gearmesh.schema gives every
#: array this ``maxItems``, every mapping this ``maxProperties``): the shipped studies' longest
#: list has 9 items, each item of a torque or speed list is a full stage run, and a longer speed
#: grid is written {start, stop, step} (at most :data:`MAX_SPEEDS`).
MAX_LIST_ITEMS = 1000
#: Most torques of one LTCA run: each is a full loaded contact over the mesh cycle, about 1.5 MB
#: per torque at the default grids (3000 torques peaked at 4.7 GB); as the impact map's torques.
MAX_LTCA_TORQUES = 100

#: Largest lead slope deviation f_Hβ (µm over the face width) the contact models take, of either
#: gear: ISO 1328-1:2013 class 11 allows f_Hβ of about 100 µm on a 1 m face of a large gear; ten
#: times that is a mounting error, not a lead deviation, and turns the contact into an edge load
#: on one face end that no slice model here describes.
MAX_LEAD_SLOPE_UM = 1000

# --------------------------------------------------------------------------------------
# Pair data
# --------------------------------------------------------------------------------------

#: Most teeth of a gear: the scope of ISO 1328-1:2013 (5 <= z <= 1000), the flank tolerance
#: system the package uses (:mod:`gearmesh.tolerance`); larger tooth counts are not made as
#: cylindrical gears, and the roll lengths of the contact models lose their precision in
#: double arithmetic long before z reaches 10⁹.
MAX_TEETH = 1000
#: Normal modules (m) the models are valid for. ISO 54:1996 standardises 1–50 mm; fine-pitch
#: instrument gears go down to about 0.1 mm and the largest mill gears to about 100 mm. The
#: slice and contact models are scale-free, but material data, ISO 6336 stiffness factors and
#: tolerances (ISO 1328-1 covers 0.5–70 mm) have no meaning far outside that range.
MODULE_RANGE = (0.1e-3, 100e-3)
#: Face width against the normal module, b/m_n >= 1: the slice models and ISO 6336-1 treat a
#: tooth slice in plane strain (E/(1 − ν²)); a face narrower than one module is a plate in
#: plane stress (the tooth is 2.25 m_n high), about 10 % softer than either model says.
MIN_FACE_WIDTH_TO_MODULE = 1.0
#: Face width against the pinion reference diameter, b/d1 <= 2: AGMA 2001-D04 (empirical
#: load-distribution factor) and ISO 6336-1's load distribution assume no wider face; beyond
#: it shaft bending and torsion shift the load to one end, which no model here includes.
MAX_FACE_WIDTH_TO_DIAMETER = 2.0
#: Deepest profile relief or crowning, as a fraction of the normal module. Modifications are
#: sized to the mesh deflection, F/(b c_γ) ≈ 1000 N/mm / 20 N/(mm µm) = 50 µm at the heaviest
#: ISO 6336 line loads, i.e. about 0.01 m_n at m_n = 5 mm; the TCA/LTCA add the depth as a gap
#: along the normal of the unmodified involute, a first-order model that holds while the depth
#: is small against the tooth (normal tip thickness ≈ 0.4–1 m_n). 0.1 m_n allows ten times the
#: usual depth and refuses what would reshape the tooth (e.g. 5 mm of crowning on 1.75 mm).
MAX_MODIFICATION_TO_MODULE = 0.1
#: Largest helix angle (rad): the limit of :func:`gearmesh.pairfile.pair_from_dict` (0 <= β < 60°).
MAX_HELIX_ANGLE = math.radians(60.0)
#: Most corners of a tolerance box (2^k) that are enumerated, and most manufactured samples.
MAX_CORNER_DIMENSIONS = 12
MAX_SAMPLES = 4096

# --------------------------------------------------------------------------------------
# Plausible values of physical inputs
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Plausible:
    """The range ``[low, high]`` a physical input has in practice, in the first of ``units``
    (name, factor to that unit; the others are the units it is likely given in by mistake), and
    where the range comes from (``source``). :meth:`check` refuses a value outside it in one line
    with the range in the unit of the key and, where one of the other units brings the value
    inside the range, that slip ("did you give N/m?")."""

    low: float
    high: float
    units: tuple[tuple[str, float], ...]
    source: str

    def check(self, value: float, field: str, unit: str | None = None) -> float:
        """``value`` (given in ``unit``, default the first of :attr:`units`) when it lies in the
        range, else GearmeshInputError naming ``field``."""
        factors = dict(self.units)
        unit = unit or self.units[0][0]
        scale = factors[unit]
        if self.low <= value * scale <= self.high:
            return value
        slip = next((f"; did you give {name}? ({value:g} {name} = {value * f / scale:.4g} {unit})"
                     for name, f in self.units if name != unit and self.low <= value * f <= self.high), "")
        raise GearmeshInputError(field, value, f"must lie in [{self.low / scale:g}, {self.high / scale:g}] {unit}, "
                                 f"{self.source}{slip}")


_STRESS_UNITS = (("MPa", 1.0), ("GPa", 1e3), ("Pa", 1e-6), ("ksi", 6.894757), ("psi", 6.894757e-3), ("kPa", 1e-3))
#: Fatigue limits of ISO 6336-5:2016 (its graphs of σ_Hlim and σ_Flim against hardness, qualities
#: ML to ME, every material class): σ_Hlim from about 300 N/mm² (grey cast iron, normalised steel
#: ML) to 1650 N/mm² (case-hardened ME); σ_Flim from about 40 N/mm² (grey cast iron) to 525 N/mm²
#: (case-hardened ME; σ_FE = 2 σ_Flim). The ranges leave room for materials beyond the graphs.
CONTACT_FATIGUE_LIMIT = Plausible(200.0, 2000.0, _STRESS_UNITS,
                                  "the span of materials (ISO 6336-5: about 300 to 1650 MPa)")
BENDING_FATIGUE_LIMIT = Plausible(30.0, 800.0, _STRESS_UNITS,
                                  "the span of materials (ISO 6336-5: about 40 to 525 MPa, sigma_Flim = sigma_FE/2)")
#: Young's modulus of gear materials: plastics (POM, PA 66, PEEK: 2.5–4 GPa) to cemented carbide
#: (about 600 GPa); beyond diamond's 1050 GPa nothing is solid.
YOUNGS_MODULUS = Plausible(0.5, 1200.0, (("GPa", 1.0), ("MPa", 1e-3), ("Pa", 1e-9), ("psi", 6.894757e-6)),
                           "from plastics to cemented carbide")
#: Density of gear materials: plastics (about 1000 kg/m³) to tungsten alloys (19 300 kg/m³).
DENSITY = Plausible(500.0, 25000.0, (("kg/m3", 1.0), ("g/cm3", 1e3), ("lb/in3", 27679.9)),
                    "from plastics to tungsten")
#: Stiffness of a gear's bearings at the gear centre: from a miniature ball bearing lightly loaded
#: (a few N/µm) to large roller bearings (10³–10⁴ N/µm; the default study's tapered roller bearings:
#: 230–3166 N/µm by Palmgren's law, gearmesh.supports); beyond 10⁵ N/µm a support is rigid for any
#: mesh (give ``rigid``).
BEARING_STIFFNESS = Plausible(1.0, 1e5, (("N/um", 1.0), ("N/m", 1e-6), ("N/mm", 1e-3), ("lbf/in", 1.751268e-4)),
                              "what rolling bearings have ('rigid' for none)")
#: Kinematic viscosity of gear oils: ISO 3448 grades VG 2 to VG 3200 at 40 °C, and their values
#: at 100 °C (about 1 to 200 mm²/s).
VISCOSITY_40C = Plausible(1.5, 5000.0, (("mm2/s", 1.0), ("m2/s", 1e6)), "ISO 3448 grades VG 2 to VG 3200")
VISCOSITY_100C = Plausible(0.5, 500.0, (("mm2/s", 1.0), ("m2/s", 1e6)), "gear oils at 100 degC")
#: Flank and root roughness of gears: superfinished (Ra 0.02, Rz 0.1 µm) to cast or rough-hobbed
#: (Ra 25, Rz 100 µm).
ROUGHNESS_RA = Plausible(0.01, 25.0, (("um", 1.0), ("mm", 1e3), ("nm", 1e-3)), "superfinished to rough-hobbed")
ROUGHNESS_RZ = Plausible(0.05, 100.0, (("um", 1.0), ("mm", 1e3), ("nm", 1e-3)), "superfinished to rough-hobbed")
#: The plausible range of each pair-file rating input (gearmesh.pairfile.check_rating_input).
RATING_INPUT_RANGES = {
    "contact_fatigue_limit_MPa": CONTACT_FATIGUE_LIMIT, "bending_fatigue_limit_MPa": BENDING_FATIGUE_LIMIT,
    "flank_Ra_um": ROUGHNESS_RA, "flank_Rz_um": ROUGHNESS_RZ, "root_Rz_um": ROUGHNESS_RZ,
    "viscosity_40C_mm2_s": VISCOSITY_40C, "viscosity_100C_mm2_s": VISCOSITY_100C,
}
#: Lengths given in mm, and the units a length is likely given in by mistake.
LENGTH_UNITS_MM = (("mm", 1.0), ("m", 1e3), ("cm", 10.0), ("in", 25.4))
#: Thinnest web of a gear body, as a fraction of its face width. ISO 6336-1's gear blank factor
#: C_R of the single stiffness c' takes webs from b_s/b = 0.2 (thinner ones as 0.2); thin-webbed
#: aerospace gears go to about 0.15 b.
#: Thinner, the web carries the tooth load by stretching, not by the bending of gearmesh.body's
#: Kirchhoff plate (its deflection passes its thickness), and the body's compliance grows as 1/t³
#: without bound (a 1 nm web: a mesh stiffness of 10⁻²⁰ N/µm).
MIN_WEB_TO_FACE = 0.1

#: The ISO 6336 factors a user may give instead of the computed ones (``--factor NAME=VALUE``,
#: :func:`gearmesh.rating.check_factors`) and the range each has in the standard:
#:
#: * the load factors K_A, K_v, K_Hβ, K_Fβ, K_Hα, K_Fα are at least 1 (ISO 6336-1 defines none
#:   below); the standard caps none of them, its methods give below about 3 for a gear worth
#:   rating (K_A: ISO 6336-1:2006 Annex B, 1.0 to 2.25 for heavy shocks on both sides), so 10 refuses
#:   only what no method gives a working gear;
#: * the life factors over every material of ISO 6336-2 Table 2 (Z_NT: 0.85 at 10¹⁰ cycles to 1.6
#:   static) and ISO 6336-3 Table 3 (Y_NT: 0.85 to 2.5 static);
#: * Z_L, Z_v over their formulas' span (ISO 6336-2 clause 11: C_ZL 0.83–0.91, any ν40 and v),
#:   Z_R over R_z10 of 0.5–40 µm, Z_W 1 to 1.2 (clause 12), Z_X 0.75 to 1 (clause 13);
#: * Y_δrelT, Y_RrelT, Y_X over ISO 6336-3 clauses 12–14 (every material, static values included);
#: * Y_M, the mean stress factor of ISO 6336-3:2019 (1 for one-way bending, 0.7 for an idler gear's
#:   reversed bending, :mod:`gearmesh.choices` IDLER_GEARS), from 0.5 (below the standard's values
#:   for reversed bending of any material, with margin) to 1;
#: * the minimum safety factors S_Hmin, S_Fmin from 1 (below, failure is accepted) to 5.
FACTOR_RANGES = {
    "K_A": (1.0, 10.0), "K_v": (1.0, 10.0), "K_Hbeta": (1.0, 10.0), "K_Fbeta": (1.0, 10.0),
    "K_Halpha": (1.0, 10.0), "K_Falpha": (1.0, 10.0),
    "Z_NT": (0.85, 1.6), "Y_NT": (0.85, 2.5), "Z_L": (0.83, 1.31), "Z_v": (0.85, 1.19), "Z_R": (0.65, 1.35),
    "Z_W": (1.0, 1.2), "Z_X": (0.75, 1.0), "Y_deltarelT": (0.7, 1.5), "Y_RrelT": (0.9, 1.12), "Y_X": (0.7, 1.0),
    "Y_M": (0.5, 1.0),
    "S_Hmin": (1.0, 5.0), "S_Fmin": (1.0, 5.0),
}


# --------------------------------------------------------------------------------------
# Loads, speeds and work sizes
# --------------------------------------------------------------------------------------

#: Two torques or speeds are one operating point when they differ by at most this fraction of
#: the one looked for: what a stage computed at 1000 N m is found again at 1000.0000000001
#: (a value passed through a unit conversion or a pinion/gear torque ratio) and nowhere else.
SAME_POINT_RTOL = 1e-9


def same_point(values, target: float) -> np.ndarray:
    """Boolean mask (shape of ``values``): which of ``values`` are the operating point ``target``
    (torque or speed, any unit) to :data:`SAME_POINT_RTOL` of ``target``.

    Parameters
    ----------
    values : array_like
        Torques or speeds, any shape.
    target : float
        The operating point looked for, in the unit of ``values``.

    Returns
    -------
    numpy.ndarray of bool
        Shape of ``values``.
    """
    return np.abs(np.asarray(values, dtype=float) - target) <= SAME_POINT_RTOL * abs(target)


#: Highest pinion speed accepted (rpm): beyond any gear drive (turbo gears run at up to ~1e5 rpm).
MAX_SPEED_RPM = 1e6
#: Most speeds of one dynamics sweep (a 500–50 000 rpm grid in steps of 100 rpm has 496).
MAX_SPEEDS = 20000
#: Cap on RK4 steps at one speed (a very low speed would otherwise run for hours: the
#: transient lasts a fixed physical time while the step is bounded by the highest mode).
MAX_STEPS_PER_SPEED = 2_000_000
#: Work limits of one dynamics job, checked before any job runs
#: (:func:`gearmesh.datasets.dynamics.check_dynamics_settings`).
#: RK4 speed-steps (steps of the longest speed × speeds, one vectorised batch): measured about
#: 5e6 per second (the low-fluctuation paper pair, 496 speeds × 17664 steps in 2 s), so 1e9 is a few minutes.
MAX_SPEED_STEPS = 1_000_000_000
#: Most (window positions × approaches × points per line) of a contact table: its build costs
#: about 0.4 s per 10⁶ (256 × 96 × 50 with the default pair's 4–5 tooth pairs: 0.4 s, measured),
#: so the limit is about a minute and ~130 MB for the table (chunked build).
MAX_TABLE_POINTS = 200_000_000
#: Most speeds of the 9-DOF train: it keeps the time series and spectra of every speed.
MAX_TRAIN_SPEEDS = 50

#: Highest nominal contact stress σ_H0 (Pa) accepted: ISO 6336-5's highest allowable contact
#: stress number (case-hardened steel, quality ME: σ_Hlim = 1650 MPa) times ISO 6336-2's static
#: life factor Z_NT = 1.6. Above it every steel flank yields or pits at the first cycles, so a
#: linear-elastic result has no meaning.
MAX_CONTACT_STRESS = 1650e6 * 1.6
#: Largest nominal mesh deflection F_bt/(c_γα b), as a fraction of the normal module: the slice
#: and contact models are linear, for deflections small against the tooth (2.25 m_n high).
#: Steel pairs at :data:`MAX_CONTACT_STRESS` deflect about 0.02–0.06 m_n; 0.1 m_n also bounds
#: soft materials, whose contact stress stays low while the teeth bend away.
MAX_DEFLECTION_TO_MODULE = 0.1
#: Young's modulus (Pa) of the steel that ISO 6336-1's c' refers to; c' scales with E/E_st.
ISO6336_STEEL_MODULUS = 206e9

#: Most slice × position points of one slice-model stiffness run: measured about 400 bytes per
#: point (the low-fluctuation paper pair, 1000 slices × 2000 positions: 0.9 GB, 2.5 s), so 4e6 points stay under
#: about 1.6 GB.
MAX_STIFFNESS_POINTS = 4_000_000
#: Most position × point candidates of one TCA/LTCA torque: measured about 1 kB per candidate
#: (2000 positions × 50 points: 0.2 GB), so 1e6 stay under about 1 GB.
MAX_CONTACT_POINTS = 1_000_000
#: Most candidate points per contact line a physics function accepts (a study's ``points`` is at
#: most 2000, :mod:`gearmesh.settings`): the bound the LTCA's counts had (gearmesh.contact_model).
MAX_LINE_POINTS = 100_000
#: Highest centrifugal hoop stress ρ·v_a² (Pa) at the tip circle accepted: the ultimate tensile
#: strength of maraging steel 18Ni(300), about 2.0 GPa (ASM Handbook vol. 1, 1990), above that
#: of any carburising or through-hardening gear steel (EN 10084 18CrNiMo7-6 core: 1.08–1.32 GPa).
#: ρv² is the hoop stress of a thin ring rotating at rim speed v (Timoshenko & Goodier, Theory
#: of Elasticity, §32); a solid or webbed body of that rim speed carries at most (3 + ν)/4 of it
#: at a small bore, a thin rim loaded by its teeth more. Steel (7850 kg/m³) reaches it at a tip
#: speed of about 505 m/s, well above the pitch-line velocities of high-speed turbo gear units
#: (of the order of 100–200 m/s): beyond, the gear bursts, and no model here has centrifugal
#: loads or rim growth, or teeth that are not quasi-static (the ratio of the mesh frequency to a
#: tooth's first natural frequency grows as the pitch-line velocity over the speed of sound).
MAX_RIM_STRESS = 2.0e9
#: Density (kg/m³) of steel, for a pair without a material (as :data:`ISO6336_STEEL_MODULUS`).
STEEL_DENSITY = 7850.0

#: Most helix angles of a sweep: each is a full pair geometry and contact-line run (about
#: 10 ms); the seeds use fewer than 100.
MAX_SWEEP_ANGLES = 2000
#: Most torques of a load-window grid (its top over its step; an optimum's and the impact stage's),
#: each an impact evaluation of the standard gear and of the optimum; the default study's grid (up
#: to 1.25 × 1600 N m in 50 N m steps) has 40.
MAX_WINDOW_TORQUES = 2000


def max_speed_rpm(geom: Any, on: str = "pinion") -> float:
    """Highest speed (rpm) of the ``on`` gear ('pinion' or 'gear') at which the faster tip circle
    stays within :data:`MAX_RIM_STRESS`: ρ (ω_g r_a,g)² ≤ σ_max for both gears, ω2 = ω1 z1/z2.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (tip radii in m; density of its material in kg/m³, steel's when it has none).
    on : {'pinion', 'gear'}, default 'pinion'
        The gear whose speed is returned.

    Returns
    -------
    float
        Highest speed of the ``on`` gear (rpm).

    References
    ----------
    .. [1] Timoshenko S. P., Goodier J. N., Theory of Elasticity, McGraw-Hill, §32 (rotating disks):
       hoop stress ρ v² of a thin rotating ring.
    """
    pair = geom.pair
    density = pair.material.density if pair.material else STEEL_DENSITY
    v_max = math.sqrt(MAX_RIM_STRESS / density)
    z1, z2 = pair.teeth
    ratio_to_pinion = 1.0 if on == "pinion" else z2 / z1  # ω1 = ω_on × ratio
    omega1 = min(v_max / float(geom.tip_radius[0]), v_max / float(geom.tip_radius[1]) * z2 / z1)
    return omega1 / ratio_to_pinion * 30.0 / math.pi


def positive_values(values, field: str, unit: str, maximum: float = math.inf, note: str = "",
                    max_items: int = MAX_LIST_ITEMS) -> np.ndarray:
    """A positive number or a list of them as a 1-d float array; refuses more than ``max_items``
    (measured before any item is read), empty, non-numeric, non-finite, non-positive and (if
    given) values above ``maximum``, naming ``field`` and the ``unit`` (GearmeshInputError);
    ``note`` is added to the rule of a non-positive value.

    Parameters
    ----------
    values : float or sequence of float
        One value or a list.
    field : str
        The field an error names (an item as ``field[k]``).
    unit : str
        The values' unit, as an error says it.
    maximum : float, default inf
        Largest value accepted, in ``unit``.
    note : str, default ""
        Added to the rule of a non-positive value.
    max_items : int, default MAX_LIST_ITEMS
        Most values accepted.

    Returns
    -------
    numpy.ndarray
        The values, shape (n,), float, in ``unit``.

    Raises
    ------
    GearmeshInputError
        Naming ``field`` (or ``field[k]``) for too many, no, non-numeric, non-finite, non-positive
        or too large values.
    """
    if isinstance(values, (int, float, np.floating, np.integer)) and not isinstance(values, bool):
        values = [values]
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise GearmeshInputError(field, values, f"must be a positive number or a list of them ({unit})")
    if len(values) > max_items:
        raise GearmeshInputError(field, f"{len(values)} values", f"must have at most {max_items} items "
                                 "(gearmesh.limits): split the work into several runs")
    vals = list(values)
    if not vals:
        raise GearmeshInputError(field, values, f"must name at least one value ({unit})")
    for k, v in enumerate(vals):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(v):
            raise GearmeshInputError(f"{field}[{k}]", v, f"must be a finite number ({unit})")
        if v <= 0:
            raise GearmeshInputError(f"{field}[{k}]", v, f"must be positive ({unit}){note}")
        if v > maximum:
            raise GearmeshInputError(f"{field}[{k}]", v, f"must lie in (0, {maximum:g}] {unit}")
    return np.asarray(vals, dtype=float)


def check_speeds(geom: Any, speeds_rpm, field: str = "speeds_rpm", on: str = "pinion",
                 max_items: int = MAX_SPEEDS, empty_ok: bool = False) -> np.ndarray:
    """Speeds (rpm of the ``on`` gear) as a 1-d float array: at most ``max_items`` of them (a
    sweep's grid: :data:`MAX_SPEEDS`; a list in a config is bounded by its schema first), each
    finite and positive (:func:`positive_values`); with a pair's ``geom`` none above
    :func:`max_speed_rpm` (the centrifugal hoop stress of the faster tip circle would exceed
    :data:`MAX_RIM_STRESS`; the advice is to lower the speed); and none above
    :data:`MAX_SPEED_RPM`. The one speed check of the package; ``empty_ok``: no speed is a
    valid answer (e.g. no sampled speeds).

    Parameters
    ----------
    geom : PairGeometry or None
        The pair's geometry; None: no rim-speed check.
    speeds_rpm : float or sequence of float
        Speeds of the ``on`` gear (rpm).
    field : str, default "speeds_rpm"
        The field an error names.
    on : {'pinion', 'gear'}, default 'pinion'
        The gear the speeds are of.
    max_items : int, default MAX_SPEEDS
        Most speeds accepted.
    empty_ok : bool, default False
        Accept an empty list (returns an empty array).

    Returns
    -------
    numpy.ndarray
        The speeds (rpm), shape (n,).

    Raises
    ------
    GearmeshInputError
        Naming ``field`` (or ``field[k]``): everything :func:`positive_values` refuses, a speed above
        :func:`max_speed_rpm` or above :data:`MAX_SPEED_RPM`.
    """
    if empty_ok and hasattr(speeds_rpm, "__len__") and not isinstance(speeds_rpm, str) and len(speeds_rpm) == 0:
        return np.zeros(0)
    values = positive_values(speeds_rpm, field, "rpm", max_items=max_items)
    if geom is not None:
        limit = max_speed_rpm(geom, on)
        if values.max() > limit:
            k = int(np.argmax(values))
            pair = geom.pair
            pitch = float(values[k]) * math.pi / 30 * float(geom.reference_radius[0 if on == "pinion" else 1])
            raise GearmeshInputError(f"{field}[{k}]" if values.size > 1 else field, float(values[k]),
                                     f"rpm of the {on} of {pair.name} is a pitch-line velocity of {pitch:.4g} m/s; "
                                     f"at most {limit:.5g} rpm, where the centrifugal hoop stress rho v^2 of the tip "
                                     f"circle reaches {MAX_RIM_STRESS / 1e9:g} GPa, the strength of the strongest "
                                     "steels (gearmesh.limits.MAX_RIM_STRESS): lower the speed")
    if values.max() > MAX_SPEED_RPM:
        k = int(np.argmax(values))
        raise GearmeshInputError(f"{field}[{k}]", float(values[k]), f"must lie in (0, {MAX_SPEED_RPM:g}] rpm")
    return values


def check_grid(field: str, value: object, points: int, limit: int, what: str) -> None:
    """Refuse a stage grid of ``points`` (e.g. slices × positions) above ``limit``.

    Parameters
    ----------
    field : str
        The setting an error names.
    value : object
        The setting's value as given.
    points : int
        The grid's size.
    limit : int
        Largest size accepted.
    what : str
        What a point of the grid is (plural), as the error says.

    Raises
    ------
    GearmeshInputError
        Naming ``field`` and ``value`` when ``points > limit``.
    """
    if points > limit:
        raise GearmeshInputError(field, value, f"gives {points:.3g} {what}; at most {limit:.3g} "
                                 "(memory, see gearmesh.limits)")


def _count(field: str, value) -> int:
    """``value`` as an integer >= 1 (a grid size), refused naming ``field`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise GearmeshInputError(field, value, "must be an integer >= 1")
    return int(value)


def check_slice_grid(slices, positions, names: tuple[str, str] = ("slices", "positions")) -> tuple[int, int]:
    """``slices`` and ``positions`` of a slice-model run as integers, refused (naming them as
    ``names``) when their product exceeds :data:`MAX_STIFFNESS_POINTS`.

    Parameters
    ----------
    slices : int
        Slices over the face width (≥ 1).
    positions : int
        Mesh positions (≥ 1).
    names : tuple of str, default ("slices", "positions")
        The fields an error names.

    Returns
    -------
    slices, positions : int

    Raises
    ------
    GearmeshInputError
        For a count that is not an integer ≥ 1, or a product above :data:`MAX_STIFFNESS_POINTS`.
    """
    slices, positions = _count(names[0], slices), _count(names[1], positions)
    check_grid(names[0], slices, slices * positions, MAX_STIFFNESS_POINTS, "slice-positions")
    return slices, positions


def check_sweep(start: float, stop: float, step: float, prefix: str = "") -> int:
    """The number of helix angles from ``start`` to ``stop`` (included on the grid) in steps of
    ``step`` (degrees), computed from the three numbers before any grid exists, refused above
    :data:`MAX_SWEEP_ANGLES` or when the range is empty (fields ``prefix`` + start_deg/step_deg).

    Parameters
    ----------
    start, stop : float
        First and last helix angle (deg).
    step : float
        Step (deg), positive.
    prefix : str, default ""
        Prefix of the fields an error names (e.g. ``"helix_sweep."``).

    Returns
    -------
    int
        The number of helix angles.

    Raises
    ------
    GearmeshInputError
        Naming ``step_deg`` (not a positive finite number, or too many angles) or ``stop_deg``
        (below ``start``).
    """
    if not (math.isfinite(start) and math.isfinite(stop) and math.isfinite(step)) or step <= 0:
        raise GearmeshInputError(f"{prefix}step_deg", step, "must be a positive finite number (degrees)")
    if stop < start:
        raise GearmeshInputError(f"{prefix}stop_deg", stop, f"must not be below start_deg ({start:g})")
    count = math.floor((stop - start) / step + 0.5) + 1
    check_grid(f"{prefix}step_deg", step, count, MAX_SWEEP_ANGLES, "helix angles per pair")
    return count


def check_contact_grid(positions, points) -> tuple[int, int]:
    """``positions`` and ``points`` of a TCA/LTCA as integers, refused when the (positions + 1) ×
    points candidates per contact line exceed :data:`MAX_CONTACT_POINTS`.

    Parameters
    ----------
    positions : int
        Mesh positions of the TCA/LTCA (≥ 1).
    points : int
        Points per contact line (≥ 1).

    Returns
    -------
    positions, points : int

    Raises
    ------
    GearmeshInputError
        For a count that is not an integer ≥ 1, or ``points`` when (positions + 1) × points exceeds
        :data:`MAX_CONTACT_POINTS`.
    """
    positions, points = _count("positions", positions), _count("points", points)
    check_grid("points", points, (positions + 1) * points, MAX_CONTACT_POINTS, "contact candidates per line")
    return positions, points
