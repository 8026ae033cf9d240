"""Lumped-parameter gear dynamics: the 8-DOF helical pair (the low-fluctuation paper §4) and the 9-DOF
three-gear train (the improved potential-energy paper), with time-varying mesh stiffness or the real tooth contact and
backlash, integrated over a whole speed sweep.

The subpackage, data flowing one way: :mod:`~gearmesh.dynamics.excitation` (what drives a mesh:
stiffness and error, or the contact table of :mod:`gearmesh.meshforce`) →
:mod:`~gearmesh.dynamics.model` (mass, bearing and mesh matrices, reduced) →
:mod:`~gearmesh.dynamics.integrate` (the compiled RK4 sweep) → :mod:`~gearmesh.dynamics.reference`
(the numpy batch RK4 it replaced and solve_ivp on the full equations, for checks).

Conventions (SI: m, rad, s, N, kg). The frame is gearmesh's (:mod:`gearmesh.contact`): the
pinion centre at the origin, the gear centre at (a, 0, 0), x along the line of centres, the
pinion turning counter-clockwise about +z, the transverse line of action along
d = (sin αwt, cos αwt). Every rotation θ is measured positive in the sense in which that gear
turns (pinion counter-clockwise, gear clockwise), as φ1, φ2 of :mod:`gearmesh.contact`.

8-DOF pair (the low-fluctuation paper §4, corrected)
-----------------------------------
Coordinates x_p, y_p, z_p, θ_p, x_g, y_g, z_g, θ_g. The dynamic transmission error along the
*normal* to the flanks (the seed's "mesh line") is::

    δ = cos βb·[(x_p − x_g) sin αwt + (y_p − y_g) cos αwt + r_b1 θ_p − r_b2 θ_g]
        − h (z_p − z_g) sin βb − e(t)                                          (1)

with h = +1 for a right-hand pinion, −1 for a left-hand one. The mesh force (normal) is::

    F = [c_m δ̇ + k_m(t) f(δ)]·[in contact],   f(δ) = δ (δ > 0), 0 (−2b0 ≤ δ ≤ 0),
                                                     δ + 2b0 (δ < −2b0)        (2)

and the equations of motion follow from the virtual work −F ∂δ/∂q::

    m_p ẍ_p + c_x ẋ_p + k_x x_p = −F sin αwt cos βb     m_g ẍ_g + … = +F sin αwt cos βb
    m_p ÿ_p + c_y ẏ_p + k_y y_p = −F cos αwt cos βb     m_g ÿ_g + … = +F cos αwt cos βb
    m_p z̈_p + c_z ż_p + k_z z_p = +h F sin βb            m_g z̈_g + … = −h F sin βb
    I_p θ̈_p = T_in − F r_b1 cos βb                        I_g θ̈_g = F r_b2 cos βb − T_out

What was changed from the low-fluctuation paper's printed equations, and why:

* The projections use the transverse operating pressure angle αwt and the base helix angle
  βb, where the seed writes αn and β: the normal to an involute helicoid lies in the plane
  of action, inclined at βb to the transverse plane (Litvin & Fuentes 2004 §14), and the
  transverse line of action is inclined at αwt to the y axis in this frame; αn and β are
  reference-cylinder angles that no force acts along.
* The rotation term is r_b1 θ_p − r_b2 θ_g (θ_g positive in the gear's sense of rotation)
  with the load torque opposing it, I_g θ̈_g = F r_b2 cos βb − T_out. The seed's
  r_bp θ_p + r_bg θ_g together with I_g θ̈_g + F r_bg cos β = T_out is the same model with
  θ_g measured against the rotation; only with that reading are its signs consistent.
  T_in = T_out r_b1/r_b2 so that the rigid-body mode is in equilibrium.
* The axial sign carries the helix hand: a right-hand pinion slice turns forward as z grows
  (gearmesh.contact), so an axial shift +w of the pinion moves its flank back by w tan βb
  along the transverse line of action; the seed's (Z_g − Z_p) sin β is the right-hand case.
* Backlash: f is the Kahraman & Singh (1990) dead zone with its origin moved to the onset of
  drive-side contact, so that δ is the elastic approach (mean F/k for a steady load), the gap
  is −2b0 < δ < 0 and back-side contact is δ < −2b0. The mesh damper acts only while the
  teeth touch (a viscous damper across an open gap would transmit force without contact).
* Static transmission error e(t): the low-fluctuation paper puts the loaded static TE e = F/K(t) into (1)
  *and* keeps k_m(t) in (2). Then the quasi-static solution still has δ = F/K(t), but the
  approach of the bodies, δ + e (what the rotations and bearings see), is 2F/K(t): the
  stiffness fluctuation is counted twice. The default here (``excitation='tvms'``) is the
  consistent form: e(t) is the *unloaded* (kinematic) TE, zero for unmodified flanks, and
  the fluctuation of k_m(t) is the excitation, whose quasi-static response is an approach
  δ = F/K(t), the LSTE of the low-fluctuation paper §2. ``excitation='lste'`` reproduces the seed literally;
  a tabulated unloaded TE (e.g. from LTCA) can be added with ``transmission_error``.

Stiffness: k_m(t) is the stiffness along the normal, K_n = K/cos²βb, with K the transverse
TVMS of :func:`gearmesh.stiffness.mesh_stiffness`, as a function of the pinion roll
r_b1·Ω·t (Ω the nominal speed; the vibration does not change the mesh phase, the usual
assumption). Either its Fourier series of order 3 (the improved potential-energy paper) or the full tabulated curve
(periodic linear interpolation). Mesh damping: ζ = 0.07 by default (a mid value of the range
0.03–0.17 used in gear-pair models, e.g. Kahraman & Singh 1990, J. Sound Vib. 142:49; Parker,
Vijayakar & Imajo 2000, J. Sound Vib. 237:435) is the *modal damping ratio of the mesh mode*
(the mode with the largest share of its strain energy in the mesh; −Re λ/|λ| of the complex
eigenvalues of the linearised model, bearing damping included): c_m = s·2ζ√(k̄_n m_e),
m_e = 1/[cos²βb·(r_b1²/I_p + r_b2²/I_g)] the torsional equivalent mass along δ, with the scale s
found so (s = 1 with rigid supports; with s = 1 always, on the default pair the mesh mode, which also moves
the bodies on their bearings, would have ζ = 0.095).

Supports (:mod:`gearmesh.supports`): each gear body sits on a radial (x, y) and an axial (z)
spring from the pair file (bearings, with the shaft's bending in series); a rigid direction is
no coordinate of the model (held at zero), so both rigid is the torsional model of ISO 6336-1's
resonance speed n_E1 (:mod:`gearmesh.dynamics.iso6336`).

The rigid-body rotation is removed: the rotations enter only through the relative
(transverse) coordinates q_i = r_b,drv θ_drv − r_b,drn θ_drn of each mesh; with J the
inertias and R the map θ → q, q̈ = R J⁻¹ τ − R J⁻¹ Rᵀ (∂δ/∂q)ᵀ F. The mean rotation never
appears, so long runs cannot drift.

9-DOF train (the improved potential-energy paper)
----------------------
Plate (P) drives blanket (B) drives impression (I): coordinates y, z, θ per gear, y along
the line of centres (the seed's "radial" direction), the three centres on one line. Mesh 1
(P→B) and mesh 2 (B→I) have::

    δ_1 = cos βb [(y_P − y_B) sin αwt + r_b θ_P − r_b θ_B] − h (z_P − z_B) sin βb − e_1(t)
    δ_2 = cos βb [(y_B − y_I) sin αwt + r_b θ_B − r_b θ_I] − h (z_B − z_I) sin βb − e_2(t)

with each θ positive in the direction its gear turns. The axial terms follow from one rule:
a screw motion of a helical gear (axial slide dz with the turn dθ = tan βb dz / r_b, its
helicoid mapped onto itself) changes no δ. The blanket has the other hand *and* turns the
other way, so in its own coordinates its screw has the same sense as the plate's and the
impression's, and its two meshes load it on opposite sides: the idler carries no net
thrust (its two axial forces cancel), plate and impression carry ±F sin βb. The improved potential-energy paper
prints δ_1 = (y_P − y_B) cos βb +
(z_P − z_B) sin βb + r_bP θ_P − r_bB θ_B − e_1: its y term has no pressure-angle projection
and its rotation term no cos βb, which do not follow from one normal direction; the form
above does, and it gives the seed's observations (radial forces on B cancel, P and I move in
opposite phase). The tangential bearing direction is not a degree of freedom in this model
(rigid), as in the seed. Torque T on P, load T on I, B idles.

Excitation by the real contact (``excitation='contact'``)
--------------------------------------------------------
Instead of k_m(t)·f(δ − e(t)), the mesh force is the contact's own: with x = δ/cos βb the
bodies' transverse approach (δ without e) and w the position in the mesh cycle,

    F = F_c(x, w)/cos βb + c_m (δ̇ − cos βb·ġ_min)   while the flanks touch (x > g_min(w)),

F_c the total load of all candidate points of all tooth pairs (flanks and tip edges, both
gears' modifications and lead slopes) from :mod:`gearmesh.meshforce` — the LTCA's contact
model, so its quasi-static limit is the LTCA's loaded TE — and g_min(w) the first-touch
separation (the unloaded TE). The entering pair then touches before A whenever the pairs in
mesh are deflected beyond its separation there, off the line of action, and the mesh-in impact
happens in the simulation. Back flanks (taken as mirror images of the drive flanks, in phase
with them, as the stiffness excitation assumes) touch across the backlash when
−x − 2b0/cos βb > g_min(w). The damper acts on the rate of the elastic approach of the first
touching point and only while flanks touch. The modes, the step size and the starting state use
the linearisation about the static state (the ``ltca`` form built from the same table; the step
from the largest tangent stiffness anywhere in the table).

Solver
------
:func:`simulate` integrates each speed with classical RK4 and a step per speed: m_i steps per
mesh period, m_i = max(m_min, ⌈T_mesh/Δt_max⌉), Δt_max = c/ω_max (ω_max the highest natural
frequency of the linearised model at the maximum stiffness, c = 0.25 by default), so the mesh
phase of every stage is exact. Transients are discarded by physical time (docs/modelling.md):
each speed starts from the static equilibrium of the linearised model, integrates
⌈n_τ/(σ_min T_mesh)⌉ mesh periods with σ_min = min(−Re λ) over its modes (n_τ = 10: transients
decay to e^-10 of their start), then records n_rec whole mesh periods (8). The change of the
deflection fluctuation between the two halves of the record window is kept as a steady-state
check. The step loop is compiled (numba; :mod:`gearmesh.dynamics.integrate`).
"""

