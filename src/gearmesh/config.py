"""Study configs: validation with defaults, resolving pair names to pair files, and the checks
of everything a study needs before any job runs.

The settings a config may hold are declared once, typed, in :mod:`gearmesh.settings`; the
study schema is built from them (and published as ``schemas/config.schema.yaml``, linked as
``workflow/schemas/``). ``gearmesh validate`` and the Snakefile both judge a config with
:func:`validate_study` and :func:`check_study`, filling the declared defaults.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Iterator, Mapping

from .choices import pair_excitation
from .errors import GearmeshInputError
from .gear import GearPair, pinion_torque
from .inputfile import read_yaml
from .pairfile import load_named_pair, variant_pair
from .limits import same_point
from .schema import validate
from .registry import stages, study_schema
from .settings import lste_compared
from .stages import Grid, Speeds, Torques, required_sections


def validate_study(config: Mapping[str, Any]) -> dict[str, Any]:
    """A copy of ``config`` with defaults filled; GearmeshInputError naming the first bad field
    (a NaN or infinite number anywhere, then the first error of the study schema,
    :func:`gearmesh.registry.study_schema`). A ``__use_yte__`` key is named for what it is: it
    turns on Snakemake's YTE template engine, which runs the file's Python when Snakemake loads it.

    Parameters
    ----------
    config : mapping
        A study config as read (YAML mapping).

    Returns
    -------
    dict
        The config with every declared default filled.

    Raises
    ------
    GearmeshInputError
        Naming the first bad field: ``__use_yte__``, a NaN or infinite number, or the first error
        against the study schema.
    """
    if isinstance(config, Mapping) and "__use_yte__" in config:
        raise GearmeshInputError("__use_yte__", config["__use_yte__"], "turns on Snakemake's YTE template engine, "
                                 "which runs Python from the config when Snakemake loads it (before any check): a "
                                 "gearmesh study is plain data; remove the key, and run studies with 'gearmesh run' "
                                 "(the workflow documentation's trust model)")
    return validate(config, study_schema())


def load_study(path: str | Path) -> dict[str, Any]:
    """Read and validate a study config file.

    Parameters
    ----------
    path : str or pathlib.Path
        The study config file (YAML).

    Returns
    -------
    dict
        The validated config, defaults filled (:func:`validate_study`).

    Raises
    ------
    GearmeshInputError
        Naming "config file" for a file :func:`gearmesh.inputfile.read_yaml` refuses or one that is not
        a mapping, else the first bad field.
    """
    data = read_yaml(path, "config file")
    if not isinstance(data, Mapping):
        raise GearmeshInputError("config file", str(path), "must be a YAML mapping")
    return validate_study(data)


def workflow_config(config: Mapping[str, Any], configfiles: list[str | Path]) -> dict[str, Any]:
    """The config Snakemake built, judged as ``gearmesh validate`` judges a study: each of its
    files re-read with :func:`read_yaml` (bounded; refuses aliases and duplicated keys, which
    Snakemake's loader lets through), then the merged config validated with its defaults
    filled (:func:`validate_study`). The Snakefile calls it before anything else.

    Parameters
    ----------
    config : mapping
        The config Snakemake merged from its files and ``--config``.
    configfiles : list of str or pathlib.Path
        The config files Snakemake read.

    Returns
    -------
    dict
        The validated config, defaults filled.

    Raises
    ------
    GearmeshInputError
        Naming "file" for a config file refused or not a mapping, else the first bad field.
    """
    for path in configfiles:
        if not isinstance(read_yaml(path, "file"), Mapping):
            raise GearmeshInputError("file", str(path), "must be a YAML mapping")
    return validate_study(config)


def pair_path(config: Mapping[str, Any], name: str, root: str | Path = ".") -> Path:
    """The pair file of pair ``name`` of a validated study config.

    Parameters
    ----------
    config : mapping
        A validated study config (its ``pairs_dir``).
    name : str
        The pair's name.
    root : str or pathlib.Path, default "."
        The folder the study runs in.

    Returns
    -------
    pathlib.Path
        ``root/pairs_dir/name.yaml`` (not checked to exist).
    """
    return Path(root) / config["pairs_dir"] / f"{name}.yaml"


def study_pairs(config: Mapping[str, Any], root: str | Path = ".") -> dict[str, GearPair]:
    """Every pair the study names (``pairs`` and the sweep/design lists), loaded and checked.

    Parameters
    ----------
    config : mapping
        A validated study config.
    root : str or pathlib.Path, default "."
        The folder the study runs in.

    Returns
    -------
    dict of str to GearPair
        Every named pair, in the order named (``pairs`` first).

    Raises
    ------
    GearmeshInputError
        Naming ``pairs`` for a pair without a pair file, or the pair file's first bad field.
    """
    names = list(config["pairs"])
    for section in ("helix_sweep", "low_fluctuation_design", "stiffness_table", "slice_convergence"):
        names += [n for n in config.get(section, {}).get("pairs", []) if n not in names]
    out = {}
    for name in names:
        path = pair_path(config, name, root)
        if not path.exists():
            raise GearmeshInputError("pairs", name, f"has no pair file {path}")
        out[name] = load_named_pair(path)
    return out


def check_study(config: Mapping[str, Any], root: str | Path = ".") -> dict[str, GearPair]:
    """Everything a study will need, checked before any job runs (one error, naming the field):
    every pair loads and works, has the material and bore the always-run stiffness stage
    needs, every micro-geometry variant and every stiffness-table variant gives a working
    pair, sweep ranges are not empty, and the folders its jobs write into under ``root`` are
    folders where they exist (:func:`gearmesh.io.check_output_tree`).

    Parameters
    ----------
    config : mapping
        A validated study config, defaults filled.
    root : str or pathlib.Path, default "."
        The folder the study runs in (pair files and results under it).

    Returns
    -------
    dict of str to GearPair
        Every pair the study names (:func:`study_pairs`).

    Raises
    ------
    GearmeshInputError
        The first failed check, naming the config field (``variants.NAME.…``, ``ltca.torques_Nm``, …).
    """
    from .datasets.optimise import check_optimise
    from .datasets.stiffness import apply_variant
    from .io import check_output_tree, study_folders
    from .gear import pair_geometry
    from .tooth import require_stiffness_data

    pairs = study_pairs(config, root)
    for name, pair in pairs.items():
        geom = pair_geometry(pair)
        if name in config["pairs"]:
            require_stiffness_data(geom)
        for variant, spec in config.get("variants", {}).items():
            with _section(f"variants.{variant}"):
                pair_geometry(variant_pair(pair, variant, spec))
    table = config.get("stiffness_table", {})
    for name in table.get("pairs", []):
        for variant, overrides in (table.get("variants") or {}).items():
            try:
                pair_geometry(apply_variant(pairs[name], variant, overrides))
            except (TypeError, ValueError) as exc:
                if isinstance(exc, GearmeshInputError):
                    raise GearmeshInputError(f"stiffness_table.variants.{variant}.{exc.field}", exc.value,
                                             exc.rule) from None
                raise GearmeshInputError(f"stiffness_table.variants.{variant}", dict(overrides), str(exc)) from None
    check_required_sections(config)
    if lste_compared(config, "ltca"):
        stiffness, ltca = config["stiffness"], config["ltca"]
        for name in config["pairs"]:
            t_k = pinion_torque(pairs[name], stiffness["torque_Nm"], stiffness["torque_on"])
            if not _among(t_k, pairs[name], ltca):
                raise GearmeshInputError("ltca.torques_Nm", ltca["torques_Nm"],
                                         f"must include the stiffness LSTE torque ({stiffness['torque_Nm']} N m on "
                                         f"the {stiffness['torque_on']}) for the LSTE comparison")
    dyn = config.get("dynamics", {})
    if study_excitation(config) == "ltca" and "ltca" in config:
        ltca = config["ltca"]
        torques = dyn["torques_Nm"]
        for name in config["pairs"]:
            for t in torques if isinstance(torques, list) else [torques]:
                t_d = pinion_torque(pairs[name], t, dyn["on"])
                if not _among(t_d, pairs[name], ltca):
                    raise GearmeshInputError("ltca.torques_Nm", ltca["torques_Nm"],
                                             f"must include the dynamics torque ({t} N m on the "
                                             f"{dyn['on']}): the LTCA excites the dynamics")
    if "dynamics" in config and dyn.get("excitation") == "ltca" and "ltca" not in config:
        raise GearmeshInputError("dynamics.excitation", "ltca", "needs an ltca section in the study")
    _check_impact(config.get("impact"))
    _check_signoff(config, pairs)
    sweep = config.get("helix_sweep")
    if sweep and sweep["stop_deg"] < sweep["start_deg"]:
        raise GearmeshInputError("helix_sweep.stop_deg", sweep["stop_deg"],
                                 f"must not be below start_deg ({sweep['start_deg']})")
    check_stages(config, pairs)
    check_optimise(config, pairs)
    check_output_tree(study_folders(config), root)
    return pairs


@contextmanager
def _section(prefix: str) -> Iterator[None]:
    """Re-raise a GearmeshInputError of a stage's own check under the config section's name."""
    try:
        yield
    except GearmeshInputError as exc:
        if exc.field.startswith(prefix + "."):
            raise
        raise GearmeshInputError(f"{prefix}.{exc.field}", exc.value, exc.rule) from None


def check_required_sections(config: Mapping[str, Any]) -> None:
    """Every stage the study runs has the sections it needs (:func:`gearmesh.stages.required_sections`:
    those of the stages it reads in every study, and those it declares): a study with a rating
    section and no ltca section is refused here, before any job runs.

    Parameters
    ----------
    config : mapping
        A validated study config.

    Raises
    ------
    GearmeshInputError
        Naming the section of the first stage that lacks a section it needs.
    """
    for section, stage in stages().items():
        if section not in config:
            continue
        for needed in required_sections(stage):
            if needed not in config:
                raise GearmeshInputError(section, dict(config[section]), f"needs a {needed} section in the study: the "
                                         f"{section} stage reads its results" if needed in {r.stage for r in stage.reads}
                                         else f"needs a {needed} section in the study")


def check_stages(config: Mapping[str, Any], pairs: Mapping[str, GearPair]) -> None:
    """The stage settings the schema cannot judge, checked before any job runs: each stage's
    declared work limits (:attr:`gearmesh.stages.Stage.limits`: grid sizes, every torque against
    the contact-stress and deflection limits of every pair it loads, every speed against the
    burst speed), the stiffness Fourier order, helix-sweep size, dynamics comparison couples and
    the full dynamics and train settings with their work estimate
    (:func:`gearmesh.datasets.dynamics.check_dynamics_settings`).

    Parameters
    ----------
    config : mapping
        A validated study config, defaults filled.
    pairs : mapping of str to GearPair
        The study's pairs (:func:`study_pairs`).

    Raises
    ------
    GearmeshInputError
        Naming the first setting over a limit (``SECTION.KEY`` or ``SECTION.RUN.KEY``, with ``[k]``
        for an entry of a list): a torque over the contact-stress or deflection limit, a speed over
        the burst speed, a grid over its work limit, or an inconsistent dynamics setting.
    """
    from .datasets.dynamics.checks import check_dynamics_settings
    from .gear import pair_geometry
    from .limits import check_sweep
    from .loads import check_load

    geoms = {name: pair_geometry(pair) for name, pair in pairs.items()}
    stiffness = config["stiffness"]
    if not 2 * stiffness["fourier_order"] < stiffness["positions"]:
        raise GearmeshInputError("stiffness.fourier_order", stiffness["fourier_order"],
                                 f"needs more than twice as many positions ({stiffness['positions']})")
    for section, stage in stages().items():
        if section not in config:
            continue
        named = config[section].items() if stage.scope == "run" else [(None, config[section])]
        for run, settings in named:
            prefix = section if run is None else f"{section}.{run}"
            for limit in stage.limits:
                _check_limit(limit, settings, prefix, pairs, geoms, settings.get("pairs", config["pairs"]))
    if sweep := config.get("helix_sweep"):
        check_sweep(sweep["start_deg"], sweep["stop_deg"], sweep["step_deg"], "helix_sweep.")
    for k, couple in enumerate(config.get("dynamics_comparison", {}).get("couples") or []):
        for name in couple:
            if name not in config["pairs"]:
                raise GearmeshInputError(f"dynamics_comparison.couples[{k}]", couple, f"{name!r} is not a pair of "
                                         "the study's pairs")
    if "dynamics_comparison" in config and "dynamics" not in config:
        raise GearmeshInputError("dynamics_comparison", config["dynamics_comparison"],
                                 "needs a dynamics section: it compares the pairs' speed sweeps")
    if "ltca" in config and config.get("dynamics", {}).get("transmission_error_um") is not None:
        raise GearmeshInputError("dynamics.transmission_error_um", config["dynamics"]["transmission_error_um"],
                                 "must be null when the study runs the LTCA: the LTCA excites the dynamics")
    train = config.get("train_dynamics")
    if train and train.get("torque_Nm") is None and train.get("static_force_N") is not None:
        force = train["static_force_N"]  # normal force -> gear torque F r_b2 cos βb
        for name in config["pairs"]:
            g = geoms[name]
            t2 = force * float(g.base_radius[1]) * math.cos(g.base_helix_angle)
            check_load(g, pinion_torque(pairs[name], t2, "gear"), "train_dynamics.static_force_N", force)
    for section, is_train in (("dynamics", False), ("train_dynamics", True)):
        if section in config:
            points = config["ltca"]["positions"] if section == "dynamics" and "ltca" in config \
                else config["stiffness"]["positions"]
            for name in config["pairs"]:
                with _section(section):
                    check_dynamics_settings(pairs[name], config[section], train=is_train, excitation_points=points)


def _check_limit(limit: Torques | Speeds | Grid, settings: Mapping[str, Any], prefix: str,
                 pairs: Mapping[str, GearPair], geoms: Mapping[str, Any], names: Any) -> None:
    """One declared work limit of a stage's ``settings`` (config section ``prefix``) on the pairs ``names``."""
    from .limits import check_grid, check_speeds
    from .loads import check_load

    if isinstance(limit, Grid):
        check_grid(f"{prefix}.{limit.size}", settings[limit.size], limit.points(settings), limit.limit, limit.what)
        return
    values = settings.get(limit.key)
    if values is None:
        return
    field = f"{prefix}.{limit.key}"
    if isinstance(limit, Speeds):
        for name in names:
            check_speeds(geoms[name], values, field)
        return
    on = settings.get(limit.on, "pinion") if limit.on else "pinion"
    for k, value in enumerate(values if isinstance(values, list) else [values]):
        for name in names:
            check_load(geoms[name], pinion_torque(pairs[name], value, on), field + (f"[{k}]" if isinstance(values, list)
                                                                                  else ""), value)


def _check_impact(impact: Mapping[str, Any] | None) -> None:
    """The impact map's design speed is one of its speeds, its design torque and its simulated torques are
    among its torques (``impact``: the validated section, defaults filled)."""
    if not impact:
        return
    speeds = impact["speeds_rpm"]
    if not same_point(speeds, impact["design_speed_rpm"]).any():
        raise GearmeshInputError("impact.design_speed_rpm", impact["design_speed_rpm"],
                                 f"must be one of impact.speeds_rpm {speeds}")
    torques = impact["torques_Nm"]
    design = impact["design_torque_Nm"]
    if design is not None and not same_point(torques, design).any():
        raise GearmeshInputError("impact.design_torque_Nm", design, f"must be one of impact.torques_Nm {torques}")
    for key in ("simulate_torques_Nm", "tolerance_torques_Nm"):
        for k, t in enumerate(impact.get(key) or ()):
            if not same_point(torques, t).any():
                raise GearmeshInputError(f"impact.{key}[{k}]", t, f"must be one of impact.torques_Nm {torques}")


def _check_signoff(config: Mapping[str, Any], pairs: Mapping[str, GearPair]) -> None:
    """The sign-off table has what it reads (basis population: the tolerances section with samples),
    its reference among the variants, and every LTCA torque among the impact's (and the dynamics')
    torques."""
    signoff = config.get("signoff")
    if signoff is None:
        return  # the sections it reads: check_required_sections
    tolerances = config.get("tolerances") or {}
    if signoff.get("basis") == "population" and not (tolerances.get("population") and (
            tolerances.get("grade") is not None or tolerances.get("modification"))):
        raise GearmeshInputError("signoff.basis", "population", "needs a tolerances section with a grade or "
                                 "modification tolerances and a population (the manufactured gears it judges); or "
                                 "basis: nominal")
    variants = list(config.get("variants", {}))
    if signoff["reference"] not in variants:
        raise GearmeshInputError("signoff.reference", signoff["reference"], f"must be one of the variants {variants}")
    ltca = config["ltca"]
    for section in ("impact", "dynamics"):
        sec = config.get(section)
        if sec is None:
            continue
        torques = sec["torques_Nm"]
        judged = sec.get("tolerance_torques_Nm") if section == "impact" and signoff.get("basis") == "population" \
            else None
        field = "impact.tolerance_torques_Nm" if judged is not None else f"{section}.torques_Nm"
        torques = torques if judged is None else judged
        own = {"torques_Nm": torques if isinstance(torques, list) else [torques], "on": sec.get("on", "pinion")}
        for name in config["pairs"]:
            for t in ltca["torques_Nm"]:
                if not _among(pinion_torque(pairs[name], t, ltca["on"]), pairs[name], own):
                    raise GearmeshInputError(field, torques, f"must include every LTCA torque "
                                             f"({t} N m on the {ltca['on']}) for the sign-off table")


def _among(t1: float, pair: GearPair, ltca: Mapping[str, Any]) -> bool:
    """Whether pinion torque ``t1`` is one of the LTCA's torques (as pinion torques)."""
    return bool(same_point([pinion_torque(pair, t, ltca["on"]) for t in ltca["torques_Nm"]], t1).any())


def study_excitation(config: Mapping[str, Any]) -> str | None:
    """The excitation of the study's dynamics (None: the study has none): the section's, or the
    LTCA's when the study runs the LTCA (:func:`gearmesh.choices.pair_excitation`).

    Parameters
    ----------
    config : mapping
        A validated study config.

    Returns
    -------
    {'tvms', 'lste', 'ltca', 'contact'} or None
        The excitation of the study's dynamics; None without a dynamics section.
    """
    if "dynamics" not in config:
        return None
    return pair_excitation((config.get("dynamics") or {}).get("excitation"), "ltca" in config)
