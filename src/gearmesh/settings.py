"""The settings of a study config, declared once (typed).

Every study key is a field of one of the frozen dataclasses below, declared with
:func:`gearmesh.schema.setting` (type, default, bounds, description). From them come the
study schema (:func:`gearmesh.registry.study_schema`; published as ``schemas/config.schema.yaml``, linked as
``workflow/schemas/``, by :mod:`gearmesh.published`), which ``gearmesh validate`` and the
Snakefile validate a config with and fill its defaults from; the argument checks of the stage
functions (:func:`gearmesh.arguments.check_arguments`: the API refuses what the schema refuses) and
the reference of every key (``config/README.md``). The keys of a pair file are declared beside
them in :mod:`gearmesh.pair_keys`. ``gearmesh schema`` prints each.

A stage's section also declares the stage (``STAGE``, :class:`gearmesh.stages.Stage`): the
function that takes its keys as keyword arguments (and its defaults from here, through
:func:`gearmesh.arguments.check_arguments`), the result it writes, the results it reads and the
figures it draws; the workflow's rules, the study's targets and the upstream checks derive
from it (:func:`gearmesh.registry.stages`, docs/architecture.md "Each stage declared once"). Every bound is
this module's or :mod:`gearmesh.limits`'s. Engineering units, the unit in the key name
(``torque_Nm``, ``speed_rpm``). Reading a config imports no physics: this module needs :mod:`gearmesh.choices`,
:mod:`gearmesh.contact_model`, :mod:`gearmesh.limits`, :mod:`gearmesh.schema` and :mod:`gearmesh.stages` only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar, Literal, Mapping

from .choices import (CONTACT_LAWS, DEFAULT_CONTACT_LAW, DEFAULT_CYCLE_POSITIONS, DEFAULT_TOOTH_METHOD,  # noqa: F401
                      PAIR_EXCITATIONS, TOOTH_METHODS)
from .contact_model import (DEFAULT_LTCA_POINTS, DEFAULT_TABLE_POINTS, LoadedContactSection, OverridingContactSection,
                            TableContactSection)
from .limits import FACTOR_RANGES, MAX_CONTACT_POINTS, MAX_LTCA_TORQUES, MAX_STIFFNESS_POINTS
from .schema import REQUIRED, nested_sections, setting
from .stages import (Figure, Grid, Read, Speeds, Stage, Table, Torques, always, contact_drives, ltca_drives, method_fe,
                     runs)

#: Names of studies and of the pairs a study uses: a folder of results/{study}/{pair}/, no path characters.
NAME = r"^[A-Za-z0-9_-]+$"
#: Longest study, pair or variant name in a study: results/{study}/{pair}/{variant}/ stays a short path.
NAME_LENGTH = 64
#: The slice models of the tooth compliance (:mod:`gearmesh.stiffness`, :mod:`gearmesh.fe`).
Method = Literal[TOOTH_METHODS]
Gear = Literal["pinion", "gear"]
ContactLaw = Literal[CONTACT_LAWS]
#: What drives the 8-DOF pair (:mod:`gearmesh.dynamics`); how each speed reaches its steady state.
PairExcitation = Literal[PAIR_EXCITATIONS]
SteadyState = Literal["shooting", "transient"]

_METHOD = ("slice model of the tooth compliance: traditional, improved or transition (hob fillet) potential-energy "
           "cantilever, or fe (2-D finite elements)")
_CORNER = "candidate tip-edge contacts beyond the active zone, in transverse base pitches"
_LAW = "local contact law: palmgren (F ∝ δ^1.11 per slice) or linear"


# Settings that several sections have, declared once each (a fresh dataclass field per call).


def _method(extra: str = "") -> Any:
    return setting(DEFAULT_TOOTH_METHOD, _METHOD + extra)


def _slices() -> Any:
    return setting(200, "slices over the face width", minimum=1, maximum=20000)


def _positions(default: int = 360, maximum: int = 100000, what: str = "") -> Any:
    return setting(default, f"rotation positions over one mesh cycle{what}", minimum=8, maximum=maximum)


def _points(default: int = DEFAULT_LTCA_POINTS, what: str = "") -> Any:
    return setting(default, f"points per contact line{what}", minimum=2, maximum=2000)


def _contact_law(what: str = "") -> Any:
    return setting(DEFAULT_CONTACT_LAW, _LAW + what)


def _corner_extension() -> Any:
    return setting(0.25, _CORNER, minimum=0, maximum=1)


def _torque_on() -> Any:
    return setting("pinion", "the gear torque_Nm acts on")


def _pairs() -> Any:
    return setting(REQUIRED, "the pairs (names in pairs_dir)", min_items=1, pattern=NAME, max_length=NAME_LENGTH)


def lste_compared(config: Mapping[str, Any], section: str) -> bool:
    """Whether the study compares the LTCA with F/K: it runs the LTCA on the standard variant and
    the stiffness stage has an LSTE torque.

    Parameters
    ----------
    config : Mapping
        The study config, defaults filled.
    section : str
        The section of the job asking (unused: the signature of a ``wanted`` condition).
    """
    return "ltca" in config and "standard" in config.get("variants", {}) and "torque_Nm" in config.get("stiffness", {})


def engagement_tabled(config: Mapping[str, Any], section: str) -> bool:
    """Whether the study sets the energy method's F_s beside the dynamics (the engagement table):
    the real tooth contact drives its dynamics and it has an impact section.

    Parameters
    ----------
    config : Mapping
        The study config, defaults filled.
    section : str
        The section of the job asking (unused, as in :func:`gearmesh.stages.contact_drives`).
    """
    return contact_drives(config, section) and "impact" in config


def nsga2_run(run: Mapping[str, Any]) -> bool:
    """Whether an optimisation (its settings) is NSGA-II's, with a Pareto front to draw.

    Parameters
    ----------
    run : Mapping
        One named run of the ``optimise`` section, defaults filled.
    """
    return run["method"] == "nsga2"


#: The work limits of a stage's contact grid and of its slice grid (gearmesh.limits).
_CONTACT_GRID = Grid("points", "positions", MAX_CONTACT_POINTS, "contact candidates per line", extra=1)
_SLICE_GRID = Grid("slices", "positions", MAX_STIFFNESS_POINTS, "slice-positions")


def fe_wanted(config: Mapping[str, Any], section: str) -> bool:
    """Whether a study gets the pair's finite-element tooth tables (its ``section``,
    fe_compliance, is always filled): when a stage of it uses the FE tooth (its ``method``, or
    among a table's ``methods``), so that every pair's tables are computed once and drawn.

    Parameters
    ----------
    config : Mapping
        The study config, defaults filled.
    section : str
        ``fe_compliance`` (unused: the signature of a ``wanted`` condition).
    """
    return any((config.get(s) or {}).get("method") == "fe" or "fe" in (config.get(s) or {}).get("methods", ())
               for s, _ in nested_sections(Study) if isinstance(config.get(s), Mapping))


@dataclass(frozen=True, kw_only=True)
class SpeedRange:
    """Speeds from start to stop (included) in steps of step."""

    start: float = setting(REQUIRED, "first speed", units="r/min", exclusive_minimum=0)
    stop: float = setting(REQUIRED, "last speed (included when on the grid)", units="r/min", exclusive_minimum=0)
    step: float = setting(REQUIRED, "speed step", units="r/min", exclusive_minimum=0)


# --------------------------------------------------------------------------------------
# Pair stages
# --------------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class Geometry:
    """Grids of the geometry stage: the transverse tooth profile with its hob fillet and the
    flank surface of each gear (geometry.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.geometry:geometry_dataset", "geometry.nc", "pair", category="Geometry",
        draws="gearmesh.plots.geometry:geometry_figures", figures=(Figure("tooth_profile"),))
    involute_points: int = setting(120, "points on each involute flank of the transverse profile", minimum=8,
                                   maximum=5000)
    fillet_points: int = setting(60, "points on each root fillet (the hob's trochoid)", minimum=4, maximum=5000)
    face_points: int = setting(21, "points across the face width of the flank surface", minimum=2, maximum=2000)


@dataclass(frozen=True, kw_only=True)
class ContactLines:
    """Contact lines in the plane of action and their total length over one mesh cycle (contact_lines.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.geometry:contact_lines_dataset", "contact_lines.nc", "pair",
        category="Contact lines", draws="gearmesh.plots.geometry:contact_lines_figures",
        figures=(Figure("contact_length"), Figure("contact_lines")))
    positions: int = _positions(what=" (one transverse base pitch)")


@dataclass(frozen=True, kw_only=True)
class Stiffness:
    """Time-varying mesh stiffness by the slice potential-energy method, its Fourier series and
    ISO 6336-1's value; with a torque the loaded static transmission error F/K (stiffness.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.stiffness:stiffness_dataset", "stiffness.nc", "pair",
        priority=5,  # every variant's dynamics reads it: done early, it holds none of them back (Dynamics)
        reads=(Read("fe_compliance", method_fe()),), category="Stiffness",
        draws="gearmesh.plots.stiffness:stiffness_figures", figures=(Figure("stiffness"),),
        limits=(_SLICE_GRID, Torques("torque_Nm", "torque_on")))
    method: Method = _method()
    slices: int = _slices()
    positions: int = _positions()
    fourier_order: int = setting(3, "order of the Fourier series fitted to K(φ)", minimum=0, maximum=30)
    torque_Nm: float | None = setting(None, "torque of the loaded static transmission error F/K(φ); left out: none",
                                      exclusive_minimum=0, fill=False)
    torque_on: Gear = _torque_on()


