"""Lumped-parameter gear dynamics: the 8-DOF helical pair (seed 001 §4) and the 9-DOF
three-gear train (seed 004), with time-varying mesh stiffness and backlash, integrated over a
whole speed sweep at once.

Conventions (SI: m, rad, s, N, kg). The frame is gearmesh's (:mod:`gearmesh.contact`): the
pinion centre at the origin, the gear centre at (a, 0, 0), x along the line of centres, the
pinion turning counter-clockwise about +z, the transverse line of action along
d = (sin αwt, cos αwt). Every rotation θ is measured positive in the sense in which that gear
turns (pinion counter-clockwise, gear clockwise), as φ1, φ2 of :mod:`gearmesh.contact`.

8-DOF pair (seed 001 §4, corrected)
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

What was changed from seed 001's printed equations, and why:

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
* Static transmission error e(t): seed 001 puts the loaded static TE e = F/K(t) into (1)
  *and* keeps k_m(t) in (2). Then the quasi-static solution still has δ = F/K(t), but the
  approach of the bodies, δ + e (what the rotations and bearings see), is 2F/K(t): the
  stiffness fluctuation is counted twice. The default here (``excitation='tvms'``) is the
  consistent form: e(t) is the *unloaded* (kinematic) TE, zero for unmodified flanks, and
  the fluctuation of k_m(t) is the excitation, whose quasi-static response is an approach
  δ = F/K(t), the LSTE of seed 001 §2. ``excitation='lste'`` reproduces the seed literally;
  a tabulated unloaded TE (e.g. from LTCA) can be added with ``transmission_error``.

Stiffness: k_m(t) is the stiffness along the normal, K_n = K/cos²βb, with K the transverse
TVMS of :func:`gearmesh.stiffness.mesh_stiffness`, as a function of the pinion roll
r_b1·Ω·t (Ω the nominal speed; the vibration does not change the mesh phase, the usual
assumption). Either its Fourier series of order 3 (seed 004) or the full tabulated curve
(periodic linear interpolation). Mesh damping c_m = 2ζ√(k̄_n m_e), m_e = 1/[cos²βb·
(r_b1²/I_p + r_b2²/I_g)] the equivalent mass along δ, ζ = 0.07 by default (a mid value of
the range 0.03–0.17 used in gear-pair models, e.g. Kahraman & Singh 1990, J. Sound Vib.
142:49; Parker, Vijayakar & Imajo 2000, J. Sound Vib. 237:435).

The rigid-body rotation is removed: the rotations enter only through the relative
(transverse) coordinates q_i = r_b,drv θ_drv − r_b,drn θ_drn of each mesh; with J the
inertias and R the map θ → q, q̈ = R J⁻¹ τ − R J⁻¹ Rᵀ (∂δ/∂q)ᵀ F. The mean rotation never
appears, so long runs cannot drift.

9-DOF train (seed 004)
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
thrust (its two axial forces cancel), plate and impression carry ±F sin βb. Seed 004
prints δ_1 = (y_P − y_B) cos βb +
(z_P − z_B) sin βb + r_bP θ_P − r_bB θ_B − e_1: its y term has no pressure-angle projection
and its rotation term no cos βb, which do not follow from one normal direction; the form
above does, and it gives the seed's observations (radial forces on B cancel, P and I move in
opposite phase). The tangential bearing direction is not a degree of freedom in this model
(rigid), as in the seed. Torque T on P, load T on I, B idles.

Solver
------
:func:`simulate` integrates all speeds as one numpy batch with classical RK4 and a step per
speed: m_i steps per mesh period, m_i = max(m_min, ⌈T_mesh/Δt_max⌉), Δt_max = c/ω_max
(ω_max the highest natural frequency of the linearised model at the maximum stiffness,
c = 0.25 by default), so the mesh phase of every step is exact and k, e are tabulated once
per speed. Transients are discarded by physical time (docs/modelling.md): the run starts from the
static equilibrium at the mean stiffness, integrates ⌈n_τ/(σ_min T_mesh)⌉ mesh periods with
σ_min = min(−Re λ) over the modes of the linearised model (n_τ = 10, i.e. transients decay
to e^-10 of their start), then records n_rec whole mesh periods (8). Speeds with fewer
steps start later (their step is 0 until then), so all speeds end together and every
statistic of a speed is independent of the other speeds of the batch. The change of the DTE
fluctuation between the two halves of the record window is kept as a steady-state check.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from .errors import GearmeshInputError
from .gear import PairGeometry

#: Seed 001 §4 bearing values: k_x = k_y = 1.5e8 N/m, k_z = 1e7 N/m, c = 1000 N·s/m.
SEED001_BEARING = {"k_radial": 1.5e8, "k_axial": 1.0e7, "c_radial": 1.0e3, "c_axial": 1.0e3}
#: Mesh damping ratio ζ: a mid value of the 0.03–0.17 range of gear-pair models (module docstring).
DEFAULT_DAMPING_RATIO = 0.07
EXCITATIONS = ("tvms", "lste")
STIFFNESS_FORMS = ("fourier", "table")


# --------------------------------------------------------------------------------------
# Mesh description
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class MeshLaw:
    """Stiffness and excitation of one mesh over one mesh cycle (normal direction, SI).

    ``phase`` (P,) mesh-cycle fraction in [0, 1) of the tabulated points; ``k`` (N/m) the
    normal mesh stiffness there (or None with ``fourier``); ``fourier`` = (mean, a, b) of
    k(ψ) = mean + Σ a_j cos(jψ) + b_j sin(jψ), ψ = 2π·phase; ``e`` (m) the static TE along
    the normal at ``e_phase`` (None for none); ``phase_offset`` (cycles) shifts this mesh.
    """

    k_mean: float
    k_max: float
    fourier: tuple[float, np.ndarray, np.ndarray] | None = None
    phase: np.ndarray | None = None
    k: np.ndarray | None = None
    e_phase: np.ndarray | None = None
    e: np.ndarray | None = None
    phase_offset: float = 0.0

    def stiffness(self, phase: np.ndarray) -> np.ndarray:
        """k (N/m) at mesh-cycle fractions ``phase`` (any real numbers, periodic)."""
        ph = np.mod(np.asarray(phase, dtype=float) + self.phase_offset, 1.0)
        if self.fourier is not None:
            mean, a, b = self.fourier
            psi = 2.0 * np.pi * ph
            out = np.full(ph.shape, mean)
            for j in range(len(a)):
                out += a[j] * np.cos((j + 1) * psi) + b[j] * np.sin((j + 1) * psi)
            return out
        return _periodic_interp(ph, self.phase, self.k)

    def error(self, phase: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """e (m) and de/dphase (m per cycle) at ``phase``; zeros without excitation."""
        ph = np.mod(np.asarray(phase, dtype=float) + self.phase_offset, 1.0)
        if self.e is None:
            return np.zeros(ph.shape), np.zeros(ph.shape)
        xp = np.concatenate([self.e_phase, [self.e_phase[0] + 1.0]])
        fp = np.concatenate([self.e, [self.e[0]]])
        slope = np.diff(fp) / np.diff(xp)
        i = np.clip(np.searchsorted(xp, ph, side="right") - 1, 0, slope.size - 1)
        return fp[i] + slope[i] * (ph - xp[i]), slope[i]


def _periodic_interp(ph, xp, fp):
    xp = np.concatenate([xp, [xp[0] + 1.0]])
    fp = np.concatenate([fp, [fp[0]]])
    return np.interp(ph, xp, fp)


@dataclass(frozen=True)
class GearModel:
    """A linear multi-body gear model with nonlinear meshes, rigid-body rotation removed.

    Reduced coordinates y = (translations u, relative mesh rotations q), n of them; the
    equations are ÿ = −Kr y − Cr ẏ − B F + f0 with the mesh forces F (m,) of (2) and
    δ = G y − e(t). ``names`` label y; ``gears``, ``directions`` give each translation's
    gear and direction; ``full`` keeps the unreduced matrices for checks (M, K_b, C_b,
    G_full, forces) in the coordinates ``full_names``.
    """

    name: str
    names: tuple[str, ...]
    n_trans: int
    Kr: np.ndarray
    Cr: np.ndarray
    B: np.ndarray
    G: np.ndarray
    f0: np.ndarray
    meshes: tuple[MeshLaw, ...]
    damping: np.ndarray  # (m,) c_m in N·s/m
    backlash: float  # 2b0 (m); inf = no backlash (linear contact)
    static_force: np.ndarray  # (m,) normal mesh force of the torque balance (N)
    mesh_frequency_per_rpm: float  # Hz per rpm of the reference speed
    teeth_driver: int
    full: Mapping[str, Any] = field(default_factory=dict, repr=False)

    @property
    def n(self) -> int:
        return len(self.names)

    @property
    def m(self) -> int:
        return len(self.meshes)

    def linear_matrices(self, k: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Stiffness and damping matrices (s⁻², s⁻¹) of the reduced model with the meshes
        closed at stiffness ``k`` (N/m; default the mean)."""
        k = np.array([ml.k_mean for ml in self.meshes]) if k is None else np.asarray(k)
        return self.Kr + self.B @ (k[:, None] * self.G), self.Cr + self.B @ (self.damping[:, None] * self.G)

    def modes(self, k: np.ndarray | None = None) -> dict[str, np.ndarray]:
        """Modes of the linearised model (meshes in contact at stiffness ``k``).

        Returns natural frequencies ``frequency_Hz`` = |λ|/2π (undamped-equivalent),
        ``damped_Hz`` = Im λ/2π, ``damping_ratio`` = −Re λ/|λ|, ``decay_rate`` = −Re λ (s⁻¹),
        sorted by frequency, one per conjugate pair, and ``shapes`` (n, modes).
        """
        import scipy.linalg

        K, C = self.linear_matrices(k)
        n = self.n
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
        lam, vec = scipy.linalg.eig(A)
        keep = lam.imag > 0
        over = (lam.imag == 0)  # overdamped modes: real eigenvalues
        lam_k, vec_k = lam[keep], vec[:n, keep]
        if over.any():
            lam_k = np.concatenate([lam_k, lam[over]])
            vec_k = np.concatenate([vec_k, vec[:n, over]], axis=1)
        order = np.argsort(np.abs(lam_k))
        lam_k, vec_k = lam_k[order], vec_k[:, order]
        return {"eigenvalue": lam_k, "frequency_Hz": np.abs(lam_k) / (2 * np.pi),
                "damped_Hz": lam_k.imag / (2 * np.pi), "damping_ratio": -lam_k.real / np.abs(lam_k),
                "decay_rate": -lam_k.real, "shapes": vec_k}

    def static_state(self) -> np.ndarray:
        """Static equilibrium y (n,) with the meshes at mean stiffness and mean e (m, rad→m)."""
        K, _ = self.linear_matrices()
        k = np.array([ml.k_mean for ml in self.meshes])
        e_mean = np.array([float(np.mean(ml.error(np.linspace(0, 1, 512, endpoint=False))[0]))
                           for ml in self.meshes])
        return np.linalg.solve(K, self.f0 + self.B @ (k * e_mean))


