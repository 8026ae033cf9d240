"""The ``gearmesh`` command line: validate inputs and print a stage's headline numbers.

Bad input exits with code 2 and one line ``gearmesh: error: FIELD = VALUE: RULE`` on
stderr; nothing is written. This module is the parser (one builder per group of commands, the
options that are settings made from their declarations) and :func:`main`; what each command
does and prints is :mod:`gearmesh.commands`'.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys
from collections.abc import Mapping, Sequence
from typing import Any

from . import __version__
from .commands import (DEVIATION_OPTIONS, cmd_check, cmd_dynamics, cmd_example, cmd_geometry, cmd_impact, cmd_ltca,
                       cmd_manufactured, cmd_optimise, cmd_rating, cmd_run, cmd_schema, cmd_stiffness, cmd_validate,
                       emit, rating_text)
from .errors import GearmeshInputError
from .pairfile import pair_notes
from .schema import check_value, defaults, field_schema, key_of, settings_fields
from .settings import Constraints, Dynamics, Impact, Ltca, Optimise, Rating, Stiffness, Tolerances

EXIT_BAD_INPUT = 2


def _deviation_options(p) -> None:
    """The manufacturing deviations as options; each replaces the pair file's key (:mod:`gearmesh.deviation`)."""
    for flag, nargs, text in DEVIATION_OPTIONS:
        p.add_argument(flag, type=float, nargs=nargs, metavar="UM", default=None,
                       help=f"{text}; replaces the pair file's {flag[2:].replace('-', '_')}")


def _factor_option(text: str) -> tuple[str, float]:
    """``NAME=VALUE`` of ``--factor`` as (name, value); the names and bounds are the rating's."""
    name, sep, value = text.partition("=")
    if not sep:
        raise ValueError(text)
    return name.strip(), float(value)


_factor_option.__name__ = "NAME=VALUE (e.g. K_v=1.1)"  # argparse names the type in its refusal


def _backlash_option(text: str):
    """--backlash-um: 'pair' (the pair's own backlash) or a number of µm (its range is the stage's check)."""
    if text == "pair":
        return text
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is neither 'pair' nor a number of µm") from None


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


def build_parser() -> argparse.ArgumentParser:
    """The ``gearmesh`` parser: every subcommand, group by group, in the order ``--help`` lists them.

    Returns
    -------
    argparse.ArgumentParser
        Its refusals are the one line ``gearmesh: error: ARGUMENT = VALUE: RULE`` (exit 2); each
        subcommand sets ``func`` (its :mod:`gearmesh.commands` function) and, where options are
        settings, ``setting_options`` (option -> its declaration, checked by :func:`main`).
    """
    parser = _Parser(prog="gearmesh", description="Helical gear pairs from their design data: geometry, contact, "
                     "mesh stiffness, loaded contact, mesh-in impact, micro-geometry optimisation and dynamics; "
                     "each command prints its headline numbers (--json: one JSON object).",
                     formatter_class=_HelpFormatter,
                     epilog="Start with 'gearmesh example' (the shipped pairs), 'gearmesh example NAME > p.yaml' "
                            "and 'gearmesh geometry p.yaml'; 'gearmesh command --help' for its options.")
    parser.add_argument("--version", action="version", version=f"gearmesh {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="command")
    for add_commands in (_pair_commands, _workflow_commands, _contact_commands, _dynamic_commands, _optimise_command):
        add_commands(sub)
    return parser


def _pair_commands(sub) -> None:
    """The pair file itself: the shipped examples, validation (of a study config too), a
    manufactured gear printed as a pair file, and the pair's geometry."""
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


def _workflow_commands(sub) -> None:
    """The study workflow: run it, check a results folder, print the schemas of its files."""
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


def _contact_commands(sub) -> None:
    """The static stages at one load: mesh stiffness, loaded tooth contact and load capacity."""
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
    p.set_defaults(text=rating_text)


def _dynamic_commands(sub) -> None:
    """The stages at speed: mesh-in impact at one speed, the dynamics over a speed sweep."""
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


def _optimise_command(sub) -> None:
    """The micro-geometry optimisation: its load spectrum, tolerances and GA options by hand, and
    every other setting of a study's optimisation and every constraint from their declarations."""
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


def main(argv: Sequence[str] | None = None) -> int:
    """Run one ``gearmesh`` command: parse, check every option that is a setting against its
    declaration and the numbers for finiteness, run the command, print its result.

    Everything after ``run`` is Snakemake's (not parsed here). The pair file's notes are printed
    before the command's own. A reader that stops early (``gearmesh example | head``) ends it quietly.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after ``gearmesh`` (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code: 0, or 2 (:data:`EXIT_BAD_INPUT`) on a refusal, printed on stderr as the one
        line ``gearmesh: error: FIELD = VALUE: RULE`` with nothing on stdout (``validate --json``
        also prints ``{"file", "valid": false, "errors"}``). The result goes to stdout through
        :func:`gearmesh.commands.emit` (text, or one JSON object with ``--json``).

    Raises
    ------
    SystemExit
        From argparse: code 2 for a malformed command line (the same one line), 0 after
        ``--help`` or ``--version``.
    """
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
            emit(result, args.json, getattr(args, "text", None))
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
