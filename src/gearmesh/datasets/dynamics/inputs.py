"""The settings of a dynamics run checked and converted at the boundary (engineering units in,
SI out): speeds, torques, bearings, backlash, the solver rules and the contact-table settings,
each against its declaration (:class:`gearmesh.settings.Dynamics`, :class:`gearmesh.settings.TrainDynamics`).
"""

from __future__ import annotations

import math
from typing import Any, Mapping, Sequence, get_args

import numpy as np

from ...dynamics import SolverSettings
from ...contact_model import TABLE_CONTACT, ContactModel
from ...errors import GearmeshInputError
from ...gear import GearPair, PairGeometry
from ...limits import BEARING_STIFFNESS, MAX_SPEEDS, MAX_TABLE_POINTS
from ...schema import UNIT_SUFFIXES, check_value, defaults, jsonable, key_of, settings_fields, settings_object
from ...settings import Dynamics, PairExcitation, SteadyState, Stiffness, TrainDynamics

#: The pair sweep's default speeds {start, stop, step} (rpm): the declared one (:class:`gearmesh.settings.Dynamics`).
DEFAULT_SPEEDS = jsonable(settings_object(Dynamics, {}).speeds_rpm)


def parse_speeds(text: str) -> dict[str, float] | list[float]:
    """'START:STOP:STEP' (rpm) as {start, stop, step}, or 'SPEED' as [speed]: the forms of a
    study's ``speeds_rpm`` (GearmeshInputError naming ``speeds_rpm``).

    Parameters
    ----------
    text : str
        ``'START:STOP:STEP'`` or ``'SPEED'`` (r/min), e.g. from a command-line option.

    Returns
    -------
    dict or list of float
        ``{start, stop, step}`` (r/min) or ``[speed]`` (r/min); checked by :func:`speed_grid`.

    Raises
    ------
    GearmeshInputError
        ``speeds_rpm`` when the text is not numbers or has neither one nor three parts.
    """
    try:
        values = [float(p) for p in text.split(":")]
    except ValueError:
        raise GearmeshInputError("speeds_rpm", text, "must be START:STOP:STEP numbers") from None
    if len(values) == 1:
        return values
    if len(values) == 3:
        return dict(zip(("start", "stop", "step"), values))
    raise GearmeshInputError("speeds_rpm", text, "must be START:STOP:STEP or one speed")


def speed_grid(speeds: Mapping[str, float] | Sequence[float] | str | float) -> np.ndarray:
    """Speeds (rpm) from {start, stop, step} (stop included), a list, 'START:STOP:STEP' or one number.

    Refuses non-positive or non-finite speeds, stop < start, step <= 0 and more than
    :data:`MAX_SPEEDS` speeds (GearmeshInputError naming ``speeds_rpm``).

    Parameters
    ----------
    speeds : Mapping or sequence of float or str or float
        ``{start, stop, step}`` (r/min, stop included when on the grid), a list of speeds (r/min),
        ``'START:STOP:STEP'`` or one speed (r/min).

    Returns
    -------
    numpy.ndarray
        The speeds (S,) (r/min).

    Raises
    ------
    GearmeshInputError
        ``speeds_rpm`` (or ``speeds_rpm.start``, ``.stop``, ``.step``, an unknown key) naming the rule broken.
    """
    if isinstance(speeds, str):
        speeds = parse_speeds(speeds)
    if isinstance(speeds, Mapping):
        unknown = sorted(set(speeds) - {"start", "stop", "step"})
        if unknown:
            raise GearmeshInputError(f"speeds_rpm.{unknown[0]}", speeds[unknown[0]], "unknown key (start, stop, step)")
        try:
            start, stop, step = (float(speeds[k]) for k in ("start", "stop", "step"))
        except KeyError as exc:
            raise GearmeshInputError(f"speeds_rpm.{exc.args[0]}", None, "is required") from None
        except (TypeError, ValueError):
            raise GearmeshInputError("speeds_rpm", dict(speeds), "start, stop, step must be numbers") from None
        if not all(map(math.isfinite, (start, stop, step))):
            raise GearmeshInputError("speeds_rpm", dict(speeds), "start, stop, step must be finite")
        if start <= 0:
            raise GearmeshInputError("speeds_rpm.start", start, "must be positive")
        if step <= 0:
            raise GearmeshInputError("speeds_rpm.step", step, "must be positive")
        if stop < start:
            raise GearmeshInputError("speeds_rpm.stop", stop, f"must not be below start ({start})")
        count = int(math.floor((stop - start) / step + 1e-9)) + 1
        if count > MAX_SPEEDS:
            raise GearmeshInputError("speeds_rpm", dict(speeds), f"gives {count} speeds; at most {MAX_SPEEDS}")
        return start + step * np.arange(count)
    arr = np.atleast_1d(np.asarray(speeds, dtype=float)) if not isinstance(speeds, (bool,)) else None
    if arr is None or arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        raise GearmeshInputError("speeds_rpm", speeds, "must be positive finite speeds")
    if arr.size > MAX_SPEEDS:
        raise GearmeshInputError("speeds_rpm", f"{arr.size} speeds", f"at most {MAX_SPEEDS}")
    return arr


