"""Manufacturing deviations of a gear pair as pair data: lead and profile slope deviations of each
gear and the mesh misalignment, and the separations they open in the mesh (SI units).

A manufactured gear is never its drawing. ISO 1328-1:2013 measures each flank's deviations in the
transverse plane along the base tangent (the transverse line of action), so each adds to the
transverse separation of :mod:`gearmesh.tca` unchanged:

* **helix (lead) slope deviation** f_Hβ (ISO 1328-1:2013, 3.3.4): the slope of the mean helix
  line over the face width b, pair-file key ``lead_slope_deviation_um: [pinion, gear]``;
* **profile slope deviation** f_Hα (ISO 1328-1:2013, 3.2.4): the slope of the mean profile line
  over the profile evaluation range, here the active flank from the start of active profile to
  the tip (roll lengths ρ_SAP … ρ_EAP of that gear), key ``profile_slope_deviation_um``;
* **mesh misalignment** f_ma (ISO 6336-1:2019, 7.6.2.1): the lead mismatch of the mesh in the
  plane of action from manufacturing beyond the gears' own helices (housing bores, bearings),
  key ``mesh_misalignment_um``; not stated, it is zero in the analyses and the rating takes
  ISO's f_ma from the accuracy grade (:mod:`gearmesh.rating`).

Sign convention (one for every door; docs/modelling.md)
-------------------------------------------------------
The face runs from the *trailing* to the *leading* face end: with the pinion driving, a tooth
pair's contact line reaches the start of active profile (and later leaves the path) first at the
leading end. In the model frame of :mod:`gearmesh.contact` (z along the pinion axis) the leading
end is z = +b/2 for a right-hand pinion and z = −b/2 for a left-hand one: ζ = h·z, h = ±1 the
hand, runs from trailing (−b/2) to leading (+b/2).

* A lead slope deviation is **positive when the flank stands proud of its design helix (more
  material, towards its mate) at the leading face end.** The mesh sees the sum of both gears'
  deviations, F = f1 + f2 + f_ma: same signs add, equal and opposite ones cancel exactly (a pair
  whose deviations cancel is the aligned pair). A helix angle larger than drawn by the same amount
  on both gears of a pair (opposite hands) keeps them conjugate: in this convention that is
  f2 = −f1. The separation is

      g_lead(ζ) = −F·ζ/b + |F|/2 ≥ 0,

  zero at the face end that stands proud (the approach counts from the first point to touch).
* A profile slope deviation is **positive when the flank stands proud at the tip** (more material
  towards the tip than the design involute: the pressure angle smaller than drawn). Of gear i at
  its roll length ρ_i, over its active profile L_i = ρ_EAP,i − ρ_SAP,i with mid-point ρ_c,i:

      g_profile = Σ_i [f_Hα,i·(ρ_c,i − ρ_i)/L_i + |f_Hα,i|/2] ≥ 0  (ρ_i clipped to the active flank).

Both are linear in the deviations: a tolerance sample of the manufactured population costs no new
geometry (:mod:`gearmesh.tolerance`). The mesh misalignment of the system deflection
(:mod:`gearmesh.deflection`, ISO's f_sh) adds to F in the same convention.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from .errors import GearmeshInputError
from .limits import MAX_LEAD_SLOPE_UM

__all__ = ["DEVIATION_KEYS", "Deviations", "read_deviations", "lead_gap", "profile_gap", "mesh_lead_sum", "with_misalignment"]

#: The pair-file keys of the manufacturing deviations (µm).
DEVIATION_KEYS = ("lead_slope_deviation_um", "profile_slope_deviation_um", "mesh_misalignment_um")


@dataclass(frozen=True)
class Deviations:
    """A manufactured pair's deviations (m, signed; module docstring): ``lead_slope`` and
    ``profile_slope`` [pinion, gear]; ``mesh_misalignment`` f_ma, or None when the pair file does
    not state it (zero in the analyses; the rating takes ISO's from the accuracy grade)."""

    lead_slope: tuple[float, float] = (0.0, 0.0)
    profile_slope: tuple[float, float] = (0.0, 0.0)
    mesh_misalignment: float | None = None

    def __post_init__(self) -> None:
        for key, values in (("lead_slope_deviation_um", self.lead_slope),
                            ("profile_slope_deviation_um", self.profile_slope)):
            if len(values) != 2:
                raise GearmeshInputError(key, values, "must be a [pinion, gear] pair")
            for i, v in enumerate(values):
                _check(f"{key}[{i}]", v)
        if self.mesh_misalignment is not None:
            _check("mesh_misalignment_um", self.mesh_misalignment)

    @property
    def misalignment(self) -> float:
        """f_ma (m) as the analyses take it: the stated value, else 0."""
        return 0.0 if self.mesh_misalignment is None else float(self.mesh_misalignment)

    @property
    def is_zero(self) -> bool:
        return not any(self.lead_slope) and not any(self.profile_slope) and not self.misalignment

    def to_dict(self) -> dict[str, Any]:
        """The pair-file keys (µm) of what differs from the drawing (empty for a perfect gear)."""
        out: dict[str, Any] = {}
        if any(self.lead_slope):
            out["lead_slope_deviation_um"] = [_um(v) for v in self.lead_slope]
        if any(self.profile_slope):
            out["profile_slope_deviation_um"] = [_um(v) for v in self.profile_slope]
        if self.mesh_misalignment is not None:
            out["mesh_misalignment_um"] = _um(self.mesh_misalignment)
        return out


def _um(value: float) -> float:
    """m → µm, the float as it is (a manufactured gear written out reads back bit for bit)."""
    return float(value) * 1e6


def _check(field: str, value: Any) -> None:
    """A deviation (m): finite and within ±MAX_LEAD_SLOPE_UM (µm), named by its pair-file key."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)) \
            or not math.isfinite(value):
        raise GearmeshInputError(field, value, "must be a finite number (µm)")
    if abs(value) > MAX_LEAD_SLOPE_UM * 1e-6 * (1 + 1e-12):
        raise GearmeshInputError(field, value * 1e6, f"must lie within ±{MAX_LEAD_SLOPE_UM} µm (a deviation, "
                                                     "not a modification)")


def _pair_um(key: str, value: Any) -> tuple[float, float]:
    if isinstance(value, (list, tuple)):
        if len(value) != 2:
            raise GearmeshInputError(key, value, "must be a [pinion, gear] pair of numbers (µm)")
        items = value
    else:
        raise GearmeshInputError(key, value, "must be a [pinion, gear] pair of numbers (µm)")
    out = []
    for i, v in enumerate(items):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise GearmeshInputError(f"{key}[{i}]", v, "must be a finite number (µm)")
        out.append(float(v) * 1e-6)
    return out[0], out[1]


def read_deviations(spec: Mapping[str, Any]) -> Deviations:
    """The deviation keys of a pair-file mapping (others ignored; module docstring), µm → m.

    Parameters
    ----------
    spec : Mapping
        The pair-file mapping: ``lead_slope_deviation_um`` and ``profile_slope_deviation_um``
        [pinion, gear] (µm), ``mesh_misalignment_um`` (µm), each optional.

    Returns
    -------
    Deviations
        ``lead_slope``, ``profile_slope`` (m, [pinion, gear]) and ``mesh_misalignment`` (m or None).

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth, 3.2.4, 3.3.4.
    .. [2] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1: Basic
       principles, introduction and general influence factors, 7.6.2.1.
    """
    lead = spec.get(DEVIATION_KEYS[0])
    profile = spec.get(DEVIATION_KEYS[1])
    mis = spec.get(DEVIATION_KEYS[2])
    if mis is not None and (isinstance(mis, bool) or not isinstance(mis, (int, float)) or not math.isfinite(mis)):
        raise GearmeshInputError(DEVIATION_KEYS[2], mis, "must be a finite number (µm, signed, in the plane of action)")
    return Deviations(lead_slope=(0.0, 0.0) if lead is None else _pair_um(DEVIATION_KEYS[0], lead),
                      profile_slope=(0.0, 0.0) if profile is None else _pair_um(DEVIATION_KEYS[1], profile),
                      mesh_misalignment=None if mis is None else float(mis) * 1e-6)


def mesh_lead_sum(lead_slope, misalignment=0.0) -> np.ndarray:
    """F = f1 + f2 + misalignment (m): the mesh's lead mismatch; ``lead_slope`` (..., 2).

    Parameters
    ----------
    lead_slope : array_like
        (..., 2) lead slope deviations f_Hβ1, f_Hβ2 (m).
    misalignment : float or array_like, default 0.0
        Mesh misalignment f_ma (m), broadcast against ``lead_slope[..., 0]``.

    Returns
    -------
    ndarray
        F (m), shape (...).
    """
    return np.sum(np.asarray(lead_slope, dtype=float), axis=-1) + np.asarray(misalignment, dtype=float)


def lead_gap(geom, lead_slope, z, misalignment=0.0) -> np.ndarray:
    """Transverse separation (m) opened by the lead mismatch at axial positions ``z`` (m, model
    frame): g = −F·h·z/b + |F|/2 (module docstring), F = f1 + f2 + ``misalignment``.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    lead_slope : array_like
        A pair (f1, f2) or an array (..., 2) (m) whose leading axes broadcast against ``z``
        (one pair per row of a batch).
    z : array_like
        Axial positions (m), face centre at 0.
    misalignment : float or array_like, default 0.0
        f_ma (m), broadcast like ``lead_slope[..., 0]``.

    Returns
    -------
    ndarray
        g ≥ 0 (m), broadcast(F, z).

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth, 3.3.4.
    .. [2] ISO 6336-1:2019, Calculation of load capacity of spur and helical gears — Part 1: Basic
       principles, introduction and general influence factors, 7.6.2.1.
    """
    f = mesh_lead_sum(lead_slope, misalignment)
    hand = 1.0 if geom.pair.helix_hand == "right" else -1.0  # gearmesh.contact.hand_sign (below it here)
    zeta = hand * np.asarray(z, dtype=float)
    return -f * zeta / geom.face_width + 0.5 * np.abs(f)


def profile_gap(geom, profile_slope, rho_pinion, rho_gear) -> np.ndarray | float:
    """Transverse separation (m) opened by both gears' profile slope deviations ``profile_slope``
    (f_Hα1, f_Hα2) (m) at the touched roll lengths ``rho_pinion``, ``rho_gear`` (m) (module
    docstring); 0.0 for a pair without profile deviations.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (:func:`gearmesh.gear.pair_geometry`).
    profile_slope : sequence of float
        (f_Hα1, f_Hα2) (m).
    rho_pinion, rho_gear : array_like
        Roll lengths of the contact on each gear (m), clipped to its active flank; broadcast.

    Returns
    -------
    ndarray or float
        g ≥ 0 (m).

    References
    ----------
    .. [1] ISO 1328-1:2013, Cylindrical gears — ISO system of flank tolerance classification — Part 1:
       Definitions and allowable values of deviations relevant to flanks of gear teeth, 3.2.4.
    """
    gap: Any = 0.0
    for gear, rho in enumerate((rho_pinion, rho_gear)):
        f = float(profile_slope[gear])
        if not f:
            continue
        lo, hi = float(geom.rho_sap[gear]), float(geom.rho_eap[gear])
        r = np.clip(np.asarray(rho, dtype=float), lo, hi)
        gap = gap + f * (0.5 * (lo + hi) - r) / (hi - lo) + 0.5 * abs(f)
    return gap


def with_misalignment(lead, misalignment: float) -> np.ndarray:
    """Lead-slope rows (..., 2) (m) carrying a further mesh misalignment (m) in the pinion's entry:
    the separations depend on the mesh's sum f1 + f2 + misalignment alone (:func:`lead_gap`), so
    this is exact; a result keeps the rows' own slopes apart.

    Parameters
    ----------
    lead : array_like
        (..., 2) lead slope deviations (m).
    misalignment : float
        Mesh misalignment to add (m).

    Returns
    -------
    ndarray
        A copy of ``lead`` (..., 2) (m).
    """
    out = np.array(lead, dtype=float)
    out[..., 0] += misalignment
    return out
