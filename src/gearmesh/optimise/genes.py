"""The genes: the mesh-in impact paper's six modification parameters y1..y6 of the modified gear(s)
in engineering units (µm, mm), their bounds, and their decoding into valid modifications.

The method, the objective and the constraints: :mod:`gearmesh.optimise`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ..errors import GearmeshInputError
from ..gear import GEARS, PairGeometry
from ..limits import MAX_MODIFICATION_TO_MODULE
from ..surface import fit_modifications

#: Pair-file keys of y1..y6, in the order of :data:`gearmesh.surface.MODIFICATION_FIELDS`.
GENE_KEYS = ("root_relief_um", "tip_relief_um", "root_relief_length_mm", "tip_relief_length_mm", "crowning_um",
             "unmodified_lead_length_mm")
GENE_SYMBOLS = ("y1", "y2", "y3", "y4", "y5", "y6")
GENE_UNITS = ("um", "um", "mm", "mm", "um", "mm")
_TO_SI = np.array([1e-6, 1e-6, 1e-3, 1e-3, 1e-6, 1e-3])


# --------------------------------------------------------------------------------------
# Genes
# --------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Gene:
    """One free gene: parameter ``field`` (index into y1..y6) of gear ``gear`` (0 pinion, 1 gear),
    bounds ``low``..``high`` in its engineering unit (µm or mm)."""

    gear: int
    field: int
    low: float
    high: float

    @property
    def name(self) -> str:
        return f"{GEARS[self.gear]}.{GENE_KEYS[self.field]}"

    @property
    def symbol(self) -> str:
        return f"{GENE_SYMBOLS[self.field]} ({GEARS[self.gear]})"

    @property
    def unit(self) -> str:
        return GENE_UNITS[self.field]


def impact_paper_bounds(geom: PairGeometry) -> np.ndarray:
    """The mesh-in impact paper's bounds (6, 2) of y1..y6 in µm / mm.

    y1, y2, y5 in [0.001, 0.015]·m_n, y3, y4 in [0.1, 0.8]·m_n, y6 in (0, 0.5·B] (B the meshing face width).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (normal module m_n and face width B, m).

    Returns
    -------
    numpy.ndarray
        (6, 2) [low, high] of y1..y6: amounts in µm, lengths in mm.

    References
    ----------
    .. [1] Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears (the mesh-in impact paper,
       docs/references.md).
    """
    mn, b = geom.pair.normal_module, geom.face_width
    si = np.array([[0.001 * mn, 0.015 * mn]] * 2 + [[0.1 * mn, 0.8 * mn]] * 2 + [[0.001 * mn, 0.015 * mn],
                                                                                  [0.0, 0.5 * b]])
    return si / _TO_SI[:, None]


def _limits(geom: PairGeometry, gear: int) -> np.ndarray:
    """Largest value (µm / mm) of each parameter that :func:`gearmesh.gear.validate_modifications`
    accepts on its own."""
    depth = MAX_MODIFICATION_TO_MODULE * geom.pair.normal_module
    active = float(geom.rho_eap[gear] - geom.rho_sap[gear])
    return np.array([depth, depth, active, active, depth, geom.face_width]) / _TO_SI


def gene_table(geom: PairGeometry, modify=("pinion",), bounds: Mapping[str, Any] | None = None,
               fixed: Mapping[str, Any] | None = None) -> tuple[tuple[Gene, ...], np.ndarray]:
    """The free genes and the base parameters (2, 6) (m).

    The base is the pair's own modification, with the modified gears' parameters set to their ``fixed`` values (0 until
    a gene sets them).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    modify : sequence of {'pinion', 'gear'}, default ('pinion',)
        The gears whose six parameters are optimised.
    bounds : mapping or None
        {pair-file key: [low, high]} overriding the mesh-in impact paper's bounds (µm / mm, on every modified gear).
    fixed : mapping or None
        {key: value} (µm / mm) fixing a parameter instead of optimising it.

    Returns
    -------
    genes : tuple of Gene
        The free genes (gear, parameter, bounds in µm / mm).
    base : numpy.ndarray
        (2, 6) base modification parameters (m).
    """
    from ..surface import modification_parameters

    if isinstance(modify, str):
        modify = [modify]
    if not isinstance(modify, (list, tuple)) or not modify or len(set(modify)) != len(modify):
        raise GearmeshInputError("modify", modify, "must name 'pinion', 'gear' or both, once each")
    for g in modify:
        if g not in GEARS:
            raise GearmeshInputError("modify", g, f"must be one of {list(GEARS)}")
    bounds, fixed = dict(bounds or {}), dict(fixed or {})
    for section, spec in (("bounds", bounds), ("fixed", fixed)):
        for key in spec:
            if key not in GENE_KEYS:
                raise GearmeshInputError(f"{section}.{key}", spec[key], f"is not a gene; the genes are {list(GENE_KEYS)}")
    both = set(bounds) & set(fixed)
    if both:
        key = sorted(both)[0]
        raise GearmeshInputError(f"fixed.{key}", fixed[key], "is also given bounds: a gene is either free or fixed")
    table = impact_paper_bounds(geom)
    base = modification_parameters(geom).copy()
    genes = []
    for gear in sorted(GEARS.index(g) for g in modify):
        limits = _limits(geom, gear)
        base[gear] = 0.0
        for f, key in enumerate(GENE_KEYS):
            if key in fixed:
                v = fixed[key]
                if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                        or not 0 <= v <= limits[f]:
                    raise GearmeshInputError(f"fixed.{key}", v, f"must lie in [0, {limits[f]:.6g}] {GENE_UNITS[f]}")
                base[gear, f] = v * _TO_SI[f]
                continue
            low, high = table[f]
            if key in bounds:
                pair_ = bounds[key]
                if not isinstance(pair_, (list, tuple)) or len(pair_) != 2 or any(
                        isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in pair_):
                    raise GearmeshInputError(f"bounds.{key}", pair_, f"must be [low, high] in {GENE_UNITS[f]}")
                low, high = (float(v) for v in pair_)
                if not 0 <= low < high <= limits[f]:
                    raise GearmeshInputError(f"bounds.{key}", pair_, f"must satisfy 0 <= low < high <= "
                                             f"{limits[f]:.6g} {GENE_UNITS[f]} (the {GEARS[gear]}'s flank)")
            genes.append(Gene(gear, f, float(low), float(high)))
    if not genes:
        raise GearmeshInputError("fixed", fixed, "leaves no gene to optimise")
    return tuple(genes), base


def decode(geom: PairGeometry, genes: tuple[Gene, ...], base: np.ndarray, values) -> np.ndarray:
    """Modification parameters (C, 2, 6) in m of gene values (C, G) (µm / mm).

    Made valid modifications by :func:`gearmesh.surface.fit_modifications` (:mod:`gearmesh.optimise`).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    genes : tuple of Gene
        The free genes (:func:`gene_table`).
    base : numpy.ndarray
        (2, 6) base parameters (m).
    values : array_like
        (C, G) gene values (µm for amounts, mm for lengths).

    Returns
    -------
    numpy.ndarray
        (C, 2, 6) modification parameters (m).
    """
    values = np.atleast_2d(np.asarray(values, dtype=float))
    p = np.broadcast_to(base, (values.shape[0], 2, 6)).copy()
    for k, gene in enumerate(genes):
        p[:, gene.gear, gene.field] = values[:, k] * _TO_SI[gene.field]
    return fit_modifications(geom, p)
