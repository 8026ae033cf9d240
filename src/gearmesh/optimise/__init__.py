"""Micro-geometry optimisation against the mesh-in impact (the mesh-in impact paper) over a load spectrum and the
manufacturing tolerances, with pygad.

Genes
-----
The mesh-in impact paper's six modification parameters y1..y6 (root and tip relief amounts, their lengths,
lead crowning, unmodified lead length; :data:`gearmesh.surface.MODIFICATION_FIELDS`) of
the gear(s) being modified, in engineering units (µm for amounts, mm for lengths: the
pair-file keys). The mesh-in impact paper's bounds, in terms of the normal module m_n and the face width B:

    0.001 m_n ≤ y1, y2, y5 ≤ 0.015 m_n,   0.1 m_n ≤ y3, y4 ≤ 0.8 m_n,   0 < y6 ≤ 0.5 B,

each overridable; any gene can be fixed instead. Every decoded candidate is a valid
modification by construction (:func:`gearmesh.surface.fit_modifications`): relief lengths whose
sum exceeds the active roll length of the flank are scaled down to fit it, an amount without a
length (or the reverse) is no relief, and the unmodified lead length stays inside the face — so
:func:`gearmesh.gear.validate_modifications` accepts every candidate and a run never
stops on one.

Objective
---------
A quantity per (torque, manufactured sample) — ``force``: the mesh-in impact paper's F_s^max
(:func:`gearmesh.impact.impact_response`, closed form) at the pinion speed ``speed_rpm``;
``velocity``: the impact velocity |v_n| (the mesh-in impact paper's alternative); ``robust``: F_s like
``force``, the name for its load-spectrum and tolerance form (refused without either);
``dynamic``: the peak dynamic mesh force (not available yet: one function, added to
:data:`OBJECTIVE_VALUES`) — reduced in two steps:

1. over the **load spectrum** ``torques`` (pinion torques; default the design torque alone):
   the worst case (``statistic: max``) or the duty-cycle mean (``mean`` with ``weights`` the
   time shares) — one number per manufactured gear;
2. over the **manufactured population** (:mod:`gearmesh.tolerance`: the nominal and the
   tolerance samples, drawn once per run): ``tolerance_statistic`` max, mean, percentile or
   CVaR at ``tolerance_level`` %; None evaluates the nominal alone.

Every gear of the population is scored over the whole spectrum first, because a gear is made
once and then runs the whole duty cycle. The mesh-in impact paper asks for the modification that minimises the
impact "across a specified operational load range" and warns that a single-load optimum
degrades off-design; a single-torque nominal objective finds grazing touches (zero closing
velocity at exactly one load) that are worse elsewhere. A candidate whose entering pair never
touches in the search window (scenario 'none') or whose value is not finite, at any torque
and sample evaluated, is *failed*: its objective is :data:`FAILURE_FACTOR` times the standard
gear's, and failures are counted. So is a candidate whose touch has no closing velocity (a
crossing the impact model did not resolve: its zero force would be an artefact the GA would
exploit).

Constraints (optional) are an exterior static penalty (Homaifar, Qi & Lai 1994, Simulation
62(4); Coello Coello 2002, Comput. Methods Appl. Mech. Engrg. 191, §3.1): with m_k a criterion
of the loaded contact (:func:`gearmesh.impact.ltca_criteria`: LTE, line load, TE orders,
pressure, root stress; by default the tolerance statistic over the manufactured gears,
``criteria_over_samples``) or of the impact and the dynamics, and m_k,std the standard gear's,

    J = f + penalty · f_std · Σ_k max(0, m_k / (factor_k · m_k,std) − 1),

so a candidate that spoils a criterion by more than ``factor_k`` pays in
proportion to the excess, in units of the standard gear's objective f_std.

Diagnostics of every optimum (:func:`diagnose`): its **load window** — the contiguous range of
torques around the design torque over which its F_s beats the standard gear's, on a grid of
``load_window_step`` finer than the spectrum (:func:`load_grid`) — its F_s under every
tolerance sample at each spectrum torque (the **spread**), and the scenario at each torque.

Methods
-------
``ga``: pygad's GA as its authors intend — three-argument fitness returning −J (pygad
maximises), one batch per generation (``fitness_batch_size`` = population; the batch is every
candidate × torque × sample in one impact evaluation), per-gene ``gene_space`` {low, high},
``random_seed``, ``on_generation`` recording the history.
Mutation is Gaussian (:func:`_gaussian_mutation`, a pygad user-defined mutation), crossover
scattered (uniform), parents by 3-tournament, the best ``keep_elitism`` kept.
``nsga2``: pygad's NSGA-II on (F_s, LTE p-p) at the design torque, with the Pareto front of
every evaluated candidate. ``random``: uniform random search with the GA's nominal budget
(population × (generations + 1) evaluations, the same seed handling); as the baseline of a GA
run (``random_baseline``) it gets exactly the GA's number of distinct evaluations. Candidates already
evaluated are not evaluated again (a cache keyed by the genes), so ``evaluations`` counts
distinct candidates. Same settings and seed → bit-identical history and optimum.

The package
-----------
One module per topic, data flowing down this list: :mod:`~gearmesh.optimise.checks` (the run's
settings, resolved once from the declaration), :mod:`~gearmesh.optimise.genes` (genes, bounds, decoding),
:mod:`~gearmesh.optimise.evaluation` (the problem, an evaluation, the objective quantities),
:mod:`~gearmesh.optimise.constraints` (criteria, ratios, safety factors, the penalised objective),
:mod:`~gearmesh.optimise.objective` (the problem set up, candidates evaluated, an optimum diagnosed)
and :mod:`~gearmesh.optimise.search` (the runs and the optimum's verification). This file
re-exports their public names, so ``from gearmesh.optimise import X`` keeps working; inside the
package each name is imported from its module.
"""

from __future__ import annotations

from ..impact.energy import load_grid, load_window
from .checks import (LOAD_STATISTICS, METHODS, OBJECTIVES, PARETO_OBJECTIVES, OptimiseSettings, check_rules,
                     resolve_settings)
from .genes import GENE_KEYS, GENE_SYMBOLS, GENE_UNITS, Gene, decode, gene_table, impact_paper_bounds
from .evaluation import (FAILURE_FACTOR, OBJECTIVE_VALUES, Evaluation, ImpactValues, Problem, impact_values,
                         load_statistic)
from .constraints import constraint_factors, safety_factors, worst_ratio
from .objective import Diagnostics, diagnose, evaluate, problem, standard_penalised_objective
from .search import LOG, VERIFY_LIMIT, History, OptimisationResult, Verification, optimise, pareto_mask, random_search

__all__ = [
    "GENE_KEYS", "GENE_SYMBOLS", "GENE_UNITS", "METHODS", "OBJECTIVES", "PARETO_OBJECTIVES", "OBJECTIVE_VALUES", "FAILURE_FACTOR", "Gene",
    "OptimiseSettings", "resolve_settings", "check_rules", "impact_paper_bounds", "gene_table", "decode", "Problem",
    "problem", "Evaluation", "evaluate", "load_statistic", "load_grid", "load_window", "Diagnostics", "diagnose",
    "History", "OptimisationResult", "optimise", "random_search", "pareto_mask", "worst_ratio", "constraint_factors",
    "safety_factors", "ImpactValues", "impact_values", "LOAD_STATISTICS", "standard_penalised_objective", "LOG",
    "VERIFY_LIMIT", "Verification",
]