from .excitation import EXCITATIONS, FOURIER_TABLE_POINTS, STIFFNESS_FORMS, MeshLaw, contact_mesh_law, mesh_law
from .integrate import FIRST_PART_AFTER_A, MAX_STEPS_PER_SPEED, SolverSettings, SweepResult, simulate, step_plan
from .model import (DAMPING_MEANING, DEFAULT_DAMPING_RATIO, RESONANCE_OFFSETS, full_translations, mesh_mode, LOW_FLUCTUATION_BEARING, TRAIN_GEARS, GearModel, mesh_energy_fraction,
                    pair_model, require_dynamics_data, resonance_band, resonance_speeds, train_model)
from .reference import reference_solution, simulate_numpy

__all__ = [
    "EXCITATIONS", "FOURIER_TABLE_POINTS", "STIFFNESS_FORMS", "MeshLaw", "contact_mesh_law", "mesh_law",
    "FIRST_PART_AFTER_A", "MAX_STEPS_PER_SPEED", "SolverSettings", "SweepResult", "simulate", "step_plan",
    "DAMPING_MEANING", "DEFAULT_DAMPING_RATIO", "full_translations", "mesh_mode", "LOW_FLUCTUATION_BEARING", "TRAIN_GEARS", "GearModel", "pair_model", "require_dynamics_data",
    "resonance_speeds", "resonance_band", "mesh_energy_fraction", "RESONANCE_OFFSETS", "train_model", "reference_solution", "simulate_numpy",
]
