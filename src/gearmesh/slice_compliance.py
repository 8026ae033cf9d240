"""The slice compliance of a tooth: one transverse slice of one tooth by the potential energy
method, tabulated against roll length for each gear and resampled for a tooth pair.

The stiffness stage (:func:`gearmesh.stiffness.mesh_stiffness`), the LTCA
(:mod:`gearmesh.ltca`) and the mesh force (:mod:`gearmesh.meshforce`) take their slices'
compliance from here; the helical assembly of the slices into a mesh stiffness is
:mod:`gearmesh.stiffness`'s. Everything inside is SI: lengths in m, angles in rad, forces in N.
A *per-unit-width* stiffness k0 is in N/m per m of face width (N/m²) and its compliance
c0 = 1/k0 in m²/N; a slice of transverse width Δz then has stiffness k0·Δz (N/m).

Model (one transverse slice of one tooth, the slice theory of the transition-curve and
improved potential-energy papers)
--------------------------------------------------------------------------------
The tooth is a non-uniform cantilever along its centre line (y axis, gear centre at the
origin; half-thickness x(y)). A unit load at the contact point P = (x_P, y_P) of roll
length ρ acts along the line of action, at the load angle α1 = α_ρ − ψ_ρ to the normal of
the centre line (α_ρ = arctan(ρ/r_b) the profile pressure angle, ψ_ρ = ψ_b − inv α_ρ the
half-thickness angle at P, ψ_b = s_t/(2r) + inv α_t on the base circle). Castigliano's
theorem on the strain energy of bending, shear and axial compression gives, per unit
face width (Yang & Lin 1987, J. Mech. Transm. Autom. Des. 109:189; Tian 2004, MSc
thesis, U. Alberta; Chaari, Fakhfakh & Haddar 2009, Eur. J. Mech. A 28:461)::

    c_b = ∫ [(y_P − y) cos α1 − x_P sin α1]² / (E·I(y)) dy,   I = (2x)³/12 = 2x³/3
    c_s = ∫ 1.2 cos² α1 / (G·A(y)) dy,                       A = 2x
    c_a = ∫ sin² α1 / (E·A(y)) dy

from the cantilever root y_root to y_P; the moment arm x_P is the real half-thickness
at the contact point. The fillet-foundation (body) compliance is Sainsot, Velex &
Duverger (2004, J. Mech. Des. 126:748) per unit width, and the local (Hertz) contact
is πE/(4(1−ν²)) per unit length of contact line (docs/modelling.md; the transition-curve paper).

The three cantilever models (``method``):

* ``'traditional'`` — Tian (2004): the involute from the base circle to P, whatever the
  root circle. When r_b > r_f the material between root and base circles is ignored
  (too stiff); when r_b < r_f the involute below the root circle is *fictitious* tooth
  inside the gear body (too compliant), on top of the foundation term.
* ``'improved'`` — the cantilever always starts at the root circle (the improved potential-energy paper's aim):
  r_b ≥ r_f: a straight segment of constant half-thickness r_b sin ψ_b from the root
  circle to the base circle, then the involute; r_b < r_f: the involute from the root
  circle. The improved potential-energy paper writes that for r_b < r_f "the integration starts from the base
  circle, as the segment between the base and root circles is not part of the ...
  cantilever" — that sentence contradicts itself (starting at the base circle *includes*
  that segment); the physically right reading, used here, starts at the root circle.
* ``'transition'`` (default) — the transition-curve paper: the hob-generated trochoid fillet from the root
  circle to the true start of the involute (form circle), integrating the real
  half-thickness of :mod:`gearmesh.profile`, then the involute. The transition-curve paper's fillet
  bending integral divides by 2E(2y₁)³; with I = (2y₁)³/12 the right factor is
  12/(E(2y₁)³) = 3/(2E·y₁³), i.e. the transition-curve paper's term is 8× too small. Used here: 1/(E·I).

Fillet-foundation term: per slice. Sainsot's formula is for a tooth of width L loaded
uniformly; the slice theory cuts the tooth into uncoupled transverse slices, each loaded
at its own height, so its per-unit-width form (L → 1, local α1 and u_f, as the transition-curve paper does)
is the consistent choice and reduces exactly to Sainsot's spur formula for β = 0. The improved
potential-energy paper's single per-tooth term with the face width B and the nominal pressure angle ignores
where the load sits and how much of the face is loaded (wrong while a line enters or
leaves the face); the low-fluctuation paper's single k_f in series with *all* contact lines is
dimensionally a series element shared by parallel paths, which is not physical.
Its geometry: h_f = r_f/r_int, u_f = distance along the centre line from the root circle
to where the load line crosses it, S_f = 2 r_f θ_f with θ_f the half angle of the tooth
where its flank meets the root circle — the real fillet/root-circle junction for
'transition' (π/z for a full-radius tool tip), the involute's half angle on the root
circle when r_b < r_f, and for r_b ≥ r_f the radial line (ψ_b, 'traditional') or the
constant-thickness segment (arcsin(r_b sin ψ_b / r_f), 'improved').

Speed (docs/modelling.md): each gear's slice compliance is evaluated by Gauss–Legendre at a few
hundred roll lengths once (:func:`slice_compliance_table`) and resampled as one pair table on
a fine uniform grid of s (:func:`pair_slice_table`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from numpy.polynomial.legendre import leggauss as _leggauss

from .choices import DEFAULT_TOOTH_METHOD, TOOTH_METHODS
from .errors import GearmeshInputError
from .gear import GEARS, PairGeometry
# the shared tooth types live below both tooth models (re-exported here); the slice compliance chooses the method
from .tooth import (COMPONENTS, PEM_METHODS, SliceComplianceTable, ToothModel, _involute_dy_da,  # noqa: F401
                    _involute_xy, base_half_angle, contact_point, require_stiffness_data, tooth_model)

#: the potential-energy cantilever models; 'fe' is the finite-element tooth of :mod:`gearmesh.fe`
METHODS = TOOTH_METHODS


@lru_cache(maxsize=16)
def leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre nodes and weights on [−1, 1] (numpy), cached (read-only arrays).

    Parameters
    ----------
    n : int
        Number of nodes.

    Returns
    -------
    nodes, weights : ndarray
        (n,) each, read-only.
    """
    t, w = _leggauss(n)
    t.flags.writeable = False
    w.flags.writeable = False
    return t, w