def positive_quantity(name: str, value) -> float:
    """``value`` as a float when it is a positive finite number (a torque, force or frequency at the boundary).

    Parameters
    ----------
    name : str
        The setting's name, for the error (``torque_Nm``, ``static_force_N``, ``mesh_frequency_Hz``).
    value : float
        The value given, in the unit its name carries (N m, N, Hz).

    Returns
    -------
    float
        ``value``, in its given unit.

    Raises
    ------
    GearmeshInputError
        ``name`` when ``value`` is not a positive finite number (a bool refused).
    """
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        unit = next((u for suffix, u in UNIT_SUFFIXES if name.endswith(suffix)), "")
        raise GearmeshInputError(name, value, f"must be a positive finite number{f' ({unit})' if unit else ''}")
    return float(value)


def _bearing(k_radial_N_per_m, k_axial_N_per_m, c_radial_Ns_per_m, c_axial_Ns_per_m) -> dict[str, float]:
    """The model's ``bearing`` overrides: a stiffness ``'pair'`` is the pair file's supports (left out)."""
    out = {}
    for key, name, v, positive in (("k_radial", "bearing_k_radial_N_per_m", k_radial_N_per_m, True),
                                   ("k_axial", "bearing_k_axial_N_per_m", k_axial_N_per_m, True),
                                   ("c_radial", "bearing_c_radial_Ns_per_m", c_radial_Ns_per_m, False),
                                   ("c_axial", "bearing_c_axial_Ns_per_m", c_axial_Ns_per_m, False)):
        if positive and v == "pair":
            continue
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v < 0 \
                or (positive and v == 0):
            raise GearmeshInputError(name, v, "must be a positive finite number" if positive
                                     else "must be a non-negative finite number")
        if positive:  # a stiffness: within what bearings have, in the key's N/m
            BEARING_STIFFNESS.check(v, name, "N/m")
        out[key] = float(v)
    return out


def supports_note(pair: GearPair, bearing_k_radial_N_per_m="pair", bearing_k_axial_N_per_m="pair") -> str:
    """The supports a dynamics result used, one sentence (dataset attrs, CLI JSON).

    Parameters
    ----------
    pair : GearPair
        The pair (its own supports and Young's modulus, Pa).
    bearing_k_radial_N_per_m, bearing_k_axial_N_per_m : float or 'pair'
        The study's bearing stiffnesses (N/m) of both gears; ``'pair'`` the pair file's supports.

    Returns
    -------
    str
        The supports as the result used them.
    """
    own = pair.supports.describe(pair.material.youngs_modulus)
    if bearing_k_radial_N_per_m == "pair" and bearing_k_axial_N_per_m == "pair":
        return own
    return (f"supports set by the study (both gears): radial {bearing_k_radial_N_per_m} N/m, axial "
            f"{bearing_k_axial_N_per_m} N/m, 'pair' meaning the pair file's: {own}")


#: The declared defaults of the dynamics settings (:class:`gearmesh.settings.Dynamics`).
_DEFAULTS = defaults(Dynamics)
#: The keys each settings class declares: a stage function parses them itself, once
#: (:func:`gearmesh.schema.settings_object`), so :func:`gearmesh.arguments.check_arguments` leaves them to it.
SECTION_KEYS = {cls: tuple(key_of(f) for f in settings_fields(cls)) for cls in (Dynamics, TrainDynamics)}


def _solver(settings: Dynamics | TrainDynamics) -> SolverSettings:
    """The solver rules of parsed ``settings`` (:func:`gearmesh.schema.settings_object`: every
    bound of its declaration met) as :class:`gearmesh.dynamics.SolverSettings`."""
    s = settings
    return SolverSettings(courant=float(s.courant), steps_per_cycle_min=s.steps_per_cycle_min,
                          transient_tau=float(s.transient_tau), record_cycles=s.record_cycles,
                          steady_state=s.steady_state)


