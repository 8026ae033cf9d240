"""Manufacturing tolerances of a pair's micro-geometry: the deviation model, its samples and
the statistics over them.

A gear is never made to its nominal micro-geometry. The deviation model here has two parts:

* each modification parameter of the mesh-in impact paper (relief and crowning amounts, their lengths) lies
  within ± its tolerance (a study setting, µm / mm per pair-file key) — on every flank where the
  nominal parameter is not zero (a relief that is not designed is not made: zero stays zero);
* the lead (helix) slope deviation of each gear lies within ±f_Hβ of an ISO 1328-1 flank
  tolerance class: ISO 1328-1:2013, 5.3.4.1, Formula (10),

      f_HβT = (0.05·√d + 0.35·√b + 4)·(√2)^(A − 5)   µm,  d, b in mm,

  d the reference diameter and b the face width of that gear, A the class (1 … 11); the
  unrounded value (the standard's rounding is for drawings). Its scope (clause 1): 5 ≤ z ≤ 1000,
  5 ≤ d ≤ 15 000 mm, 0.5 ≤ m_n ≤ 70 mm, 4 ≤ b ≤ 1200 mm, β ≤ 45°. f_Hβ is measured over the
  gear's own face width; over the meshing face width b_m it tilts the flank by f·b_m/b
  (:func:`gearmesh.deviation.lead_gap` takes slopes over b_m). The two gears' slopes add in the
  mesh; the separations are linear in them, so a sample costs no new geometry.

Samples are unit deviations u ∈ [−1, 1]^k over the k toleranced quantities (each scaled by its
half-width): ``lhs`` a seeded Latin hypercube (McKay, Beckman & Conover 1979, Technometrics
21(2); scipy.stats.qmc), ``corners`` the vertices of the tolerance box (all 2^k, or a seeded
subset of them). They are drawn once per run — every candidate meets the same manufactured
population (common random numbers), and the same seed gives the same samples bit for bit. The
nominal is always evaluated with them, as sample 0.

Statistics over the samples (:func:`sample_statistic`) — each over the nominal and the samples,
equally weighted: ``max`` (worst case), ``mean``, ``percentile`` (linear interpolation between
order statistics, Hyndman & Fan 1996 definition 7, numpy's default) and ``cvar`` (the
conditional value at risk: the mean of the worst (1 − α) share of the population, with the
share of the atom at the α-quantile; Rockafellar & Uryasev 2002, J. Banking & Finance 26,
Prop. 8 for a discrete distribution).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
from .limits import MAX_CORNER_DIMENSIONS, MAX_SAMPLES
from .surface import fit_modifications

__all__ = ["GRADES", "SAMPLINGS", "STATISTICS", "helix_slope_tolerance", "ToleranceModel", "tolerance_model",
           "unit_deviations", "apply_deviations", "manufactured_population", "sample_statistic", "check_statistic", "study_tolerances",
           "study_population"]

GRADES = tuple(range(1, 12))
SAMPLINGS = ("lhs", "corners", "box")
STATISTICS = ("max", "mean", "percentile", "cvar")
#: Pair-file keys of the six parameters (order of :data:`gearmesh.surface.MODIFICATION_FIELDS`).
_KEYS = ("root_relief_um", "tip_relief_um", "root_relief_length_mm", "tip_relief_length_mm", "crowning_um",
         "unmodified_lead_length_mm")
_TO_SI = np.array([1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-3])


def helix_slope_tolerance(reference_diameter: float, face_width: float, grade: int) -> float:
    """ISO 1328-1:2013 helix slope tolerance f_HβT (m) of a gear of reference diameter d (m) and
    face width b (m) in flank tolerance class ``grade`` (module docstring, Formula (10)).

    Parameters
    ----------
    reference_diameter : float
        d (m).
    face_width : float
        b (m) of that gear.
    grade : int
        Flank tolerance class A (1 … 11).

    Returns
    -------
    float
        f_HβT (m), unrounded.

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth, 5.3.4.1, Formula (10).
    """
    d, b = reference_diameter * 1e3, face_width * 1e3
    return (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4.0) * math.sqrt(2.0) ** (grade - 5) * 1e-6


@dataclass(frozen=True)
class ToleranceModel:
    """Half-widths of the deviations: ``modification`` (2, 6) ± per gear and parameter (m; 0 = held
    exact), ``lead`` (2,) ±f_Hβ per gear (m over the meshing face width); ``grade`` the ISO 1328-1
    class behind ``lead`` (or None). ``dimensions`` lists the toleranced quantities."""

    modification: np.ndarray
    lead: np.ndarray
    grade: int | None = None

    @property
    def dimensions(self) -> list[tuple[str, int, int]]:
        """(kind, gear, parameter) of each toleranced quantity: ('modification', g, k) or ('lead', g, -1)."""
        dims = [("modification", g, k) for g in range(2) for k in range(6) if self.modification[g, k] > 0]
        return dims + [("lead", g, -1) for g in range(2) if self.lead[g] > 0]

    def labels(self) -> list[str]:
        return [f"{GEARS[g]}.{_KEYS[k]}" if kind == "modification" else f"{GEARS[g]}.lead_slope_deviation_um"
                for kind, g, k in self.dimensions]


def _number(field: str, value: Any, low: float, high: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value) or not low <= value <= high:
        raise GearmeshInputError(field, value, f"must be a number in [{low:g}, {high:g}] {unit}")
    return float(value)


def tolerance_model(geom: PairGeometry, grade: int | None = None, lead_on=("pinion", "gear"),
                    modification: Mapping[str, Any] | None = None, field: str = "tolerances") -> ToleranceModel:
    """The deviation model of ``geom``'s pair: lead slope ±f_Hβ of ISO 1328-1 class ``grade`` on the
    gears ``lead_on`` (None: no lead deviation), and ± ``modification`` {pair-file key: value in
    µm / mm} on every nonzero modification parameter. Refuses bad values naming ``field``.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    grade : int, optional
        ISO 1328-1 flank tolerance class (1 … 11) of the lead slope; None: no lead deviation.
        Refused outside the standard's scope (clause 1).
    lead_on : str or sequence of {'pinion', 'gear'}, default both
        The gears whose lead slope deviates.
    modification : mapping, optional
        Half-widths {pair-file key: value} in the key's unit (µm or mm), in [0, 1000].
    field : str, default 'tolerances'
        The config key named in refusals.

    Returns
    -------
    ToleranceModel
        ``modification`` (2, 6) and ``lead`` (2,) half-widths (m; lead over the meshing face width),
        ``grade``.

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth, clause 1 (scope), 5.3.4.1, Formula (10).
    """
    lead = np.zeros(2)
    if grade is not None:
        if isinstance(grade, bool) or not isinstance(grade, (int, np.integer)) or grade not in GRADES:
            raise GearmeshInputError(f"{field}.grade", grade, "must be an ISO 1328-1 flank tolerance class 1 ... 11")
        if isinstance(lead_on, str):
            lead_on = [lead_on]
        if not isinstance(lead_on, (list, tuple)) or len(set(lead_on)) != len(lead_on) or any(
                g not in GEARS for g in lead_on):
            raise GearmeshInputError(f"{field}.lead_on", lead_on, "must name 'pinion', 'gear' or both, once each")
        pair = geom.pair
        widths = np.broadcast_to(np.asarray(pair.face_width, dtype=float), (2,))
        for g in (GEARS.index(name) for name in lead_on):
            d, b = 2.0 * float(geom.reference_radius[g]), float(widths[g])
            scope = ((pair.teeth[g], 5, 1000, "teeth"), (d * 1e3, 5, 15000, "reference diameter (mm)"),
                     (pair.normal_module * 1e3, 0.5, 70, "normal module (mm)"), (b * 1e3, 4, 1200, "face width (mm)"),
                     (math.degrees(pair.helix_angle), 0, 45, "helix angle (deg)"))
            for value, low, high, what in scope:
                if not low <= value <= high:
                    raise GearmeshInputError(f"{field}.grade", grade, f"ISO 1328-1 does not cover the {GEARS[g]}'s "
                                                                     f"{what} {value:.4g} (scope {low} ... {high})")
            lead[g] = helix_slope_tolerance(d, b, int(grade)) * geom.face_width / b
    mod = np.zeros((2, 6))
    for key, value in dict(modification or {}).items():
        if key not in _KEYS:
            raise GearmeshInputError(f"{field}.modification.{key}", value, f"is not a parameter; use {list(_KEYS)}")
        k = _KEYS.index(key)
        unit = "um" if key.endswith("_um") else "mm"
        mod[:, k] = _number(f"{field}.modification.{key}", value, 0.0, 1000.0, unit) * _TO_SI[k]
    return ToleranceModel(modification=mod, lead=lead, grade=None if grade is None else int(grade))


def unit_deviations(dimensions: int, samples: int, sampling: str = "lhs", seed: int = 0) -> np.ndarray:
    """``samples`` deviation samples (S, k) in [−1, 1]^k, k = ``dimensions`` (module docstring):
    a seeded Latin hypercube (``lhs``) or corners of the box (``corners``: all 2^k when
    ``samples`` ≥ 2^k, else a seeded choice of them without repetition, in a fixed order).

    Parameters
    ----------
    dimensions : int
        k, the number of toleranced quantities.
    samples : int
        S requested, in [0, :data:`gearmesh.limits.MAX_SAMPLES`].
    sampling : {'lhs', 'corners'}, default 'lhs'
        Latin hypercube or box corners (at most :data:`gearmesh.limits.MAX_CORNER_DIMENSIONS`).
    seed : int, default 0
        Seed of numpy's default generator.

    Returns
    -------
    ndarray
        (S, k) unit deviations (-); (0, k) when there is nothing to sample; for ``corners``
        S = min(samples, 2^k).

    References
    ----------
    .. [1] M. D. McKay, R. J. Beckman, W. J. Conover, "A comparison of three methods for selecting
       values of input variables in the analysis of output from a computer code", Technometrics
       21(2) (1979) 239–245.
    """
    if sampling not in SAMPLINGS or sampling == "box":  # box: a design's own worst gears (gearmesh.robust)
        raise GearmeshInputError("sampling", sampling, f"must be one of {list(SAMPLINGS[:2])} here")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or not 0 <= samples <= MAX_SAMPLES:
        raise GearmeshInputError("tolerance_samples", samples, f"must be an integer in [0, {MAX_SAMPLES}]")
    if samples == 0 or dimensions == 0:
        return np.zeros((0, dimensions))
    rng = np.random.default_rng(seed)
    if sampling == "lhs":
        from scipy.stats import qmc

        return 2.0 * qmc.LatinHypercube(d=dimensions, seed=rng).random(int(samples)) - 1.0
    if dimensions > MAX_CORNER_DIMENSIONS:
        raise GearmeshInputError("sampling", sampling, f"corners of {dimensions} toleranced quantities are too many "
                                                       f"(at most {MAX_CORNER_DIMENSIONS}); use lhs")
    n = 2**dimensions
    index = np.arange(n) if samples >= n else np.sort(rng.choice(n, size=int(samples), replace=False))
    bits = (index[:, None] >> np.arange(dimensions)[None, :]) & 1
    return 2.0 * bits - 1.0


def apply_deviations(model: ToleranceModel, params: np.ndarray, lead_slope, units: np.ndarray):
    """The manufactured variants of parameter sets ``params`` (C, 2, 6) (m) with nominal lead slopes
    ``lead_slope`` (2,) (m): (C, S + 1, 2, 6) parameters and (C, S + 1, 2) lead slopes, sample 0
    the nominal, sample s the unit deviation ``units[s − 1]`` scaled by the half-widths. A
    deviation applies only where the nominal parameter is nonzero, and amounts and lengths are
    clipped at zero (the caller repairs what the deviation made invalid, e.g. relief lengths that
    no longer fit the flank).

    Parameters
    ----------
    model : ToleranceModel
        Half-widths of the deviations (:func:`tolerance_model`).
    params : ndarray
        (C, 2, 6) nominal modification parameters of C candidates (m, order of
        :data:`gearmesh.surface.MODIFICATION_FIELDS`).
    lead_slope : array_like
        (2,) nominal lead slope deviations (m).
    units : ndarray
        (S, k) unit deviations (:func:`unit_deviations`), k = ``len(model.dimensions)``.

    Returns
    -------
    params : ndarray
        (C, S + 1, 2, 6) parameters (m).
    lead : ndarray
        (C, S + 1, 2) lead slopes (m).
    """
    params = np.asarray(params, dtype=float)
    nc, ns = params.shape[0], units.shape[0]
    p = np.repeat(params[:, None], ns + 1, axis=1)
    lead = np.broadcast_to(np.asarray(lead_slope, dtype=float), (nc, ns + 1, 2)).copy()
    for j, (kind, g, k) in enumerate(model.dimensions):
        if kind == "lead":
            lead[:, 1:, g] += units[:, j] * model.lead[g]
        else:
            nominal = params[:, g, k][:, None]
            p[:, 1:, g, k] = np.where(nominal > 0, np.maximum(nominal + units[:, j] * model.modification[g, k], 0.0),
                                      nominal)
    return p, lead


def manufactured_population(geom: PairGeometry, model: ToleranceModel, params: np.ndarray, lead_slope,
                            units: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The manufactured gears of parameter sets ``params`` (C, 2, 6) (m) with nominal lead slopes
    ``lead_slope`` (2,) (m) as flat rows: parameters (C·(S + 1), 2, 6) and lead slopes
    (C·(S + 1), 2), candidate-major, sample 0 of each candidate the nominal
    (:func:`apply_deviations`), every row made a valid modification
    (:func:`gearmesh.surface.fit_modifications`). The one population of the optimiser and the
    impact stage.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    model : ToleranceModel
        Half-widths of the deviations (:func:`tolerance_model`).
    params : ndarray
        (C, 2, 6) nominal modification parameters of C candidates (m, order of
        :data:`gearmesh.surface.MODIFICATION_FIELDS`).
    lead_slope : array_like
        (2,) nominal lead slope deviations (m).
    units : ndarray
        (S, k) unit deviations (:func:`unit_deviations`), k = ``len(model.dimensions)``.

    Returns
    -------
    params : ndarray
        (C·(S + 1), 2, 6) valid modification parameters (m).
    lead : ndarray
        (C·(S + 1), 2) lead slopes (m).
    """
    p, lead = apply_deviations(model, params, lead_slope, units)
    return fit_modifications(geom, p.reshape(-1, 2, 6)), lead.reshape(-1, 2)


