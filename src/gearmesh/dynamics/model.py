"""The linear multi-body gear models with nonlinear meshes: the 8-DOF helical pair (the low-fluctuation paper §4)
and the 9-DOF plate–blanket–impression train (the improved potential-energy paper); equations and the corrections made to
the documents in the package docstring (:mod:`gearmesh.dynamics`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping, Sequence

import numpy as np

from ..errors import GearmeshInputError
from ..gear import PairGeometry
from ..pairfile import missing_key
from ..meshforce import MeshForceTable
from ..supports import DEFAULT_SUPPORTS_N_PER_UM
from .excitation import MeshLaw, contact_mesh_law, mesh_law

#: The low-fluctuation paper §4 bearing values: k_x = k_y = 1.5e8 N/m, k_z = 1e7 N/m, c = 1000 N·s/m. The
#: stiffnesses are the supports of a pair file that gives none (:mod:`gearmesh.supports`); the
#: damping values are the bearing damping of every model unless the call says otherwise.
LOW_FLUCTUATION_BEARING = {"k_radial": DEFAULT_SUPPORTS_N_PER_UM["bearing_radial_stiffness_N_per_um"] * 1e6,
                   "k_axial": DEFAULT_SUPPORTS_N_PER_UM["bearing_axial_stiffness_N_per_um"] * 1e6,
                   "c_radial": 1.0e3, "c_axial": 1.0e3}
#: Mesh damping ratio ζ: a mid value of the 0.03–0.17 range of gear-pair models (package docstring).
DEFAULT_DAMPING_RATIO = 0.07
#: What ``damping_ratio`` means (dataset attrs): :func:`_with_mesh_damping`.
DAMPING_MEANING = ("modal damping ratio of the mesh mode (the mode with the largest share of its strain energy in "
                   "the mesh; complex eigenvalues of the linearised model at the mean mesh stiffness, bearing damping "
                   "included); the mesh damper c_m is sized to give it")

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
    cos_beta_b: float = 1.0  # normal = cos βb × transverse (mesh coordinates)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)  # modes(), static_state()

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
        sorted by frequency, one per conjugate pair, and ``shapes`` (n, modes). Those at the mean
        stiffness are computed once per model (the step plan and the resonance speeds ask again).
        """
        if k is None:
            if "modes" not in self._cache:
                self._cache["modes"] = _read_only(self._eigen(None))
            return dict(self._cache["modes"])
        return self._eigen(k)

    def largest_eigenvalue(self, k: np.ndarray | None = None) -> float:
        """max |λ| (s⁻¹) of the linearised model at mesh stiffness ``k`` (eigenvalues alone)."""
        return float(np.max(np.abs(np.linalg.eigvals(self._state_matrix(k)))))

    def _state_matrix(self, k: np.ndarray | None) -> np.ndarray:
        K, C = self.linear_matrices(k)
        n = self.n
        return np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])

    def _eigen(self, k: np.ndarray | None) -> dict[str, np.ndarray]:
        import scipy.linalg

        n = self.n
        lam, vec = scipy.linalg.eig(self._state_matrix(k))
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
        if "static" not in self._cache:
            self._cache["static"] = _read_only({"y": self._static_state()})
        return self._cache["static"]["y"].copy()

    def _static_state(self) -> np.ndarray:
        K, _ = self.linear_matrices()
        k = np.array([ml.k_mean for ml in self.meshes])
        e_mean = np.array([float(np.mean(ml.error(np.linspace(0, 1, 512, endpoint=False))[0]))
                           for ml in self.meshes])
        return np.linalg.solve(K, self.f0 + self.B @ (k * e_mean))