def slice_grid(slices: int | None, positions: int | None) -> tuple[int, int]:
    """The slice model's grid (slices, positions) of a dynamics run given no stiffness dataset: the
    stiffness stage's (:class:`gearmesh.settings.Stiffness`; its declared default where None),
    keywords of the Python API beside the section (a study's dynamics reads the stiffness stage).

    Parameters
    ----------
    slices : int or None
        Slices across the face width; None the stiffness stage's default.
    positions : int or None
        Mesh positions over one mesh cycle; None the stiffness stage's default.

    Returns
    -------
    (int, int)
        (slices, positions), checked against :class:`gearmesh.settings.Stiffness`.

    Raises
    ------
    GearmeshInputError
        ``slices`` or ``positions`` outside its declaration.
    """
    grid = settings_object(Stiffness, {k: v for k, v in (("slices", slices), ("positions", positions))
                                       if v is not None})
    return grid.slices, grid.positions


def settings_speeds(speeds_rpm) -> np.ndarray:
    """The speeds (rpm) of a parsed ``speeds_rpm`` (a :class:`gearmesh.settings.SpeedRange` or a
    tuple) as :func:`speed_grid` reads them.

    Parameters
    ----------
    speeds_rpm : SpeedRange or tuple of float
        The parsed section's ``speeds_rpm`` (r/min).

    Returns
    -------
    numpy.ndarray
        The speeds (S,) (r/min), refused (GearmeshInputError naming ``speeds_rpm``) as :func:`speed_grid` does.
    """
    return speed_grid(jsonable(speeds_rpm))


def table_keywords(settings: Dynamics | TrainDynamics) -> dict[str, Any]:
    """The contact-table settings of parsed ``settings`` as :func:`contact_tables` takes them beside the
    section's contact model (``settings.contact_model()``).

    Parameters
    ----------
    settings : Dynamics or TrainDynamics
        The parsed section.

    Returns
    -------
    dict of str to Any
        ``table_positions``, ``table_approaches`` and ``table_force_factor`` (a factor on F_bt).
    """
    return {k: getattr(settings, k) for k in _TABLE_KEYS}


#: How each speed reaches its steady state (:class:`gearmesh.dynamics.SolverSettings`).
STEADY_STATES = get_args(SteadyState)
#: Excitations of the pair model; None (the default) is 'ltca' when an LTCA dataset is given, else 'tvms'.
PAIR_EXCITATIONS = get_args(PairExcitation)


def _backlash(geom: PairGeometry, backlash_um) -> float | None:
    """Total backlash 2b0 (m) along the normal: 'pair' the pair's own (its centre distance and
    shifts), a number (µm), or None (no backlash: contact never lost)."""
    if backlash_um == "pair":
        return float(geom.backlash_normal)
    if backlash_um is not None and (isinstance(backlash_um, bool) or not isinstance(backlash_um, (int, float))
                                    or not math.isfinite(backlash_um) or backlash_um < 0):
        raise GearmeshInputError("backlash_um", backlash_um, "must be 'pair', a non-negative number (µm) or null (none)")
    return None if backlash_um is None else float(backlash_um) * 1e-6


def backlash_source(backlash_um) -> str:
    """Where the backlash of a result came from, for its ``backlash_source`` attribute.

    Parameters
    ----------
    backlash_um : float or 'pair' or None
        The section's ``backlash_um``: a number (µm), the pair's own or none.

    Returns
    -------
    str
        "the pair's own (centre distance and shifts)", "given" or "none".
    """
    return ("the pair's own (centre distance and shifts)" if backlash_um == "pair"
            else ("none" if backlash_um is None else "given"))


#: Settings of the contact table (:func:`contact_table`) beside its contact model, with their defaults.
_TABLE_KEYS = {k: _DEFAULTS[k] for k in ("table_positions", "table_approaches", "table_force_factor")}


def _table_settings(contact: ContactModel = TABLE_CONTACT, **settings: Any) -> dict[str, Any]:
    """The contact-table settings (:data:`_TABLE_KEYS`; the declared defaults for those not
    given), each checked against its declaration, and their product with the ``contact`` model's
    points against the work limit :data:`MAX_TABLE_POINTS` (GearmeshInputError naming the key)."""
    unknown = sorted(set(settings) - set(_TABLE_KEYS))
    if unknown:
        raise GearmeshInputError(unknown[0], settings[unknown[0]], f"is not a contact-table setting {list(_TABLE_KEYS)}")
    s = {**_TABLE_KEYS, **settings}
    for key, value in s.items():
        check_value(Dynamics, key, value)
    positions, approaches, points = s["table_positions"], s["table_approaches"], contact.points
    if positions * approaches * points > MAX_TABLE_POINTS:
        raise GearmeshInputError("table_positions", positions, f"× table_approaches {approaches} × points {points} "
                                 f"must be at most {MAX_TABLE_POINTS:.0e} (the table's build time and memory)")
    return {"positions": positions, "approaches": approaches, "factor": float(s["table_force_factor"])}
