"""The contact-driven dynamics of a population of micro-geometries of one pair: the peak dynamic
mesh force of each over a speed range and a load spectrum, for the optimiser's ``dynamic``
objective and constraint (:mod:`gearmesh.optimise`).

For every micro-geometry (modification parameters and lead slopes, e.g. a GA candidate or one of
its manufactured samples) the mesh force table is tabulated from one shared
:class:`gearmesh.meshforce.TableLayout` (the geometry, compliances and candidate points of the
pair are computed once; only the separations change, :meth:`TableLayout.gaps`), and at each
torque the 8-DOF pair with that table (:func:`pair_model` with ``contact``) is run to its
periodic steady state at every speed of a fixed grid *and* around the resonance speeds of its own
linearised model (:func:`resonance_band`: a modification shifts the mean mesh stiffness and with
it the resonance, whose peak a fixed grid would straddle). The result per micro-geometry and
torque is the **dynamic factor** K_v = max over those speeds of the largest normal mesh force in
the steady state over the static normal mesh force T_out/(r_b2 cos βb) (-): the quantity ISO
6336-1 calls the dynamic factor, here from the simulated contact rather than from its empirical
method B. Its largest value over the speeds is the peak dynamic mesh force over the static one.

Why the 8-DOF pair and not the torsional (rigid-bearing) model: with the compiled loop and the
shooting solve one speed of the 8-DOF pair costs about 0.2 ms, as much as the torsional model, and
on the default pair its supports (the pair file's) move the mesh resonance from about 4900 r/min
(torsional) to about 7200 r/min (8-DOF), so the torsional model would rank candidates on the wrong
resonance.

The table of a population member is coarser than the study's (``positions`` 64, ``approaches``
32, ``points`` 50 by default): on the default pair the peak mesh forces of 7 speeds agree with the
study's table (256 × 96 × 200 points) within 0.05 % (tests/test_dynamics_contact.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..contact_model import DEFAULT_LTCA_POINTS, TABLE_CONTACT, ContactModel
from ..errors import GearmeshInputError
from ..deflection import mesh_misalignment
from ..deviation import with_misalignment
from ..gear import PairGeometry
from ..meshforce import TableLayout, table_layout, tabulate
from .integrate import SolverSettings, simulate
from .model import DEFAULT_DAMPING_RATIO, pair_model, require_dynamics_data, resonance_band

__all__ = ["PopulationDynamics", "population_dynamics", "dynamic_factors"]

#: Table size of a population member (module docstring).
POPULATION_TABLE = {"positions": 64, "approaches": 32}
#: The contact model of those tables: a mesh force table's (:data:`gearmesh.contact_model.TABLE_CONTACT`) on the
#: LTCA's 50 points per line.
POPULATION_CONTACT = TABLE_CONTACT.with_(points=DEFAULT_LTCA_POINTS)
#: Harmonics of the mesh frequency whose resonances are added to the speed grid (a modified
#: candidate's peak can lie at the second: 1.063 against 1.026 with the first alone), the offsets
#: around each (in modal damping ratios) and the least share of a mode's strain energy in the
#: mesh for it to count (a bearing mode with less is barely driven by the mesh).
POPULATION_HARMONICS = (1, 2)
POPULATION_OFFSETS = (-0.5, 0.0, 0.5)
POPULATION_MESH_ENERGY = 0.05
#: The table reaches this many times the largest static transverse force (as the study's table).
POPULATION_FORCE_FACTOR = 4.0
#: The solver of a population member: from a periodic orbit found by shooting, two recorded
#: periods and none to settle (every period repeats the first to the shooting tolerance, so K_v
#: is the same to it as over more); four periods after the physical-time transient, where the
#: shooting finds no stable periodic orbit and the response need not repeat. Up to 20 Newton
#: steps: near a resonance the chord iteration can take 13–14 (3 of 1080 speeds of 40 random
#: candidates of the default study), and each speed it gives up on costs the physical-time
#: transient, ~10³ periods, for the same orbit.
POPULATION_SOLVER = SolverSettings(record_cycles=4, settle_cycles=0, periodic_record_cycles=2,
                                   shooting_iterations=20)


@dataclass(frozen=True)
class PopulationDynamics:
    """What every member's dynamics shares (SI): the table ``layout``, the gear torques
    ``torques_out`` (T,) N·m of the pinion torques ``pinion_torques`` (T,), the speed grid
    ``speeds_rpm`` (rpm) and its range, the table's ``force_max`` (N) and ``approaches``, the
    backlash (m), the mesh damping ratio and the solver settings; ``misalignment_torque`` the pinion
    torque (N m) whose mesh misalignment every table carries (None: each torque's own)."""

    layout: TableLayout
    pinion_torques: np.ndarray
    torques_out: np.ndarray
    speeds_rpm: np.ndarray
    force_max: float
    approaches: int
    backlash: float
    damping_ratio: float
    settings: SolverSettings
    misalignment_torque: float | None = None

    @property
    def geom(self) -> PairGeometry:
        return self.layout.geom


def population_dynamics(geom: PairGeometry, pinion_torques, speeds_rpm, backlash: float | None = None,
                        damping_ratio: float = DEFAULT_DAMPING_RATIO, contact: ContactModel = POPULATION_CONTACT,
                        positions: int = POPULATION_TABLE["positions"],
                        approaches: int = POPULATION_TABLE["approaches"],
                        settings: SolverSettings = POPULATION_SOLVER, tables=None,
                        misalignment_torque: float | None = None) -> PopulationDynamics:
    """Set up :func:`dynamic_factors` for ``geom`` at pinion torques over a speed grid.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (with bore radius and material).
    pinion_torques : array_like
        (T,) pinion torques (N·m).
    speeds_rpm : array_like
        Speed grid (rpm, ≥ 2 speeds: its range bounds the resonance speeds added).
    backlash : float or None
        2b0 (m); None: the pair's own normal backlash j_bn.
    damping_ratio : float
        Modal damping ratio ζ (-) of the mesh mode (:func:`pair_model`).
    contact : ContactModel, default :data:`POPULATION_CONTACT`
        The member tables' contact model: points per line, contact law, tooth model, reach
        (:class:`gearmesh.contact_model.ContactModel`).
    positions, approaches : int
        The member tables' mesh positions and approaches (default ``POPULATION_TABLE``: 64, 32).
    settings : SolverSettings
        Solver settings (default ``POPULATION_SOLVER``).
    tables : optional
        The per-gear slice compliance tables to reuse (:func:`gearmesh.meshforce.table_layout`).
    misalignment_torque : float or None
        A pinion torque (N m) whose mesh misalignment every member's one table carries (None: one table per torque at
        its own, as the dynamics stage; a screening can take the design torque's: the system deflection's f_sh moves
        with the load by a fraction of the modifications).

    Returns
    -------
    PopulationDynamics
        The shared setup: table ``layout``, ``torques_out`` (T,) N·m, ``speeds_rpm``, ``force_max`` (N), backlash (m),
        damping ratio and solver settings.
    """
    require_dynamics_data(geom)
    torques = np.atleast_1d(np.asarray(pinion_torques, dtype=float))
    speeds = np.unique(np.atleast_1d(np.asarray(speeds_rpm, dtype=float)))
    if speeds.size < 2 or not np.all(np.isfinite(speeds)) or np.any(speeds <= 0):
        raise GearmeshInputError("dynamic_speeds_rpm", speeds.tolist(), "must give at least two positive speeds "
                                                                         "(their range bounds the resonances)")
    if torques.size == 0 or not np.all(np.isfinite(torques)) or np.any(torques <= 0):
        raise GearmeshInputError("torques_Nm", torques.tolist(), "must be positive torques")
    rb1, rb2 = (float(r) for r in geom.base_radius)
    backlash = float(geom.backlash_normal) if backlash is None else float(backlash)
    if not (math.isfinite(backlash) and backlash >= 0):
        raise GearmeshInputError("backlash_um", backlash * 1e6, "must be a non-negative finite backlash")
    layout = table_layout(geom, positions, contact, tables=tables)
    return PopulationDynamics(layout=layout, pinion_torques=torques, torques_out=torques * rb2 / rb1, speeds_rpm=speeds,
                              force_max=POPULATION_FORCE_FACTOR * float(torques.max()) / rb1, approaches=approaches,
                              backlash=backlash, damping_ratio=float(damping_ratio), settings=settings,
                              misalignment_torque=misalignment_torque)


def dynamic_factors(pd: PopulationDynamics, params: np.ndarray, lead_slope: np.ndarray) -> np.ndarray:
    """Dynamic factor K_v (N, T) of N micro-geometries at the setup's torques (module docstring).

    Each torque's table carries its mesh misalignment (:func:`gearmesh.deflection.mesh_misalignment`, as the study's
    tables); torques of one misalignment share it.

    Parameters
    ----------
    pd : PopulationDynamics
        The setup (:func:`population_dynamics`).
    params : numpy.ndarray
        (N, 2, 6) modification parameters (m).
    lead_slope : numpy.ndarray
        (N, 2) lead slopes [pinion, gear] (m over the face width).

    Returns
    -------
    numpy.ndarray
        (N, T) K_v (-): the largest steady-state normal mesh force over the speeds / the static T_out/(r_b2 cos βb).

    References
    ----------
    .. [1] ISO 6336-1:2019 (the dynamic factor K_v, here from the simulated contact rather than method B).
    """
    params = np.asarray(params, dtype=float)
    torques = pd.pinion_torques if pd.misalignment_torque is None else np.full(pd.pinion_torques.size,
                                                                                 pd.misalignment_torque)
    misalignment = mesh_misalignment(pd.geom, torques / float(pd.geom.base_radius[0]))
    gaps = {float(m): pd.layout.gaps(params, with_misalignment(lead_slope, float(m))) for m in np.unique(misalignment)}
    lo, hi = float(pd.speeds_rpm[0]), float(pd.speeds_rpm[-1])
    out = np.empty((params.shape[0], pd.torques_out.size))
    for n in range(params.shape[0]):
        tables = {m: tabulate(pd.layout, g[n], pd.force_max, pd.approaches) for m, g in gaps.items()}
        for t, torque in enumerate(pd.torques_out):
            model = pair_model(pd.geom, float(torque), None, contact=tables[float(misalignment[t])], backlash=pd.backlash,
                               damping_ratio=pd.damping_ratio)
            speeds = np.unique(np.concatenate([pd.speeds_rpm, resonance_band(model, lo, hi, POPULATION_HARMONICS, POPULATION_OFFSETS,
                                                                     POPULATION_MESH_ENERGY)]))
            result = simulate(model, speeds, pd.settings)
            out[n, t] = float(np.max(result.force_max[0])) / float(model.static_force[0])
    return out
