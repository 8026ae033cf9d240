"""What drives a mesh of the dynamic models: the mesh law of one mesh over one mesh cycle.

Three excitations (package docstring, :mod:`gearmesh.dynamics`), all along the *normal* to the
flanks (the models' coordinate δ = cos βb × transverse):

* ``tvms`` — a time-varying stiffness k(t) of the slice model and a kinematic error e(t) (zero
  for perfect flanks, or a tabulated unloaded TE): F = k(t)·(δ − e(t)) + c(δ̇ − ė);
* ``lste`` — the low-fluctuation paper's literal form, e = F/K(t) as well as k(t) (counts the fluctuation twice;
  kept to reproduce the document);
* ``ltca`` — the LTCA's loaded stiffness k_L(t) and equivalent error e = LTE − F/k_L (Velex &
  Ajmi 2006, J. Sound Vib. 290:882): the linearisation of the real contact about its static
  state at one torque;
* ``contact`` — the real contact: F(x, t) of :mod:`gearmesh.meshforce`, nonlinear in the approach,
  with the entering pair touching before A when the pairs in mesh deflect and contact lost where
  the approach falls below every separation. Its linearisation about the static state (the
  ``ltca`` form from the same table) serves the modes, the step size and the start.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import GearmeshInputError
from ..gear import PairGeometry
from ..meshforce import MeshForceTable

EXCITATIONS = ("tvms", "lste", "ltca", "contact")
STIFFNESS_FORMS = ("fourier", "table")
#: Points of the fine table that holds a Fourier-represented error e(phase).
FOURIER_TABLE_POINTS = 1024


@dataclass(frozen=True)
class MeshLaw:
    """Stiffness and excitation of one mesh over one mesh cycle (normal direction, SI).

    ``phase`` (P,) mesh-cycle fractions k/P of the tabulated ``k`` (N/m, the normal mesh
    stiffness; None with ``fourier``); ``fourier`` = (mean, a, b) of k(ψ) = mean + Σ a_j cos(jψ)
    + b_j sin(jψ), ψ = 2π·phase; ``e`` (m) the static TE along the normal at ``e_phase``
    (uniform, k/Q; None for none); ``phase_offset`` (cycles) shifts this mesh. With ``contact``
    the mesh force is the table's (:mod:`gearmesh.meshforce`) and ``k``, ``e`` are its
    linearisation about the static state (modes, step size, start).
    """

    k_mean: float
    k_max: float
    fourier: tuple[float, np.ndarray, np.ndarray] | None = None
    phase: np.ndarray | None = None
    k: np.ndarray | None = None
    e_phase: np.ndarray | None = None
    e: np.ndarray | None = None
    phase_offset: float = 0.0
    contact: MeshForceTable | None = None

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
        return periodic_interp(ph, self.phase, self.k)

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


def periodic_interp(ph, xp, fp):
    """Linear interpolation in a periodic table.

    Parameters
    ----------
    ph : array_like
        Phases at which to interpolate (fractions of the period, in [0, 1)).
    xp : numpy.ndarray
        (P,) table phases, increasing over one period [0, 1).
    fp : numpy.ndarray
        (P,) table values (any unit).

    Returns
    -------
    numpy.ndarray
        Values at ``ph`` (the unit of ``fp``), the last interval wrapping to the first point.
    """
    xp = np.concatenate([xp, [xp[0] + 1.0]])
    fp = np.concatenate([fp, [fp[0]]])
    return np.interp(ph, xp, fp)


def mesh_law(geom: PairGeometry, K_transverse: np.ndarray, torque: float, stiffness_form: str = "fourier",
             order: int = 3, excitation: str = "tvms", transmission_error=None, phase_offset: float = 0.0) -> MeshLaw:
    """The :class:`MeshLaw` of a pair from a transverse stiffness curve (``tvms``, ``lste``, ``ltca``).

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry (βb).
    K_transverse : numpy.ndarray
        (P,) transverse mesh stiffness K (N/m; :attr:`~gearmesh.stiffness.MeshStiffness.K` or the LTCA's k_L) evenly over p_bt.
    torque : float
        Pinion torque T1 (N·m), for the low-fluctuation paper's excitation e = F/K.
    stiffness_form, order : {'fourier', 'table'}, int
        Fourier series of ``order`` (default 'fourier', 3: the improved potential-energy paper [2]_) or the full curve.
    excitation : {'tvms', 'ltca', 'lste'}, default 'tvms'
        'tvms', 'ltca': e = ``transmission_error`` or none; 'lste': the low-fluctuation paper's literal [1]_
        e = F_bt/K(t) along the transverse line of action, × cos βb along the normal; 'contact': :func:`contact_mesh_law`.
    transmission_error : numpy.ndarray or None
        (Q,) static TE (m) along the *transverse* line of action evenly over one base pitch (unloaded, or the LTCA's
        e = LTE − F/k_L), added to e; with ``stiffness_form='fourier'`` its Fourier series of ``order`` too.
    phase_offset : float, default 0
        Mesh-cycle fraction (-) added to this mesh's phase.

    Returns
    -------
    MeshLaw
        Normal mesh stiffness (``k_mean``, ``k_max``, ``fourier`` or ``k``, N/m) and error ``e`` (m, normal).

    References
    ----------
    .. [1] [untitled] Low mesh-stiffness fluctuation design of helical gears (docs/references.md).
    .. [2] A Comprehensive Study on Meshing Characteristics of Helical Gear Pairs Using an Improved Potential Energy Method
       for Time-Varying Meshing Stiffness.
    """
    from ..stiffness import fourier_fit

    if stiffness_form not in STIFFNESS_FORMS:
        raise GearmeshInputError("stiffness_form", stiffness_form, f"must be one of {list(STIFFNESS_FORMS)}")
    if excitation not in EXCITATIONS[:3]:
        raise GearmeshInputError("excitation", excitation, f"must be one of {list(EXCITATIONS[:3])} here")
    cb2 = math.cos(geom.base_helix_angle) ** 2
    K = np.asarray(K_transverse, dtype=float)
    phase = np.arange(K.size) / K.size
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
            e = e + periodic_interp(phase, te_phase, te) * cb
    return MeshLaw(k_mean=k_mean, k_max=k_max, fourier=fourier, phase=phase, k=k_n if stiffness_form == "table"
                   else None, e_phase=e_phase, e=e, phase_offset=phase_offset)


def contact_mesh_law(geom: PairGeometry, table: MeshForceTable, torque: float, phase_offset: float = 0.0) -> MeshLaw:
    """The ``contact`` :class:`MeshLaw`: the mesh force of ``table`` at pinion torque ``torque``.

    The table's own static solution F(x, w) = F_bt = T1/r_b1 is its linearisation (k = dF/dx, e = x − F_bt/k, the
    ``ltca`` form, on the table's rows resampled to evenly spaced mesh phases), and the largest stiffness is the largest
    tangent anywhere in the table.

    Parameters
    ----------
    geom : PairGeometry
        The pair's geometry.
    table : MeshForceTable
        The pair's mesh force table (:func:`gearmesh.meshforce.mesh_force_table`).
    torque : float
        Pinion torque T1 (N·m).
    phase_offset : float, default 0
        Mesh-cycle fraction (-) added to this mesh's phase.

    Returns
    -------
    MeshLaw
        ``contact`` the table; ``k`` (N/m) and ``e`` (m) its linearisation along the normal.

    References
    ----------
    .. [1] Velex P., Ajmi M., J. Sound Vib. 290 (2006) 882: the equivalent error e = LTE − F/k_L of the ``ltca`` form.
    """
    cb = math.cos(geom.base_helix_angle)
    force = torque / float(geom.base_radius[0])
    x_s, k_s = table.static_approach(force)
    n = table.positions
    phase = np.arange(n) / n
    w = table.window_position(phase * table.pitch)
    k_t = np.interp(w, table.window, k_s)
    e_t = np.interp(w, table.window, x_s) - force / k_t
    k_n = k_t / cb**2
    return MeshLaw(k_mean=float(np.mean(k_n)), k_max=float(np.max(table.stiffness)) / cb**2, phase=phase, k=k_n,
                   e_phase=phase, e=e_t * cb, phase_offset=phase_offset, contact=table)
