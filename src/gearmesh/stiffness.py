"""Time-varying mesh stiffness (TVMS) of helical gears by the potential energy method.

Everything inside is SI: lengths in m, angles in rad, forces in N, stiffness in N/m.
A *per-unit-width* stiffness k0 is in N/m per m of face width (N/m²) and its compliance
c0 = 1/k0 in m²/N; a slice of transverse width Δz then has stiffness k0·Δz (N/m).

The compliance of one transverse slice of one tooth (the potential-energy cantilevers and
the fillet foundation, tabulated against roll length) is :mod:`gearmesh.slice_compliance`'s;
this module assembles the slices of the helical mesh.

Helical assembly and conventions
--------------------------------
The face width b is cut into N transverse slices of width Δz = b/N (centres z_k). For a
pinion roll distance r_b1·φ1 the slice k of tooth pair j touches at s on the line of
action (:func:`gearmesh.contact.contact_roll_positions`); pinion roll length
ρ1 = ρ_SAP1 + s, gear ρ2 = ρ_EAP2 − s. In a slice the pinion tooth, the contact and the
gear tooth are springs in series::

    1/k_slice = (c_1(ρ1) + c_2(ρ2) + c_h) / Δz,    c_i = c_b + c_s + c_a + c_f

and all slices of all lines in contact are in parallel: K(φ) = Σ_lines Σ_slices k_slice.
(The low-fluctuation paper writes K = 1/(Σ_i 1/k_t^i + 1/k_f), a series sum of lines: wrong, the lines
share the deflection, not the load. The transition-curve paper first sums each component along a line and
then combines components in series; that assumes each component deflects uniformly along
the line, which is not so: here each slice is in series first.)

K is the *transverse* mesh stiffness along the transverse line of action: the transverse
load F_bt = T1/r_b1 over the transverse approach δ_t = r_b1·Δφ1 + r_b2·Δφ2. The cantilever
and foundation slices are spur slices loaded by the transverse component (slice theory);
the contact of a slice is a line of length Δz/cos βb under the normal load F_bt/cos βb,
whose normal approach is δ_t·cos βb, so its transverse per-width stiffness is
k_h0·cos βb. The stiffness along the normal is K_n = K/cos²βb (:attr:`MeshStiffness.K_normal`).
For β = 0 every convention coincides with the spur model.

Slices: rule 'centre' takes a slice when its centre is in the active zone (the points of
contact_roll_positions; the line ends are rounded to whole slices, error O(Δz)); rule
'clip' (default) clips the end slices to the active zone (error O(Δz²); then 200 slices
are within 1e-6 of the limit for the low-fluctuation paper pair 1, where 'centre' needs ~1000 for 1e-3).

Speed (docs/modelling.md): each gear's slice compliance is evaluated by Gauss–Legendre at a few
hundred roll lengths once (:func:`gearmesh.slice_compliance.slice_compliance_table`), resampled
as one pair table on a fine uniform grid of s (:func:`gearmesh.slice_compliance.pair_slice_table`); the mesh is then interpolation and
sums over the runs of slices in contact (:func:`mesh_stiffness`). The straightforward
baseline is :func:`mesh_stiffness_reference` (adaptive quadrature per slice per position).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping

import numpy as np

from .body import mesh_body_compliance
from .contact import contact_length_breakpoints, contact_roll_positions, hand_sign, mesh_cycle_rolls, tooth_pair_indices
from .choices import DEFAULT_TOOTH_METHOD
from .errors import GearmeshInputError
from .gear import PairGeometry
from .limits import ISO6336_STEEL_MODULUS, check_slice_grid
from .slice_compliance import (PairSliceTable, check_method, fixed_moments_quad, hertz_compliance_transverse,
                               pair_slice_table, slice_compliance_table, tooth_slice_compliance_quad)
from .tooth import PEM_METHODS, SliceComplianceTable, require_stiffness_data, tooth_model


# --------------------------------------------------------------------------------------
# Helical mesh: slices, lines, pairs
# --------------------------------------------------------------------------------------


def slice_centres(geom: PairGeometry, n_slices: int) -> tuple[np.ndarray, float]:
    """Centres z_k (m) of ``n_slices`` equal transverse slices over [−b/2, b/2] and their width Δz (m).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (face width b in m).
    n_slices : int
        Number of equal slices (≥ 1).

    Returns
    -------
    z : ndarray
        (n_slices,) slice centres (m), z = 0 at mid-face.
    dz : float
        Slice width Δz = b/n_slices (m).
    """
    if n_slices < 1:
        raise GearmeshInputError("n_slices", n_slices, "must be at least 1")
    dz = geom.face_width / n_slices
    return -0.5 * geom.face_width + dz * (np.arange(n_slices) + 0.5), dz


SLICE_RULES = ("centre", "clip")


@dataclass(frozen=True)
class SliceSamples:
    """Every slice in contact at every roll (SI), ordered by roll, tooth pair, slice.

    ``line`` (N,) flat index p·J + j of the contact line of each entry, ``slice_index``
    (N,) its slice k, ``s`` (N,) the evaluation position on the line of action (m),
    ``width`` (N,) the width of face it stands for (m); ``shape`` = (P, J, S).
    """

    shape: tuple[int, int, int]
    line: np.ndarray
    slice_index: np.ndarray
    s: np.ndarray
    width: np.ndarray

    def line_sums(self, values: np.ndarray) -> np.ndarray:
        """Σ of ``values`` (..., N) over the entries of each line: (..., P, J)."""
        p, j, _ = self.shape
        out = np.zeros(values.shape[:-1] + (p * j,))
        if self.line.size:
            starts = np.flatnonzero(np.diff(self.line, prepend=-1))
            out[..., self.line[starts]] = np.add.reduceat(values, starts, axis=-1)
        return out.reshape(values.shape[:-1] + (p, j))


def slice_samples(geom: PairGeometry, roll, n_slices: int, pairs: np.ndarray | None = None,
                  rule: str = "centre") -> SliceSamples:
    """Where and with what width every slice of every tooth pair touches, at every roll.

    Along one contact line s is linear in the slice index, so the slices in contact form
    one run of consecutive k computed in closed form (±1 slice, then checked exactly):
    no (P, J, S) array is formed.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    roll : array_like
        (P,) pinion roll distances r_b1·φ1 (m).
    n_slices : int
        Number of equal transverse slices over the face width.
    pairs : ndarray, optional
        (J,) tooth-pair indices (default :func:`gearmesh.contact.tooth_pair_indices`).
    rule : {'centre', 'clip'}
        'centre' (default) — a slice is in contact when its centre is in the active zone
        [0, g_α], evaluated at its centre, full width Δz: exactly the points (bit for bit)
        of :func:`gearmesh.contact.contact_roll_positions`; first-order convergence in Δz
        because the line ends are rounded to whole slices. 'clip' — each slice, whose
        contact runs over s ± Δz·tan βb/2, is clipped to the active zone, weighted by the
        fraction inside and evaluated at the middle of that part (second order). For
        β = 0 both rules coincide.

    Returns
    -------
    SliceSamples
        Per entry in contact: its line, slice index, position s (m) and width (m).
    """
    if rule not in SLICE_RULES:
        raise GearmeshInputError("rule", rule, f"must be one of {list(SLICE_RULES)}")
    roll = np.asarray(roll, dtype=float)
    pairs = tooth_pair_indices(geom) if pairs is None else np.asarray(pairs)
    z, dz = slice_centres(geom, n_slices)
    tb = math.tan(geom.base_helix_angle)
    g = geom.path_of_contact
    hz = hand_sign(geom) * z * tb  # (S,) offset of slice k, as in contact_roll_positions
    u = (roll[:, None] + pairs[None, :] * geom.transverse_base_pitch).ravel()  # (L,) line at z = 0
    half = 0.5 * dz * tb
    n_lines = u.size
    if half == 0.0:  # β = 0: a line is all in or all out
        inside = (u >= 0) & (u <= g)
        k_lo = np.where(inside, 0, n_slices)
        k_hi = np.where(inside, n_slices - 1, -1)
    else:
        step = hz[1] - hz[0] if n_slices > 1 else 1.0
        # centre of slice k ≈ u + hz[0] + step·k; the run overlapping [−half, g + half]
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            ka = np.clip((-half - u - hz[0]) / step, -2.0, n_slices + 2.0)
            kb = np.clip((g + half - u - hz[0]) / step, -2.0, n_slices + 2.0)
        k_lo = np.floor(np.minimum(ka, kb)).astype(np.int64) - 1
        k_hi = np.ceil(np.maximum(ka, kb)).astype(np.int64) + 1
        k_lo = np.clip(k_lo, 0, n_slices)
        k_hi = np.clip(k_hi, -1, n_slices - 1)
    count = np.maximum(k_hi - k_lo + 1, 0)
    total = int(count.sum())
    line = np.repeat(np.arange(n_lines), count)
    first = np.cumsum(count) - count
    k = np.arange(total) - np.repeat(first - k_lo, count)
    p_idx, j_idx = np.divmod(line, pairs.size)
    # the same floating-point expression as contact.contact_roll_positions
    sc = roll[p_idx] + pairs[j_idx] * geom.transverse_base_pitch + hz[k]
    shape = (roll.size, pairs.size, n_slices)
    if rule == "centre" or half == 0.0:
        keep = (sc >= 0) & (sc <= g)
        sc = sc[keep]
        return SliceSamples(shape, line[keep], k[keep], sc, np.full(sc.shape, dz))
    # slice k spans sc ± half; in units of half, [−1, 1] ∩ [−sc, g − sc]/half (no cancellation
    # for tiny β)
    with np.errstate(over="ignore"):
        lo = np.maximum(-1.0, -sc / half)
        hi = np.minimum(1.0, (g - sc) / half)
    keep = hi > lo
    lo, hi = lo[keep], hi[keep]
    return SliceSamples(shape, line[keep], k[keep], sc[keep] + 0.5 * half * (lo + hi), 0.5 * dz * (hi - lo))


def line_slice_sum(geom: PairGeometry, roll, n_slices: int, per_width: Callable[[np.ndarray], np.ndarray],
                   rule: str = "centre") -> np.ndarray:
    """Σ over the slices of each contact line of per_width(s)·(slice width) (N/m): (P, J).

    The building block of the slice method; slices out of contact give 0. Pair indices
    are :func:`gearmesh.contact.tooth_pair_indices`.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    roll : array_like
        (P,) pinion roll distances r_b1·φ1 (m).
    n_slices : int
        Number of equal transverse slices over the face width.
    per_width : callable
        Maps positions s (N,) on the line of action (m) to a per-unit-width stiffness (N/m²).
    rule : {'centre', 'clip'}
        Slice rule of :func:`slice_samples` (default 'centre').

    Returns
    -------
    ndarray
        (P, J) stiffness of each contact line (N/m).
    """
    smp = slice_samples(geom, roll, n_slices, rule=rule)
    return smp.line_sums(per_width(smp.s) * smp.width)


@dataclass(frozen=True)
class MeshStiffness:
    """TVMS of a helical pair (SI, transverse convention of the module docstring).

    roll : (P,) pinion roll distance r_b1·φ1 (m) over one mesh cycle (one base pitch).
    K : (P,) total mesh stiffness (N/m) along the transverse line of action.
    pair_roll : (Q,) position (m) on the line of action of the mid-face contact of one
        tooth pair followed over its whole engagement (0 = mid-face at the SAP).
    k_pair : (Q,) its stiffness (N/m); K(roll) = Σ_j k_pair(roll + j·p_bt) (the teeth alone:
        with the pair file's gear bodies K is 1/(1/Σ_j k_pair + c_body), :mod:`gearmesh.body`).
    components : series-equivalent stiffness (N/m) of each component at each roll: with
        U_x the strain energy stored in component x under the slice load sharing,
        1/K_x = 2U_x/F², so that 1/K = Σ_x 1/K_x exactly. Keys 'bending_pinion', …,
        'fillet_gear', 'hertz' (and 'body' with the pair file's gear bodies). Empty if not requested.
    roll_breakpoints, K_breakpoints : K (N/m) also at the rolls (m) where a contact line
        end crosses a corner of the active zone (the kinks of K,
        :func:`gearmesh.contact.contact_length_breakpoints`), so that :attr:`min`,
        :attr:`max` and :attr:`fluctuation` do not depend on the sampling of ``roll``.
    """

    name: str
    method: str
    n_slices: int
    rule: str
    roll: np.ndarray
    K: np.ndarray
    pair_roll: np.ndarray
    k_pair: np.ndarray
    components: Mapping[str, np.ndarray]
    roll_breakpoints: np.ndarray
    K_breakpoints: np.ndarray
    base_pitch: float
    base_radius: np.ndarray
    base_helix_angle: float

    @property
    def mean(self) -> float:
        """Mean of K over the mesh cycle (N/m), from the evenly spaced samples."""
        return float(np.mean(self.K))

    @property
    def min(self) -> float:
        """Minimum of K (N/m) over the samples and the kinks."""
        return float(min(np.min(self.K), np.min(self.K_breakpoints, initial=np.inf)))

    @property
    def max(self) -> float:
        """Maximum of K (N/m) over the samples and the kinks."""
        return float(max(np.max(self.K), np.max(self.K_breakpoints, initial=-np.inf)))

    @property
    def fluctuation(self) -> float:
        """ε_k = (K_max − K_min)/K_min (-), the low-fluctuation paper (as a fraction, not %)."""
        return (self.max - self.min) / self.min

    @property
    def K_normal(self) -> np.ndarray:
        """Mesh stiffness along the normal to the flank, K/cos²βb (N/m)."""
        return self.K / math.cos(self.base_helix_angle) ** 2

    def summary(self) -> dict[str, float]:
        """Headline numbers: mean/min/max K in N/µm (1 N/µm = 1e6 N/m) and ε_k (-)."""
        return {"mean_N_per_um": self.mean * 1e-6, "min_N_per_um": self.min * 1e-6,
                "max_N_per_um": self.max * 1e-6, "fluctuation": self.fluctuation}


#: Default slice count and rule, from the convergence study (tests/test_stiffness.py and the
#: report): with the 'clip' rule the error falls as N⁻² and N = 200 is within 1e-6 of the
#: N → ∞ limit for the low-fluctuation paper pair 1 (pointwise); the 'centre' rule converges as N⁻¹ and
#: needs N ≈ 1000 for 1e-3 (the improved potential-energy paper's N = 1000 cures the artefact of that rule).
DEFAULT_SLICES = 200
DEFAULT_RULE = "clip"


def _sum_slices(geom: PairGeometry, pair_table: PairSliceTable, roll: np.ndarray, n_slices: int,
                pairs: np.ndarray, rule: str, components: bool):
    """Line stiffnesses (P, J) in N/m and, optionally, the per-roll component compliance sums."""
    smp = slice_samples(geom, roll, n_slices, pairs, rule)
    t = smp.s * (1.0 / pair_table.ds)
    n_int = pair_table.total.size - 1
    i = np.minimum(t.astype(np.intp), n_int - 1)
    w = t - i
    c = np.take(pair_table.total, i)
    c += w * np.take(pair_table.total_slope, i)
    k_lines = smp.line_sums(smp.width / c)
    if not components:
        return k_lines, None
    # energy share of component x: 1/K_x = (1/K²) Σ width·c_x/c²
    cx = np.take(pair_table.values, i, axis=1)  # (C, N)
    cx += w * np.take(pair_table.slopes, i, axis=1)
    cx *= smp.width / c**2
    return k_lines, smp.line_sums(cx).sum(axis=-1)  # (C, P)


def mesh_stiffness(geom: PairGeometry, n_positions: int = 360, n_slices: int = DEFAULT_SLICES,
                   method: str = DEFAULT_TOOTH_METHOD, components: bool = True, n_nodes: int = 257,
                   tables: tuple[SliceComplianceTable, SliceComplianceTable] | None = None,
                   pair_table: PairSliceTable | None = None, rule: str = DEFAULT_RULE,
                   contact_compliance: float | None = None) -> MeshStiffness:
    """Time-varying mesh stiffness of a helical pair by the slice potential energy method.

    Tabulates each gear's slice compliance once (:func:`~gearmesh.slice_compliance.slice_compliance_table`),
    resamples the pair slice compliance on a fine uniform grid of s, then for every roll position, tooth
    pair and slice in contact (:func:`slice_samples`, the points of :func:`gearmesh.contact.contact_roll_positions`)
    interpolates linearly and sums k_slice = width/(c1 + c2 + c_h) over slices and lines.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    n_positions, n_slices : int
        Roll positions over one base pitch (default 360); transverse slices over the face
        width (default :data:`DEFAULT_SLICES`).
    method : {'fe', 'traditional', 'improved', 'transition'}
        Tooth model (default :data:`gearmesh.choices.DEFAULT_TOOTH_METHOD`, 'fe').
    components : bool
        Also compute the series-equivalent component stiffnesses (default True).
    n_nodes : int
        Gauss-evaluated roll-length nodes per gear (default 257).
    tables, pair_table : SliceComplianceTable pair, PairSliceTable, optional
        Precomputed tables to reuse (e.g. in a sweep of n_slices).
    rule : {'clip', 'centre'}
        Slice rule of :func:`slice_samples`: 'clip' (default, error O(Δz²)) or 'centre' (O(Δz)).
    contact_compliance : float, optional
        Contact term (m²/N per unit transverse width) of :func:`~gearmesh.slice_compliance.pair_slice_table`;
        None: Yang & Sun's constant [1] (ignored with ``pair_table``).

    Returns
    -------
    MeshStiffness
        ``roll`` (P,) m, ``K`` (P,) N/m, ``k_pair`` N/m, ``components`` N/m; ``mean``, ``min``, ``max`` N/m.

    References
    ----------
    .. [1] Yang D.C.H., Sun Z.S., "A rotary model for spur gear dynamics", J. Mech. Transm.
       Autom. Des. 107 (1985) 529–535.
    """
    check_method(method)
    require_stiffness_data(geom)
    n_slices, n_positions = check_slice_grid(n_slices, n_positions, ("n_slices", "n_positions"))
    if tables is not None and any(tab.method != method for tab in tables):
        raise GearmeshInputError("method", method, f"differs from the method of the given tables "
                                 f"({tables[0].method!r}, {tables[1].method!r})")
    if pair_table is None:
        if tables is None:
            tables = (slice_compliance_table(geom, 0, method, n_nodes),
                      slice_compliance_table(geom, 1, method, n_nodes))
        pair_table = pair_slice_table(geom, tables, contact_compliance=contact_compliance)
    roll = mesh_cycle_rolls(geom, n_positions)
    pairs = tooth_pair_indices(geom)
    k_lines, sums = _sum_slices(geom, pair_table, roll, n_slices, pairs, rule, components)
    K = k_lines.sum(axis=1)
    comps: dict[str, np.ndarray] = {}
    if components:
        for name, row in zip(pair_table.columns, sums):
            with np.errstate(divide="ignore"):  # a component without compliance ('fe': shear, axial): inf
                comps[name] = K**2 / row
    roll_bp = contact_length_breakpoints(geom)
    K_bp = _sum_slices(geom, pair_table, roll_bp, n_slices, pairs, rule, False)[0].sum(axis=1)
    c_body = mesh_body_compliance(geom)
    if c_body:  # the bodies' axial bending in series with the teeth (gearmesh.body)
        K, K_bp = 1.0 / (1.0 / K + c_body), 1.0 / (1.0 / K_bp + c_body)
        if components:
            comps["body"] = np.full(K.shape, 1.0 / c_body)
    # one pair over its engagement: u = roll + j·p_bt, ordered by j then roll
    u = (roll[None, :] + pairs[:, None] * geom.transverse_base_pitch).ravel()
    kp = k_lines.T.ravel()
    nz = np.flatnonzero(kp)
    lo, hi = (max(nz[0] - 1, 0), min(nz[-1] + 2, kp.size)) if nz.size else (0, 0)
    return MeshStiffness(name=geom.pair.name, method=method, n_slices=n_slices, rule=rule, roll=roll, K=K,
                         pair_roll=u[lo:hi], k_pair=kp[lo:hi], components=comps,
                         roll_breakpoints=roll_bp, K_breakpoints=K_bp,
                         base_pitch=geom.transverse_base_pitch, base_radius=geom.base_radius.copy(),
                         base_helix_angle=geom.base_helix_angle)


def mesh_stiffness_reference(geom: PairGeometry, n_positions: int, n_slices: int, method: str) -> np.ndarray:
    """Straightforward baseline of :func:`mesh_stiffness` with ``rule='centre'`` (N/m): at
    every roll position, every slice of every tooth pair in contact
    (:func:`gearmesh.contact.contact_roll_positions`) gets its compliance by adaptive
    quadrature (:func:`~gearmesh.slice_compliance.tooth_slice_compliance_quad`); no tables, no interpolation. Slow:
    for tests and benchmark baselines on small grids (about 5 ms per slice and position).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    n_positions : int
        Roll positions over one base pitch.
    n_slices : int
        Transverse slices over the face width.
    method : {'traditional', 'improved', 'transition'}
        One of the potential-energy cantilevers (:data:`PEM_METHODS`).

    Returns
    -------
    ndarray
        (n_positions,) mesh stiffness K (N/m) along the transverse line of action.
    """
    if method not in PEM_METHODS:
        raise GearmeshInputError("method", method, f"must be one of {list(PEM_METHODS)} (the reference is the "
                                 "potential-energy cantilever's)")
    require_stiffness_data(geom)
    models = (tooth_model(geom, 0, method), tooth_model(geom, 1, method))
    moments = tuple(fixed_moments_quad(m) for m in models)
    ch = hertz_compliance_transverse(geom)
    roll = mesh_cycle_rolls(geom, n_positions)
    z, dz = slice_centres(geom, n_slices)
    s = contact_roll_positions(geom, roll, z)
    K = np.zeros(n_positions)
    for p in range(n_positions):
        for sv in s[p][np.isfinite(s[p])]:
            c1 = sum(tooth_slice_compliance_quad(models[0], geom.rho_sap[0] + sv, moments=moments[0]).values())
            c2 = sum(tooth_slice_compliance_quad(models[1], geom.rho_eap[1] - sv, moments=moments[1]).values())
            K[p] += dz / (c1 + c2 + ch)
    return K


# --------------------------------------------------------------------------------------
# Post-processing: LSTE, Fourier series, ISO 6336-1
# --------------------------------------------------------------------------------------


def lste(result: MeshStiffness, torque: float) -> np.ndarray:
    """Loaded static transmission error (m) along the transverse line of action.

    e = F_bt / K(φ) with F_bt = T1/r_b1 the transverse load along the line of action
    (the low-fluctuation paper e = F/K; the transition-curve paper x = T_p/(R_p k_c) with R_p the pinion base radius).
    Multiply by cos βb for the approach along the flank normal (= F_n/K_n).

    Parameters
    ----------
    result : MeshStiffness
        The pair's mesh stiffness (:func:`mesh_stiffness`).
    torque : float
        Pinion torque T1 (N·m).

    Returns
    -------
    ndarray
        (P,) LSTE e (m) at the rolls of ``result.roll``.
    """
    return torque / result.base_radius[0] / result.K


@dataclass(frozen=True)
class FourierFit:
    """Truncated Fourier series f(θ) = mean + Σ_n a_n cos nθ + b_n sin nθ over one period.

    θ = 2π·(position in the period); ``rms_error`` is the RMS of (samples − series) in the
    units of the samples and ``relative_rms_error`` that over the mean.
    """

    order: int
    mean: float
    a: np.ndarray
    b: np.ndarray
    rms_error: float
    relative_rms_error: float

    def __call__(self, theta) -> np.ndarray:
        theta = np.asarray(theta, dtype=float)
        n = np.arange(1, self.order + 1)
        ang = theta[..., None] * n
        return self.mean + np.sum(self.a * np.cos(ang) + self.b * np.sin(ang), axis=-1)


def fourier_fit(values, order: int = 3) -> FourierFit:
    """Least-squares Fourier series of ``order`` of samples evenly spaced over one period.

    For evenly spaced samples the least-squares coefficients are the DFT ones
    (scipy.fft.rfft); the improved potential-energy paper uses order 3 for the TVMS (k_m + Σ a_j cos + b_j sin).

    Parameters
    ----------
    values : array_like
        (P,) samples over one period, end point excluded (any units).
    order : int
        Highest harmonic kept (default 3); needs P > 2·order.

    Returns
    -------
    FourierFit
        ``mean``, ``a``, ``b`` (order,) and ``rms_error`` in the units of ``values``;
        ``relative_rms_error`` (-).
    """
    from scipy.fft import rfft

    v = np.asarray(values, dtype=float)
    p = v.size
    if order < 0 or p <= 2 * order:
        raise GearmeshInputError("order", order, f"needs 0 <= order < {p}/2 samples")
    f = rfft(v) / p
    a = 2.0 * f.real[1:order + 1]
    b = -2.0 * f.imag[1:order + 1]
    fit = FourierFit(order=order, mean=float(f.real[0]), a=a, b=b, rms_error=0.0, relative_rms_error=0.0)
    theta = 2.0 * np.pi * np.arange(p) / p
    err = float(np.sqrt(np.mean((v - fit(theta)) ** 2)))
    return FourierFit(order=order, mean=fit.mean, a=a, b=b, rms_error=err,
                      relative_rms_error=err / abs(fit.mean) if fit.mean else math.inf)


def iso6336_stiffness(geom: PairGeometry) -> dict[str, float]:
    """ISO 6336-1 (method B) single and mesh stiffness (docs/modelling.md formulas).

    q' = 0.04723 + 0.15551/zn1 + 0.25791/zn2 − 0.00635x1 − 0.11654x1/zn1 − 0.00193x2
         − 0.24188x2/zn2 + 0.00529x1² + 0.00182x2²   (mm·µm/N),  c'th = 1/q',
    zn = z/(cos²βb cos β), c' = c'th·CM·CR·CB·cos β with CM = 0.8, CR = 1 (solid wheels),
    CB = [1 + 0.5(1.2 − hfP/mn)]·[1 − 0.02(20° − αPn)] (mean of pinion and gear when their
    basic-rack dedendums differ), cγα = c'(0.75εα + 0.25), cγβ = 0.85cγα.

    q' is fitted to steel on steel (E_st = 206 000 N/mm²); for another modulus ISO 6336-1
    (9.3.1, "other material combinations") scales c' by E/E_st, E = 2E1E2/(E1 + E2) (here
    one material for both gears: the pair's E; steel when the pair gives none). The factor is
    returned as ``material_factor``.


    Known difference from the slice model: the slices are transverse sections (the
    transition-curve and improved potential-energy papers), whose profile thickens with β, while ISO scales by cos β on the virtual spur
    gear. The ratio PEM/ISO therefore grows with β: 1.18, 1.21, 1.29, 1.42, 1.62 at β =
    0, 10, 20, 30, 40° for 29/49 teeth, m_n 1.75, αn 20°. The CB formula is also used
    here outside the usual basic-rack range (the transition-curve paper's 2.2 m_n deep hobs give CB 0.57);
    both are reported as computed, not corrected.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (teeth, helix angle, profile shifts, basic rack, face width, material).

    Returns
    -------
    dict of str to float
        c_prime_th, c_prime, c_gamma_alpha, c_gamma_beta in N/(mm·µm); q_prime (mm·µm/N);
        zn1, zn2, C_M, C_R, C_B, material_factor (-); K_gamma_alpha = cγα·b,
        K_gamma_beta = cγβ·b in N/m (mean transverse mesh stiffness of the face width b,
        comparable to :attr:`MeshStiffness.mean`).

    References
    ----------
    .. [1] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1:
       Basic principles, introduction and general influence factors, clause 9 (tooth
       stiffness parameters c′ and cγ, method B).
    """
    pair = geom.pair
    beta, beta_b = pair.helix_angle, geom.base_helix_angle
    zn = np.array(pair.teeth, dtype=float) / (math.cos(beta_b) ** 2 * math.cos(beta))
    x1, x2 = (float(x) for x in geom.profile_shift)
    q = (0.04723 + 0.15551 / zn[0] + 0.25791 / zn[1] - 0.00635 * x1 - 0.11654 * x1 / zn[0]
         - 0.00193 * x2 - 0.24188 * x2 / zn[1] + 0.00529 * x1**2 + 0.00182 * x2**2)
    c_th = 1.0 / q
    c_m, c_r = 0.8, 1.0
    alpha_pn = math.degrees(pair.normal_pressure_angle)
    cb_each = [(1 + 0.5 * (1.2 - hf)) * (1 - 0.02 * (20.0 - alpha_pn)) for hf in pair.dedendum_coefficient]
    c_b = 0.5 * (cb_each[0] + cb_each[1])
    material = pair.material
    xi = (material.youngs_modulus if material is not None else ISO6336_STEEL_MODULUS) / ISO6336_STEEL_MODULUS
    c_prime = c_th * c_m * c_r * c_b * math.cos(beta) * xi
    c_ga = c_prime * (0.75 * geom.eps_alpha + 0.25)
    c_gb = 0.85 * c_ga
    b_mm = geom.face_width * 1e3
    per_um_to_si = 1e6  # N/µm -> N/m
    return {
        "zn1": float(zn[0]), "zn2": float(zn[1]), "q_prime": q, "c_prime_th": c_th,
        "C_M": c_m, "C_R": c_r, "C_B": c_b, "material_factor": xi, "c_prime": c_prime,
        "c_gamma_alpha": c_ga, "c_gamma_beta": c_gb,
        "K_gamma_alpha": c_ga * b_mm * per_um_to_si, "K_gamma_beta": c_gb * b_mm * per_um_to_si,
    }