def _read_only(arrays: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """``arrays`` with each array made read-only (a cached result shared by its callers)."""
    for a in arrays.values():
        a.flags.writeable = False
    return arrays


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
    """Refuse a pair without the bore radius or material the masses and inertias need.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.

    Returns
    -------
    None
        Raises :class:`~gearmesh.errors.GearmeshInputError` naming the missing field.
    """
    if geom.pair.material is None:
        raise GearmeshInputError("material", None, "is required for the dynamics (density for the masses, "
                                 "Young's modulus for the mesh stiffness)")
    if geom.pair.bore_radius is None:
        raise missing_key("bore_radius_mm", "the dynamics (gear body masses and inertias, as the low-fluctuation "
                                            "paper's Table 1)")


#: Points of the fine table that holds a Fourier-represented error e(phase).

def _equivalent_mass(cb: float, rb, inertia) -> float:
    """Equivalent mass (kg) along the normal δ of one mesh: 1/[cos²βb Σ r_b²/I]."""
    return 1.0 / (cb**2 * sum(r**2 / j for r, j in zip(rb, inertia)))


#: The reduced matrices of recent (masses, bearings, mesh geometry, torque): a population of
#: micro-geometries of one pair builds many models that differ in the mesh law alone.
_REDUCED: dict[bytes, tuple] = {}


def _reduced_matrices(M, Kb, Cb, Gfull, tau, rot_idx, R):
    """Kr, Cr, B, G, f0 (read-only) of the reduced model (:func:`_reduce`), computed once per distinct
    input (its bytes are the key: the same input gives the same matrices, bit for bit)."""
    key = b"".join(np.ascontiguousarray(a, dtype=float).tobytes() for a in (M, Kb, Cb, Gfull, tau, R)) \
        + np.asarray(rot_idx, dtype=np.int64).tobytes()
    if key in _REDUCED:
        return _REDUCED[key]
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
    out = (Kr, Cr, B, G, f0)
    for a in out:
        a.flags.writeable = False
    if len(_REDUCED) >= 64:
        _REDUCED.clear()
    _REDUCED[key] = out
    return out


def _reduce(name, M, Kb, Cb, Gfull, tau, rot_idx, R, meshes, damping, backlash, static_force, fmesh_per_rpm,
            teeth, names_full, cos_beta_b, translations):
    """Reduced model from full matrices: translations kept, rotations → q = R θ."""
    Kr, Cr, B, G, f0 = _reduced_matrices(M, Kb, Cb, Gfull, tau, rot_idx, R)
    trans = [i for i in range(M.shape[0]) if i not in rot_idx]
    names = tuple([names_full[i] for i in trans] + [f"q{i + 1}" for i in range(R.shape[0])])
    full = {"M": M, "K_bearing": Kb, "C_bearing": Cb, "G": Gfull, "forces": tau, "names": tuple(names_full),
            "R": R, "rotations": tuple(rot_idx), "translations": tuple(translations)}
    return GearModel(name=name, names=names, n_trans=len(trans), Kr=Kr, Cr=Cr, B=B, G=G, f0=f0, meshes=tuple(meshes),
                     damping=np.asarray(damping, dtype=float), backlash=backlash,
                     static_force=np.asarray(static_force, dtype=float), mesh_frequency_per_rpm=fmesh_per_rpm,
                     teeth_driver=teeth, full=full, cos_beta_b=float(cos_beta_b))


def _bearing_settings(geom: PairGeometry, bearing: Mapping[str, float] | None) -> dict[str, Any]:
    """The supports of each gear: the pair file's (:class:`gearmesh.supports.Supports`, shaft
    bending included) with any of ``bearing``'s keys overriding them for both gears (stiffness
    > 0 in N/m or inf for rigid: an unsupported direction would leave a rigid-body mode), and
    the bearing damping (≥ 0, N·s/m; default the low-fluctuation paper's). Stiffnesses as [pinion, gear] tuples."""
    given = dict(bearing or {})
    for key, v in given.items():
        if key not in LOW_FLUCTUATION_BEARING:
            raise GearmeshInputError(f"bearing.{key}", v, f"unknown key; allowed {sorted(LOW_FLUCTUATION_BEARING)}")
        if key.startswith("k_"):
            if not (isinstance(v, (int, float, np.floating)) and v == math.inf):
                _check_positive(f"bearing.{key}", v)
        else:
            _check_nonneg(f"bearing.{key}", v)
    sup = geom.pair.supports
    out: dict[str, Any] = {"k_radial": sup.radial(geom.pair.material.youngs_modulus), "k_axial": sup.axial(),
                           "c_radial": LOW_FLUCTUATION_BEARING["c_radial"], "c_axial": LOW_FLUCTUATION_BEARING["c_axial"]}
    for key, v in given.items():
        out[key] = (float(v), float(v)) if key.startswith("k_") else float(v)
    return out


def _constrain(names, M, Kb, Cb, G, tau, rot_idx):
    """The full matrices without the translations on rigid (infinite) supports, which hold their
    coordinate at zero and so leave the model; rotation indices remapped."""
    keep = [i for i in range(len(names)) if i in rot_idx or math.isfinite(Kb[i, i])]
    ix = np.ix_(keep, keep)
    rot = [keep.index(i) for i in rot_idx]
    return (tuple(names[i] for i in keep), M[ix], np.where(np.isfinite(Kb[ix]), Kb[ix], 0.0), Cb[ix],
            G[:, keep], tau[keep], rot)


def full_translations(model: "GearModel", a: np.ndarray, axis: int = 0) -> np.ndarray:
    """``a`` with every translation of the unconstrained model in its place, zero where a support is rigid.

    Parameters
    ----------
    model : GearModel
        The model (``model.full['translations']``).
    a : numpy.ndarray
        Array with the model's n_trans translations first along ``axis`` (m or any unit).
    axis : int, default 0
        The axis of the translations.

    Returns
    -------
    numpy.ndarray
        ``a`` with the unconstrained model's translations along ``axis``.
    """
    a = np.moveaxis(np.asarray(a), axis, 0)
    names = model.full.get("translations", model.names[:model.n_trans])
    kept = list(model.names[:model.n_trans])
    out = np.zeros((len(names),) + a.shape[1:], dtype=a.dtype)
    for i, nm in enumerate(names):
        if nm in kept:
            out[i] = a[kept.index(nm)]
    return np.moveaxis(out, 0, axis)


def pair_model(geom: PairGeometry, torque_out: float, K_transverse: np.ndarray | None, *,
               bearing: Mapping[str, float] | None = None, damping_ratio: float = DEFAULT_DAMPING_RATIO,
               backlash: float | None = 60e-6, stiffness_form: str = "fourier", order: int = 3,
               excitation: str = "tvms", transmission_error=None, mesh_damping: float | None = None,
               contact: MeshForceTable | None = None) -> GearModel:
    """The 8-DOF bending–torsion–axial helical pair of the low-fluctuation paper §4 (package docstring, eqs. 1–2).

    Parameters
    ----------
    geom : PairGeometry
        Pair geometry with bore radius and material (masses, inertias).
    torque_out : float
        Output (gear) torque T_out (N·m), > 0; T_in = T_out r_b1/r_b2.
    K_transverse : numpy.ndarray or None
        (P,) transverse TVMS K (N/m) evenly over one base pitch.
    bearing : mapping or None
        Overrides for both gears of k_radial, k_axial (N/m, inf: rigid), c_radial, c_axial (N·s/m); the stiffnesses
        default to the pair file's supports (:mod:`gearmesh.supports`, the low-fluctuation paper's 1.5e8 / 1e7 when it
        gives none), the damping to the low-fluctuation paper's 1000 N·s/m.
    damping_ratio : float
        Modal damping ratio ζ (-) of the mesh mode, the mesh damper sized to give it (:func:`_with_mesh_damping`;
        ignored when ``mesh_damping`` is given).
    backlash : float or None, default 60e-6
        Total backlash 2b0 (m) along the normal; None = no backlash (contact never lost: f(δ) = δ, a linear
        time-varying model).
    stiffness_form, order, excitation, transmission_error
        See :func:`mesh_law`.
    mesh_damping : float or None
        Mesh damping coefficient (N·s/m), instead of ``damping_ratio``.
    contact : MeshForceTable or None
        The mesh force table of the pair (:func:`gearmesh.meshforce.mesh_force_table`): the ``contact`` excitation
        (then ``K_transverse`` and the four above are unused).

    Returns
    -------
    GearModel
        The model (SI): mass, stiffness and damping matrices, its mesh laws and the static state.

    References
    ----------
    .. [1] [untitled] Low mesh-stiffness fluctuation design of helical gears (the low-fluctuation paper,
       docs/references.md), §4, eqs. 1–2, corrected as the package docstring says.
    .. [2] Kahraman A., Singh R., "Non-linear dynamics of a spur gear pair", J. Sound Vib. 142 (1990) 49–75: the
       backlash dead zone.
    """
    require_dynamics_data(geom)
    torque_out = _check_positive("torque_Nm", torque_out)
    bearing = _bearing_settings(geom, bearing)
    damping_ratio = _check_nonneg("damping_ratio", damping_ratio)
    rb1, rb2 = (float(r) for r in geom.base_radius)
    torque_in = torque_out * rb1 / rb2
    if contact is not None:
        law = contact_mesh_law(geom, contact, torque_in)
    else:
        law = mesh_law(geom, K_transverse, torque_in, stiffness_form, order, excitation, transmission_error)
    a, bb = geom.operating_pressure_angle, geom.base_helix_angle
    cb, sb = math.cos(bb), math.sin(bb)
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    mp, mg = (float(x) for x in geom.mass)
    ip, ig = (float(x) for x in geom.inertia)
    names = ("x_pinion", "y_pinion", "z_pinion", "theta_pinion", "x_gear", "y_gear", "z_gear", "theta_gear")
    M = np.diag([mp, mp, mp, ip, mg, mg, mg, ig])
    (kr1, kr2), (ka1, ka2), cr, ca = bearing["k_radial"], bearing["k_axial"], bearing["c_radial"], bearing["c_axial"]
    Kb = np.diag([kr1, kr1, ka1, 0, kr2, kr2, ka2, 0])
    Cb = np.diag([cr, cr, ca, 0, cr, cr, ca, 0])
    g = np.array([[cb * math.sin(a), cb * math.cos(a), -h * sb, cb * rb1,
                   -cb * math.sin(a), -cb * math.cos(a), h * sb, -cb * rb2]])
    tau = np.array([0, 0, 0, torque_in, 0, 0, 0, -torque_out])
    R = np.array([[rb1, -rb2]])
    f_static = torque_out / (rb2 * cb)
    trans = tuple(nm for i, nm in enumerate(names) if i not in (3, 7))
    names, M, Kb, Cb, g, tau, rot = _constrain(names, M, Kb, Cb, g, tau, [3, 7])
    model = _reduce(geom.pair.name, M, Kb, Cb, g, tau, rot, R, [law], [0.0],
                    math.inf if backlash is None else _check_nonneg("backlash_um", backlash),
                    [f_static], geom.pair.teeth[0] / 60.0, geom.pair.teeth[0], names, cb, trans)
    return _with_mesh_damping(model, mesh_damping, damping_ratio, (rb1, rb2), (ip, ig))


def mesh_mode(model: GearModel) -> int:
    """Index (in :meth:`GearModel.modes`) of the mesh mode.

    The mode with the largest share of its strain energy in the meshes (:func:`mesh_energy_fraction`).

    Parameters
    ----------
    model : GearModel
        The model.

    Returns
    -------
    int
        Index of the mesh mode.
    """
    return int(np.argmax(mesh_energy_fraction(model, model.modes()["shapes"])))


def _with_mesh_damping(model: GearModel, mesh_damping: float | None, damping_ratio: float, rb, inertia) -> GearModel:
    """``model`` with its mesh damping: ``mesh_damping`` (N·s/m) on every mesh when given, else
    the damping that makes the modal damping ratio of the mesh mode (:func:`mesh_mode`: complex
    eigenvalues of the state matrix, ζ = −Re λ/|λ|, bearing damping included) equal to
    ``damping_ratio``. The meshes share one scale s on c_0 = 2ζ√(k̄ m_e) (m_e the torsional
    equivalent mass along the normal, :func:`_equivalent_mass`): with rigid supports s = 1, the
    torsional mode's ζ. The scale comes from :func:`_ray_damping_scale` (a few small linear solves)
    and is checked on the damped model's own modes, which the returned model keeps (its
    :meth:`GearModel.modes`); where that check fails (modes that share the mesh's energy) the
    secant search on the eigenvalues :func:`_secant_damping_scale` decides."""
    if mesh_damping is not None:
        return replace(model, damping=np.full(model.m, _check_nonneg("mesh_damping_Ns_per_m", mesh_damping)))
    me = _equivalent_mass(model.cos_beta_b, rb, inertia)
    c0 = np.array([2 * damping_ratio * math.sqrt(ml.k_mean * me) for ml in model.meshes])
    if damping_ratio == 0:
        return replace(model, damping=c0)
    s = _ray_damping_scale(model, c0, damping_ratio)
    if s is not None:
        damped = replace(model, damping=s * c0)
        md = damped.modes()
        if abs(md["damping_ratio"][mesh_mode(damped)] - damping_ratio) <= 1e-7 * damping_ratio:
            return damped
    return replace(model, damping=_secant_damping_scale(model, c0, damping_ratio) * c0)


def _ray_damping_scale(model: GearModel, c0: np.ndarray, zeta: float) -> float | None:
    """The scale s > 0 of the mesh dampers s·c_0 (N·s/m) that puts an eigenvalue of the reduced model
    on the ray λ = ω(−ζ + i√(1−ζ²)) near the undamped mesh mode, or None if none is found.

    Derivation: the model's characteristic matrix is Q(λ) = Q_0(λ) + λ s B diag(c_0) G with
    Q_0(λ) = λ²I + λC_r + K_r + B diag(k̄) G (bearing damping only); by the matrix determinant lemma
    det Q = det Q_0 · det(I_m + λ s H(λ)), H = diag(c_0) G Q_0⁻¹ B (m × m). So λ is an eigenvalue
    exactly when μ = −1/(λs) is an eigenvalue of H(λ): on the ray (one real unknown ω) the
    condition is arg(−λμ) = 0 for the dominant μ (the mode nearest λ), and then s = 1/|λμ|. The
    root is found by secant steps in ω from the undamped mesh mode (:func:`mesh_energy_fraction`
    of the real modes of K_r + B k̄ G); each step costs one n × n complex solve, no eigensolve of
    the 2n × 2n state matrix (ζ of the mesh mode to 10⁻¹² in 3–5 steps)."""
    K, _ = model.linear_matrices()
    w2, vec = np.linalg.eig(K)
    w2, vec = w2.real, vec.real
    ok = w2 > 0
    if not ok.any():
        return None
    share = np.where(ok, mesh_energy_fraction(model, vec), -1.0)
    ray = complex(-zeta, math.sqrt(1.0 - zeta**2))
    eye = np.eye(model.n)
    BC = model.B * c0[None, :]

    def residual(w: float) -> tuple[float, complex]:
        lam = w * ray
        H = model.G @ np.linalg.solve(lam * lam * eye + lam * model.Cr + K, BC)
        if H.shape[0] == 1:
            mu = complex(H[0, 0])
        else:
            mu = np.linalg.eigvals(H)
            mu = mu[np.argmax(np.abs(mu))]
        return math.atan2((-lam * mu).imag, (-lam * mu).real), lam * mu

    w0 = math.sqrt(float(w2[int(np.argmax(share))]))
    w1 = w0 * (1.0 + zeta**2)
    f0, _ = residual(w0)
    f1, lm = residual(w1)
    for _ in range(12):
        if abs(f1) <= 1e-12:
            s = 1.0 / abs(lm)
            return s if math.isfinite(s) and s > 0 else None
        if f1 == f0:
            return None
        w0, f0, w1 = w1, f1, w1 - f1 * (w1 - w0) / (f1 - f0)
        if not (w1 > 0 and math.isfinite(w1)):
            return None
        f1, lm = residual(w1)
    return None


def _mesh_mode_eigenvalue(model: GearModel, damping: np.ndarray, near: complex | None = None) -> complex:
    """Eigenvalue λ of the mesh mode (:func:`mesh_mode`) with mesh damping ``damping`` (N·s/m); with
    ``near``, the eigenvalue (Im λ > 0) nearest it, from the eigenvalues alone (the same mode while the
    damping changes: cheaper than the shapes)."""
    trial = replace(model, damping=np.asarray(damping, dtype=float))
    if near is None:
        return complex(trial.modes()["eigenvalue"][mesh_mode(trial)])
    lam = np.linalg.eigvals(trial._state_matrix(None))
    lam = lam[lam.imag > 0]
    return complex(lam[np.argmin(np.abs(lam - near))])


def _secant_damping_scale(model: GearModel, c0: np.ndarray, damping_ratio: float) -> float:
    """The scale s of the mesh dampers s·c_0 from the complex eigenvalues of the state matrix: ζ(s)
    of the mesh mode is nearly affine in s, secant steps reach it to 10⁻⁹ in two or three
    eigenvalue solves; 0 when the bearings alone damp the mesh mode more than ζ."""
    def zeta(lam: complex) -> float:
        return -lam.real / abs(lam)

    lam1 = _mesh_mode_eigenvalue(model, c0)
    s0, z0 = 0.0, zeta(_mesh_mode_eigenvalue(model, 0 * c0, near=lam1))
    if z0 >= damping_ratio:
        return 0.0
    s1, z1 = 1.0, zeta(lam1)
    for _ in range(8):
        if abs(z1 - damping_ratio) <= 1e-9 * damping_ratio or z1 == z0:
            break
        s0, z0, s1 = s1, z1, max(s1 + (damping_ratio - z1) * (s1 - s0) / (z1 - z0), 0.5 * s1)
        lam1 = _mesh_mode_eigenvalue(model, s1 * c0, near=lam1)
        z1 = zeta(lam1)
    return s1


TRAIN_GEARS = ("plate", "blanket", "impression")


def train_model(geom: PairGeometry, torque: float, K_transverse: np.ndarray | None, *, bearing=None,
                damping_ratio: float = DEFAULT_DAMPING_RATIO, backlash: float | None = 60e-6,
                stiffness_form: str = "fourier", order: int = 3, excitation: str = "tvms",
                phase_offsets: Sequence[float] = (0.0, 0.0), mesh_damping: float | None = None,
                contact: MeshForceTable | None = None) -> GearModel:
    """The 9-DOF plate–blanket–impression train of the improved potential-energy paper (package docstring).

    The three gears are the pair file's gear (index 1) repeated, the pair's TVMS serving both meshes (assumption: the
    improved potential-energy paper's gears are alike, 88 teeth each), the plate driven by ``torque`` and the impression
    loaded by it; y along the line of centres, each gear on the pair file's gear supports (radial for y, axial for z).

    Parameters
    ----------
    geom : PairGeometry
        Pair geometry with bore radius and material; its gear (index 1) is used three times.
    torque : float
        Torque driving the plate and loading the impression (N·m).
    K_transverse : numpy.ndarray or None
        (P,) transverse TVMS K (N/m) evenly over one base pitch, serving both meshes.
    bearing, damping_ratio, backlash, stiffness_form, order, excitation, mesh_damping
        As in :func:`pair_model`.
    phase_offsets : sequence of float, default (0, 0)
        Shift of each mesh's TVMS (mesh cycles); default in phase: the improved potential-energy paper finds the two
        mesh forces nearly identical.
    contact : MeshForceTable or None
        The pair's mesh force table: both meshes driven by the real contact.

    Returns
    -------
    GearModel
        The 9-DOF model (SI).

    References
    ----------
    .. [1] A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an Improved Potential Energy
       Method for Time-Varying Meshing Stiffness (the improved potential-energy paper, docs/references.md).
    """
    require_dynamics_data(geom)
    torque = _check_positive("torque_Nm", torque)
    bearing = _bearing_settings(geom, bearing)
    if len(phase_offsets) != 2 or not all(math.isfinite(float(p)) for p in phase_offsets):
        raise GearmeshInputError("phase_offsets", phase_offsets, "must give two finite mesh-cycle offsets")
    rb = float(geom.base_radius[1])
    m_, j_ = float(geom.mass[1]), float(geom.inertia[1])
    a, bb = geom.operating_pressure_angle, geom.base_helix_angle
    cb, sb = math.cos(bb), math.sin(bb)
    h = 1.0 if geom.pair.helix_hand == "right" else -1.0
    torque_pinion = torque * float(geom.base_radius[0]) / rb  # the same transverse force on the pair's table
    if contact is not None:
        laws = [contact_mesh_law(geom, contact, torque_pinion, float(p)) for p in phase_offsets]
    else:
        laws = [mesh_law(geom, K_transverse, torque_pinion, stiffness_form, order, excitation, None, float(p))
                for p in phase_offsets]
    names = tuple(f"{d}_{g}" for g in TRAIN_GEARS for d in ("y", "z", "theta"))
    M = np.diag([m_, m_, j_] * 3)
    kr, ka, cr, ca = bearing["k_radial"][1], bearing["k_axial"][1], bearing["c_radial"], bearing["c_axial"]
    Kb = np.diag([kr, ka, 0] * 3)
    Cb = np.diag([cr, ca, 0] * 3)
    sa = math.sin(a)
    G = np.zeros((2, 9))
    G[0, [0, 1, 2, 3, 4, 5]] = [cb * sa, -h * sb, cb * rb, -cb * sa, h * sb, -cb * rb]
    G[1, [3, 4, 5, 6, 7, 8]] = [cb * sa, -h * sb, cb * rb, -cb * sa, h * sb, -cb * rb]
    tau = np.zeros(9)
    tau[2], tau[8] = torque, -torque
    R = np.array([[rb, -rb, 0.0], [0.0, rb, -rb]])
    f_static = torque / (rb * cb)
    trans = tuple(nm for i, nm in enumerate(names) if i not in (2, 5, 8))
    names, M, Kb, Cb, G, tau, rot = _constrain(names, M, Kb, Cb, G, tau, [2, 5, 8])
    model = _reduce("train", M, Kb, Cb, G, tau, rot, R, laws, [0.0, 0.0],
                    math.inf if backlash is None else _check_nonneg("backlash_um", backlash),
                    [f_static, f_static], geom.pair.teeth[1] / 60.0, geom.pair.teeth[1], names, cb, trans)
    return _with_mesh_damping(model, mesh_damping, damping_ratio, (rb, rb), (j_, j_))


def resonance_speeds(model: GearModel, harmonics: Sequence[int] = (1, 2, 3)) -> dict[str, np.ndarray]:
    """Speeds (rpm) where harmonic j of the mesh frequency meets a natural frequency of the linearised model.

    n = f_n/(j·z_drv/60).

    Parameters
    ----------
    model : GearModel
        The model (its modes at the mean stiffness).
    harmonics : sequence of int, default (1, 2, 3)
        Mesh-frequency harmonics j.

    Returns
    -------
    dict
        'frequency_Hz' (modes,) natural frequencies (Hz) and 'speed_rpm' (harmonic, mode) driver speeds (rpm).
    """
    fn = model.modes()["frequency_Hz"]
    h = np.asarray(harmonics, dtype=float)
    return {"frequency_Hz": fn, "speed_rpm": fn[None, :] / (h[:, None] * model.mesh_frequency_per_rpm)}


#: Relative offsets of the speeds around each predicted resonance speed n_r, in units of the
#: mode's damping ratio ζ (the half-power band of a resonance is about n_r(1 ± ζ)).
RESONANCE_OFFSETS = (-1.0, -0.5, -0.25, 0.0, 0.25, 0.5, 1.0)


def resonance_band(model: GearModel, low: float, high: float, harmonics: Sequence[int] = (1, 2, 3),
                   offsets: Sequence[float] = RESONANCE_OFFSETS, min_mesh_energy: float = 0.0) -> np.ndarray:
    """Speeds (rpm) strictly inside (``low``, ``high``) around every resonance speed n_r of :func:`resonance_speeds`.

    n_r(1 + c ζ_r) for c in ``offsets``, ζ_r the mode's damping ratio clipped to [0.005, 0.2] (overdamped modes have no
    peak to resolve), of the modes with at least ``min_mesh_energy`` of their strain energy in the meshes
    (:func:`mesh_energy_fraction`). Unsorted.

    Parameters
    ----------
    model : GearModel
        The model.
    low, high : float
        Bounds of the speed range (rpm), excluded.
    harmonics : sequence of int, default (1, 2, 3)
        Mesh-frequency harmonics.
    offsets : sequence of float
        Offsets c in damping ratios (-); default :data:`RESONANCE_OFFSETS`.
    min_mesh_energy : float, default 0
        Smallest fraction (-) of a mode's strain energy in the meshes.

    Returns
    -------
    numpy.ndarray
        Speeds (rpm), unsorted.
    """
    res = resonance_speeds(model, harmonics)
    md = model.modes()
    zeta = np.clip(np.nan_to_num(md["damping_ratio"], nan=0.0), 0.005, 0.2)
    driven = mesh_energy_fraction(model, md["shapes"]) >= min_mesh_energy if min_mesh_energy > 0 \
        else np.ones(zeta.size, dtype=bool)
    extra = [n * (1 + c * z) for row in res["speed_rpm"] for n, z, d in zip(row, zeta, driven) if d for c in offsets]
    return np.array([n for n in extra if np.isfinite(n) and low < n < high])


def mesh_energy_fraction(model: GearModel, shapes: np.ndarray) -> np.ndarray:
    """Fraction (-) of each mode's strain energy in the meshes (mean stiffness).

    k (G φ)² over Σ k_b,i φ_i² + k (G φ)², φ the displacement part of the mode shape (made real by removing its phase).
    A mode with little energy in the mesh is barely driven by the mesh excitation.

    Parameters
    ----------
    model : GearModel
        The model.
    shapes : numpy.ndarray
        (2n or n, modes) mode shapes as columns (:meth:`GearModel.modes`), complex.

    Returns
    -------
    numpy.ndarray
        (modes,) fractions in [0, 1] (-).
    """
    k = np.array([ml.k_mean for ml in model.meshes])
    trans = [i for i in range(model.full["M"].shape[0]) if i not in model.full["rotations"]]
    kb = np.diag(model.full["K_bearing"])[trans]
    big = np.argmax(np.abs(shapes), axis=0)
    v = np.real(shapes * np.exp(-1j * np.angle(shapes[big, np.arange(shapes.shape[1])]))[None, :])
    mesh = np.sum(k[:, None] * (model.G @ v) ** 2, axis=0)
    return mesh / (np.sum(kb[:, None] * v[:model.n_trans] ** 2, axis=0) + mesh)