@dataclass(frozen=True, kw_only=True)
class FeCompliance:
    """Finite-element tooth compliance of both gears of every pair along the active profile,
    beside the three potential-energy cantilevers (fe_compliance.nc); stiffness method fe uses
    these settings too."""

    STAGE: ClassVar = Stage("gearmesh.datasets.fe:fe_compliance_dataset", "fe_compliance.nc", "pair",
        category="Stiffness", draws="gearmesh.plots.fe:fe_compliance_figures", figures=(Figure("fe_compliance"),),
        wanted=fe_wanted, priority=10)  # with method fe the optimiser (priority 10, the longest job) waits for it
    plane: Literal["strain", "stress"] = setting("strain", "plane strain (a wide face) or plane stress (a thin disc)")
    size: float = setting(0.05, "element edge on the loaded tooth", units="normal modules", minimum=0.01,
                          maximum=0.5)
    roll_nodes: int = setting(17, "load positions along the active profile", minimum=4, maximum=200)


@dataclass(frozen=True, kw_only=True)
class Variant:
    """One micro-geometry variant: a modification that replaces the pair file's, the optimum of
    one of the study's optimisations, or nothing (the unmodified pair)."""

    modification: dict[str, Any] | None = setting(
        None, "{pinion: {...}, gear: {...}} with the six keys of the pair file's modification", fill=False)
    from_: str | None = setting(
        None, "optimise.NAME: the optimum of the study's optimisation NAME "
        "(results/{study}/{pair}/optimise/NAME/pair.yaml)", key="from", pattern=r"^optimise\.[A-Za-z0-9_]+$",
        fill=False)


@dataclass(frozen=True, kw_only=True)
class Tca:
    """Unloaded tooth contact analysis of every pair and variant over one mesh cycle (tca.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.ltca:tca_dataset", "tca.nc", "variant", category="TCA",
        draws="gearmesh.plots.ltca:tca_figures", figures=(Figure("tca"),), limits=(_CONTACT_GRID,))
    positions: int = _positions(DEFAULT_CYCLE_POSITIONS, 10000)
    points: int = _points()
    corner_extension: float = _corner_extension()


@dataclass(frozen=True, kw_only=True)
class Ltca(LoadedContactSection):
    """Loaded tooth contact analysis of every pair and variant at each torque over one mesh
    cycle: loaded and load transmission error, contact pattern, loaded mesh stiffness (ltca.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.ltca:ltca_dataset", "ltca.nc", "variant",
        priority=4,  # with the rating the chain the sign-off table waits for after an optimisation (Dynamics)
        reads=(Read("fe_compliance", method_fe()),), category="LTCA", draws="gearmesh.plots.ltca:ltca_figures",
        figures=(Figure("te_lte"), Figure("contact_pattern")), limits=(_CONTACT_GRID, Torques("torques_Nm")),
        tables=(Table("lte_table", "gearmesh.datasets.ltca:lte_table_dataset", "lte_table.nc", "pair", "LTCA",
                      (Read("ltca", every_variant=True),), csv=True),
                Table("lste_comparison", "gearmesh.datasets.ltca:lste_comparison_dataset", "lste_comparison.nc",
                      "study", "LTCA", (Read("stiffness", every_pair=True), Read("ltca", every_pair=True)), csv=True,
                      wanted=lste_compared)))
    torques_Nm: tuple[float, ...] = setting((400, 1000, 1600), "torques", exclusive_minimum=0, min_items=1,
                                            max_items=MAX_LTCA_TORQUES)
    on: Gear = setting("pinion", "the gear the torques act on")
    positions: int = _positions(DEFAULT_CYCLE_POSITIONS, 10000)
    points: int = _points()
    contact_law: ContactLaw = _contact_law()
    method: Method = _method()
    corner_extension: float = _corner_extension()