def check_statistic(statistic: str | None, level_percent: float, field: str = "tolerance_statistic") -> None:
    """Refuse an unknown statistic or a level outside its range (percentile [0, 100], cvar [0, 100)).

    Parameters
    ----------
    statistic : {'max', 'mean', 'percentile', 'cvar'} or None
        The statistic; None is the nominal only.
    level_percent : float
        Its level (%).
    field : str, default 'tolerance_statistic'
        The config key named in refusals (its ``level_percent`` sibling for the level).
    """
    if statistic is not None and statistic not in STATISTICS:
        raise GearmeshInputError(field, statistic, f"must be one of {list(STATISTICS)} (or null: nominal only)")
    high = math.nextafter(100.0, 0.0) if statistic == "cvar" else 100.0
    _number(field.replace("statistic", "level_percent"), level_percent, 0.0, high, "%")


def sample_statistic(values: np.ndarray, statistic: str, level_percent: float = 90.0) -> np.ndarray:
    """The statistic over the last axis of ``values`` (samples equally weighted; module docstring):
    ``max``, ``mean``, ``percentile`` at ``level_percent`` or ``cvar`` at α = level_percent/100.

    Parameters
    ----------
    values : array_like
        (..., N) values over the nominal and the samples, in any unit.
    statistic : {'max', 'mean', 'percentile', 'cvar'}
        The statistic.
    level_percent : float, default 90.0
        Level of ``percentile`` and ``cvar`` (%).

    Returns
    -------
    ndarray
        (...) the statistic, in the unit of ``values``.

    References
    ----------
    .. [1] R. J. Hyndman, Y. Fan, "Sample quantiles in statistical packages", The American
       Statistician 50(4) (1996) 361–365 (definition 7).
    .. [2] R. T. Rockafellar, S. Uryasev, "Conditional value-at-risk for general loss distributions",
       Journal of Banking & Finance 26 (2002) 1443–1471 (Proposition 8).
    """
    x = np.asarray(values, dtype=float)
    if statistic == "max":
        return x.max(axis=-1)
    if statistic == "mean":
        return x.mean(axis=-1)
    if statistic == "percentile":
        return np.percentile(x, level_percent, axis=-1)
    if statistic == "cvar":
        alpha = level_percent / 100.0
        n = x.shape[-1]
        s = np.sort(x, axis=-1)
        k = max(1, math.ceil(alpha * n - 1e-12))  # the atom holding the α-quantile (1-based)
        tail = s[..., k:].sum(axis=-1) / n + (k / n - alpha) * s[..., k - 1]
        return tail / (1.0 - alpha)
    raise GearmeshInputError("statistic", statistic, f"must be one of {list(STATISTICS)}")


