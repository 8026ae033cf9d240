"""Mesh-in impact of a modified helical pair (the mesh-in impact paper): mesh-in point, impact velocity,
local stiffness and the energy-method impact force — in the TCA/LTCA framework.

Everything inside is SI (m, N, s, rad, kg). Displacements, separations and forces follow the
transverse line-of-action convention of :mod:`gearmesh.tca` and :mod:`gearmesh.ltca`
(transverse displacement r_b1·Δφ1 with the gear held, force F_bt = T1/r_b1).

The event
---------
Under load the pairs already in mesh are compressed by their approach δ(roll) (the LTE);
the entering tooth pair still has its unloaded separation g(roll, z) — flank points in the
active zone and the mating tip edge outside it (:func:`gearmesh.separation.separation_basis`),
with both gears' modifications and lead slope errors. The entering pair first touches at
the first roll where

    min_z g(roll, z) = δ_others(roll),

δ_others the approach of the other pairs alone (the entering pair carries nothing before it
touches). This is the mesh-in impact paper's TE(φ)/LTE(φ) intersection, solved in roll by a bracketing
root-finder (a grid over a window from the outer end of the tip-edge candidates to one
base pitch past the theoretical start of engagement φ1A, then Illinois regula falsi with
the exact separation and a final Newton step on the exact δ). The point of the entering pair
where it happens is the mesh-in point M; the mesh-in impact paper's two scenarios are where M lies:
``edge`` — a tip edge outside the active zone (the mesh-in impact paper scenario 1: "tip point to tooth
surface") — or ``surface`` — two (modified) flanks inside it (scenario 2). One formulation,
no separate code paths.

Driver
------
With the pinion driving the roll grows in time and pairs enter at the start of the path
of contact A (the gear's tip edge meets the pinion flank). With the gear driving (a speed
increaser), the same flanks carry the same static loads (reverse every rotation of a
pinion-driven mesh: the gear now pushes the pinion), so the LTCA is unchanged and time runs
backwards along the path: pairs enter at its end E, the pinion's tip edge meeting the gear
flank. ``tau`` below is the time-like roll σ·(roll − roll_engagement), σ = +1 / −1.

Impact velocity
---------------
The closing rate of g − δ at the touch, v_t = −d(g − δ)/dτ · r_b1·ω1, is the relative
velocity in the transverse line-of-action coordinate — the coordinate of the equivalent mass
m_eq = J1·J2/(J1·r_b2² + J2·r_b1²) (the mesh-in impact paper). Independently, :func:`vector_velocity`
evaluates the mesh-in impact paper's v = (ω1 − ω2) × r − E × ω2 at the true closest points of the two exact
(modified) transverse profiles with their common normal. In the edge case they are the same
quantity exactly (the pinion flank's normal is tangent to its base circle, so the pinion
point's normal velocity is r_b1·ω1 and the gap of the tip edge closes at v·n); in the
surface case they agree to first order in the relief slopes (the true closest points lie off
the line of action by slope/curvature). The 3-D normal velocity is v·n with the helicoid
normal, smaller by cos βb; the mesh-in impact paper puts it into E_k = ½·m_eq·v², which mixes a normal
velocity with a transverse mass: the consistent form is v_t (default,
``energy_velocity='transverse'``), the seed's literal form is kept as ``'normal'``.

Local stiffness and force
-------------------------
The mesh-in impact paper loads the entering pair alone, quasi-statically, with its points' separations
relative to M at the touch instant: here exactly that, with the LTCA's point compliances
(:func:`gearmesh.ltca_model.point_compliance`) and contact law, giving the F–δ curve of the
impact. The energy balance ½·m_eq·v² = ∫F dδ is solved on that curve (piecewise power-law
integration, exact for a pure power law), and F = K_s·δ^n is fitted (log-log least squares
on 24 points evenly spaced in δ over [δ_s/24, δ_s], the range the impact reaches) for seed
000's closed form F_s = ((n+1)/2·m_eq·v²)^(n/(n+1))·K_s^(1/(n+1)). Both are reported.
:func:`simulate_engagement` checks the energy method against a direct time integration of
the same event.

The package
-----------
One module per topic, data flowing down this list: :mod:`~gearmesh.impact.model` (the impact
model of a pair, inertias and equivalent mass), :mod:`~gearmesh.impact.static` (the touch, the
mesh-in point and the F–δ curve), :mod:`~gearmesh.impact.energy` (velocity, energy balance, fitted
stiffness, closed form; the load window), :mod:`~gearmesh.impact.criteria` (the loaded contact over
a mesh cycle), :mod:`~gearmesh.impact.kinematics` (M in 3-D and the independent velocity checks)
and :mod:`~gearmesh.impact.engagement` (the direct time integration). This file re-exports their
public names, so ``from gearmesh.impact import X`` and the ``gearmesh.impact:...`` names of the
stage declarations keep working; inside the package each name is imported from its module.
"""

from __future__ import annotations

from .model import (DRIVERS, SCENARIO_EDGE, SCENARIO_NONE, SCENARIO_SURFACE, SCENARIOS, ImpactModel, WindowPoints,
                    equivalent_mass, impact_model, impact_paper_inertia)
from .static import ImpactStatic, impact_static
from .energy import (ENERGY_VELOCITIES, ImpactResponse, closed_form_force, energy_balance, fit_power_law,
                     impact_response, load_grid, load_window)
from .criteria import LTCACriteria, ltca_criteria, ltca_metrics
from .kinematics import mesh_in_point, seed_edge_roll, vector_velocity
from .engagement import simulate_engagement

__all__ = [
    "SCENARIOS", "DRIVERS", "impact_paper_inertia", "equivalent_mass", "ImpactModel", "impact_model",
    "ImpactStatic", "impact_static", "ImpactResponse", "impact_response", "closed_form_force",
    "energy_balance", "fit_power_law", "vector_velocity", "seed_edge_roll", "simulate_engagement",
    "LTCACriteria", "ltca_criteria", "ltca_metrics", "load_grid", "load_window", "SCENARIO_NONE", "SCENARIO_SURFACE",
    "SCENARIO_EDGE", "ENERGY_VELOCITIES", "WindowPoints", "mesh_in_point",
]