@dataclass(frozen=True, kw_only=True)
class Rating:
    """Load capacity of every pair and variant at the LTCA's torques: ISO 6336-2/-3 method B
    (S_H, S_F) with the LTCA's contact pressure, root stress and load factors (rating.nc). Material,
    accuracy, roughness and oil are the pair file's (defaults named in the dataset's notes)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.rating:rating_dataset", "rating.nc", "variant", reads=(Read("ltca"),),
        priority=4,  # after its variant's LTCA, before the study tables (Dynamics)
        category="Load capacity", draws="gearmesh.plots.rating:rating_figures",
        figures=(Figure("pressure_map"), Figure("root_stress_face")),
        limits=(Speeds("speed_rpm"),),  # the README's promise: no rating above the burst speed
        tables=(Table("load_capacity_table", "gearmesh.datasets.rating:load_capacity_table_dataset",
                      "load_capacity_table.nc", "pair", "Load capacity",
                      (Read("rating", every_variant=True), Read("scuffing", runs("scuffing"), every_variant=True)),
                      csv=True),))
    speed_rpm: float = setting(REQUIRED, "pinion speed of the rating", exclusive_minimum=0)
    application_factor: float = setting(1.0, "application factor K_A (ISO 6336-1)", minimum=FACTOR_RANGES["K_A"][0],
                                        maximum=FACTOR_RANGES["K_A"][1])
    life_hours: float | None = setting(None, "required life for Z_NT, Y_NT (null: the long-life end, 1e10 cycles)", exclusive_minimum=0)
    method: Literal["iso", "ltca"] = setting("ltca", "where K_Hbeta, K_Fbeta, K_Halpha, K_Falpha come from: the "
                                                     "standard's methods B/C or the LTCA's load distribution")


@dataclass(frozen=True, kw_only=True)
class Scuffing:
    """Scuffing load capacity of every pair and variant at the rating's speed and load factors:
    Blok's flash temperature of every contact point from the LTCA's line load along the path of
    contact, and the rated values of ISO/TS 6336-20 (flash temperature method: θ_B, S_B) and
    ISO/TS 6336-21 (integral temperature method: θ_int, S_intS) at each LTCA torque (scuffing.nc).
    Oil, roughness and FZG load stage are the pair file's (defaults named in the dataset's notes)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.scuffing:scuffing_dataset", "scuffing.nc", "variant",
        reads=(Read("ltca"), Read("rating")), category="Load capacity", draws="gearmesh.plots.scuffing:scuffing_figures",
        figures=(Figure("flash_temperature"),),
        tables=(Table("scuffing_table", "gearmesh.datasets.scuffing:scuffing_table_dataset", "scuffing_table.nc",
                      "pair", "Load capacity", (Read("scuffing", every_variant=True),), csv=True),))
    path_bins: int = setting(48, "bins of the path of contact A–E in which the figure keeps the largest flash "
                                 "temperature over the face", minimum=4, maximum=10000)


@dataclass(frozen=True, kw_only=True)
class Impact(LoadedContactSection):
    """Mesh-in impact of every pair and variant over a torque × speed grid: where the entering
    pair first touches, edge or surface contact, impact velocity and force by the energy method,
    the variants side by side at the design speed, and a direct simulation of the engagement
    as a check (impact.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.impact:impact_dataset", "impact.nc", "variant",
        priority=6,  # a variant's longest stage (its box search): first once an optimisation ends
        reads=(Read("fe_compliance", method_fe()),), category="Impact", draws="gearmesh.plots.impact:impact_figures",
        figures=(Figure("force_speed", "impact_speed"), Figure("trajectory", "mesh_in_trajectory"),
                 Figure("simulation", "impact_simulation")),
        carries=("tolerances",), variant_name=True, limits=(Torques("torques_Nm"), Speeds("speeds_rpm")),
        tables=(Table("impact_table", "gearmesh.datasets.impact:impact_table_dataset", "impact_table.nc", "pair",
                      "Impact", (Read("impact", every_variant=True),), csv=True,
                      draws="gearmesh.plots.impact:impact_study_figures",
                      figures=(Figure("impact_force"), Figure("robustness"))),))
    torques_Nm: tuple[float, ...] = setting((400, 1000, 1600), "torques of the map", exclusive_minimum=0,
                                            min_items=1, max_items=100)
    on: Gear = setting("pinion", "the gear the torques act on")
    speeds_rpm: tuple[float, ...] = setting((5000,), "pinion speeds of the map", exclusive_minimum=0,
                                            maximum=1000000, min_items=1, max_items=200)
    design_speed_rpm: float = setting(5000, "speed of the variants table and the simulation; one of speeds_rpm",
                                      exclusive_minimum=0, maximum=1000000)
    driver: Gear = setting("pinion", "the gear that drives")
    points: int = _points(what=" of the loaded contact")
    energy_velocity: Literal["transverse", "normal"] = setting(
        "transverse", "velocity in ½ m_eq v²: transverse (consistent with m_eq) or normal (the source literally)")
    added_inertia_kg_m2: tuple[float, float] = setting(
        (0.0, 0.0), "inertia of what hangs on each shaft [pinion, gear], added to the gear bodies'", minimum=0)
    simulate_torques_Nm: tuple[float, ...] = setting(
        (), "torques (among torques_Nm) whose engagement is also integrated in time at the design speed",
        exclusive_minimum=0, max_items=20)
    contact_law: ContactLaw = _contact_law()
    method: Method = _method()
    corner_extension: float = _corner_extension()
    window_positions: int = setting(32, "rolls of the mesh-in search window (one base pitch and the corner "
                                        "extension)", minimum=8, maximum=10000)
    face_samples: int = setting(257, "samples of the entering contact line across the face (its smallest "
                                     "separation)", minimum=9, maximum=100000)
    design_torque_Nm: float | None = setting(
        None, "torque the load windows are anchored at, one of torques_Nm (null: the middle one)",
        exclusive_minimum=0)
    load_window_step_Nm: float | None = setting(
        None, "F_s also on a torque grid of this step up to 1.25 × the largest torque at the design speed: the "
        "variants' load windows in the impact table (null: none)", exclusive_minimum=0)
    tolerance_torques_Nm: tuple[float, ...] | None = setting(
        None, "torques (among torques_Nm) at which the manufactured gears are judged (the worst over the "
        "tolerance box, the populations): the sign-off table's, the LTCA's (null: every one of torques_Nm)",
        exclusive_minimum=0, min_items=1, max_items=100)


# --------------------------------------------------------------------------------------
# Optimisation and tolerances
# --------------------------------------------------------------------------------------


def _mesh_orders(description: str) -> Any:
    """Loaded-TE mesh orders, default 1 and 2, distinct, from 1 to 3: the orders ltca.nc and the
    optimiser's criteria compute (gearmesh.ltca.MESH_ORDERS)."""
    return setting((1, 2), description, minimum=1, maximum=3, min_items=1, max_items=3, unique=True)