def study_population(tolerances: Mapping[str, Any] | None) -> tuple[int, int, int, int]:
    """The study's ``tolerances:`` section's populations beside the optimisers' samples: (population,
    seed, heldout, heldout_seed) (:class:`gearmesh.settings.Tolerances`; no section: none).

    Parameters
    ----------
    tolerances : mapping or None
        The study config's ``tolerances:`` section.

    Returns
    -------
    tuple of int
        (population, seed, heldout, heldout_seed); all 0 without a section.
    """
    from .schema import object_schema, validate
    from .settings import Tolerances

    if not tolerances:
        return 0, 0, 0, 0
    tol = validate(tolerances, object_schema(Tolerances), prefix="tolerances")
    return tol["population"], tol["seed"], tol["heldout"], tol["heldout_seed"]


def study_tolerances(geom: PairGeometry, tolerances: Mapping[str, Any] | None):
    """The study's ``tolerances:`` section as (ToleranceModel, samples, sampling, seed); None or {} is
    no tolerance (nominal only). Keys (:class:`gearmesh.settings.Tolerances`): grade (ISO 1328-1 class of the lead slope, null: none),
    lead_on, modification {pair-file key: ±}, samples, sampling, seed (of the samples: the same
    manufactured population for every optimisation and the impact stage).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    tolerances : mapping or None
        The study config's ``tolerances:`` section.

    Returns
    -------
    model : ToleranceModel
        The deviation model (:func:`tolerance_model`).
    samples : int
        Number of samples.
    sampling : str
        'lhs' or 'corners'.
    seed : int
        Seed of the samples.
    """
    from .schema import object_schema, validate
    from .settings import Tolerances

    # checked against the declarations, their defaults filled (no section: no samples either)
    tol = validate(tolerances or {"samples": 0}, object_schema(Tolerances), prefix="tolerances")
    model = tolerance_model(geom, tol["grade"], tol["lead_on"], tol["modification"])
    return model, tol["samples"], tol["sampling"], tol["seed"]
