"""The ``gearmesh`` command line: validate inputs and print a stage's headline numbers.

Bad input exits with code 2 and one line ``gearmesh: error: FIELD = VALUE: RULE`` on
stderr; nothing is written.
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

from . import __version__
from .choices import DEFAULT_CONTACT_LAW, DEFAULT_TOOTH_METHOD
from .config import check_study, load_study, validate_study
from .contact import contact_length_summary
from .deviation import read_deviations
from .errors import GearmeshInputError
from .gear import (NAME_PATTERN, example_pair, example_pairs, load_pair, missing_needs, pair_geometry, pair_notes,
                   pair_to_dict,
                   pinion_torque, read_yaml)
from .limits import MAX_CONTACT_POINTS, MAX_STIFFNESS_POINTS, check_grid
from .loads import check_load
from .schema import check_value, defaults, field_schema, key_of, settings_fields
from .settings import Constraints, Dynamics, Impact, Ltca, Optimise, Rating, Stiffness, Tolerances

EXIT_BAD_INPUT = 2


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


def _emit(result: Mapping[str, Any], as_json: bool, text=None) -> None:
    """Print a result: one JSON object, or its text (``text(result)``: the command's own lines),
    or one ``key  value`` line per number (nested keys dotted) and, for a speed sweep, a table
    with one row per speed."""
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
    "PASS: S_H 1.98 >= S_Hmin 1, S_F 4.83 >= S_Fmin 1 (the weaker gear of each)"."""
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


def _rating_text(result: Mapping[str, Any]) -> list[str]:
    """The text output of ``gearmesh rating``: the verdict line first, then the result by group
    (:data:`RATING_GROUPS`), each key with its value (per-gear values named by gear), the notes
    last, one a line."""
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
_DEVIATION_OPTIONS = (("--lead-slope-deviation-um", 2, "helix slope deviations f_Hbeta [pinion, gear] (um), positive "
                       "where the flank stands proud at the leading face end"),
                      ("--profile-slope-deviation-um", 2, "profile slope deviations f_Halpha [pinion, gear] (um), "
                       "positive where the flank stands proud at the tip"),
                      ("--mesh-misalignment-um", None, "mesh misalignment f_ma in the plane of action (um)"))


def _deviation_options(p) -> None:
    """The manufacturing deviations as options; each replaces the pair file's key (:mod:`gearmesh.deviation`)."""
    for flag, nargs, text in _DEVIATION_OPTIONS:
        p.add_argument(flag, type=float, nargs=nargs, metavar="UM", default=None,
                       help=f"{text}; replaces the pair file's {flag[2:].replace('-', '_')}")


def _with_deviations(pair, args: argparse.Namespace):
    """``pair`` with the deviations the command line gives in place of its pair file's."""
    given = {flag[2:].replace("-", "_"): getattr(args, flag[2:].replace("-", "_"), None)
             for flag, _, _ in _DEVIATION_OPTIONS}
    given = {k: v for k, v in given.items() if v is not None}
    if not given:
        return pair
    return pair.with_changes(deviations=read_deviations({**pair.deviations.to_dict(), **given}))


def cmd_validate(args: argparse.Namespace) -> dict[str, Any]:
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
    from .settings import study_schema

    if not isinstance(data, Mapping):
        return False
    study_only = set(study_schema()["properties"]) - set(pair_schema()["properties"])
    return "__use_yte__" in data or bool(study_only & set(map(str, data)))


def cmd_geometry(args: argparse.Namespace) -> dict[str, Any]:
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
    from .datasets.stiffness import stiffness_summary

    check_grid("--slices", args.slices, args.slices * args.positions, MAX_STIFFNESS_POINTS, "slice-positions")
    pair = _pair(args)[0]
    result = stiffness_summary(pair, method=args.method, slices=args.slices, positions=args.positions,
                               torque_Nm=args.torque_Nm, torque_on=args.on)
    return result if args.torque_Nm is None else {**result, **_torque(pair, args.torque_Nm, args.on)}


def cmd_impact(args: argparse.Namespace) -> dict[str, Any]:
    from .datasets.impact import impact_summary

    return impact_summary(_pair(args)[0], args.torque_Nm, args.speed_rpm, on=args.on, driver=args.driver,
                          points=args.points, simulate=args.simulate, energy_velocity=args.energy_velocity)


def cmd_ltca(args: argparse.Namespace) -> dict[str, Any]:
    from .datasets.ltca import ltca_summary

    check_grid("--points", args.points, (args.positions + 1) * args.points, MAX_CONTACT_POINTS,
               "contact candidates per line")
    return ltca_summary(_pair(args)[0], args.torque_Nm, on=args.on, positions=args.positions,
                        points=args.points, contact_law=args.contact_law, method=args.method)


def _factor_option(text: str) -> tuple[str, float]:
    """``NAME=VALUE`` of ``--factor`` as (name, value); the names and bounds are the rating's."""
    name, sep, value = text.partition("=")
    if not sep:
        raise ValueError(text)
    return name.strip(), float(value)


_factor_option.__name__ = "NAME=VALUE (e.g. K_v=1.1)"  # argparse names the type in its refusal


def cmd_rating(args: argparse.Namespace) -> dict[str, Any]:
    from .datasets.rating import rating_summary

    factors = {}
    for name, value in args.factor or []:
        if name in factors:
            raise GearmeshInputError("--factor", name, "must be given once")
        factors[name] = value
    return rating_summary(_pair(args)[0], args.torque_Nm, args.speed_rpm, on=args.on,
                          application_factor=args.application_factor, life_hours=args.life_hours, factors=factors,
                          method=args.method, positions=args.positions, points=args.points)


def cmd_dynamics(args: argparse.Namespace) -> dict[str, Any]:
    from .datasets.dynamics import (check_dynamics_settings, dynamics_summary, model_choices, parse_speeds,
                                    positive_torque, supports_note)

    positive_torque("torque_Nm", args.torque_Nm)
    pair, geom = _pair(args)
    speeds = parse_speeds(args.speeds)
    check_dynamics_settings(pair, {"torques_Nm": args.torque_Nm, "on": args.on, "speeds_rpm": speeds,
                                   "backlash_um": args.backlash_um, "sample_speeds_rpm": [],
                                   "excitation": args.excitation})
    excitation = {"excitation": args.excitation}
    if args.excitation == "ltca":  # the loaded TE and stiffness of this pair at this torque excite the model
        from .datasets.ltca import ltca_dataset

        torque_1 = pinion_torque(pair, args.torque_Nm, args.on)
        excitation["ltca"] = ltca_dataset(pair, torques_Nm=[torque_1], on="pinion")  # the LTCA stage's defaults
    rows = dynamics_summary(pair, torque_Nm=args.torque_Nm, speeds=speeds, on=args.on,
                            backlash_um=args.backlash_um, progress=_progress(), **excitation)
    from .dynamics import DAMPING_MEANING, DEFAULT_DAMPING_RATIO
    return {"name": pair.name, **_torque(pair, args.torque_Nm, args.on), "excitation": args.excitation,
            **model_choices(args.excitation, DEFAULT_TOOTH_METHOD, DEFAULT_CONTACT_LAW, ltca=excitation.get("ltca")),
            **_backlash(geom, args.backlash_um), "supports": supports_note(pair),
            "damping_ratio": DEFAULT_DAMPING_RATIO, "damping_ratio_meaning": DAMPING_MEANING, "speeds": rows}


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
    (:mod:`gearmesh.settings`: the files published under ``schemas/`` and ``config/README.md``)."""
    from .pair_keys import pair_schema
    from .published import pair_reference, pair_schema_text, study_reference, study_schema_text
    from .settings import study_schema

    form = args.format or ("yaml" if args.kind == "study" else "json")
    if form == "markdown":
        text = study_reference() if args.kind == "study" else pair_reference()
    elif form == "json":
        text = pair_schema_text() if args.kind == "pair" else json.dumps(study_schema(), indent=2, ensure_ascii=False) + "\n"
    else:
        text = study_schema_text() if args.kind == "study" else yaml_text(pair_schema())
    sys.stdout.write(text)


def yaml_text(data: Any) -> str:
    import yaml

    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=110, default_flow_style=None)


def _backlash_option(text: str):
    """--backlash-um: 'pair' (the pair's own backlash) or a number of µm (its range is the stage's check)."""
    if text == "pair":
        return text
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is neither 'pair' nor a number of µm") from None


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
    from .datasets.optimise import optimise_summary, optimum_pair
    from .optimise import LOG
    from .pipeline import write_pair

    torques = _numbers("--torques-Nm", args.torques_Nm)
    weights = _numbers("--weights", args.weights)
    if args.torque_Nm is None and torques is None:
        raise GearmeshInputError("--torque-Nm", None, "is required, or --torques-Nm (a load spectrum, its middle "
                                                      "torque the design torque)")
    # the design torque: given, or the middle torque of the spectrum (the lower of two middles)
    design = args.torque_Nm if args.torque_Nm is not None else sorted(torques)[(len(torques) - 1) // 2]
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
    samples = args.samples
    tolerances = {"grade": args.grade, "samples": samples, "sampling": args.sampling}
    modification = {}
    if args.amount_tolerance_um:
        modification |= {k: args.amount_tolerance_um for k in ("root_relief_um", "tip_relief_um", "crowning_um")}
    if args.length_tolerance_mm:
        modification |= {k: args.length_tolerance_mm for k in ("root_relief_length_mm", "tip_relief_length_mm")}
    if modification:
        tolerances["modification"] = modification
    statistic = args.tolerance_statistic if samples else None
    summary, ds = optimise_summary(pair, objective=args.objective, torque_Nm=design, torques_Nm=torques,
                                   weights=weights, statistic="mean" if weights else args.statistic, on=args.on,
                                   speed_rpm=args.speed_rpm, modify=args.modify, method=args.method, seed=args.seed,
                                   population=args.population, generations=args.generations,
                                   tolerance_statistic=statistic, tolerance_level_percent=args.tolerance_level_percent,
                                   tolerances=tolerances, dynamic_speeds_rpm=_numbers("--dynamic-speeds-rpm",
                                                                                      args.dynamic_speeds_rpm),
                                   backlash_um=args.backlash_um,
                                   constraints={key: getattr(args, key) for key in args.constraint_keys},
                                   **{key: getattr(args, key) for key in args.optimise_keys})
    summary["pinion_torque_Nm"] = float(pinion_torque(pair, design, args.on))
    if args.objective == "dynamic" or args.dynamic_factor is not None:  # the candidates' dynamics
        summary.update(_backlash(geom, args.backlash_um))
    if out is not None:
        write_pair(optimum_pair(pair, ds, name=out.stem), out)
        summary["pair_file"] = str(out)
        summary["notes"] = [*summary.get("notes", []), f"{out} states the optimum to the drawing's resolution "
                            f"(depths 0.01 µm, lengths 0.001 mm); genes above are the optimiser's own values"]
    return summary


#: The lead tolerance class of ``gearmesh optimise`` when none is given: the robust objective (the
#: default) needs a manufactured population, and a study has its tolerances section where the
#: command has none; class 6 is the default study's (ISO 1328-1:2013, a ground gear's grade).
CLI_LEAD_GRADE = 6


def _grade_option(text: str) -> int | None:
    """``--grade``: an ISO 1328-1 class within the declared bounds of ``tolerances.grade``, or 'none'
    (no lead deviation)."""
    if text.strip().lower() == "none":
        return None
    try:
        grade = int(text)
        check_value(Tolerances, "grade", grade)
        return grade
    except (ValueError, GearmeshInputError):
        raise GearmeshInputError("--grade", text, "must be an ISO 1328-1 class 1-11 or 'none'") from None


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


PAIR_HELP = "gear pair file (YAML, engineering units; 'gearmesh example NAME' prints one)"
#: One description of the tooth model for every command that takes --method.
TOOTH_MODEL_HELP = ("tooth model of the slice compliance: fe (2-D plane-strain finite elements), "
                    "transition (potential-energy cantilever with the hob-generated fillet), improved or traditional "
                    "(potential-energy cantilever root cases)")


class _HelpFormatter(argparse.HelpFormatter):
    """Help with each option's default once: appended where the help text does not already
    name it, left out for required options, flags and options without a default."""

    def _get_help_string(self, action: argparse.Action) -> str:
        text = action.help or ""
        default = action.default
        if (action.required or not action.option_strings or default is None or default is False
                or default == argparse.SUPPRESS or "default" in text):
            return text
        apart = " " if action.nargs in ("+", "*") else ","  # as the option is written: words apart, or a comma list
        shown = apart.join(map(str, default)) if isinstance(default, (list, tuple)) else str(default)
        return f"{text} (default: {shown.replace('%', '%%')})"


def _command(sub, name: str, func, help: str, pair_help: str = PAIR_HELP):
    """A subcommand with its input file and --json."""
    p = sub.add_parser(name, help=help, description=help, formatter_class=_HelpFormatter)
    p.add_argument("pair" if name != "validate" else "file", help=pair_help)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=func)
    return p


def _setting_option(p, flag: str, section: type, help: str, key: str | None = None, dest: str | None = None,
                    **kwargs) -> None:
    """An option that is the setting ``key`` (default: the option's name) of ``section``
    (:mod:`gearmesh.settings`), kept as ``dest`` (default: ``key``): its default and choices are
    the declaration's, and :func:`main` checks its value against the declaration before the
    command runs, naming the option."""
    key = key or flag.lstrip("-").replace("-", "_")
    dest = dest or key
    field = next(f for f in settings_fields(section) if key_of(f) == key)
    schema = field_schema(section, field)
    choices = schema.get("enum") or schema.get("items", {}).get("enum")
    if choices and "choices" not in kwargs:
        kwargs["choices"] = [c for c in choices if c is not None]
    p.add_argument(flag, dest=dest, default=defaults(section).get(key), help=help, **kwargs)
    p.set_defaults(setting_options={**(p.get_default("setting_options") or {}), dest: (section, key, flag)})


def _value_reader(schema: Mapping[str, Any]):
    """How the command line writes a value of a setting whose JSON schema is ``schema``: a number,
    an integer, true/false, a word, or comma-separated items for a list; 'none' for null where
    the setting allows it. Its range is checked against the declaration afterwards."""
    kinds = schema.get("type", "string")
    kinds = {kinds} if isinstance(kinds, str) else set(kinds)
    items = _value_reader(schema.get("items", {})) if "array" in kinds else None

    def read(text: str) -> Any:
        word = text.strip()
        if "null" in kinds and word.lower() in ("none", "null"):
            return None
        if items is not None:
            return [items(v) for v in word.split(",")]
        if "boolean" in kinds:
            if word.lower() not in ("true", "false"):
                raise ValueError(text)
            return word.lower() == "true"
        if "integer" in kinds:
            return int(word)
        return float(word) if "number" in kinds else word

    read.__name__ = ("comma-separated " if items is not None else "") + \
        ("/".join(sorted(k for k in kinds if k not in ("null", "array"))) or "value") + " value"
    return read


def _declared_options(p, section: type, skip: Sequence[str] = ()) -> list[str]:
    """An option for every setting of ``section`` but ``skip`` and those of a mapping type, each
    made from its declaration (:func:`_setting_option`: ``--KEY-WITH-DASHES``, its default,
    choices and bounds, its description as the help): the keys, so a setting added to the
    declaration is an option of the command without a line here."""
    keys = []
    for field in settings_fields(section):
        key = key_of(field)
        schema = field_schema(section, field)
        if key in skip or "object" in str(schema.get("type")) or "oneOf" in schema:
            continue
        words = schema.get("enum") or schema.get("items", {}).get("enum")
        help = schema.get("description", key.replace("_", " "))
        kwargs = {}
        if words and ("array" in str(schema.get("type")) or None in words):  # a list or null: checked as a whole
            help += " (" + ", ".join("none" if w is None else str(w) for w in words) + ")"
            kwargs["choices"] = None
        metavar = "{true,false}" if schema.get("type") == "boolean" else key.upper()
        _setting_option(p, "--" + key.replace("_", "-"), section, key=key, help=help, type=_value_reader(schema),
                        metavar=metavar, **kwargs)
        keys.append(key)
    return keys


def _check_setting_options(args: argparse.Namespace) -> None:
    """The values of the options that are settings, each against its declaration (the bounds a
    study config has), refused naming the option."""
    for dest, (section, key, flag) in (getattr(args, "setting_options", None) or {}).items():
        value = getattr(args, dest)
        if value is None and defaults(section).get(key) is None:
            continue  # not given, and the setting's own "none"
        try:
            check_value(section, key, value)
        except GearmeshInputError as exc:
            raise GearmeshInputError(flag + exc.field[len(key):], exc.value, exc.rule) from None


def _torque_options(p, required: bool, section: type, on: str = "on") -> None:
    """--torque-Nm and --on, the gear it acts on: the setting ``on`` of ``section``."""
    p.add_argument("--torque-Nm", dest="torque_Nm", type=float, required=required,
                   help="torque (N m), on the pinion unless --on gear")
    _setting_option(p, "--on", section, key=on, dest="on", help="the gear the torque acts on")


def cmd_example(args: argparse.Namespace) -> dict[str, Any] | None:
    """The example pairs shipped with the package: their names and sources, or one of them
    printed as it is (a pair file every command reads)."""
    if args.name is None:
        return {name: _source(path) for name, path in example_pairs().items()}
    sys.stdout.write(example_pair(args.name).read_text(encoding="utf-8"))
    return None


def cmd_manufactured(args: argparse.Namespace) -> None:
    """One manufactured gear of a variant's impact.nc printed as a pair file
    (:func:`gearmesh.robust.manufactured_pair`)."""
    import yaml

    from .datasets.impact import manufactured_gear

    pair = manufactured_gear(args.impact, heldout=args.heldout, population=args.population, worst=args.worst,
                             torque_Nm=args.torque_Nm)
    sys.stdout.write(yaml.safe_dump(pair_to_dict(pair), sort_keys=False, allow_unicode=True))


def _source(path: Path) -> str:
    """The ``source`` of an example pair file (what it is taken from)."""
    data = read_yaml(path, "example")
    return str(data.get("source", "")) if isinstance(data, Mapping) else ""


class _Parser(argparse.ArgumentParser):
    """argparse with its refusals as the one line ``gearmesh: error: ARGUMENT = VALUE: RULE``
    (exit 2), not the usage text."""

    def error(self, message: str):
        choice = re.fullmatch(r"argument ([^:]+): invalid choice: '(.*)' \(choose from (.*)\)", message, flags=re.S)
        value = re.fullmatch(r"argument ([^:]+): (.*?): '(.*)'", message, flags=re.S)
        required = re.fullmatch(r"the following arguments are required: (.*)", message, flags=re.S)
        if choice:
            exc = GearmeshInputError(choice[1], choice[2], f"must be one of {choice[3]}")
        elif value:
            exc = GearmeshInputError(value[1], value[3], value[2])
        elif required:
            exc = GearmeshInputError(required[1], None, "is required")
        else:
            exc = GearmeshInputError("arguments", None, message)
        self.exit(EXIT_BAD_INPUT, f"gearmesh: error: {exc}\n")


class _Problems(GearmeshInputError):
    """Several files refused by ``gearmesh check``: one line each."""

    def __init__(self, lines: list[str]):
        ValueError.__init__(self, "\ngearmesh: error: ".join(lines))


def cmd_check(args) -> dict[str, Any] | None:
    """``gearmesh check RESULTS [--configfile C] [--json]``: every problem of a study's results
    folder (:func:`gearmesh.upstream.check_tree`), one line each; nothing printed when all is well
    (``--json``: one object, ``ok`` and ``problems``). The files record their paths relative to
    the folder the run ran in, the one above ``results/``: the check runs there, whatever folder
    it is called from and however RESULTS is written (relative or absolute)."""
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
    bounded loader and validated (:mod:`gearmesh.launch`), then Snakemake started with the same
    arguments: its own loader (and template engine) never sees a file that failed."""
    import shutil

    from .launch import check_inputs, snakemake_inputs

    check_inputs(snakemake_inputs(args.snakemake_args))
    exe = shutil.which("snakemake", path=str(Path(sys.executable).parent)) or shutil.which("snakemake")
    if exe is None:
        raise GearmeshInputError("snakemake", None, "is not installed: pip install 'gearmesh[workflow]'")
    sys.stdout.flush()
    os.execv(exe, [exe, *args.snakemake_args])


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="gearmesh", description="Helical gear pairs from their design data: geometry, contact, "
                     "mesh stiffness, loaded contact, mesh-in impact, micro-geometry optimisation and dynamics; "
                     "each command prints its headline numbers (--json: one JSON object).",
                     formatter_class=_HelpFormatter,
                     epilog="Start with 'gearmesh example' (the shipped pairs), 'gearmesh example NAME > p.yaml' "
                            "and 'gearmesh geometry p.yaml'; 'gearmesh command --help' for its options.")
    parser.add_argument("--version", action="version", version=f"gearmesh {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="command")

    p = sub.add_parser("example", help="list the example pairs shipped with gearmesh, or print one (a pair file)",
                       description="List the example pairs shipped with gearmesh, or print one as a pair file: "
                                   "gearmesh example NAME > my_pair.yaml", formatter_class=_HelpFormatter)
    p.add_argument("name", nargs="?", default=None, help="the example to print (without: list them)")
    p.add_argument("--json", action="store_true", help="the list as one JSON object")
    p.set_defaults(func=cmd_example)

    _command(sub, "validate", cmd_validate, "check a gear pair file or a study config (exit 0, or 2 with the reason)",
             "a pair file or a study config")

    p = sub.add_parser("manufactured", help="print a manufactured gear of a variant's impact.nc as a pair file: a "
                       "held-out or population gear, or the worst gear of a criterion",
                       description="Print one manufactured gear of a variant's results (impact.nc: the sign-off's "
                                   "manufactured gears) as a pair file with its modification and lead slope "
                                   "deviations: gearmesh manufactured impact.nc --heldout 17 > gear.yaml",
                       formatter_class=_HelpFormatter)
    p.add_argument("impact", help="a variant's impact.nc")
    which = p.add_mutually_exclusive_group(required=True)
    which.add_argument("--heldout", type=int, metavar="GEAR", help="a gear of the held-out population")
    which.add_argument("--population", type=int, metavar="GEAR", help="a gear of the population (0: the nominal)")
    which.add_argument("--worst", metavar="CRITERION", help="the worst gear over the tolerance box of a criterion "
                       "(impact_force, lte_order_1, ..., peak_root_stress), with --torque-Nm")
    p.add_argument("--torque-Nm", dest="torque_Nm", type=float, help="pinion torque of --worst")
    p.set_defaults(func=cmd_manufactured)

    _command(sub, "geometry", cmd_geometry, "contact ratios, radii, backlash, masses and contact-line lengths")

    p = sub.add_parser("run", help="run the workflow of a gearmesh checkout: check every study config and profile "
                       "with the bounded loader, then snakemake with the same arguments", description="Run the "
                       "workflow as 'snakemake ARGS' in a checkout of the gearmesh repository (the Snakefile, the "
                       "workflow and the study configs are not part of the installed package; the folder you run it "
                       "in must hold them), after reading every config Snakemake would read before the workflow's own "
                       "checks (each --configfile, or config/config.yaml; every profile: --profile, "
                       "$SNAKEMAKE_PROFILE, --workflow-profile or the workflow's profiles/default, and the config "
                       "files a profile names) with gearmesh's bounded loader and validating it, so a file Snakemake "
                       "would parse without limits (a huge or nested file, a FIFO, a __use_yte__ template that runs "
                       "Python) never reaches Snakemake. Example, in the checkout: "
                       "gearmesh run --cores 2 --configfile config/studies/contact_lines.yaml",
                       formatter_class=_HelpFormatter)
    p.add_argument("snakemake_args", nargs=argparse.REMAINDER, help="the arguments for snakemake")
    p.set_defaults(func=cmd_run)

    p = sub.add_parser("check", help="check a study's results folder: name every damaged, foreign, edited or stale "
                       "file (exit 0, or 2 with one line per file)",
                       description="Check every netCDF file, CSV table, PNG figure and optimum pair file under "
                       "RESULTS (e.g. results/impact_case, from any folder, relative or absolute): readable, a gearmesh "
                       "result at its own path, its data matching its digest, made by the current code from inputs "
                       "that are still the files it was made from (a table or figure: the one its job wrote or drew, "
                       "unedited, from files unchanged since); with --configfile also made with that study's settings "
                       "and pair data. Each problem is one line naming the file and the command that remakes it, to "
                       "be run in the folder above results/.", formatter_class=_HelpFormatter)
    p.add_argument("results", help="a study's results folder (results/STUDY)")
    p.add_argument("--configfile", default=None, help="the study config the results must agree with")
    p.add_argument("--json", action="store_true", help="print one JSON object: ok and the problems, one line each")
    p.set_defaults(func=cmd_check)

    p = sub.add_parser("schema", help="print the JSON schema of a study config or a pair file (for editors), or "
                       "every key as a Markdown table")
    p.add_argument("kind", choices=("study", "pair"), help="study config or pair file")
    p.add_argument("--format", choices=("yaml", "json", "markdown"), default=None,
                   help="default: yaml for a study, json for a pair")
    p.set_defaults(func=cmd_schema)

    p = _command(sub, "stiffness", cmd_stiffness,
                 "time-varying mesh stiffness (slice method over the face width; tooth model --method), ISO 6336-1, LSTE")
    _setting_option(p, "--method", Stiffness, help=TOOTH_MODEL_HELP)
    _setting_option(p, "--slices", Stiffness, type=int, help="slices over the face width")
    _setting_option(p, "--positions", Stiffness, type=int, help="rotation positions per mesh cycle")
    _torque_options(p, required=False, section=Stiffness, on="torque_on")

    p = _command(sub, "ltca", cmd_ltca, "loaded tooth contact analysis at one torque: TE, LTE, line load, stiffness",
                 PAIR_HELP.replace(";", ", with its modification if any;"))
    _deviation_options(p)
    _torque_options(p, required=True, section=Ltca)
    _setting_option(p, "--positions", Ltca, type=int, help="rotation positions per mesh cycle")
    _setting_option(p, "--points", Ltca, type=int, help="points per contact line")
    _setting_option(p, "--contact-law", Ltca, help="local contact law: palmgren (approach ∝ F^0.9, n = 1.11) or "
                    "linear")
    _setting_option(p, "--method", Ltca, help=TOOTH_MODEL_HELP)

    p = _command(sub, "rating", cmd_rating, "load capacity at one torque and speed: ISO 6336-2/-3 method B "
                 "(S_H, S_F) with the LTCA's contact pressure and root stress",
                 PAIR_HELP.replace(";", ", with its modification and rating inputs if any;"))
    _deviation_options(p)
    _torque_options(p, required=True, section=Ltca)  # the rating's torques are the LTCA's
    p.add_argument("--speed-rpm", dest="speed_rpm", type=float, required=True,
                   help="speed (rpm) of the gear the torque acts on")
    _setting_option(p, "--application-factor", Rating, type=float, help="application factor K_A (ISO 6336-1)")
    _setting_option(p, "--life-hours", Rating, type=float,
                    help="required life (h) for the life factors Z_NT, Y_NT (default: the long-life end, 1e10 cycles)")
    p.add_argument("--factor", type=_factor_option, action="append", metavar="NAME=VALUE",
                   help="a factor given instead of computed (K_v, K_Hbeta, K_Fbeta, K_Halpha, K_Falpha, Z_L, Z_v, "
                        "Z_R, Z_W, Z_X, Z_NT, Y_NT, Y_deltarelT, Y_RrelT, Y_X, Y_M, S_Hmin, S_Fmin); repeatable")
    _setting_option(p, "--method", Rating,
                    help="where K_Hbeta, K_Fbeta, K_Halpha, K_Falpha come from: the LTCA's load distribution under "
                         "the mesh misalignment (f_sh + f_ma) or the standard's methods B/C (both are printed)")
    _setting_option(p, "--positions", Ltca, type=int, help="LTCA rotation positions per mesh cycle")
    _setting_option(p, "--points", Ltca, type=int, help="LTCA points per contact line")
    p.set_defaults(text=_rating_text)

    p = _command(sub, "impact", cmd_impact, "mesh-in impact at one torque and speed: scenario, mesh-in point, "
                 "velocity, local stiffness, impact force", PAIR_HELP.replace(";", ", with its modification if any;"))
    _deviation_options(p)
    _torque_options(p, required=True, section=Impact)
    p.add_argument("--speed-rpm", dest="speed_rpm", type=float, required=True, help="pinion speed (rpm)")
    _setting_option(p, "--driver", Impact, help="which gear drives")
    _setting_option(p, "--points", Impact, type=int, help="points per contact line")
    _setting_option(p, "--energy-velocity", Impact, help="velocity in 1/2 m_eq v^2: transverse (the coordinate m_eq "
                    "belongs to) or normal (as the mesh-in impact source document writes it)")
    p.add_argument("--simulate", action="store_true",
                   help="also integrate the engagement in time and print the simulated peak force")

    p = _command(sub, "dynamics", cmd_dynamics, "steady-state speed sweep of the 8-DOF bending-torsion-axial "
                 "model of the pair")
    _deviation_options(p)
    _torque_options(p, required=True, section=Dynamics)
    p.add_argument("--speeds", required=True, help="pinion speeds START:STOP:STEP in rpm (stop included)")
    _setting_option(p, "--backlash-um", Dynamics, type=_backlash_option,
                    help="total backlash 2b0 along the normal (µm), or 'pair': the pair's own from its centre "
                         "distance and shifts")
    p.add_argument("--excitation", choices=("tvms", "ltca", "contact"), default="tvms",
                   help="tvms: slice-model stiffness K(t), unloaded TE zero; ltca: loaded stiffness and loaded TE "
                        "of an LTCA at this torque (the ltca command's defaults); contact: the mesh force of "
                        "the real tooth contact of every tooth pair, the mesh-in impact included")

    p = _command(sub, "optimise", cmd_optimise, "GA optimisation of the six micro-geometry parameters (root and tip "
                 "relief amounts and lengths, crowning, unmodified lead length) against the mesh-in impact over a "
                 "load spectrum and the manufacturing tolerances")
    _deviation_options(p)
    _setting_option(p, "--objective", Optimise,
                    help="force: F_s; velocity: |v_n|; robust: F_s over the spectrum and tolerances (needs either); "
                        "dynamic: the dynamic factor (peak over static mesh force) of the contact-driven 8-DOF pair "
                        "over the speed range")
    p.add_argument("--dynamic-speeds-rpm", dest="dynamic_speeds_rpm", default=None,
                   help="speeds of the dynamic objective/constraint, comma-separated (rpm; default 0.2, 1 and 3 times "
                        "--speed-rpm), resonances within their range added per candidate")
    _setting_option(p, "--backlash-um", Optimise, type=_backlash_option,
                    help="backlash of the candidates' dynamics (µm, or 'pair': the pair's own)")
    p.add_argument("--torque-Nm", dest="torque_Nm", type=float, default=None,
                   help="design torque (N m; default the middle of --torques-Nm)")
    p.add_argument("--torques-Nm", dest="torques_Nm", default=None,
                   help="load spectrum, comma-separated (N m; default the design torque alone)")
    p.add_argument("--weights", default=None, help="time shares of --torques-Nm, comma-separated (duty-cycle mean); "
                                                  "without: the worst case over the spectrum")
    _setting_option(p, "--statistic", Optimise, help="over the load spectrum")
    _setting_option(p, "--on", Optimise, help="the gear the torques act on")
    _setting_option(p, "--speed-rpm", Optimise, type=float, help="pinion speed (rpm)")
    _setting_option(p, "--tolerance-samples", Tolerances, key="samples", type=int,
                    help="manufactured samples evaluated with the nominal (0: nominal only, a single-point optimum "
                         "when the spectrum is one torque)")
    p.add_argument("--grade", type=_grade_option, default=CLI_LEAD_GRADE,
                   help="ISO 1328-1:2013 flank tolerance class 1-11: lead slope within ±f_Hβ on both gears ('none': "
                        f"no lead deviation); unless given, class {CLI_LEAD_GRADE} as in the shipped case study")
    p.add_argument("--amount-tolerance-um", dest="amount_tolerance_um", type=float, default=0.0,
                   help="± on every relief and crowning amount (µm)")
    p.add_argument("--length-tolerance-mm", dest="length_tolerance_mm", type=float, default=0.0,
                   help="± on every relief length (mm)")
    _setting_option(p, "--sampling", Tolerances, help="seeded Latin hypercube (lhs), corners of the tolerance box, or "
                    "the unmodified pair's worst gears of its box (box)")
    _setting_option(p, "--tolerance-statistic", Optimise, help="over the nominal and the samples")
    _setting_option(p, "--tolerance-level", Optimise, key="tolerance_level_percent", type=float, metavar="PERCENT",
                    help="level (%%) of percentile and cvar")
    _setting_option(p, "--modify", Optimise, nargs="+", help="the gear(s) whose six parameters are optimised")
    _setting_option(p, "--method", Optimise, help="GA, random search or NSGA-II")
    _setting_option(p, "--seed", Optimise, type=int, help="random seed (GA and tolerance samples)")
    _setting_option(p, "--population", Optimise, type=int, help="candidates per generation")
    _setting_option(p, "--generations", Optimise, type=int, help="generations")
    p.add_argument("--write-pair", dest="write_pair", default=None, metavar="OUT.yaml",
                   help="write the optimum as a pair file OUT.yaml (its name: OUT), readable by every subcommand")
    # every other setting of a study's optimisation, and every constraint (the sign-off criteria),
    # from their declarations: a study's optimum is reproduced by giving its section's keys
    given = {a.dest for a in p._actions}
    p.set_defaults(optimise_keys=_declared_options(p, Optimise, skip=tuple(given | {"constraints"})),
                   constraint_keys=_declared_options(p, Constraints))
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:1] == ["run"] and argv[1:2] not in (["-h"], ["--help"]):  # everything after 'run' is Snakemake's
        args = argparse.Namespace(command="run", snakemake_args=argv[1:], func=cmd_run, json=False)
    else:
        args = parser.parse_args(argv)
    if args.command is None:  # bare 'gearmesh': what it can do
        parser.print_help()
        return 0
    try:
        _check_setting_options(args)
        for option in ("torque_Nm", "speed_rpm", "application_factor", "life_hours"):  # signs: the stages' own checks
            value = getattr(args, option, None)
            if value is not None and not math.isfinite(value):
                raise GearmeshInputError(option, value, "must be a finite number")
        result = args.func(args)
        if result is not None and getattr(args, "loaded_pair", None) is not None:
            own = [n for n in result.get("notes", []) if n not in pair_notes(args.loaded_pair)]
            result["notes"] = pair_notes(args.loaded_pair) + own
        if result is not None:
            _emit(result, args.json, getattr(args, "text", None))
        sys.stdout.flush()
    except GearmeshInputError as exc:
        print(f"gearmesh: error: {exc}", file=sys.stderr)
        if args.command == "validate" and args.json:
            print(json.dumps({"file": args.file, "valid": False, "errors": [str(exc)]}))
        return EXIT_BAD_INPUT
    except BrokenPipeError:  # the reader stopped early ('gearmesh example | head'): nothing more to say
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # so the exit flush cannot fail again
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