def _ratio_limit(what: str, after: str = "") -> Any:
    """A constraint "``what`` at most this times the unmodified pair's[``after``]" (null: free)."""
    return setting(None, f"{what} at most this times the unmodified pair's{after} (null: free)", exclusive_minimum=0)


@dataclass(frozen=True, kw_only=True)
class Constraints:
    """Constraints of an optimisation as penalties: J = f + penalty·f_std·Σ max(0, m/(factor·m_std) − 1),
    m against the unmodified pair's m_std."""

    lte_factor: float | None = _ratio_limit("loaded transmission error peak-to-peak at the design torque")
    line_load_factor: float | None = _ratio_limit("largest line load at the design torque")
    dynamic_factor: float | None = _ratio_limit("dynamic factor at every torque")
    harmonic_factor: float | None = _ratio_limit("amplitude of each loaded-TE mesh order of harmonic_orders at every "
                                                 "spectrum torque")
    harmonic_orders: tuple[int, ...] = _mesh_orders("the loaded-TE mesh orders of harmonic_factor (and of NSGA-II's "
                                                    "te_harmonics)")
    pressure_factor: float | None = _ratio_limit("largest contact pressure at every spectrum torque", ", flank against "
                                                 "flank and tip edge against tip edge")
    root_stress_factor: float | None = _ratio_limit("largest tooth-root stress of either gear at every spectrum torque")
    impact_factor: float | None = _ratio_limit("nominal impact force F_s at every spectrum torque")
    worst_impact_factor: float | None = _ratio_limit("the worst nominal F_s over the spectrum torques", " worst")
    criteria_over_samples: bool = setting(
        True, "evaluate the loaded-contact criteria (LTE, line load, TE orders, pressure, root stress) for every "
        "manufactured gear (the nominal and the tolerance samples) and reduce each by tolerance_statistic, against the "
        "unmodified pair's population likewise, as ISO 6336-1's K_Hbeta counts the lead deviation; false, or no "
        "tolerance_statistic: the nominal gears. S_Hmin and S_Fmin stay nominal")
    S_Hmin: float | None = setting(
        None, "ISO 6336-2 safety factor against pitting of the weaker gear at every spectrum torque at least this "
        "(method B at speed_rpm, K_Hbeta and K_Halpha from the candidate's LTCA; null: free)", exclusive_minimum=0,
        maximum=10)
    S_Fmin: float | None = setting(
        None, "ISO 6336-3 safety factor against tooth breakage of the weaker gear at every spectrum torque at least "
        "this (as S_Hmin; null: free)", exclusive_minimum=0, maximum=10)
    penalty: float = setting(10, "weight of a violated constraint", exclusive_minimum=0)