def _check_positive(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(value) or value <= 0:
        raise GearmeshInputError(name, value, "must be a positive finite number")
    return float(value)


def _check_nonneg(name: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)) \
            or not math.isfinite(value) or value < 0:
        raise GearmeshInputError(name, value, "must be a non-negative finite number")
    return float(value)


def require_dynamics_data(geom: PairGeometry) -> None:
    """Refuse a pair without the bore radius or material the masses and inertias need."""
    if geom.pair.material is None:
        raise GearmeshInputError("material", None, "is required for the dynamics (density for the masses, "
                                 "Young's modulus for the mesh stiffness)")
    if geom.pair.bore_radius is None:
        raise GearmeshInputError("bore_radius_mm", None, "is required for the dynamics (gear body masses and "
                                 "inertias, seed 001 Table 1 convention)")


#: Points of the fine table that holds a Fourier-represented error e(phase).
FOURIER_TABLE_POINTS = 1024


def mesh_law(geom: PairGeometry, K_transverse: np.ndarray, torque: float, stiffness_form: str = "fourier",
             order: int = 3, excitation: str = "tvms", transmission_error=None, phase_offset: float = 0.0,
             roll: np.ndarray | None = None) -> MeshLaw:
    """The :class:`MeshLaw` of a pair from its transverse TVMS.

    Parameters
    ----------
    geom : pair geometry.
    K_transverse : (P,) transverse mesh stiffness K (N/m) at evenly spaced pinion rolls over
        one base pitch (:attr:`gearmesh.stiffness.MeshStiffness.K`).
    torque : pinion torque T1 (N·m), for the seed-001 excitation e = F/K.
    stiffness_form : 'fourier' (series of ``order``, seed 004) or 'table' (full curve).
    excitation : 'tvms' (e = 0 unless ``transmission_error``) or 'lste' (seed 001 literal:
        e = F_bt/K(t) along the transverse line of action, times cos βb along the normal).
    transmission_error : optional (Q,) unloaded static TE (m) along the *transverse* line of
        action at evenly spaced rolls over one base pitch (e.g. LTCA), added to e; with
        ``stiffness_form='fourier'`` it is represented by its Fourier series of ``order`` too.
    phase_offset : mesh-cycle fraction (-) added to this mesh's phase.
    """
    from .stiffness import fourier_fit

    if stiffness_form not in STIFFNESS_FORMS:
        raise GearmeshInputError("stiffness_form", stiffness_form, f"must be one of {list(STIFFNESS_FORMS)}")
    if excitation not in EXCITATIONS:
        raise GearmeshInputError("excitation", excitation, f"must be one of {list(EXCITATIONS)}")
    cb2 = math.cos(geom.base_helix_angle) ** 2
    K = np.asarray(K_transverse, dtype=float)
    phase = np.arange(K.size) / K.size if roll is None else np.asarray(roll) / geom.transverse_base_pitch
    k_n = K / cb2
    fourier = None
    if stiffness_form == "fourier":
        fit = fourier_fit(k_n, order)
        fourier = (fit.mean, fit.a, fit.b)
        grid = np.linspace(0, 1, 1024, endpoint=False)
        vals = MeshLaw(k_mean=fit.mean, k_max=0, fourier=fourier).stiffness(grid)
        k_mean, k_max = fit.mean, float(vals.max())
    else:
        k_mean, k_max = float(np.mean(k_n)), float(np.max(k_n))
    e = None
    e_phase = None
    cb = math.cos(geom.base_helix_angle)
    if excitation == "lste":
        if stiffness_form == "fourier":
            kk = MeshLaw(k_mean=k_mean, k_max=k_max, fourier=fourier).stiffness(phase) * cb2
        else:
            kk = K
        e = torque / geom.base_radius[0] / kk * cb
        e_phase = phase
    if transmission_error is not None:
        te = np.asarray(transmission_error, dtype=float)
        if te.ndim != 1 or te.size < 2 or not np.all(np.isfinite(te)):
            raise GearmeshInputError("transmission_error", "array", "must be a finite 1-D array of >= 2 values (m)")
        te_phase = np.arange(te.size) / te.size
        if stiffness_form == "fourier":
            # the same smooth representation as k: the Fourier series of the same order,
            # tabulated finely (a piecewise-linear e has kinks that cost RK4 its order)
            fit_e = fourier_fit(te, min(order, (te.size - 1) // 2))
            te_phase = np.arange(FOURIER_TABLE_POINTS) / FOURIER_TABLE_POINTS
            te = fit_e(2 * np.pi * te_phase)
        if e is None:
            e, e_phase = te * cb, te_phase
        else:
            e = e + _periodic_interp(phase, te_phase, te) * cb
    return MeshLaw(k_mean=k_mean, k_max=k_max, fourier=fourier, phase=phase, k=k_n if stiffness_form == "table"
                   else None, e_phase=e_phase, e=e, phase_offset=phase_offset)


def _equivalent_mass(cb: float, rb, inertia) -> float:
    """Equivalent mass (kg) along the normal δ of one mesh: 1/[cos²βb Σ r_b²/I]."""
    return 1.0 / (cb**2 * sum(r**2 / j for r, j in zip(rb, inertia)))


def _reduce(name, M, Kb, Cb, Gfull, tau, rot_idx, R, meshes, damping, backlash, static_force, fmesh_per_rpm,
            teeth, names_full):
    """Reduced model from full matrices: translations kept, rotations → q = R θ."""
    n_full = M.shape[0]
    trans = [i for i in range(n_full) if i not in rot_idx]
    J = M[np.ix_(rot_idx, rot_idx)]
    Jinv = np.linalg.inv(J)
    Mu = M[np.ix_(trans, trans)]
    Muinv = np.linalg.inv(Mu)
    nt, m = len(trans), R.shape[0]
    n = nt + m
    Kr = np.zeros((n, n))
    Cr = np.zeros((n, n))
    Kr[:nt, :nt] = Muinv @ Kb[np.ix_(trans, trans)]
    Cr[:nt, :nt] = Muinv @ Cb[np.ix_(trans, trans)]
    # δ = G_u u + G_θ θ with G_θ = G_q R  ⇒  G_q = G_θ R⁺ (exact: rows of G_θ lie in R's row space)
    Gu = Gfull[:, trans]
    Gth = Gfull[:, rot_idx]
    Gq = Gth @ np.linalg.pinv(R)
    if not np.allclose(Gq @ R, Gth, rtol=1e-12, atol=1e-15):
        raise ValueError("mesh rotations are not functions of the relative coordinates")
    G = np.hstack([Gu, Gq])
    B = np.zeros((n, m))
    B[:nt] = Muinv @ Gu.T
    B[nt:] = R @ Jinv @ R.T @ Gq.T
    f0 = np.zeros(n)
    f0[nt:] = R @ Jinv @ tau[rot_idx]
    names = tuple([names_full[i] for i in trans] + [f"q{i + 1}" for i in range(m)])
    full = {"M": M, "K_bearing": Kb, "C_bearing": Cb, "G": Gfull, "forces": tau, "names": tuple(names_full),
            "R": R, "rotations": tuple(rot_idx)}
    return GearModel(name=name, names=names, n_trans=nt, Kr=Kr, Cr=Cr, B=B, G=G, f0=f0, meshes=tuple(meshes),
                     damping=np.asarray(damping, dtype=float), backlash=backlash,
                     static_force=np.asarray(static_force, dtype=float), mesh_frequency_per_rpm=fmesh_per_rpm,
                     teeth_driver=teeth, full=full)


def _bearing_settings(bearing: Mapping[str, float] | None) -> dict[str, float]:
    """Seed 001's bearing values overridden by ``bearing``: known keys, stiffness > 0 (an
    unsupported direction would leave a rigid-body mode), damping ≥ 0."""
    out = {**SEED001_BEARING, **(bearing or {})}
    for key, v in out.items():
        if key not in SEED001_BEARING:
            raise GearmeshInputError(f"bearing.{key}", v, f"unknown key; allowed {sorted(SEED001_BEARING)}")
        (_check_positive if key.startswith("k_") else _check_nonneg)(f"bearing.{key}", v)
    return out


def pair_model(geom: PairGeometry, torque_out: float, K_transverse: np.ndarray, *, bearing: Mapping[str, float]
               | None = None, damping_ratio: float = DEFAULT_DAMPING_RATIO, backlash: float | None = 60e-6,
               stiffness_form: str = "fourier", order: int = 3, excitation: str = "tvms",
               transmission_error=None, mesh_damping: float | None = None) -> GearModel:
    """The 8-DOF bending–torsion–axial helical pair of seed 001 §4 (module docstring, eqs. 1–2).

    Parameters
    ----------
    geom : pair geometry with bore radius and material (masses, inertias).
    torque_out : output (gear) torque T_out (N·m), > 0; T_in = T_out r_b1/r_b2.
    K_transverse : (P,) transverse TVMS K (N/m) evenly over one base pitch.
    bearing : k_radial, k_axial (N/m), c_radial, c_axial (N·s/m), same for both gears
        (default seed 001: 1.5e8, 1e7, 1000, 1000).
    damping_ratio : mesh damping ratio ζ (-) on the mean normal stiffness and the equivalent
        mass (ignored when ``mesh_damping`` (N·s/m) is given).
    backlash : total backlash 2b0 (m) along the normal; None = no backlash (contact never
        lost: f(δ) = δ, a linear time-varying model).
    stiffness_form, order, excitation, transmission_error : see :func:`mesh_law`.
    """
    require_dynamics_data(geom)
    torque_out = _check_positive("torque_Nm", torque_out)
    bearing = _bearing_settings(bearing)
    damping_ratio = _check_nonneg("damping_ratio", damping_ratio)
    rb1, rb2 = (float(r) for r in geom.base_radius)
    torque_in = torque_out * rb1 / rb2
    law = mesh_law(geom, K_transverse, torque_in, stiffness_form, order, excitation, transmission_error)
    a, bb = geom.operating_pressure_angle, geom.base_helix_angle
    cb, sb = math.cos(bb), math.sin(bb)
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    mp, mg = (float(x) for x in geom.mass)
    ip, ig = (float(x) for x in geom.inertia)
    names = ("x_pinion", "y_pinion", "z_pinion", "theta_pinion", "x_gear", "y_gear", "z_gear", "theta_gear")
    M = np.diag([mp, mp, mp, ip, mg, mg, mg, ig])
    kr, ka, cr, ca = bearing["k_radial"], bearing["k_axial"], bearing["c_radial"], bearing["c_axial"]
    Kb = np.diag([kr, kr, ka, 0, kr, kr, ka, 0])
    Cb = np.diag([cr, cr, ca, 0, cr, cr, ca, 0])
    g = np.array([[cb * math.sin(a), cb * math.cos(a), -h * sb, cb * rb1,
                   -cb * math.sin(a), -cb * math.cos(a), h * sb, -cb * rb2]])
    tau = np.array([0, 0, 0, torque_in, 0, 0, 0, -torque_out])
    R = np.array([[rb1, -rb2]])
    me = _equivalent_mass(cb, (rb1, rb2), (ip, ig))
    c_m = mesh_damping if mesh_damping is not None else 2 * damping_ratio * math.sqrt(law.k_mean * me)
    f_static = torque_out / (rb2 * cb)
    return _reduce(geom.pair.name, M, Kb, Cb, g, tau, [3, 7], R, [law], [c_m],
                   math.inf if backlash is None else _check_nonneg("backlash_um", backlash),
                   [f_static], geom.pair.teeth[0] / 60.0, geom.pair.teeth[0], names)


TRAIN_GEARS = ("plate", "blanket", "impression")


def train_model(geom: PairGeometry, torque: float, K_transverse: np.ndarray, *, bearing=None,
                damping_ratio: float = DEFAULT_DAMPING_RATIO, backlash: float | None = 60e-6,
                stiffness_form: str = "fourier", order: int = 3, excitation: str = "tvms",
                phase_offsets: Sequence[float] = (0.0, 0.0), mesh_damping: float | None = None) -> GearModel:
    """The 9-DOF plate–blanket–impression train of seed 004 (module docstring).

    The three gears are the pair file's gear (index 1) repeated, the pair's TVMS serving both
    meshes (assumption: seed 004's gears are alike, 88 teeth each), the plate driven by
    ``torque`` (N·m) and the impression loaded by it; y along the line of centres, bearing
    'k_radial' for y, 'k_axial' for z. ``phase_offsets`` (mesh cycles) shift each mesh's
    TVMS (default in phase: seed 004 finds the two mesh forces nearly identical).
    """
    require_dynamics_data(geom)
    torque = _check_positive("torque_Nm", torque)
    bearing = _bearing_settings(bearing)
    if len(phase_offsets) != 2 or not all(math.isfinite(float(p)) for p in phase_offsets):
        raise GearmeshInputError("phase_offsets", phase_offsets, "must give two finite mesh-cycle offsets")
    rb = float(geom.base_radius[1])
    m_, j_ = float(geom.mass[1]), float(geom.inertia[1])
    a, bb = geom.operating_pressure_angle, geom.base_helix_angle
    cb, sb = math.cos(bb), math.sin(bb)
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    laws = [mesh_law(geom, K_transverse, torque * float(geom.base_radius[0]) / rb, stiffness_form, order,
                     excitation, None, float(p)) for p in phase_offsets]
    names = tuple(f"{d}_{g}" for g in TRAIN_GEARS for d in ("y", "z", "theta"))
    M = np.diag([m_, m_, j_] * 3)
    kr, ka, cr, ca = bearing["k_radial"], bearing["k_axial"], bearing["c_radial"], bearing["c_axial"]
    Kb = np.diag([kr, ka, 0] * 3)
    Cb = np.diag([cr, ca, 0] * 3)
    sa = math.sin(a)
    G = np.zeros((2, 9))
    G[0, [0, 1, 2, 3, 4, 5]] = [cb * sa, -h * sb, cb * rb, -cb * sa, h * sb, -cb * rb]
    G[1, [3, 4, 5, 6, 7, 8]] = [cb * sa, -h * sb, cb * rb, -cb * sa, h * sb, -cb * rb]
    tau = np.zeros(9)
    tau[2], tau[8] = torque, -torque
    R = np.array([[rb, -rb, 0.0], [0.0, rb, -rb]])
    me = _equivalent_mass(cb, (rb, rb), (j_, j_))
    c_m = [mesh_damping if mesh_damping is not None else 2 * damping_ratio * math.sqrt(ml.k_mean * me)
           for ml in laws]
    f_static = torque / (rb * cb)
    return _reduce("train", M, Kb, Cb, G, tau, [2, 5, 8], R, laws, c_m,
                   math.inf if backlash is None else _check_nonneg("backlash_um", backlash),
                   [f_static, f_static], geom.pair.teeth[1] / 60.0, geom.pair.teeth[1], names)


# --------------------------------------------------------------------------------------
# Batch RK4 over speeds
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class SolverSettings:
    """Step and window rules of :func:`simulate` (module docstring).

    courant : ω_max·Δt bound (-); steps_per_cycle_min : m_min; transient_tau : n_τ (-);
    record_cycles : n_rec mesh periods (even); min_transient_cycles : at least this many
    mesh periods before recording.
    """

    courant: float = 0.25
    steps_per_cycle_min: int = 32
    transient_tau: float = 10.0
    record_cycles: int = 8
    min_transient_cycles: int = 2
    block: int = 256


@dataclass
class SweepResult:
    """Steady-state statistics per speed (arrays (S,) or (n, S) / (m, S)), SI units.

    ``y_mean``, ``y_std`` (n, S) mean and standard deviation of each reduced coordinate
    (m), ``v_rms`` (n, S) RMS of its velocity (m/s); ``dte_*`` (m, S) of the mesh deflection
    δ (m, along the normal, eq. 1: the elastic approach, statically F/k; seed 001 calls it the
    DTE); ``approach_mean``, ``approach_std`` (m, S) of the gear bodies' approach along the
    normal, G·y = δ + e (statically the loaded TE × cos βb: the dynamic transmission error);
    ``force_*`` (m, S) of F (N; min and max at the steps, as ``dte_min``, ``dte_max``);
    ``gap_fraction``, ``back_fraction`` (m, S) fractions of
    the record window in contact loss (−2b0 < δ < 0) and back-side contact (δ < −2b0);
    ``steady_change`` (m, S) relative change of the DTE standard deviation between the
    two halves of the window; ``series`` optional per-speed time series.
    """

    speed_rpm: np.ndarray
    mesh_frequency: np.ndarray
    steps_per_cycle: np.ndarray
    transient_cycles: np.ndarray
    dt: np.ndarray
    y_mean: np.ndarray
    y_std: np.ndarray
    v_rms: np.ndarray
    dte_mean: np.ndarray
    dte_std: np.ndarray
    dte_rms: np.ndarray
    dte_min: np.ndarray
    dte_max: np.ndarray
    approach_mean: np.ndarray
    approach_std: np.ndarray
    force_mean: np.ndarray
    force_min: np.ndarray
    force_max: np.ndarray
    force_std: np.ndarray
    gap_fraction: np.ndarray
    back_fraction: np.ndarray
    steady_change: np.ndarray
    n_steps: int
    series: list | None = None


#: Cap on RK4 steps at one speed (a very low speed would otherwise run for hours: the
#: transient lasts a fixed physical time while the step is bounded by the highest mode).
MAX_STEPS_PER_SPEED = 2_000_000


def step_plan(model: GearModel, speed_rpm: np.ndarray, settings: SolverSettings = SolverSettings()):
    """Per speed: mesh frequency (Hz), steps per mesh period m_i, transient periods, Δt (s).

    Δt_max = courant/ω_max with ω_max = max |λ| of the model at the maximum stiffness;
    transient time n_τ/σ_min with σ_min = min(−Re λ) at the mean stiffness.
    """
    speed_rpm = np.asarray(speed_rpm, dtype=float)
    kmax = np.array([ml.k_max for ml in model.meshes])
    w_max = float(np.max(np.abs(model.modes(kmax)["eigenvalue"])))
    sigma = float(np.min(model.modes()["decay_rate"]))
    f_mesh = speed_rpm * model.mesh_frequency_per_rpm
    t_mesh = 1.0 / f_mesh
    dt_max = settings.courant / w_max
    if not (math.isfinite(settings.transient_tau) and settings.transient_tau > 0):
        raise GearmeshInputError("transient_tau", settings.transient_tau, "must be a positive finite number")
    steps_per_cycle = np.maximum(settings.steps_per_cycle_min, np.ceil(t_mesh / dt_max))
    cycles = np.maximum(settings.min_transient_cycles, np.ceil(settings.transient_tau / sigma / t_mesh))
    total = steps_per_cycle * (cycles + settings.record_cycles)
    if np.max(total) > MAX_STEPS_PER_SPEED:
        worst = int(np.argmax(total))
        raise GearmeshInputError(
            "speeds_rpm", float(speed_rpm[worst]),
            f"needs {total[worst]:.3g} time steps at this speed (limit {MAX_STEPS_PER_SPEED:.0e}): the transient "
            f"lasts {settings.transient_tau / sigma:.3g} s and a step is at most {dt_max:.3g} s; raise the speed")
    m = steps_per_cycle.astype(np.int64)
    m += m % 2  # even, so that half steps fall on the tabulated grid of 2m points
    return f_mesh, m, cycles.astype(np.int64), t_mesh / m


def _phase_tables(model: GearModel, m: np.ndarray):
    """k, e, de/dt tables at the 2m half-step phases of each speed, padded: (mesh, S, 2·max m)."""
    S, L = m.size, int(2 * m.max())
    k = np.zeros((model.m, S, L))
    e = np.zeros((model.m, S, L))
    ed = np.zeros((model.m, S, L))  # de/dphase (per cycle)
    for s in range(S):
        ph = np.arange(2 * m[s]) / (2.0 * m[s])
        for i, ml in enumerate(model.meshes):
            k[i, s, :ph.size] = ml.stiffness(ph)
            ee, ss = ml.error(ph)
            e[i, s, :ph.size] = ee
            ed[i, s, :ph.size] = ss
    return k, e, ed


def simulate(model: GearModel, speed_rpm, settings: SolverSettings = SolverSettings(),
             series: bool = False, y0: np.ndarray | None = None, progress=None) -> SweepResult:
    """Steady-state response of ``model`` at every speed (rpm), one RK4 batch (module docstring).

    ``series=True`` also returns, per speed, the record window sampled at every step:
    time (s), δ (m, meshes), F (N), y (n) and ẏ (n). Keep it for a few speeds only.
    ``progress`` (optional) is called with the fraction of steps done, about every 5 %.
    """
    speed_rpm = np.atleast_1d(np.asarray(speed_rpm, dtype=float))
    if speed_rpm.size == 0 or not np.all(np.isfinite(speed_rpm)) or np.any(speed_rpm <= 0):
        raise GearmeshInputError("speed_rpm", speed_rpm.tolist(), "must be positive finite speeds")
    if settings.record_cycles < 2 or settings.record_cycles % 2:
        raise GearmeshInputError("record_cycles", settings.record_cycles, "must be an even number >= 2")
    f_mesh, m, n_tr, dt = step_plan(model, speed_rpm, settings)
    S, n, nm = speed_rpm.size, model.n, model.m
    n_rec = settings.record_cycles
    total = (n_tr + n_rec) * m
    n_steps = int(total.max())
    start = n_steps - total  # idle (Δt = 0) before
    rec_start = n_steps - n_rec * m
    half_start = n_steps - (n_rec // 2) * m
    ktab, etab, edtab = _phase_tables(model, m)
    L = ktab.shape[2]
    has_e = any(ml.e is not None for ml in model.meshes)
    edtab = edtab * f_mesh[None, :, None]  # de/dt (m/s)
    kflat, eflat, edflat = (t.reshape(nm, S * L) for t in (ktab, etab, edtab))
    row = np.arange(S) * L
    c_m = model.damping[:, None]
    bl = model.backlash
    linear = not math.isfinite(bl)
    # state Y (2n, S); A_lin (n, 2n) = [−Kr, −Cr]
    A_lin = np.hstack([-model.Kr, -model.Cr])
    G2 = np.zeros((2 * nm, 2 * n))
    G2[:nm, :n] = model.G
    G2[nm:, n:] = model.G
    Bneg = -model.B
    f0 = model.f0[:, None]
    ys = model.static_state() if y0 is None else np.asarray(y0, dtype=float)
    Y = np.zeros((2 * n, S))
    Y[:n] = ys[:, None]
    ys_col = ys[:, None]
    d_ref = (model.G @ ys)[:, None]

    def force(Y, k, e, ed):
        d = G2 @ Y
        delta, ddot = d[:nm], d[nm:]
        if has_e:
            delta = delta - e
            ddot = ddot - ed
        if linear:
            return delta, k * delta + c_m * ddot
        f = delta - np.clip(delta, -bl, 0.0)
        F = k * f + c_m * ddot
        F *= (f != 0.0)
        return delta, F

    def deriv(Y, F):
        dY = np.empty_like(Y)
        dY[:n] = Y[n:]
        acc = A_lin @ Y
        acc += Bneg @ F
        acc += f0
        dY[n:] = acc
        return dY

    # accumulators
    z = lambda *shape: np.zeros(shape)  # noqa: E731
    sy, syy, svv = z(n, S), z(n, S), z(n, S)
    sd, sdd, sf, sff = z(nm, S), z(nm, S), z(nm, S), z(nm, S)
    sd_h, sdd_h = z(nm, S), z(nm, S)  # second half of the window
    sa, saa = z(nm, S), z(nm, S)  # approach δ + e of the bodies
    fmin, fmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
    dmin, dmax = np.full((nm, S), np.inf), np.full((nm, S), -np.inf)
    ngap, nback = z(nm, S), z(nm, S)
    rec_first = int(rec_start.min())
    store = [dict(t=[], delta=[], F=[], y=[], v=[]) for _ in range(S)] if series else None
    dt_s = dt[None, :]
    report_every = max(1, n_steps // 20)
    for b0 in range(0, n_steps, settings.block):
        if progress is not None and b0 // report_every != (b0 + settings.block) // report_every:
            progress(b0 / n_steps)
        nb = min(settings.block, n_steps - b0)
        steps = np.arange(b0, b0 + nb)
        local = steps[:, None] - start[None, :]  # (nb, S) step index within each speed's run
        active = local >= 0
        loc = np.maximum(local, 0)
        # half-step phase indices 2·loc and 2·loc+1, 2·loc+2 (mod 2m)
        i0 = (2 * loc) % (2 * m)[None, :]
        i1 = (2 * loc + 1) % (2 * m)[None, :]
        i2 = (2 * loc + 2) % (2 * m)[None, :]
        k0, k1, k2 = (np.take(kflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))  # (nm, nb, S)
        if has_e:
            e0, e1, e2 = (np.take(eflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))
            d0, d1, d2 = (np.take(edflat, idx + row[None, :], axis=1) for idx in (i0, i1, i2))
        else:
            e0 = e1 = e2 = d0 = d1 = d2 = None
        hdt_b = np.where(active, 0.5 * dt_s, 0.0)
        dt_b = np.where(active, dt_s, 0.0)
        for j in range(nb):
            step = b0 + j
            ej = (e0[:, j], d0[:, j]) if has_e else (None, None)
            delta, F = force(Y, k0[:, j], *ej)
            if step >= rec_first:
                w = (step >= rec_start)
                wf = w.astype(float)
                wh = (step >= half_start).astype(float)
                yc = Y[:n] - ys_col  # shifted by the static state: no cancellation in the variance
                yw = yc * wf
                sy += yw
                syy += yw * yc
                svv += Y[n:] * Y[n:] * wf
                dc = delta - d_ref
                dw = dc * wf
                sd += dw
                sdd += dw * dc
                sd_h += dc * wh
                sdd_h += dc * dc * wh
                ac = dc + e0[:, j] if has_e else dc
                sa += ac * wf
                saa += ac * ac * wf
                sf += F * wf
                sff += F * F * wf
                fmin = np.minimum(fmin, np.where(w, F, np.inf))
                fmax = np.maximum(fmax, np.where(w, F, -np.inf))
                dmin = np.minimum(dmin, np.where(w, delta, np.inf))
                dmax = np.maximum(dmax, np.where(w, delta, -np.inf))
                if not linear:
                    ngap += ((delta < 0) & (delta > -bl)) * wf
                    nback += (delta <= -bl) * wf
                if series:
                    for s in np.flatnonzero(w):
                        st = store[s]
                        st["t"].append((step - rec_start[s]) * dt[s])
                        st["delta"].append(delta[:, s].copy())
                        st["F"].append(F[:, s].copy())
                        st["y"].append(Y[:n, s].copy())
                        st["v"].append(Y[n:, s].copy())
            h2, h = hdt_b[j], dt_b[j]
            K1 = deriv(Y, F)
            ej = (e1[:, j], d1[:, j]) if has_e else (None, None)
            K2 = deriv(Y + h2 * K1, force(Y + h2 * K1, k1[:, j], *ej)[1])
            Yt = Y + h2 * K2
            K3 = deriv(Yt, force(Yt, k1[:, j], *ej)[1])
            Yt = Y + h * K3
            ej = (e2[:, j], d2[:, j]) if has_e else (None, None)
            K4 = deriv(Yt, force(Yt, k2[:, j], *ej)[1])
            Y = Y + (h / 6.0) * (K1 + 2.0 * K2 + 2.0 * K3 + K4)
    if progress is not None:
        progress(1.0)
    N = (n_rec * m).astype(float)[None, :]
    Nh = N / 2
    yc_mean = sy / N
    y_mean = yc_mean + ys_col
    dc_mean = sd / N
    dte_mean = dc_mean + d_ref
    dte_var = np.maximum(sdd / N - dc_mean**2, 0.0)
    m1 = (sd - sd_h) / Nh
    v1 = np.maximum((sdd - sdd_h) / Nh - m1**2, 0.0)
    m2 = sd_h / Nh
    v2 = np.maximum(sdd_h / Nh - m2**2, 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        change = np.abs(np.sqrt(v2) - np.sqrt(v1)) / np.maximum(np.sqrt(dte_var), 1e-300)
    ac_mean = sa / N
    f_mean = sf / N
    out_series = None
    if series:
        out_series = [{k: np.asarray(v) for k, v in st.items()} for st in store]
    return SweepResult(
        speed_rpm=speed_rpm, mesh_frequency=f_mesh, steps_per_cycle=m, transient_cycles=n_tr, dt=dt,
        y_mean=y_mean, y_std=np.sqrt(np.maximum(syy / N - yc_mean**2, 0.0)), v_rms=np.sqrt(svv / N),
        dte_mean=dte_mean, dte_std=np.sqrt(dte_var), dte_rms=np.sqrt(dte_var + dte_mean**2),
        dte_min=dmin, dte_max=dmax, approach_mean=ac_mean + d_ref,
        approach_std=np.sqrt(np.maximum(saa / N - ac_mean**2, 0.0)),
        force_mean=f_mean, force_min=fmin, force_max=fmax, force_std=np.sqrt(np.maximum(sff / N - f_mean**2, 0.0)),
        gap_fraction=ngap / N, back_fraction=nback / N, steady_change=change, n_steps=n_steps,
        series=out_series)


# --------------------------------------------------------------------------------------
# Reference: one speed with scipy.integrate.solve_ivp on the full (unreduced) equations
# --------------------------------------------------------------------------------------


def reference_solution(model: GearModel, speed_rpm: float, settings: SolverSettings = SolverSettings(),
                       rtol: float = 1e-10, atol: float = 1e-14, method: str = "DOP853",
                       samples_per_cycle: int = 256) -> dict[str, np.ndarray]:
    """The same steady state at one speed by :func:`scipy.integrate.solve_ivp` on the *full*
    equations (absolute rotations included, rigid-body mode not removed), from the same
    static state, over the same transient and record window (dense output sampled at
    ``samples_per_cycle`` points per mesh period). Slow; for tests and the benchmark baseline.

    Returns dte_mean, dte_std, dte_rms, force_mean/min/max (per mesh), y_std (reduced
    translations and q, for comparison), v_rms, and 'nfev'.
    """
    from scipy.integrate import solve_ivp

    f_mesh, m, n_tr, _ = step_plan(model, np.array([speed_rpm]), settings)
    f_mesh, n_tr = float(f_mesh[0]), int(n_tr[0])
    full = model.full
    M, Kb, Cb, Gf, tau = full["M"], full["K_bearing"], full["C_bearing"], full["G"], full["forces"]
    rot, R = list(full["rotations"]), full["R"]
    nf = M.shape[0]
    Minv = np.diag(1.0 / np.diag(M))
    bl, linear = model.backlash, not math.isfinite(model.backlash)
    c_m = model.damping
    # full static state from the reduced one: translations as is, rotations θ = R⁺ q
    ys = model.static_state()
    x0 = np.zeros(2 * nf)
    trans = [i for i in range(nf) if i not in rot]
    x0[trans] = ys[:model.n_trans]
    x0[rot] = np.linalg.pinv(R) @ ys[model.n_trans:]

    def laws(t):
        ph = f_mesh * t
        k = np.array([float(ml.stiffness(np.array(ph))) for ml in model.meshes])
        ee = [ml.error(np.array(ph)) for ml in model.meshes]
        return k, np.array([float(a) for a, _ in ee]), np.array([float(b) * f_mesh for _, b in ee])

    def rhs(t, x):
        q, v = x[:nf], x[nf:]
        k, e, ed = laws(t)
        delta = Gf @ q - e
        ddot = Gf @ v - ed
        if linear:
            F = k * delta + c_m * ddot
        else:
            f = delta - np.clip(delta, -bl, 0.0)
            F = (k * f + c_m * ddot) * (f != 0.0)
        acc = Minv @ (tau - Kb @ q - Cb @ v - Gf.T @ F)
        return np.concatenate([v, acc])

    t_mesh = 1.0 / f_mesh
    t_rec0 = n_tr * t_mesh
    t_end = (n_tr + settings.record_cycles) * t_mesh
    n_s = settings.record_cycles * samples_per_cycle
    t_eval = t_rec0 + np.arange(n_s) * (t_mesh / samples_per_cycle)
    sol = solve_ivp(rhs, (0.0, t_end), x0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    X = sol.y
    k_e = [laws(t) for t in t_eval]
    delta = Gf @ X[:nf] - np.array([e for _, e, _ in k_e]).T
    ddot = Gf @ X[nf:] - np.array([ed for _, _, ed in k_e]).T
    kk = np.array([k for k, _, _ in k_e]).T
    if linear:
        F = kk * delta + c_m[:, None] * ddot
    else:
        f = delta - np.clip(delta, -bl, 0.0)
        F = (kk * f + c_m[:, None] * ddot) * (f != 0.0)
    red = np.vstack([X[trans], R @ X[rot]])
    red_v = np.vstack([X[nf:][trans], R @ X[nf:][rot]])
    return {"dte_mean": delta.mean(axis=1), "dte_std": delta.std(axis=1), "dte_rms": np.sqrt((delta**2).mean(axis=1)),
            "force_mean": F.mean(axis=1), "force_min": F.min(axis=1), "force_max": F.max(axis=1),
            "y_std": red.std(axis=1), "v_rms": np.sqrt((red_v**2).mean(axis=1)), "nfev": sol.nfev,
            "t": t_eval, "delta": delta, "F": F}


def resonance_speeds(model: GearModel, harmonics: Sequence[int] = (1, 2, 3)) -> dict[str, np.ndarray]:
    """Speeds (rpm) where harmonic j of the mesh frequency meets a natural frequency of the
    linearised model: n = f_n/(j·z_drv/60). Returns 'frequency_Hz' (modes) and 'speed_rpm'
    (harmonic, mode)."""
    fn = model.modes()["frequency_Hz"]
    h = np.asarray(harmonics, dtype=float)
    return {"frequency_Hz": fn, "speed_rpm": fn[None, :] / (h[:, None] * model.mesh_frequency_per_rpm)}
