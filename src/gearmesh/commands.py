"""What each ``gearmesh`` command does and prints: the pair it loads, the stage it runs and
its result as text or one JSON object. The command line's parser and :func:`gearmesh.cli.main`,
which calls these, are :mod:`gearmesh.cli`'s.

Bad input raises :class:`gearmesh.errors.GearmeshInputError` naming the option or file; the
command line prints it as one line ``gearmesh: error: FIELD = VALUE: RULE`` (exit 2).
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import os
import re
import sys
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from .config import check_study, load_study, validate_study
from .contact import contact_length_summary
from .deviation import read_deviations
from .errors import GearmeshInputError
from .gear import pair_geometry, pinion_torque
from .inputfile import read_yaml
from .limits import MAX_CONTACT_POINTS, MAX_STIFFNESS_POINTS, check_grid
from .loads import check_load
from .pairfile import NAME_PATTERN, example_pair, example_pairs, load_pair, missing_needs, pair_to_dict


def _finite(obj: Any) -> Any:
    """JSON-safe: NaN becomes null (JSON has no NaN)."""
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, Mapping):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    if hasattr(obj, "item"):
        return _finite(obj.item())
    return obj


def emit(result: Mapping[str, Any], as_json: bool, text=None) -> None:
    """Print a result: one JSON object, or its text (``text(result)``: the command's own lines),
    or one ``key  value`` line per number (nested keys dotted) and, for a speed sweep, a table
    with one row per speed.

    Parameters
    ----------
    result : mapping
        A command's result (NaN printed as JSON null).
    as_json : bool
        One JSON object on one line.
    text : callable, optional
        ``text(result)``: the lines to print (e.g. :func:`rating_text`).
    """
    if as_json:
        print(json.dumps(_finite(result)))
        return
    if text is not None:
        print("\n".join(text(result)))
        return
    rows = result.get("speeds") if isinstance(result.get("speeds"), list) else None
    lines = _flat(_finite({k: v for k, v in result.items() if rows is None or k != "speeds"}))
    width = max(len(k) for k in lines)
    for key, value in lines.items():
        if isinstance(value, float):
            value = f"{value:.6g}"
        elif isinstance(value, list):  # sentences (notes) apart by "; ", numbers by ", "
            value = ("; " if all(isinstance(v, str) for v in value) else ", ").join(
                f"{v:.6g}" if isinstance(v, float) else str(v) for v in value)
        print(f"{key:<{width}}  {value}")
    if rows:  # a table, one row per speed
        keys = list(rows[0])
        print("  ".join(f"{k:>18}" for k in keys))
        for row in _finite(rows):
            print("  ".join(f"{v:>18.6g}" if isinstance(v, float) else f"{v!s:>18}" for v in row.values()))


def _value_text(value: Any, gears: Sequence[str] = ()) -> str:
    """One value of the text output: a number to six digits, a list of sentences apart by "; ", a
    list of numbers by ", " (per gear named, "pinion 1.98, gear 2.01", where ``gears`` names them)."""
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list):
        if all(isinstance(v, str) for v in value):
            return "; ".join(value)
        items = [_value_text(v) for v in value]
        if gears and len(items) == len(gears):
            items = [f"{g} {v}" for g, v in zip(gears, items)]
        return ", ".join(items)
    return str(value)


#: The text output of ``gearmesh rating`` in groups, in this order: (heading, the keys it holds:
#: exact dotted keys or patterns). A key of no group is printed under "other", so a key the rating
#: gains is shown without a change here.
RATING_GROUPS = (
    ("operating point", r"name|torque_Nm|torque_on|pinion_torque_Nm|speed_rpm|pitch_line_speed_m_s|"
                        r"force_tangential_N|method|accuracy_grade|load_cycles|life_factor_conditions|gears|"
                        r"factors_given"),
    ("load factors (ISO 6336-1)", r"K_\w+"),
    ("pitting (ISO 6336-2)", r"(Z_|M_\d|sigma_H|S_H)\w*"),
    ("tooth root (ISO 6336-3)", r"(Y_|sigma_F|S_F)\w*"),
    ("scuffing (ISO/TS 6336-20/-21)", r"contact_temperature_max_C|integral_temperature_C|scuffing_safety_\w+"),
    ("scuffing temperatures and inputs", r"scuffing\..+"),
    ("inputs of the ISO 6336-1 factors", r"iso_factors\..+"),
    ("where each factor comes from", r"factor_sources\..+"),
    ("loaded tooth contact", r"ltca\..+"),
)


def safety_verdict(result: Mapping[str, Any]) -> tuple[bool, str]:
    """Whether every safety factor of a rating meets its minimum, and the line that says so:
    each ``S_X`` with an ``S_Xmin`` in ``result`` (the weaker gear's against the minimum), e.g.
    "PASS: S_H 1.98 >= S_Hmin 1, S_F 4.83 >= S_Fmin 1 (the weaker gear of each)".

    Parameters
    ----------
    result : mapping
        A rating (:func:`gearmesh.datasets.rating.rating_summary`); ``S_X`` a number or per gear.

    Returns
    -------
    tuple of (bool, str)
        Met (False for a factor not finite, or none with its minimum), and the line.
    """
    parts, ok = [], True
    for key, value in result.items():
        need = result.get(f"{key}min")
        if not re.fullmatch(r"S_[A-Za-z]\w*", key) or key.endswith("min") or need is None:
            continue
        values = [float(v) for v in (value if isinstance(value, list) else [value]) if v is not None]
        least = min(values) if values and all(map(math.isfinite, values)) else math.nan  # unrated: not met
        meets = math.isfinite(least) and least >= float(need)
        ok &= meets
        parts.append(f"{key} {least:.3g} {'>=' if meets else '<'} {key}min {float(need):g}")
    if not parts:
        return False, "no safety factor with its minimum in the result"
    return ok, f"{'PASS' if ok else 'FAIL'}: {', '.join(parts)} (the weaker gear of each)"


def rating_text(result: Mapping[str, Any]) -> list[str]:
    """The text output of ``gearmesh rating``: the verdict line first, then the result by group
    (:data:`RATING_GROUPS`), each key with its value (per-gear values named by gear), the notes
    last, one a line.

    Parameters
    ----------
    result : mapping
        A rating (:func:`gearmesh.datasets.rating.rating_summary`).
    """
    lines = _flat(_finite({k: v for k, v in result.items() if k != "notes"}))
    gears = result.get("gears") if isinstance(result.get("gears"), list) else []
    groups: dict[str, dict[str, Any]] = {title: {} for title, _ in RATING_GROUPS} | {"other": {}}
    for key, value in lines.items():
        groups[next((t for t, pattern in RATING_GROUPS if re.fullmatch(pattern, key)), "other")][key] = value
    out = [safety_verdict(result)[1]]
    for title, rows in groups.items():
        if not rows:
            continue
        # a group of one nested result ("ltca.K_Hbeta", ...) under its heading without the prefix
        head = os.path.commonprefix(list(rows)).rpartition(".")[0]
        shown = {key[len(head) + 1:] if head else key: value for key, value in rows.items()}
        width = max(len(k) for k in shown)
        out += ["", f"{title} ({head})" if head else title,
                *(f"  {key:<{width}}  {_value_text(value, gears)}" for key, value in shown.items())]
    if result.get("notes"):
        out += ["", "notes", *(f"  - {note}" for note in result["notes"])]
    return out


def _flat(result: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """Nested mappings, and lists of them, as dotted keys (``material.poisson_ratio``,
    ``by_torque[0].torque_Nm``), for the text output."""
    out: dict[str, Any] = {}
    for key, value in result.items():
        if isinstance(value, Mapping):
            out.update(_flat(value, f"{prefix}{key}."))
        elif isinstance(value, list) and value and all(isinstance(v, Mapping) for v in value):
            for i, v in enumerate(value):
                out.update(_flat(v, f"{prefix}{key}[{i}]."))
        else:
            out[f"{prefix}{key}"] = value
    return out


def _pair(args: argparse.Namespace, path: str | None = None):
    """The pair file of the command (``path``, else ``args.pair``; its ``name``, or its file
    stem without one) and its geometry, a ``--torque-Nm`` checked against the load limits of
    :func:`gearmesh.loads.check_load`. Kept on ``args`` for the notes :func:`main` prints."""
    pair = _with_deviations(load_pair(path or args.pair), args)
    geom = pair_geometry(pair)
    torque = getattr(args, "torque_Nm", None)
    if torque is not None and torque > 0:
        check_load(geom, pinion_torque(pair, torque, args.on), "--torque-Nm", torque)
    args.loaded_pair = pair
    return pair, geom


#: The deviation options of the commands that load the contact: each overrides its pair-file key.
DEVIATION_OPTIONS = (("--lead-slope-deviation-um", 2, "helix slope deviations f_Hbeta [pinion, gear] (um), positive "
                      "where the flank stands proud at the leading face end"),
                     ("--profile-slope-deviation-um", 2, "profile slope deviations f_Halpha [pinion, gear] (um), "
                      "positive where the flank stands proud at the tip"),
                     ("--mesh-misalignment-um", None, "mesh misalignment f_ma in the plane of action (um)"))


def _with_deviations(pair, args: argparse.Namespace):
    """``pair`` with the deviations the command line gives in place of its pair file's."""
    given = {flag[2:].replace("-", "_"): getattr(args, flag[2:].replace("-", "_"), None)
             for flag, _, _ in DEVIATION_OPTIONS}
    given = {k: v for k, v in given.items() if v is not None}
    if not given:
        return pair
    return pair.with_changes(deviations=read_deviations({**pair.deviations.to_dict(), **given}))


def cmd_validate(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh validate``: a pair file, or a study config (a key only a study has).
    Refused naming the file's key (exit 2; ``--json`` prints ``valid: false`` too).

    Parameters
    ----------
    args : argparse.Namespace
        ``file`` (path), ``json``.

    Returns
    -------
    dict
        ``file``, ``kind``, ``valid``; a study's ``pairs``; a pair's ``name``, ``needs`` if any.
    """
    data = read_yaml(args.file, "file")
    if not data:
        raise GearmeshInputError("file", args.file, "is empty: neither a gear pair file (teeth, normal_module_mm, ...) "
                                 "nor a study config (study, pairs, ...); 'gearmesh example NAME' prints a pair file, "
                                 "'gearmesh schema study --format markdown' lists a study's keys")
    if _is_study(data):
        pairs = check_study(validate_study(data))
        return {"file": args.file, "kind": "study config", "valid": True, "pairs": list(pairs)}
    pair = _pair(args, args.file)[0]
    out = {"file": args.file, "kind": "gear pair", "valid": True, "name": pair.name}
    needs = missing_needs(pair)  # what some commands need beyond a valid pair, and which key to add
    return {**out, "needs": needs} if needs else out


def _is_study(data: Any) -> bool:
    """Whether a document is meant as a study config: a mapping with a key of a study config that no
    pair file has (or ``__use_yte__``, which only Snakemake reads), so its errors are a study's."""
    from .pair_keys import pair_schema
    from .registry import study_schema

    if not isinstance(data, Mapping):
        return False
    study_only = set(study_schema()["properties"]) - set(pair_schema()["properties"])
    return "__use_yte__" in data or bool(study_only & set(map(str, data)))


def cmd_geometry(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh geometry``: the pair's geometry and contact-line lengths.
    Refused naming the pair file's key (exit 2).

    Parameters
    ----------
    args : argparse.Namespace
        ``pair`` (path), ``json``.

    Returns
    -------
    dict
        Contact ratios, angles, radii, backlash, masses, inertias (units in the keys); contact-line
        lengths (mm), numeric and ``_closed_form``, and ``contact_length_fluctuation``.
    """
    geom = _pair(args)[1]
    result = geom.scalars()
    summary = contact_length_summary(geom)
    result.update({
        "mean_contact_length_mm": summary.numeric_mean * 1e3,
        "min_contact_length_mm": summary.numeric_min * 1e3,
        "max_contact_length_mm": summary.numeric_max * 1e3,
        "mean_contact_length_closed_form_mm": summary.mean * 1e3,
        "min_contact_length_closed_form_mm": summary.min * 1e3,
        "max_contact_length_closed_form_mm": summary.max * 1e3,
        "contact_length_fluctuation": summary.numeric_eps_l,
    })
    return result


def cmd_stiffness(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh stiffness``: the time-varying mesh stiffness, as a study's stiffness stage.
    Refused (exit 2) naming ``--slices`` (grid over its limit), ``--torque-Nm`` or the pair's key.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, ``method``, ``slices``, ``positions``; ``torque_Nm`` (N·m, optional: LSTE), ``on``.

    Returns
    -------
    dict
        :func:`gearmesh.datasets.stiffness.stiffness_summary`, and the torque if given.
    """
    from .datasets.stiffness import stiffness_summary

    check_grid("--slices", args.slices, args.slices * args.positions, MAX_STIFFNESS_POINTS, "slice-positions")
    pair = _pair(args)[0]
    result = stiffness_summary(pair, **_stiffness_section(args))
    return result if args.torque_Nm is None else {**result, **_torque(pair, args.torque_Nm, args.on)}


def _stiffness_section(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh stiffness``'s options as a study's ``stiffness:`` section, run as a study's
    (:func:`gearmesh.datasets.stiffness.stiffness_summary`). Every other key is the declared default
    (:class:`gearmesh.settings.Stiffness`: the Fourier order); the command differs from a study in
    nothing but what it prints. No ``--torque-Nm``: the key left out, as a study leaves it (no LSTE)."""
    section = {"method": args.method, "slices": args.slices, "positions": args.positions, "torque_on": args.on}
    return section if args.torque_Nm is None else {**section, "torque_Nm": args.torque_Nm}


def cmd_impact(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh impact``: the mesh-in impact at one torque and speed.
    Refused (exit 2) naming ``--torque-Nm`` (over the load limits), a setting or the pair's key.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, deviations (µm), ``torque_Nm`` (N·m), ``on``, ``speed_rpm`` (pinion, rpm),
        ``driver``, ``points``, ``energy_velocity``, ``simulate``.

    Returns
    -------
    dict
        :func:`gearmesh.datasets.impact.impact_summary` (units in the keys).
    """
    from .datasets.impact import impact_summary

    return impact_summary(_pair(args)[0], args.torque_Nm, args.speed_rpm, simulate=args.simulate,
                          **_impact_section(args))


def _impact_section(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh impact``'s options as a study's ``impact:`` section, run as a study's
    (:func:`gearmesh.datasets.impact.impact_summary`). Every other key is the declared default
    (:class:`gearmesh.settings.Impact`: contact law, tooth model, corner extension, added inertia,
    search window), but for the command's deliberate differences, made here and nowhere else:

    * one torque (``--torque-Nm``) and one speed (``--speed-rpm``) in place of the map's
      ``torques_Nm``, ``speeds_rpm`` and ``design_speed_rpm``;
    * no load window and no manufactured gears; the engagement integrated in time only with
      ``--simulate`` (at that torque and speed)."""
    return {"on": args.on, "driver": args.driver, "points": args.points, "energy_velocity": args.energy_velocity}


def cmd_ltca(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh ltca``: the loaded tooth contact at one torque.
    Refused (exit 2) naming ``--points`` (grid over its limit), ``--torque-Nm``, a setting or the pair's key.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, deviations (µm), ``torque_Nm`` (N·m), ``on``, ``positions``, ``points``,
        ``contact_law``, ``method``.

    Returns
    -------
    dict
        :func:`gearmesh.datasets.ltca.ltca_summary` (units in the keys).
    """
    from .datasets.ltca import ltca_summary

    check_grid("--points", args.points, (args.positions + 1) * args.points, MAX_CONTACT_POINTS,
               "contact candidates per line")
    return ltca_summary(_pair(args)[0], args.torque_Nm, **_ltca_section(args))


def _ltca_section(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh ltca``'s options as a study's ``ltca:`` section, run as a study's
    (:func:`gearmesh.datasets.ltca.ltca_summary`). Every other key is the declared default
    (:class:`gearmesh.settings.Ltca`: the corner extension), but for the command's deliberate
    difference, made here and nowhere else: one torque (``--torque-Nm``) in place of
    ``torques_Nm``."""
    return {"on": args.on, "positions": args.positions, "points": args.points, "contact_law": args.contact_law,
            "method": args.method}


def cmd_rating(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh rating``: ISO 6336-2/-3 method B and scuffing with the LTCA's stresses.
    Refused (exit 2) naming ``--factor`` (given twice), ``--torque-Nm``, a rating input or the pair's key.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, deviations (µm), ``torque_Nm`` (N·m), ``on``, ``speed_rpm`` (rpm, gear ``on``),
        ``application_factor``, ``life_hours`` (h), ``factor``, ``method``, ``positions``, ``points``.

    Returns
    -------
    dict
        :func:`gearmesh.datasets.rating.rating_summary`, printed by :func:`rating_text`.
    """
    from .datasets.rating import rating_summary

    factors = {}
    for name, value in args.factor or []:
        if name in factors:
            raise GearmeshInputError("--factor", name, "must be given once")
        factors[name] = value
    rating, contact = _rating_sections(args)
    return rating_summary(_pair(args)[0], args.torque_Nm, factors=factors, ltca_section=contact, **rating)


def _rating_sections(args: argparse.Namespace) -> tuple[dict[str, Any], dict[str, Any]]:
    """``gearmesh rating``'s options as a study's ``rating:`` and ``ltca:`` sections, run as a
    study's (:func:`gearmesh.datasets.rating.rating_summary`). Every other key is the declared
    default (:class:`gearmesh.settings.Rating`, :class:`gearmesh.settings.Ltca`: the LTCA's
    contact law, tooth model and corner extension), but for the command's deliberate differences,
    made here and nowhere else:

    * one torque (``--torque-Nm``) in place of the LTCA's ``torques_Nm``;
    * ``--speed-rpm`` the speed of the gear the torque acts on (``--on``), the study's the pinion's;
    * factors given instead of computed (``--factor``), which a study does not take."""
    rating = {"speed_rpm": args.speed_rpm, "application_factor": args.application_factor,
              "life_hours": args.life_hours, "method": args.method}
    return rating, {"on": args.on, "positions": args.positions, "points": args.points}


def cmd_dynamics(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh dynamics``: the 8-DOF model's steady state over a speed sweep.
    Refused (exit 2) naming ``torque_Nm``, ``speeds_rpm`` (``--speeds``), a setting or the pair's key.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, deviations (µm), ``torque_Nm`` (N·m), ``on``, ``speeds`` (START:STOP:STEP rpm),
        ``backlash_um`` (µm or 'pair'), ``excitation``.

    Returns
    -------
    dict
        The load, model choices, backlash, supports, damping and ``speeds``, a row per speed
        (:func:`gearmesh.datasets.dynamics.pair.pair_summary`).
    """
    from .datasets.dynamics.checks import check_dynamics_settings
    from .datasets.dynamics.excitation import model_choices
    from .datasets.dynamics.inputs import positive_quantity, supports_note
    from .datasets.dynamics.pair import pair_summary
    from .dynamics import DAMPING_MEANING
    from .schema import settings_object
    from .settings import Dynamics

    positive_quantity("torque_Nm", args.torque_Nm)
    pair, geom = _pair(args)
    s = settings_object(Dynamics, _dynamics_section(args))
    check_dynamics_settings(pair, s)
    ltca = None
    if s.excitation == "ltca":  # the loaded TE and stiffness of this pair at this torque excite the model
        from .datasets.ltca import ltca_dataset

        torque_1 = pinion_torque(pair, args.torque_Nm, s.on)
        ltca = ltca_dataset(pair, torques_Nm=[torque_1], on="pinion")  # the LTCA stage's defaults
    rows = pair_summary(pair, s, ltca=ltca, progress=_progress())
    return {"name": pair.name, **_torque(pair, args.torque_Nm, s.on), "excitation": s.excitation,
            **model_choices(s.excitation, s.method, s.contact_law, ltca=ltca),
            **_backlash(geom, s.backlash_um),
            "supports": supports_note(pair, s.bearing_k_radial_N_per_m, s.bearing_k_axial_N_per_m),
            "damping_ratio": s.damping_ratio, "damping_ratio_meaning": DAMPING_MEANING, "speeds": rows}


def _dynamics_section(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh dynamics``'s options as a study's ``dynamics:`` section, run as a study's
    (:func:`gearmesh.datasets.dynamics.pair.pair_summary`). Every other key is the declared
    default (:class:`gearmesh.settings.Dynamics`), but for the command's deliberate differences,
    made here and nowhere else:

    * one torque (``--torque-Nm``) and the speeds ``--speeds`` (START:STOP:STEP or one speed);
    * no kept time series (``sample_speeds_rpm`` empty): the command prints per-speed statistics
      of the speeds as given (:func:`~gearmesh.datasets.dynamics.pair.pair_summary` adds none
      around the resonances);
    * ``--excitation`` tvms by default, what the study's null means without an LTCA upstream;
      ``ltca`` runs the LTCA stage's defaults at this torque."""
    from .datasets.dynamics.inputs import parse_speeds

    return {"torques_Nm": args.torque_Nm, "on": args.on, "speeds_rpm": parse_speeds(args.speeds),
            "backlash_um": args.backlash_um, "sample_speeds_rpm": [], "excitation": args.excitation}


def _torque(pair, torque_Nm: float, on: str) -> dict[str, Any]:
    """What a result says of its load: the torque as given, the gear it acts on and the pinion
    torque it is (every command applies ``--torque-Nm`` to the pinion unless ``--on gear``)."""
    return {"torque_Nm": torque_Nm, "torque_on": on, "pinion_torque_Nm": float(pinion_torque(pair, torque_Nm, on))}


def _backlash(geom, option) -> dict[str, Any]:
    """The backlash a dynamics used (normal, µm) and where it came from: ``--backlash-um pair``
    (the default) is the pair's own, from its centre distance and shifts."""
    if option == "pair":
        return {"backlash_um": geom.backlash_normal * 1e6, "backlash_source": "pair"}
    return {"backlash_um": option, "backlash_source": "given"}


def cmd_schema(args: argparse.Namespace) -> None:
    """Print the JSON schema of a study config or a pair file, or their keys as Markdown tables
    (:mod:`gearmesh.settings`: the files published under ``schemas/`` and ``config/README.md``).

    Parameters
    ----------
    args : argparse.Namespace
        ``kind`` (study or pair), ``format`` (yaml, json, markdown; None: yaml study, json pair).
    """
    from .pair_keys import pair_schema
    from .published import pair_reference, pair_schema_text, study_reference, study_schema_text
    from .registry import study_schema

    form = args.format or ("yaml" if args.kind == "study" else "json")
    if form == "markdown":
        text = study_reference() if args.kind == "study" else pair_reference()
    elif form == "json":
        text = pair_schema_text() if args.kind == "pair" else json.dumps(study_schema(), indent=2, ensure_ascii=False) + "\n"
    else:
        text = study_schema_text() if args.kind == "study" else yaml_text(pair_schema())
    sys.stdout.write(text)


def yaml_text(data: Any) -> str:
    """``data`` as YAML in its own key order.

    Parameters
    ----------
    data : Any
        A JSON-like document.
    """
    import yaml

    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=110, default_flow_style=None)


def _progress():
    """A progress printer on stderr for long commands when stderr is a terminal, else None."""
    if not sys.stderr.isatty():
        return None

    def report(done: float) -> None:
        print(f"\r  {100 * done:5.1f} %", end="\n" if done >= 1 else "", file=sys.stderr, flush=True)

    return report


def _numbers(option: str, text: str | None) -> list[float] | None:
    """A comma-separated list of numbers (``--torques-Nm 400,1000,1600``), or None."""
    if text is None:
        return None
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise GearmeshInputError(option, text, "must be comma-separated numbers, e.g. 400,1000,1600") from None
    for v in values:
        if not math.isfinite(v):
            raise GearmeshInputError(option, text, "must be finite numbers")
    return values


def cmd_optimise(args: argparse.Namespace) -> dict[str, Any]:
    """``gearmesh optimise``: the micro-geometry optimisation, as a study's (:func:`_optimise_section`).
    Refused (exit 2, before the search) naming ``--torque-Nm``, ``--torques-Nm``, ``--weights``,
    ``--write-pair`` or a setting.

    Parameters
    ----------
    args : argparse.Namespace
        ``pair``, deviations (µm), ``torque_Nm``, ``torques_Nm``, ``weights`` (N·m, comma lists), ``on``,
        ``speed_rpm``, tolerance and GA options, declared settings and constraints, ``write_pair``.

    Returns
    -------
    dict
        :func:`gearmesh.datasets.optimise.optimise_summary`; ``pair_file`` once written.
    """
    from .datasets.optimise import optimise_summary, optimum_pair
    from .optimise.search import LOG
    from .pipeline import write_pair

    torques = _numbers("--torques-Nm", args.torques_Nm)
    weights = _numbers("--weights", args.weights)
    section, tolerances = _optimise_section(args, torques, weights)
    design = section["torque_Nm"]
    out = _output_pair_path(args.write_pair)
    pair, geom = _pair(args)
    if torques is not None:
        from .ltca import check_torques

        for t in check_torques(torques, "torques_Nm"):
            check_load(geom, pinion_torque(pair, t, args.on), "--torques-Nm", t)
    if sys.stderr.isatty():  # one line per generation on the terminal
        handler = logging.StreamHandler(sys.stderr)
        handler.setFormatter(logging.Formatter("  %(message)s"))
        LOG.addHandler(handler)
        LOG.setLevel(logging.INFO)
    summary, ds = optimise_summary(pair, **section, tolerances=tolerances)
    summary["pinion_torque_Nm"] = float(pinion_torque(pair, design, args.on))
    if args.objective == "dynamic" or args.dynamic_factor is not None:  # the candidates' dynamics
        summary.update(_backlash(geom, args.backlash_um))
    if out is not None:
        write_pair(optimum_pair(pair, ds, name=out.stem), out)
        summary["pair_file"] = str(out)
        summary["notes"] = [*summary.get("notes", []), f"{out} states the optimum to the drawing's resolution "
                            f"(depths 0.01 µm, lengths 0.001 mm); genes above are the optimiser's own values"]
    return summary


def _optimise_section(args: argparse.Namespace, torques, weights) -> tuple[dict[str, Any], dict[str, Any]]:
    """``gearmesh optimise``'s options as a study's ``optimise.NAME`` and ``tolerances:`` sections,
    run as a study's (:func:`gearmesh.datasets.optimise.run_settings`). Every key is its declared
    option's value (the declared default unless given), but for the command's deliberate
    differences, made here and nowhere else:

    * the design torque: ``--torque-Nm``, or the middle torque of ``--torques-Nm`` (the lower of
      two middles);
    * ``--weights`` make the spectrum statistic the duty-cycle mean;
    * without tolerance samples (``--tolerance-samples 0``) the objective is the nominal alone
      (``tolerance_statistic`` null), where a study refuses a statistic over no samples;
    * the manufactured population is the command's options (``--grade``, class
      :data:`gearmesh.cli.CLI_LEAD_GRADE` unless given; ± on the amounts and lengths; samples,
      sampling), where a study has its ``tolerances:`` section."""
    if args.torque_Nm is None and torques is None:
        raise GearmeshInputError("--torque-Nm", None, "is required, or --torques-Nm (a load spectrum, its middle "
                                                      "torque the design torque)")
    # the design torque: given, or the middle torque of the spectrum (the lower of two middles)
    design = args.torque_Nm if args.torque_Nm is not None else sorted(torques)[(len(torques) - 1) // 2]
    tolerances = {"grade": args.grade, "samples": args.samples, "sampling": args.sampling}
    modification = {}
    if args.amount_tolerance_um:
        modification |= {k: args.amount_tolerance_um for k in ("root_relief_um", "tip_relief_um", "crowning_um")}
    if args.length_tolerance_mm:
        modification |= {k: args.length_tolerance_mm for k in ("root_relief_length_mm", "tip_relief_length_mm")}
    if modification:
        tolerances["modification"] = modification
    section = {"objective": args.objective, "torque_Nm": design, "torques_Nm": torques, "weights": weights,
               "statistic": "mean" if weights else args.statistic, "on": args.on, "speed_rpm": args.speed_rpm,
               "modify": args.modify, "method": args.method, "seed": args.seed, "population": args.population,
               "generations": args.generations,
               "tolerance_statistic": args.tolerance_statistic if args.samples else None,
               "tolerance_level_percent": args.tolerance_level_percent,
               "dynamic_speeds_rpm": _numbers("--dynamic-speeds-rpm", args.dynamic_speeds_rpm),
               "backlash_um": args.backlash_um, "constraints": {key: getattr(args, key) for key in args.constraint_keys},
               **{key: getattr(args, key) for key in args.optimise_keys}}
    return section, tolerances


def _output_pair_path(path: str | None):
    """The ``--write-pair`` target: a .yaml file in an existing folder whose stem is a valid pair
    name (the name the written pair carries)."""

    if path is None:
        return None
    out = Path(path)
    if out.suffix not in (".yaml", ".yml"):
        raise GearmeshInputError("--write-pair", path, "must be a .yaml file")
    if not out.parent.is_dir():
        raise GearmeshInputError("--write-pair", path, "must be in an existing folder")
    if out.exists() and not out.is_file():
        raise GearmeshInputError("--write-pair", path, "is not a regular file")
    if not NAME_PATTERN.fullmatch(out.stem):  # the pair files' own rule: the written pair reads back
        raise GearmeshInputError("--write-pair", path, "must have a pair name as its stem (1 to 160 letters, digits, "
                                                       "'_', '-' or '.' (not first))")
    return out


def cmd_example(args: argparse.Namespace) -> dict[str, Any] | None:
    """The example pairs shipped with the package: their names and sources, or one of them
    printed as it is (a pair file every command reads).
    An unknown name is refused as ``example`` (exit 2).

    Parameters
    ----------
    args : argparse.Namespace
        ``name`` (None: the list), ``json``.

    Returns
    -------
    dict or None
        {name: source}, or None once the pair file is printed.
    """
    if args.name is None:
        return {name: _source(path) for name, path in example_pairs().items()}
    sys.stdout.write(example_pair(args.name).read_text(encoding="utf-8"))
    return None


def cmd_manufactured(args: argparse.Namespace) -> None:
    """One manufactured gear of a variant's impact.nc printed as a pair file
    (:func:`gearmesh.robust.manufactured_pair`).
    Refused (exit 2) naming ``impact``, ``--worst`` or ``--torque-Nm``.

    Parameters
    ----------
    args : argparse.Namespace
        ``impact`` (path); ``heldout``, ``population`` or ``worst`` (with ``torque_Nm``, pinion N·m).
    """
    import yaml

    from .datasets.impact import manufactured_gear

    pair = manufactured_gear(args.impact, heldout=args.heldout, population=args.population, worst=args.worst,
                             torque_Nm=args.torque_Nm)
    sys.stdout.write(yaml.safe_dump(pair_to_dict(pair), sort_keys=False, allow_unicode=True))


def _source(path: Path) -> str:
    """The ``source`` of an example pair file (what it is taken from)."""
    data = read_yaml(path, "example")
    return str(data.get("source", "")) if isinstance(data, Mapping) else ""


class _Problems(GearmeshInputError):
    """Several files refused by ``gearmesh check``: one line each."""

    def __init__(self, lines: list[str]):
        ValueError.__init__(self, "\ngearmesh: error: ".join(lines))


def cmd_check(args) -> dict[str, Any] | None:
    """``gearmesh check RESULTS [--configfile C] [--json]``: every problem of a study's results
    folder (:func:`gearmesh.upstream.check_tree`), one line each; nothing printed when all is well
    (``--json``: one object, ``ok`` and ``problems``). The files record their paths relative to
    the folder the run ran in, the one above ``results/``: the check runs there, whatever folder
    it is called from and however RESULTS is written (relative or absolute).
    Refused (exit 2) naming ``results``, or with every problem, one line each.

    Parameters
    ----------
    args : argparse.Namespace
        ``results``, ``configfile`` (optional), ``json``.
    """
    from .pipeline import study_pair
    from .upstream import check_tree

    workdir, results = _run_folder(args.results)
    config = None if args.configfile is None else load_study(args.configfile)  # read where it was named
    with _working_directory(workdir):
        problems = check_tree(results, config, None if config is None else lambda name, v: study_pair(config, name, v))
    if args.json:
        print(json.dumps({"results": results.as_posix(), "run_folder": str(workdir), "ok": not problems,
                          "problems": problems}))
    if problems:
        raise _Problems(problems)
    return None


def _run_folder(results: str) -> tuple[Path, Path]:
    """The folder a study ran in and its results folder relative to it (``results/STUDY``), from
    the results folder as given (relative to here, or absolute)."""
    path = Path(results)
    if not path.is_dir():
        raise GearmeshInputError("results", results, "must be a study's results folder (results/STUDY)")
    path = path.resolve()
    if path.parent.name != "results":
        raise GearmeshInputError("results", results, "must be a study's results folder results/STUDY as a run wrote "
                                 "it (its files name their paths from the folder above results/)")
    return path.parent.parent, Path("results", path.name)


@contextmanager
def _working_directory(path: Path) -> Iterator[None]:
    """Run the block in ``path`` as the working directory, then return."""
    here = os.getcwd()
    os.chdir(path)
    try:
        yield
    finally:
        os.chdir(here)


def cmd_run(args) -> None:
    """``gearmesh run SNAKEMAKE-ARGS``: every config Snakemake would read before the Snakefile runs
    (the command line's config files, every profile and the config files it names,
    ``$SNAKEMAKE_PROFILE`` and the workflow's default profile included) read with the package's
    bounded loader and validated (:mod:`gearmesh.launch`), then Snakemake run in this process with
    the same arguments (:func:`gearmesh.launch.run_snakemake`; the check already imported its
    modules): its own loader (and template engine) never sees a file that failed.
    Refused (exit 2) naming a config's or profile's key, or ``snakemake`` not installed.

    Parameters
    ----------
    args : argparse.Namespace
        ``snakemake_args``: for Snakemake, unchanged.
    """
    from importlib.util import find_spec

    if find_spec("snakemake") is None:
        raise GearmeshInputError("snakemake", None, "is not installed: pip install 'gearmesh[workflow]'")
    from .launch import check_inputs, run_snakemake, snakemake_inputs

    inputs = snakemake_inputs(args.snakemake_args)
    check_inputs(inputs)
    sys.stdout.flush()
    run_snakemake(args.snakemake_args, inputs.local_jobs)