@dataclass(frozen=True, kw_only=True)
class Optimise(OverridingContactSection):
    """One named optimisation of the six modification parameters per modified gear against the
    mesh-in impact, over a load spectrum and the study's manufacturing tolerances, once per pair
    (results/{study}/{pair}/optimise/NAME/ga.nc and pair.yaml). Its impact model is the study's
    impact section; points, contact_law, corner_extension, window_positions and face_samples
    given here override it."""

    STAGE: ClassVar = Stage("gearmesh.datasets.optimise:optimise_dataset", "ga.nc", "run",
        reads=(Read("fe_compliance", method_fe("impact")),), category="Optimisation",
        draws="gearmesh.plots.optimise:optimise_figures",
        figures=(Figure("convergence", caption="optimise_convergence"),
                 Figure("modification", caption="optimise_modification")),
        carries=("impact", "tolerances"), also_writes=(("pair", "pair.yaml"),), entry="optimise",
        priority=10,  # the longest job, and the variants it writes wait for it: start it first
        log="{pair}/optimise/{run}",
        limits=(Speeds("speed_rpm"), Speeds("dynamic_speeds_rpm"), Torques("torque_Nm"), Torques("torques_Nm")),
        tables=(Table("plot_pareto", "gearmesh.plots.optimise:pareto_figures", None, "run", "Optimisation",
                      (Read("optimise", name="ga"),), figures=(Figure("pareto", caption="optimise_pareto"),),
                      of_runs=nsga2_run, log="{pair}/optimise/pareto_{run}"),))
    method: Literal["ga", "random", "nsga2"] = setting("ga", "genetic algorithm (pygad), random search of the same "
                                                             "budget, or NSGA-II (the objective against pareto_objectives)")
    objective: Literal["force", "velocity", "robust", "dynamic"] = setting(
        "robust", "per torque and manufactured sample: force F_s or velocity |v_n| of the impact; robust: F_s, needing "
        "a load spectrum or tolerance samples; dynamic: the dynamic factor (peak over static mesh force) of the "
        "contact-driven 8-DOF pair over dynamic_speeds_rpm and the resonances within their range")
    population: int = setting(40, "candidates per generation", minimum=4, maximum=10000)
    generations: int = setting(30, "generations", minimum=1, maximum=10000)
    seed: int = setting(0, "seed of the random numbers", minimum=0, maximum=4294967295)
    torque_Nm: float = setting(1000, "design torque, one of torques_Nm when a spectrum is given",
                               exclusive_minimum=0)
    on: Gear = setting("pinion", "the gear the torques act on")
    speed_rpm: float = setting(5000, "pinion speed of the objective", exclusive_minimum=0, maximum=1000000)
    torques_Nm: tuple[float, ...] | None = setting(
        None, "the load spectrum: the objective at every torque (null: the design torque alone)",
        exclusive_minimum=0, min_items=1, max_items=50)
    statistic: Literal["max", "mean"] = setting("max", "over the load spectrum: the worst case or the duty-cycle "
                                                       "mean")
    weights: tuple[float, ...] | None = setting(None, "time shares of torques_Nm for statistic mean (null: equal "
                                                      "shares)", minimum=0)
    tolerance_statistic: Literal["max", "mean", "percentile", "cvar"] | None = setting(
        "max", "over the nominal and the study's tolerance samples (tolerances section); null: the nominal alone "
        "(a single-point optimum when the spectrum is one torque)")
    tolerance_level_percent: float = setting(90, "level of percentile and cvar (cvar below 100)", minimum=0,
                                             maximum=100)
    load_window_step_Nm: float = setting(50, "torque grid of each optimum's load window (finer than torques_Nm), up "
                                             "to 1.25 × the largest torque", exclusive_minimum=0)
    dynamic_speeds_rpm: tuple[float, ...] | None = setting(
        None, "speeds of the dynamic objective or constraint (null: 0.2, 1 and 3 × speed_rpm); each candidate adds "
        "its own resonance speeds within their range", exclusive_minimum=0, maximum=1000000, min_items=2,
        max_items=50)
    backlash_um: float | Literal["pair"] = setting("pair", "backlash of the candidates' dynamics (pair: the pair's "
                                                           "own)", minimum=0, maximum=1000)
    modify: tuple[Gear, ...] = setting(("pinion",), "the gears whose six parameters are optimised", min_items=1,
                                       max_items=2, unique=True)
    bounds: dict[str, tuple[float, float]] = setting(
        {}, "{pair-file modification key: [low, high]} in µm / mm, overriding the default bounds (reliefs and "
        "crowning 0.001–0.015 m_n, relief lengths 0.1–0.8 m_n, unmodified lead length up to half the face)")
    fixed: dict[str, float] = setting({}, "{pair-file modification key: value} in µm / mm: parameters held fixed "
                                          "instead of optimised", minimum=0)
    constraints: Constraints = setting(Constraints(), "")
    pareto_objectives: tuple[Literal["impact", "lte", "te_harmonics", "pressure", "root_stress"], ...] = setting(
        ("impact", "lte"), "method nsga2: the objectives traded, the first 'impact' (the objective J); lte the "
        "peak-to-peak LTE at the design torque, the others the worst ratio to the unmodified pair's over the load "
        "spectrum", min_items=2, max_items=5, unique=True)
    random_baseline: bool = setting(False, "also run the random search of the same budget (convergence plot)")
    mutation_probability: float = setting(0.3, "chance that a gene of an offspring mutates", exclusive_minimum=0,
                                          maximum=1)
    mutation_scale: float = setting(0.1, "standard deviation of the Gaussian mutation step, as a fraction of the "
                                         "gene's range", exclusive_minimum=0, maximum=1)
    keep_elitism: int = setting(2, "best candidates kept unchanged into the next generation", minimum=0)
    points: int | None = setting(None, "points per contact line (null: the impact section's)", minimum=2,
                                 maximum=2000)
    contact_law: ContactLaw | None = setting(None, "local contact law (null: the impact section's)")
    corner_extension: float | None = setting(None, _CORNER + " (null: the impact section's)", minimum=0, maximum=1)
    window_positions: int | None = setting(None, "rolls of the mesh-in search window (null: the impact section's)",
                                           minimum=8, maximum=10000)
    face_samples: int | None = setting(None, "samples of the entering contact line across the face (null: the "
                                             "impact section's)", minimum=9, maximum=100000)
    cycle_positions: int = setting(DEFAULT_CYCLE_POSITIONS, "rotation positions over one mesh cycle of the loaded "
                                                            "contact (LTE, line load; the LTCA stage's and the "
                                                            "impact stage's manufactured gears')", minimum=8,
                                   maximum=10000)


@dataclass(frozen=True, kw_only=True)
class Tolerances:
    """Manufacturing tolerances of the study's gears: the population of manufactured gears that
    the optimisations (tolerance_statistic) and the impact stage (its tolerance spread) evaluate
    beside the nominal. Lead slope of each gear in lead_on within ±f_Hβ of an ISO 1328-1:2013
    flank tolerance class (Formula (10)); every nonzero modification parameter within ± its
    tolerance."""

    grade: int | None = setting(None, "ISO 1328-1:2013 flank tolerance class of the lead slope (null: no lead "
                                      "deviation)", minimum=1, maximum=11)
    lead_on: tuple[Gear, ...] = setting(("pinion", "gear"), "the gears whose lead slope deviates", min_items=1,
                                        max_items=2, unique=True)
    modification: dict[str, float] = setting({}, "{pair-file modification key: ± value} in µm / mm on every nonzero "
                                                 "parameter of either gear", minimum=0)
    samples: int = setting(8, "deviation samples beside the nominal (0: the nominal only)", minimum=0, maximum=4096)
    sampling: Literal["lhs", "corners", "box"] = setting(
        "lhs", "the optimisers' samples: a seeded Latin hypercube, the corners of the tolerance box, or box: the "
        "unmodified pair's worst gears over the tolerance box at both ends of the modification tolerances (each "
        "optimum then checked on its own box)")
    seed: int = setting(0, "seed of the samples: one manufactured population for every optimisation and the impact "
                           "stage", minimum=0, maximum=4294967295)
    population: int = setting(256, "manufactured gears of the distributions beside the worst case (median, P90, "
                                   "gear for gear against the reference), a seeded Latin hypercube (seed), the same "
                                   "gears for every variant", minimum=0, maximum=4096)
    heldout: int = setting(64, "manufactured gears of the held-out check of the verdict, drawn with heldout_seed "
                               "(never seen by an optimiser)", minimum=0, maximum=4096)
    heldout_seed: int = setting(1, "seed of the held-out gears (another population than seed's)", minimum=0,
                                maximum=4294967295)