SHEAR_FACTOR = 1.2  # Timoshenko shear coefficient of a rectangular section (Yang & Lin 1987)

#: Sainsot, Velex & Duverger (2004) Table: rows L*, M*, P*, Q*; columns A…F of
#: X* = A/θf² + B·hf² + C·hf/θf + D/θf + E·hf + F (docs/modelling.md).
SAINSOT_COEFFICIENTS = np.array([
    [-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
    [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
    [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
    [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904],
])


# --------------------------------------------------------------------------------------
# Input checks
# --------------------------------------------------------------------------------------


def check_method(method: str) -> str:
    """The tooth model ``method`` if it is one of :data:`METHODS`, else a :class:`GearmeshInputError`.

    Parameters
    ----------
    method : str
        Tooth model name: 'traditional', 'improved', 'transition' or 'fe'.

    Returns
    -------
    str
        ``method`` unchanged.
    """
    if method not in METHODS:
        raise GearmeshInputError("method", method, f"must be one of {list(METHODS)}")
    return method


# --------------------------------------------------------------------------------------
# Closed-form pieces: Hertz, Sainsot foundation
# --------------------------------------------------------------------------------------


def hertz_stiffness_per_width(youngs_modulus: float, poisson_ratio: float) -> float:
    """Hertzian line-contact stiffness per unit contact-line length, k_h0 = πE/(4(1−ν²)).

    Yang & Sun (1985) [1]; docs/modelling.md and the transition-curve paper [2] (two bodies of
    the same material).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E (Pa).
    poisson_ratio : float
        Poisson's ratio ν (-).

    Returns
    -------
    float
        k_h0 in N/m per m of contact-line length (N/m²).

    References
    ----------
    .. [1] Yang D.C.H., Sun Z.S., "A rotary model for spur gear dynamics", J. Mech. Transm.
       Autom. Des. 107 (1985) 529–535.
    .. [2] [untitled] Mesh stiffness of helical gears with the hob-generated root transition
       curve (docs/references.md, document 003).
    """
    return math.pi * youngs_modulus / (4.0 * (1.0 - poisson_ratio**2))


def sainsot_coefficients(h_f: float, theta_f: float) -> np.ndarray:
    """The four coefficients (L*, M*, P*, Q*) of Sainsot, Velex & Duverger (2004).

    X* = A/θf² + B·hf² + C·hf/θf + D/θf + E·hf + F with Sainsot's table (:data:`SAINSOT_COEFFICIENTS`; the transition-curve paper
    prints A·θf² and D·θf, a typo: the fitted variables are 1/θf² and 1/θf).

    Parameters
    ----------
    h_f : float
        r_f / r_int, root over bore radius (-).
    theta_f : float
        Half angle of the tooth on the root circle (rad).

    Returns
    -------
    ndarray
        (4,) L*, M*, P*, Q* (-).

    References
    ----------
    .. [1] Sainsot P., Velex P., Duverger O., "Contribution of gear body to tooth deflections —
       a new bidimensional analytical formula", J. Mech. Des. 126 (2004) 748–752.
    """
    v = np.array([1.0 / theta_f**2, h_f**2, h_f / theta_f, 1.0 / theta_f, h_f, 1.0])
    return SAINSOT_COEFFICIENTS @ v


def fillet_foundation_compliance(load_angle, u_f, s_f: float, theta_f: float, h_f: float,
                                 youngs_modulus: float) -> np.ndarray:
    """Fillet-foundation compliance per unit face width (m²/N), Sainsot et al. (2004)::

        c_f = cos²α_m / E · [L*(u_f/S_f)² + M*(u_f/S_f) + P*(1 + Q*·tan²α_m)]

    (docs/modelling.md with the width L = 1: the compliance of a slice of width Δz is c_f/Δz.)

    Parameters
    ----------
    load_angle : array_like
        α_m, angle of the load to the normal of the tooth centre line (rad).
    u_f : array_like
        Distance (m) along the centre line from the root circle to the intersection of
        the load line with the centre line (broadcasts with ``load_angle``).
    s_f : float
        Tooth thickness on the root circle (m), S_f = 2 r_f θ_f.
    theta_f : float
        Half angle of the tooth on the root circle (rad).
    h_f : float
        r_f / r_int (-).
    youngs_modulus : float
        E (Pa).

    Returns
    -------
    ndarray
        c_f (m²/N), shaped like the broadcast of ``load_angle`` and ``u_f``.

    References
    ----------
    .. [1] Sainsot P., Velex P., Duverger O., "Contribution of gear body to tooth deflections —
       a new bidimensional analytical formula", J. Mech. Des. 126 (2004) 748–752.
    """
    lm, mm, pm, qm = sainsot_coefficients(h_f, theta_f)
    a = np.asarray(load_angle, dtype=float)
    ratio = np.asarray(u_f, dtype=float) / s_f
    return np.cos(a) ** 2 / youngs_modulus * (lm * ratio**2 + mm * ratio + pm * (1.0 + qm * np.tan(a) ** 2))


# --------------------------------------------------------------------------------------
# Per-unit-width compliance of one slice (Gauss–Legendre, vectorised over contact points)
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _FixedMoments:
    """∫ y^n/x³ dy (n = 0, 1, 2) and ∫ 1/x dy over the fixed segments (SI)."""

    j30: float
    j31: float
    j32: float
    j1: float


def _fixed_moments(model: ToothModel, n_gauss: int = 200) -> _FixedMoments:
    t, w = leggauss(n_gauss)
    j30 = j31 = j32 = j1 = 0.0
    for y_lo, y_hi, xf in model.fixed:
        yy = 0.5 * (y_hi - y_lo) * t + 0.5 * (y_hi + y_lo)
        ww = 0.5 * (y_hi - y_lo) * w
        xx = xf(yy)
        j30 += float(np.sum(ww / xx**3))
        j31 += float(np.sum(ww * yy / xx**3))
        j32 += float(np.sum(ww * yy**2 / xx**3))
        j1 += float(np.sum(ww / xx))
    return _FixedMoments(j30, j31, j32, j1)


def _foundation(model: ToothModel, x_p, y_p, alpha1):
    u_f = y_p - x_p * np.tan(alpha1) - model.root_radius
    h_f = model.root_radius / model.bore_radius
    return fillet_foundation_compliance(alpha1, u_f, model.s_f, model.theta_f, h_f, model.youngs_modulus)


def tooth_slice_compliance(model: ToothModel, rho, n_gauss: int = 64,
                           moments: _FixedMoments | None = None) -> dict[str, np.ndarray]:
    """Per-unit-width compliances (m²/N) of one tooth slice loaded at roll lengths ρ (m).

    Gauss–Legendre with ``n_gauss`` nodes over the involute (in its pressure angle, the
    integrand is smooth there including the base circle), vectorised over all ρ; the
    fixed segments below the involute enter through their moments ∫y^n/x³dy, ∫dy/x, so
    that e.g. c_b = [A²J30 − 2A cos α1 J31 + cos²α1 J32]/(E·2/3) with
    A = y_P cos α1 − x_P sin α1. Formulas: module docstring (Yang & Lin 1987; Tian 2004;
    Sainsot et al. 2004).

    Parameters
    ----------
    model : ToothModel
        The tooth's cantilever (:func:`gearmesh.tooth.tooth_model`).
    rho : array_like
        Roll lengths ρ (m) of the contact points.
    n_gauss : int
        Gauss–Legendre nodes on the involute (default 64).
    moments : _FixedMoments, optional
        Precomputed moments of the fixed segments (default: computed with 200 nodes).

    Returns
    -------
    dict of str to ndarray
        'bending', 'shear', 'axial', 'fillet' compliances (m²/N), each shaped like ``rho``.

    References
    ----------
    .. [1] Yang D.C.H., Lin J.Y., "Hertzian damping, tooth friction and bending elasticity in
       gear impact dynamics", J. Mech. Transm. Autom. Des. 109 (1987) 189–196.
    .. [2] Tian X., "Dynamic simulation for system response of gearbox including localized
       gear faults", MSc thesis, University of Alberta, 2004.
    .. [3] Sainsot P., Velex P., Duverger O., "Contribution of gear body to tooth deflections —
       a new bidimensional analytical formula", J. Mech. Des. 126 (2004) 748–752.
    """
    rho = np.asarray(rho, dtype=float)
    shape = rho.shape
    rho = rho.ravel()
    E, G = model.youngs_modulus, model.shear_modulus
    x_p, y_p, alpha1, a_p = contact_point(model, rho)
    ca, sa = np.cos(alpha1), np.sin(alpha1)
    big_a = y_p * ca - x_p * sa
    mom = _fixed_moments(model) if moments is None else moments
    # fixed segments (bending: M = A − y cos α1)
    bend = (big_a**2 * mom.j30 - 2 * big_a * ca * mom.j31 + ca**2 * mom.j32) * 1.5 / E
    inv_area = 0.5 * mom.j1
    # involute from a_start to a_P
    t, w = leggauss(n_gauss)
    a0 = model.a_start
    half = 0.5 * (a_p - a0)
    aa = half[:, None] * t[None, :] + (0.5 * (a_p + a0))[:, None]
    ww = half[:, None] * w[None, :] * _involute_dy_da(model.base_radius, model.psi_b, aa)
    xx, yy = _involute_xy(model.base_radius, model.psi_b, aa)
    arm = (big_a[:, None] - yy * ca[:, None])
    bend = bend + np.sum(ww * arm**2 / xx**3, axis=1) * 1.5 / E
    inv_area = inv_area + 0.5 * np.sum(ww / xx, axis=1)
    out = {
        "bending": bend,
        "shear": SHEAR_FACTOR * ca**2 / G * inv_area,
        "axial": sa**2 / E * inv_area,
        "fillet": _foundation(model, x_p, y_p, alpha1),
    }
    return {k: v.reshape(shape) for k, v in out.items()}


def fixed_moments_quad(model: ToothModel, epsrel: float = 1e-12) -> _FixedMoments:
    """Moments ∫y^n/x³ dy (n = 0, 1, 2) and ∫dy/x of the fixed segments by adaptive quadrature.

    Parameters
    ----------
    model : ToothModel
        The tooth's cantilever; its ``fixed`` segments (y in m, half-thickness x in m).
    epsrel : float
        Relative tolerance of :func:`scipy.integrate.quad` (default 1e-12).

    Returns
    -------
    _FixedMoments
        ``j30`` (m⁻²), ``j31`` (m⁻¹), ``j32`` (-), ``j1`` (-).
    """
    from scipy import integrate

    out = [0.0, 0.0, 0.0, 0.0]
    for lo, hi, f in model.fixed:
        def xf(y, f=f):
            return float(f(np.array([y]))[0])
        for k, fun in enumerate((lambda y: xf(y) ** -3, lambda y: y * xf(y) ** -3,
                                 lambda y: y * y * xf(y) ** -3, lambda y: 1.0 / xf(y))):
            out[k] += integrate.quad(fun, lo, hi, epsabs=0, epsrel=epsrel, limit=200)[0]
    return _FixedMoments(*out)


def tooth_slice_compliance_quad(model: ToothModel, rho: float, epsrel: float = 1e-12,
                                moments: _FixedMoments | None = None) -> dict[str, float]:
    """Reference: the same compliances (m²/N) at one roll length ρ (m) by adaptive quadrature.

    Integrates along the physical centre-line coordinate y with :func:`scipy.integrate.quad`
    (the involute's x(y) found by root-finding its pressure angle), independent of the
    parametrisation and Gauss rule of :func:`tooth_slice_compliance`. The segments below the
    involute (fillet, straight root segment) do not depend on ρ; their moments come from
    :func:`fixed_moments_quad` (pass ``moments`` to reuse them). Slow; for tests and baselines.

    Parameters
    ----------
    model : ToothModel
        The tooth's cantilever (:func:`gearmesh.tooth.tooth_model`).
    rho : float
        Roll length ρ (m) of the contact point.
    epsrel : float
        Relative tolerance of the quadrature (default 1e-12).
    moments : _FixedMoments, optional
        Moments of the fixed segments (default :func:`fixed_moments_quad`).

    Returns
    -------
    dict of str to float
        'bending', 'shear', 'axial', 'fillet' compliances (m²/N).
    """
    from scipy import integrate
    from scipy.optimize import brentq

    E, G = model.youngs_modulus, model.shear_modulus
    x_p, y_p, alpha1, a_p = (float(v) for v in contact_point(model, rho))
    ca, sa = math.cos(alpha1), math.sin(alpha1)
    rb, psi_b = model.base_radius, model.psi_b
    y0 = float(_involute_xy(rb, psi_b, model.a_start)[1])

    def x_inv(y):
        if y <= y0:
            return float(_involute_xy(rb, psi_b, model.a_start)[0])
        a = brentq(lambda s: float(_involute_xy(rb, psi_b, s)[1]) - y, model.a_start, a_p, xtol=1e-16, rtol=1e-15)
        return float(_involute_xy(rb, psi_b, a)[0])

    mom = fixed_moments_quad(model, epsrel) if moments is None else moments
    big_a = y_p * ca - x_p * sa
    bend = (big_a**2 * mom.j30 - 2 * big_a * ca * mom.j31 + ca**2 * mom.j32) * 1.5 / E
    area = 0.5 * mom.j1
    if y_p > y0:
        bend += integrate.quad(lambda y: ((y_p - y) * ca - x_p * sa) ** 2 / (E * 2.0 * x_inv(y) ** 3 / 3.0),
                               y0, y_p, epsabs=0, epsrel=epsrel, limit=200)[0]
        area += integrate.quad(lambda y: 1.0 / (2.0 * x_inv(y)), y0, y_p, epsabs=0, epsrel=epsrel, limit=200)[0]
    fil = float(_foundation(model, np.array(x_p), np.array(y_p), np.array(alpha1)))
    return {"bending": bend, "shear": SHEAR_FACTOR * ca**2 / G * area, "axial": sa**2 / E * area, "fillet": fil}


# --------------------------------------------------------------------------------------
# The table of one gear's slice compliance against roll length
# --------------------------------------------------------------------------------------


def slice_compliance_table(geom: PairGeometry, gear: int, method: str = DEFAULT_TOOTH_METHOD, n_nodes: int = 257,
                           n_gauss: int = 64, profile=None) -> SliceComplianceTable:
    """Tabulate one gear's per-unit-width slice compliance over its active flank.

    ``method='fe'``: the finite-element tooth (:func:`gearmesh.fe_tables.fe_slice_compliance_table`,
    its own roll nodes and mesh; ``n_nodes`` and ``n_gauss`` do not apply).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material and bore radius).
    gear : int
        0 pinion, 1 gear.
    method : {'fe', 'traditional', 'improved', 'transition'}
        Tooth model (default :data:`gearmesh.choices.DEFAULT_TOOTH_METHOD`, 'fe').
    n_nodes : int
        Number of equally spaced roll-length nodes on [ρ_SAP, ρ_EAP] (default 257).
    n_gauss : int
        Gauss–Legendre nodes on the involute segment (default 64).
    profile : optional
        The gear's generated tooth profile (:mod:`gearmesh.profile`) for 'transition' and
        'fe' (default: generated from ``geom``).

    Returns
    -------
    SliceComplianceTable
        ``rho`` (n,) m; ``values`` 'bending', 'shear', 'axial', 'fillet' (n,) m²/N; callable at ρ (m).
    """
    if check_method(method) == "fe":
        from .fe_tables import fe_slice_compliance_table

        return fe_slice_compliance_table(geom, gear, profile=profile)
    from scipy.interpolate import CubicSpline

    model = tooth_model(geom, gear, method, profile)
    rho = np.linspace(geom.rho_sap[gear], geom.rho_eap[gear], n_nodes)
    vals = tooth_slice_compliance(model, rho, n_gauss=n_gauss)
    splines = {k: CubicSpline(rho, v) for k, v in vals.items()}
    alpha1 = contact_point(model, rho)[2]
    return SliceComplianceTable(gear=gear, method=method, model=model, rho=rho, values=vals,
                                load_angle=alpha1, _splines=splines)


def hertz_compliance_transverse(geom: PairGeometry) -> float:
    """Per-unit-transverse-width contact compliance (m²/N) along the transverse line of action.

    A slice Δz carries a contact line Δz/cos βb long under the normal load; projected on
    the transverse line of action its stiffness is k_h0·Δz·cos βb (:mod:`gearmesh.stiffness`, helical assembly), so
    c_h = 1/(k_h0 cos βb) with k_h0 = πE/(4(1−ν²)) (Yang & Sun [1]).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (needs material; base helix angle βb in rad).

    Returns
    -------
    float
        c_h (m²/N).

    References
    ----------
    .. [1] Yang D.C.H., Sun Z.S., "A rotary model for spur gear dynamics", J. Mech. Transm.
       Autom. Des. 107 (1985) 529–535.
    """
    require_stiffness_data(geom, need_bore=False)
    mat = geom.pair.material
    return 1.0 / (hertz_stiffness_per_width(mat.youngs_modulus, mat.poisson_ratio)
                  * math.cos(geom.base_helix_angle))


# --------------------------------------------------------------------------------------
# The slice compliance of a tooth pair against the position on the line of action
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class PairSliceTable:
    """Per-unit-width compliances (m²/N) of a tooth *pair* slice against s (m) on [0, g_α].

    Uniform grid of ``n`` intervals for linear interpolation (built from the cubic splines
    of the two gears' :class:`SliceComplianceTable`); ``columns`` names the rows of
    ``values``: the four components of the pinion, the four of the gear, then 'hertz'.
    """

    s0: float
    ds: float
    columns: tuple[str, ...]
    values: np.ndarray  # (C, n+1)
    total: np.ndarray  # (n+1,)
    slopes: np.ndarray = field(repr=False, default=None)  # (C, n) differences of values
    total_slope: np.ndarray = field(repr=False, default=None)  # (n,)


def pair_slice_table(geom: PairGeometry, tables: tuple[SliceComplianceTable, SliceComplianceTable],
                     n_intervals: int = 8192, contact_compliance: float | None = None) -> PairSliceTable:
    """Resample both gears' slice compliance and the contact on a uniform s grid (m).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (path of contact g_α in m, ρ_SAP1 and ρ_EAP2 in m).
    tables : tuple of SliceComplianceTable
        (pinion, gear) slice compliance against roll length (:func:`slice_compliance_table`).
    n_intervals : int
        Intervals of the uniform grid over [0, g_α] (default 8192).
    contact_compliance : float, optional
        Contact compliance (m²/N per unit transverse width, e.g. the LTCA law's tangent at a
        load, :func:`gearmesh.ltca.contact_tangent_compliance`); None: Yang & Sun's constant
        (:func:`hertz_compliance_transverse`).

    Returns
    -------
    PairSliceTable
        ``values`` (9, n_intervals + 1) and ``total`` (n_intervals + 1,) m²/N against s (m),
        grid step ``ds`` (m).
    """
    g = geom.path_of_contact
    s = np.linspace(0.0, g, n_intervals + 1)
    rho1 = np.clip(geom.rho_sap[0] + s, tables[0].rho[0], tables[0].rho[-1])
    rho2 = np.clip(geom.rho_eap[1] - s, tables[1].rho[0], tables[1].rho[-1])
    c1, c2 = tables[0](rho1), tables[1](rho2)
    ch = hertz_compliance_transverse(geom) if contact_compliance is None else float(contact_compliance)
    cols, rows = [], []
    for name, c in zip(GEARS, (c1, c2)):
        for k in COMPONENTS:
            cols.append(f"{k}_{name}")
            rows.append(c[k])
    cols.append("hertz")
    rows.append(np.full_like(s, ch))
    values = np.vstack(rows)
    total = values.sum(axis=0)
    return PairSliceTable(s0=0.0, ds=g / n_intervals, columns=tuple(cols), values=values,
                          total=total, slopes=np.diff(values, axis=1), total_slope=np.diff(total))
