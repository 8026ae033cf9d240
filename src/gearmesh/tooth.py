"""The cantilever geometry of one tooth and the slice compliance table: the types both tooth
models share.

The potential-energy cantilevers (:mod:`gearmesh.stiffness`) and the finite-element tooth
(:mod:`gearmesh.fe`, :mod:`gearmesh.fe3d`) both describe a tooth slice by the same geometry —
the involute half-thickness, the contact point and load angle at a roll length, the root
section of the cantilever (the transition model's root chord, Sainsot's θ_f) — and both hand
the stages a :class:`SliceComplianceTable`. They live here, below both, so that the data
flows one way: ``tooth`` → ``fe`` → ``slice_compliance`` (which chooses the method). Formulas and
sources: the module docstring of :mod:`gearmesh.slice_compliance`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable, Mapping

import numpy as np

from .choices import PEM_TOOTH_METHODS
from .errors import GearmeshInputError
from .gear import PairGeometry, involute
from .pairfile import missing_key

if TYPE_CHECKING:  # scipy is imported where it is used: importing it costs ~0.5 s of a job's start-up
    from scipy.interpolate import CubicSpline

__all__ = ["PEM_METHODS", "COMPONENTS", "require_stiffness_data", "ToothModel", "base_half_angle", "tooth_model",
           "contact_point", "SliceComplianceTable"]

#: the potential-energy cantilever models (:func:`tooth_model`)
PEM_METHODS = PEM_TOOTH_METHODS
#: the components of a slice compliance table
COMPONENTS = ("bending", "shear", "axial", "fillet")


def require_stiffness_data(geom: PairGeometry, need_bore: bool = True) -> None:
    """Refuse a pair without the data the stiffness needs (GearmeshInputError naming the field).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; its pair needs ``material`` and, with ``need_bore``, positive
        ``bore_radius`` (m) for both gears.
    need_bore : bool
        Also require the bore radii (default True: the fillet foundation's h_f = r_f/r_int).

    Returns
    -------
    None
        Raises :class:`gearmesh.errors.GearmeshInputError` naming the missing or bad field.
    """
    pair = geom.pair
    if pair.material is None:
        raise GearmeshInputError("material", None,
                                 "is required for the mesh stiffness (Young's modulus and Poisson ratio)")
    if need_bore and pair.bore_radius is None:
        raise missing_key("bore_radius_mm", "the fillet-foundation stiffness (Sainsot, Velex & Duverger 2004, "
                                            "J. Mech. Design 126, use h_f = r_f / r_int)")
    if need_bore:
        for i in range(2):
            if not pair.bore_radius[i] > 0:
                raise GearmeshInputError(f"bore_radius_mm[{i}]", pair.bore_radius[i] * 1e3,
                                         "must be positive for the fillet-foundation stiffness "
                                         "(h_f = r_f / r_int)")


# --------------------------------------------------------------------------------------
# Tooth geometry for the cantilever
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class ToothModel:
    """The cantilever model of one tooth of one gear (SI).

    ``fixed`` lists the segments below the involute whose half-thickness does not depend
    on the contact point as (y_lo, y_hi, x(y)) with x a vectorised callable (m → m);
    the involute then runs from pressure angle ``a_start`` (rad) to the contact point.
    ``theta_f``, ``s_f`` describe the tooth on the root circle for the foundation term.
    """

    gear: int
    method: str
    base_radius: float
    psi_b: float  # half-thickness angle on the base circle (rad)
    root_radius: float
    bore_radius: float
    a_start: float
    fixed: tuple[tuple[float, float, Callable[[np.ndarray], np.ndarray]], ...]
    theta_f: float
    youngs_modulus: float
    poisson_ratio: float

    @property
    def s_f(self) -> float:
        """Tooth thickness on the root circle S_f = 2 r_f θ_f (m), Sainsot et al. (2004)."""
        return 2.0 * self.root_radius * self.theta_f

    @property
    def shear_modulus(self) -> float:
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def y_root(self) -> float:
        """Centre-line coordinate (m) of the cantilever root."""
        if self.fixed:
            return self.fixed[0][0]
        return float(_involute_xy(self.base_radius, self.psi_b, self.a_start)[1])


def _involute_xy(rb: float, psi_b: float, a):
    """Half-thickness x and centre-line coordinate y (m) of the involute at pressure angle a (rad)."""
    a = np.asarray(a, dtype=float)
    r = rb / np.cos(a)
    psi = psi_b - involute(a)
    return r * np.sin(psi), r * np.cos(psi)


def _involute_dy_da(rb: float, psi_b: float, a):
    """dy/da (m/rad) of the involute centre-line coordinate y(a) = r_b cos(ψ_b − inv a)/cos a."""
    a = np.asarray(a, dtype=float)
    psi = psi_b - involute(a)
    ca = np.cos(a)
    return rb * (np.sin(psi) * np.tan(a) ** 2 / ca + np.cos(psi) * np.sin(a) / ca**2)


def base_half_angle(geom: PairGeometry, gear: int) -> float:
    """Half tooth-thickness angle ψ_b on the base circle (rad): s_t/(2r) + inv α_t (ISO 21771).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (transverse thickness s_t and reference radius r in m, α_t in rad).
    gear : int
        0 pinion, 1 gear.

    Returns
    -------
    float
        ψ_b (rad).

    References
    ----------
    .. [1] ISO 21771:2007, Gears — Cylindrical involute gears and gear pairs — Concepts and
       geometry.
    """
    return float(geom.transverse_thickness[gear] / (2.0 * geom.reference_radius[gear])
                 + involute(geom.transverse_pressure_angle))


def tooth_model(geom: PairGeometry, gear: int, method: str, profile=None) -> ToothModel:
    """Build the cantilever model of one tooth (see the module docstring for the methods).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry; needs ``material`` and ``bore_radius``.
    gear : int
        0 pinion, 1 gear.
    method : {'traditional', 'improved', 'transition'}
        The potential-energy cantilever (:data:`PEM_METHODS`).
    profile : optional
        For 'transition', a tooth profile from :func:`gearmesh.profile.tooth_profile`
        (computed when None).

    Returns
    -------
    ToothModel
        Base and root radius (m), ψ_b and start angle ``a_start`` (rad), the ``fixed``
        segments below the involute (m), θ_f (rad), E (Pa) and ν (-).

    References
    ----------
    .. [1] Tian X., "Dynamic simulation for system response of gearbox including localized
       gear faults", MSc thesis, University of Alberta, 2004 ('traditional').
    .. [2] A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an
       Improved Potential Energy Method for Time-Varying Meshing Stiffness
       (docs/references.md, document 004; 'improved').
    .. [3] [untitled] Mesh stiffness of helical gears with the hob-generated root transition
       curve (docs/references.md, document 003; 'transition').
    """
    if method not in PEM_METHODS:
        raise GearmeshInputError("method", method, f"must be one of {list(PEM_METHODS)} for a cantilever model")
    require_stiffness_data(geom)
    mat = geom.pair.material
    rb = float(geom.base_radius[gear])
    rf = float(geom.root_radius[gear])
    psi_b = base_half_angle(geom, gear)
    common = dict(gear=gear, method=method, base_radius=rb, psi_b=psi_b, root_radius=rf,
                  bore_radius=float(geom.pair.bore_radius[gear]), youngs_modulus=mat.youngs_modulus,
                  poisson_ratio=mat.poisson_ratio)
    if method in ("traditional", "improved"):
        if rb >= rf:
            h_b = rb * math.sin(psi_b)
            if method == "traditional":
                # Tian (2004): radial line from the base circle down to the root circle, rigid.
                theta_f, fixed = psi_b, ()
            else:
                # Constant half-thickness r_b sin ψ_b from the root circle to the base circle.
                y_f = math.sqrt(rf**2 - h_b**2)
                theta_f = math.asin(h_b / rf)
                y_b = rb * math.cos(psi_b)
                fixed = ((y_f, y_b, lambda y, h=h_b: np.full_like(np.asarray(y, dtype=float), h)),)
            return ToothModel(a_start=0.0, fixed=fixed, theta_f=theta_f, **common)
        a_f = math.acos(rb / rf)
        theta_f = psi_b - float(involute(a_f))  # the involute's half angle on the root circle
        a_start = 0.0 if method == "traditional" else a_f
        return ToothModel(a_start=a_start, fixed=(), theta_f=theta_f, **common)
    # transition: the real hob-generated fillet
    return _transition_model(geom, gear, profile, common)


def _transition_model(geom: PairGeometry, gear: int, profile, common: dict) -> ToothModel:
    """The transition-curve paper's segmented cantilever: trochoid fillet (profile.py) then involute."""
    from . import profile as prof  # written alongside; imported lazily

    if profile is None:
        profile = prof.tooth_profile(geom, gear)
    rb, psi_b, rf = common["base_radius"], common["psi_b"], common["root_radius"]
    rack = profile.rack
    # Sainsot's root point: where the fillet meets the root circle, the end of the root arc
    # cut by the rack's tip land (profile.py: polar angle ξ_c/r; π/z for a full-radius tip).
    theta_f = min(rack.centre_xi / rack.reference_radius, math.pi / geom.pair.teeth[gear])
    y_root = rf * math.cos(theta_f)
    rho_form = float(profile.form_roll)  # profile.py's form point (tip radius as used)
    a_form = math.atan(rho_form / rb)
    y_form = float(_involute_xy(rb, psi_b, a_form)[1])

    def x_of_y(yy, _p=profile):
        return np.asarray(prof.half_thickness(_p, np.asarray(yy, dtype=float)), dtype=float)

    fixed = ((y_root, y_form, x_of_y),) if y_form > y_root else ()
    return ToothModel(a_start=a_form, fixed=fixed, theta_f=theta_f, **common)


def contact_point(model: ToothModel, rho):
    """Contact point and load angle on the involute at roll length ρ (m).

    Parameters
    ----------
    model : ToothModel
        The tooth's cantilever (:func:`tooth_model`).
    rho : array_like
        Roll lengths ρ (m).

    Returns
    -------
    x_P, y_P : ndarray
        Half-thickness and centre-line coordinate of P (m), shaped like ``rho``.
    alpha1 : ndarray
        Load angle α1 = α_ρ − ψ_ρ (rad; Tian 2004 [1]: α1 + α2 = ρ/r_b).
    a_P : ndarray
        Profile pressure angle α_ρ = arctan(ρ/r_b) (rad).

    References
    ----------
    .. [1] Tian X., "Dynamic simulation for system response of gearbox including localized
       gear faults", MSc thesis, University of Alberta, 2004.
    """
    rho = np.asarray(rho, dtype=float)
    a_p = np.arctan(rho / model.base_radius)
    x_p, y_p = _involute_xy(model.base_radius, model.psi_b, a_p)
    alpha1 = a_p - (model.psi_b - involute(a_p))
    return x_p, y_p, alpha1, a_p


@dataclass(frozen=True)
class SliceComplianceTable:
    """Per-unit-width compliance (m²/N) of one gear's tooth slice against roll length.

    ``rho`` (m) are ``n`` equally spaced nodes over the active flank [ρ_SAP, ρ_EAP]; each
    component was evaluated there by Gauss–Legendre (:func:`tooth_slice_compliance`);
    calling the table interpolates every component with a cubic spline (error O(h⁴)).
    ``load_angle`` is α1 (rad) at the nodes.
    """

    gear: int
    method: str
    model: ToothModel
    rho: np.ndarray
    values: Mapping[str, np.ndarray]
    load_angle: np.ndarray
    _splines: Mapping[str, CubicSpline] = field(repr=False, compare=False, default=None)

    def __call__(self, rho) -> dict[str, np.ndarray]:
        """The components (m²/N) at roll lengths ``rho`` (m) within the active flank."""
        return {k: self._splines[k](rho) for k in COMPONENTS}

    def total(self, rho) -> np.ndarray:
        """c_b + c_s + c_a + c_f (m²/N) at ``rho`` (m)."""
        return sum(self._splines[k](rho) for k in COMPONENTS)

    @property
    def stiffness(self) -> np.ndarray:
        """Per-unit-width tooth stiffness 1/(c_b+c_s+c_a+c_f) at the nodes (N/m²)."""
        return 1.0 / sum(self.values[k] for k in COMPONENTS)