# --------------------------------------------------------------------------------------
# Dynamics
# --------------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class _Dynamics(TableContactSection):
    """What the 8-DOF pair and the 9-DOF train share: bearings, mesh, contact table, solver."""

    backlash_um: float | Literal["pair"] | None = setting(
        "pair", "total backlash 2b0 along the normal; pair: the pair's own (centre distance and shifts); null: none",
        minimum=0)
    bearing_k_radial_N_per_m: float | Literal["pair"] = setting(
        "pair", "radial support stiffness of every gear (pair: the pair file's supports, the low-fluctuation paper's 1.5e8 when it "
        "gives none; gearmesh.supports)", exclusive_minimum=0)
    bearing_k_axial_N_per_m: float | Literal["pair"] = setting(
        "pair", "axial support stiffness of every gear (pair: the pair file's supports, the low-fluctuation paper's 1e7 when it gives "
        "none)", exclusive_minimum=0)
    bearing_c_radial_Ns_per_m: float = setting(1000, "radial bearing damping", minimum=0)
    bearing_c_axial_Ns_per_m: float = setting(1000, "axial bearing damping", minimum=0)
    damping_ratio: float = setting(0.07, "modal damping ratio ζ of the mesh mode (the mesh damper is sized to give "
                                         "it, bearing damping included)", minimum=0, maximum=1)
    mesh_damping_Ns_per_m: float | None = setting(None, "mesh damping given directly (null: from damping_ratio)",
                                                  minimum=0)
    stiffness_form: Literal["fourier", "table"] = setting("fourier", "mesh stiffness k(t) as its Fourier series to "
                                                                     "fourier_order or as the sampled table")
    fourier_order: int = setting(3, "order of the Fourier series of k(t)", minimum=0, maximum=30)
    method: Method = _method(" (the stiffness when no stiffness stage runs, the contact table)")
    contact_law: ContactLaw = _contact_law(" (contact table)")
    points: int = _points(DEFAULT_TABLE_POINTS, " of the contact table (the first touch at the face-end corner "
                          "converges as 1/points; 200 puts the default pair's within 0.03 mm of roll of 400's)")
    table_positions: int = setting(256, "positions per mesh cycle of the contact table", minimum=16, maximum=100000)
    table_approaches: int = setting(96, "approaches of the contact table", minimum=8, maximum=100000)
    table_force_factor: float = setting(4.0, "the contact table reaches this many times the largest static force",
                                        exclusive_minimum=1, maximum=100)
    steady_state: SteadyState = setting(
        "shooting", "shooting: the periodic steady state by Newton's method on the one-period map (the transient "
        "where it fails); transient: wait out transient_tau time constants")
    courant: float = setting(0.25, "bound on ω_max·Δt of the RK4 step", exclusive_minimum=0, maximum=1)
    steps_per_cycle_min: int = setting(32, "fewest RK4 steps per mesh period", minimum=8)
    transient_tau: float = setting(10.0, "transient length in time constants of the slowest mode",
                                   units="time constants", minimum=1)
    record_cycles: int = setting(8, "mesh periods recorded after the steady state (even)", minimum=2, multiple_of=2)
    # Kept time series: speeds × record_cycles × points_per_cycle × DOF values; 4096 points per mesh
    # period resolve far above max_order, and 200 mesh orders are beyond any RK4 step plan.
    points_per_cycle: int = setting(64, "points per mesh period of the kept time series", minimum=8, maximum=4096)
    max_order: int = setting(10, "highest mesh order of the kept spectra", minimum=1, maximum=200)


@dataclass(frozen=True, kw_only=True)
class Dynamics(_Dynamics):
    """Speed sweeps of the 8-DOF bending-torsion-axial helical pair at one or more torques, once
    per pair and variant: the periodic steady state at each speed, dynamic transmission error,
    mesh force, bearing displacements (dynamics.nc). The mesh stiffness comes from the stiffness
    stage, the ltca excitation from the variant's LTCA, the contact table from the variant's
    micro-geometry."""

    STAGE: ClassVar = Stage("gearmesh.datasets.dynamics:dynamics_dataset", "dynamics.nc", "variant",
        # a variant's impact (6) first, then its dynamics as soon as the LTCA (4) and the stiffness (5) it
        # reads are done, ahead of the rating (4); the study tables (0) after them all
        priority=5,
        reads=(Read("stiffness"), Read("ltca", ltca_drives), Read("fe_compliance", method_fe())), category="Dynamics",
        draws="gearmesh.plots.dynamics:dynamics_figures",
        figures=(Figure("rms", "dynamics_rms"), Figure("spectrum", "dynamics_spectrum"),
                 Figure("engagement", "dynamics_engagement", when=contact_drives)),
        variant_name=True, limits=(Torques("torques_Nm"),),
        # the peak dynamic mesh force against speed of every variant: drawn by the engagement table's
        # job where the study has one, else by a figure job of its own
        tables=(Table("engagement_table", "gearmesh.datasets.dynamics:engagement_table_dataset",
                      "engagement_table.nc", "pair", "Dynamics",
                      (Read("impact", every_variant=True), Read("dynamics", every_variant=True)), csv=True,
                      draws="gearmesh.plots.dynamics:dynamics_variants_figures",
                      figures=(Figure("dynamics_variants"),), wanted=engagement_tabled),
                Table("plot_dynamics_variants", "gearmesh.plots.dynamics:dynamics_variants_figures", None, "pair",
                      "Dynamics", (Read("dynamics", every_variant=True),), figures=(Figure("dynamics_variants"),),
                      wanted=lambda config, section: not engagement_tabled(config, section))))
    torques_Nm: float | tuple[float, ...] = setting(200.0, "one torque or a list", exclusive_minimum=0, min_items=1,
                                                    max_items=20)
    on: Gear = setting("pinion", "the gear the torques act on")
    speeds_rpm: SpeedRange | tuple[float, ...] = setting(SpeedRange(start=500, stop=50000, step=100),
                                                         "pinion speeds of the sweep: {start, stop, step} or a list",
                                                         exclusive_minimum=0, min_items=1)
    excitation: PairExcitation | None = setting(
        None, "contact: the mesh force of the real tooth contact (every tooth pair, tip edges, modifications: the "
        "mesh-in impact happens in the simulation); ltca: the LTCA's loaded stiffness and error; tvms: k(t) with the "
        "unloaded transmission error; lste: e = F/K(t) as the low-fluctuation source does (counts the fluctuation "
        "twice); null: ltca when the study runs the LTCA, else tvms")
    transmission_error_um: tuple[float, ...] | None = setting(
        None, "unloaded transmission error over one mesh cycle, evenly spaced (null: none; must be null when the "
        "study runs the LTCA)")
    sample_speeds_rpm: tuple[float, ...] = setting((5000, 13700, 27000), "speeds whose time series and spectra are "
                                                                         "kept", exclusive_minimum=0, max_items=50)
    refine_resonances: bool = setting(True, "add speeds around each resonance speed the linearised model predicts "
                                            "(on_grid marks the configured ones)")


@dataclass(frozen=True, kw_only=True)
class TrainDynamics(_Dynamics):
    """The 9-DOF plate–blanket–impression train of the printing-press source: three gears alike
    (the pair's gear), the pair's mesh in both meshes, at one load and speed (train.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.dynamics:train_dataset", "train.nc", "variant",
        reads=(Read("stiffness"), Read("fe_compliance", method_fe())), category="Dynamics",
        draws="gearmesh.plots.dynamics:train_figures", figures=(Figure("spectrum", "train_spectrum"),),
        limits=(Torques("torque_Nm", None),))
    static_force_N: float | None = setting(2832, "static normal mesh force, the load when torque_Nm is null",
                                           exclusive_minimum=0)
    torque_Nm: float | None = setting(None, "torque on the plate gear (null: from static_force_N)",
                                      exclusive_minimum=0)
    speeds_rpm: SpeedRange | tuple[float, ...] | None = setting(
        None, "gear speeds: {start, stop, step} or a list (null: the speed of mesh_frequency_Hz)", exclusive_minimum=0,
        min_items=1)
    mesh_frequency_Hz: float = setting(249.4, "mesh frequency when speeds_rpm is null", exclusive_minimum=0)
    excitation: Literal["tvms", "lste", "contact"] | None = setting(
        None, "tvms (null): the slice stiffness with the tip-edge contact the LTCA loads beyond the active zone at the torque; lste: e = F/K(t) as the low-fluctuation source does; contact: the "
        "real tooth contact of the pair in both meshes")
    phase_offsets_cycles: tuple[float, float] = setting((0.0, 0.0), "mesh phase of each mesh, in mesh cycles",
                                                        units="mesh cycles")


@dataclass(frozen=True, kw_only=True)
class Signoff:
    """The sign-off table of every pair (signoff_table.nc): each variant beside the reference at
    every LTCA torque (F_s, swept dynamic peak, loaded-TE orders, peak pressure, root stress, S_H,
    S_F) and whether it meets these criteria against the reference. Needs the ltca, rating and
    impact sections (basis population also tolerance samples); the dynamic criterion needs a
    dynamics section."""

    STAGE: ClassVar = Stage("gearmesh.datasets.signoff:signoff_table_dataset", "signoff_table.nc", "pair",
        reads=tuple(Read(s, when, every_variant=True) for s, when in (
            ("impact", always), ("ltca", always), ("rating", always), ("dynamics", runs("dynamics")))),
        category="Sign-off", csv=True, draws="gearmesh.plots.signoff:signoff_figures", figures=(Figure("signoff"),),
        pair_file=False, localrule=True,
        tables=(Table("signoff_verdict", "gearmesh.datasets.verdict:signoff_verdict_dataset", "signoff_verdict.nc",
                      "pair", "Sign-off", (Read("signoff"),), csv=True),))
    reference: str = setting("standard", "the variant the others are held against (the unmodified pair)",
                             pattern=r"^[A-Za-z0-9_]+$", max_length=NAME_LENGTH)
    basis: Literal["population", "nominal"] = setting(
        "population", "the gear the pressure, root-stress and TE-order criteria judge: population, the worst "
        "manufactured gear (the nominal and the tolerances section's samples, impact model; as the optimiser) "
        "against the reference's worst; nominal, the nominal gear (ltca and rating stages)")
    pressure_factor: float = setting(1.1, "peak contact pressure (flank or tip edge) at most this times the "
                                          "reference's", exclusive_minimum=0)
    root_stress_factor: float = setting(1.1, "peak tooth-root stress at most this times the reference's",
                                        exclusive_minimum=0)
    harmonic_orders: tuple[int, ...] = _mesh_orders("mesh orders of the loaded-TE amplitudes held against the "
                                                    "reference's")
    harmonic_factor: float = setting(1.0, "loaded-TE amplitudes at harmonic_orders at most this times the "
                                          "reference's", exclusive_minimum=0)
    impact_factor: float = setting(1.0, "F_s (nominal, at the impact section's design speed) below this times "
                                        "the reference's at every torque", exclusive_minimum=0)
    worst_impact_factor: float = setting(0.5, "the worst F_s over the torques at most this times the reference's "
                                              "worst", exclusive_minimum=0)
    dynamic_factor: float = setting(1.0, "largest dynamic mesh force over the speed sweep at most this times the "
                                         "reference's", exclusive_minimum=0)


@dataclass(frozen=True, kw_only=True)
class DynamicsComparison:
    """RMS changes between the study's pairs over their speed sweeps (dynamics_comparison.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.dynamics:dynamics_comparison_dataset", "dynamics_comparison.nc", "study",
        reads=(Read("dynamics", every_pair=True),), category="Dynamics", csv=True,
        draws="gearmesh.plots.dynamics:dynamics_comparison_figures", figures=(Figure("dynamics_comparison"),),
        pair_file=False, localrule=True)
    couples: tuple[tuple[str, str], ...] | None = setting(
        None, "[pair, reference] couples; left out: every pair against the first", min_items=1, fill=False)


# --------------------------------------------------------------------------------------
# Study-level tables
# --------------------------------------------------------------------------------------

@dataclass(frozen=True, kw_only=True)
class HelixSweep:
    """Contact-line length against helix angle for some pairs, each angle a new pair at its
    zero-backlash centre distance (helix_sweep.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.geometry:helix_sweep_dataset", "helix_sweep.nc", "study",
        category="Contact lines", draws="gearmesh.plots.geometry:helix_sweep_figures", figures=(Figure("helix_sweep"),))
    pairs: tuple[str, ...] = _pairs()
    start_deg: float = setting(REQUIRED, "first helix angle", minimum=0, maximum=59)
    stop_deg: float = setting(REQUIRED, "last helix angle (not below start_deg)", minimum=0, maximum=59)
    step_deg: float = setting(REQUIRED, "helix angle step", exclusive_minimum=0)
    positions: int = _positions()


@dataclass(frozen=True, kw_only=True)
class LowFluctuationDesign:
    """Integer-overlap-ratio designs of some pairs: the helix angle (forward and backward) or face
    width that makes the overlap ratio an integer (low_fluctuation_design.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.geometry:low_fluctuation_design_dataset", "low_fluctuation_design.nc",
                            "study", category="Geometry", csv=True, localrule=True)
    pairs: tuple[str, ...] = _pairs()


@dataclass(frozen=True, kw_only=True)
class StiffnessTable:
    """Mesh stiffness over pairs, pair-file variants and cantilever methods, one table (stiffness_table.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.stiffness:stiffness_table_dataset", "stiffness_table.nc", "study",
        category="Stiffness", csv=True, draws="gearmesh.plots.stiffness:stiffness_table_figures",
        figures=(Figure("stiffness_table"),), limits=(_SLICE_GRID, Torques("torque_Nm", "torque_on")))
    pairs: tuple[str, ...] = _pairs()
    methods: tuple[Method, ...] = setting(("transition",), "slice models compared", min_items=1)
    variants: dict[str, dict[str, Any]] | None = setting(
        None, "name → pair-file keys to override (engineering units), e.g. {normal_pressure_angle_deg: 16}; left "
        "out: the pairs as given", key_pattern=r"^[A-Za-z0-9_.-]+$", key_max_length=NAME_LENGTH, fill=False)
    slices: int = _slices()
    positions: int = _positions()
    torque_Nm: float | None = setting(None, "torque of the loaded static transmission error; left out: none",
                                      exclusive_minimum=0, fill=False)
    torque_on: Gear = _torque_on()


@dataclass(frozen=True, kw_only=True)
class SliceConvergence:
    """Mean mesh stiffness against the slice count, whole and clipped end slices (slice_convergence.nc)."""

    STAGE: ClassVar = Stage("gearmesh.datasets.stiffness:slice_convergence_dataset", "slice_convergence.nc", "study",
        category="Stiffness", csv=True, draws="gearmesh.plots.stiffness:slice_convergence_figures",
        figures=(Figure("slice_convergence"),), limits=(_SLICE_GRID,))
    pairs: tuple[str, ...] = _pairs()
    slices: tuple[int, ...] = setting((25, 50, 100, 200, 400, 1000), "slice counts", minimum=1, maximum=20000,
                                      min_items=2)
    method: Method = _method()
    positions: int = _positions()


# --------------------------------------------------------------------------------------
# The study
# --------------------------------------------------------------------------------------


@dataclass(frozen=True, kw_only=True)
class Study:
    """One study: which gear pairs to run, which stages and how finely. Engineering units in the
    key names. A section left out is a stage not run, except geometry, contact_lines, stiffness
    and variants, which every study has (their defaults filled)."""

    study: str = setting(REQUIRED, "study name; results go to results/{study}/", pattern=NAME, max_length=NAME_LENGTH)
    description: str = setting("", "what the study shows")
    source: str = setting("", "the source document the study reproduces")
    pairs_dir: str = setting("config/pairs", "folder of the pair files, relative to the working directory")
    pairs: tuple[str, ...] = setting(REQUIRED, "pair names, each a file {pairs_dir}/{name}.yaml", min_items=1,
                                     unique=True, pattern=NAME, max_length=NAME_LENGTH)
    geometry: Geometry = setting(Geometry(), "")
    contact_lines: ContactLines = setting(ContactLines(), "")
    helix_sweep: HelixSweep | None = setting(None, "", fill=False)
    low_fluctuation_design: LowFluctuationDesign | None = setting(None, "", fill=False)
    stiffness: Stiffness = setting(Stiffness(), "")
    fe_compliance: FeCompliance = setting(FeCompliance(), "")
    stiffness_table: StiffnessTable | None = setting(None, "", fill=False)
    slice_convergence: SliceConvergence | None = setting(None, "", fill=False)
    variants: dict[str, Variant] = setting(
        {"standard": {}}, "micro-geometry variants of every pair by name; standard is the unmodified pair. The "
        "later stages (tca, ltca, impact, dynamics) run once per variant: results/{study}/{pair}/{variant}/",
        key_pattern=r"^[A-Za-z0-9_]+$", key_max_length=NAME_LENGTH)
    tca: Tca | None = setting(None, "", fill=False)
    ltca: Ltca | None = setting(None, "", fill=False)
    rating: Rating | None = setting(None, "", fill=False)
    scuffing: Scuffing | None = setting(None, "", fill=False)
    impact: Impact | None = setting(None, "", fill=False)
    signoff: Signoff | None = setting(None, "", fill=False)
    optimise: dict[str, Optimise] | None = setting(
        None, "named optimisations {NAME: settings}; a variant {from: optimise.NAME} runs the later stages on the "
        "optimum", key_pattern=r"^[A-Za-z0-9_]+$", key_max_length=NAME_LENGTH, fill=False)
    tolerances: Tolerances | None = setting(None, "", fill=False)
    dynamics: Dynamics | None = setting(None, "", fill=False)
    train_dynamics: TrainDynamics | None = setting(None, "", fill=False)
    dynamics_comparison: DynamicsComparison | None = setting(None, "", fill=False)

