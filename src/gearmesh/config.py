"""Study configs: schema validation with defaults, and resolving pair names to pair files.

The schema (``schemas/config.schema.yaml``, linked as ``workflow/schemas/``) is the one
source of truth; Snakemake validates with it through ``snakemake.utils.validate`` and the
CLI through :func:`validate_study`, both filling the defaults it declares.
"""

from __future__ import annotations

import copy
import math
from contextlib import contextmanager
from importlib.resources import files
from pathlib import Path
from typing import Any, Iterator, Mapping

import jsonschema
import yaml

from .errors import GearmeshInputError
from .gear import GearPair, load_named_pair, pinion_torque, read_yaml, variant_pair

SCHEMA_PATH = Path(str(files("gearmesh") / "schemas" / "config.schema.yaml"))


def _with_defaults(validator_class):
    """A validator that fills ``default`` values while it validates (jsonschema FAQ recipe)."""
    validate_properties = validator_class.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, schema):
        if isinstance(instance, dict):
            for name, sub in properties.items():
                if "default" in sub and name not in instance:
                    instance[name] = copy.deepcopy(sub["default"])
        yield from validate_properties(validator, properties, instance, schema)

    return jsonschema.validators.extend(validator_class, {"properties": set_defaults})


def load_schema() -> dict[str, Any]:
    return yaml.safe_load(SCHEMA_PATH.read_text())


def _schema_error(err: jsonschema.ValidationError) -> GearmeshInputError:
    """One schema error as the field it is about: an unknown or missing key is named itself,
    and the message loses its leading repr of the value (the error shows an excerpt)."""
    path = [str(p) for p in err.path]
    instance = err.instance
    if err.validator == "additionalProperties" and err.validator_value is False and isinstance(instance, Mapping):
        extra = sorted((k for k in instance if k not in err.schema.get("properties", {})), key=str)
        if extra:
            allowed = sorted(err.schema.get("properties", {}))
            hint = " (YAML 1.1 reads on/off/yes/no as true/false: quote the key, e.g. \"on\")" \
                if isinstance(extra[0], bool) else ""
            return GearmeshInputError(".".join(path + [str(extra[0])]), instance[extra[0]],
                                      f"unknown key{hint}; allowed keys are {allowed}")
    if err.validator == "required" and isinstance(instance, Mapping):
        missing = [k for k in err.validator_value if k not in instance]
        if missing:
            return GearmeshInputError(".".join(path + [missing[0]]), None, "is required")
    message = err.message
    head = repr(instance)
    if message.startswith(head):
        message = message[len(head):].strip()
    return GearmeshInputError(".".join(path) or "config", instance if path else None, message)


def _first_non_finite(data: Any, path: str = "") -> tuple[str, float] | None:
    """The path and value of the first NaN or infinite number in a nested config (JSON schema
    numbers accept both; no setting of a study may be either)."""
    stack = [(path, data)]
    while stack:
        where, value = stack.pop()
        if isinstance(value, float) and not math.isfinite(value):
            return where or "config", value
        if isinstance(value, Mapping):
            stack += [(f"{where}.{k}" if where else str(k), v) for k, v in reversed(list(value.items()))]
        elif isinstance(value, (list, tuple)):
            stack += [(f"{where}[{i}]", v) for i, v in reversed(list(enumerate(value)))]
    return None


def validate_study(config: Mapping[str, Any]) -> dict[str, Any]:
    """A copy of ``config`` with defaults filled; GearmeshInputError naming the first bad field
    (a NaN or infinite number anywhere, then the schema's first error)."""
    bad = _first_non_finite(config)
    if bad:
        raise GearmeshInputError(bad[0], bad[1], "must be a finite number")
    schema = load_schema()
    data = copy.deepcopy(dict(config))
    validator = _with_defaults(jsonschema.Draft202012Validator)(schema)
    errors = sorted(validator.iter_errors(data), key=lambda e: (len(e.path), list(map(str, e.path))))
    if errors:
        raise _schema_error(errors[0])
    # Fill defaults a second time: nested defaults of objects created by the first pass.
    for _ in validator.iter_errors(data):
        pass
    return data


def load_study(path: str | Path) -> dict[str, Any]:
    """Read and validate a study config file."""
    data = read_yaml(path, "config file")
    if not isinstance(data, Mapping):
        raise GearmeshInputError("config file", str(path), "must be a YAML mapping")
    return validate_study(data)


def workflow_config(config: Mapping[str, Any], configfiles: list[str | Path]) -> dict[str, Any]:
    """The config Snakemake built, judged as ``gearmesh validate`` judges a study: each of its
    files re-read with :func:`read_yaml` (bounded; refuses aliases and duplicated keys, which
    Snakemake's loader lets through), then the merged config validated with its defaults
    filled (:func:`validate_study`). The Snakefile calls it before anything else."""
    for path in configfiles:
        if not isinstance(read_yaml(path, "file"), Mapping):
            raise GearmeshInputError("file", str(path), "must be a YAML mapping")
    return validate_study(config)


def pair_path(config: Mapping[str, Any], name: str, root: str | Path = ".") -> Path:
    return Path(root) / config.get("pairs_dir", "config/pairs") / f"{name}.yaml"


def study_pairs(config: Mapping[str, Any], root: str | Path = ".") -> dict[str, GearPair]:
    """Every pair the study names (``pairs`` and the sweep/design lists), loaded and checked."""
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
    folders where they exist (:func:`gearmesh.io.check_output_tree`). Returns the pairs."""
    from .datasets.optimise import check_optimise
    from .datasets.stiffness import apply_variant
    from .io import check_output_tree, study_folders
    from .gear import pair_geometry
    from .stiffness import require_stiffness_data

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
    if lste_comparison_wanted(config):
        stiffness, ltca = config["stiffness"], config["ltca"]
        for name in config["pairs"]:
            t_k = pinion_torque(pairs[name], stiffness["torque_Nm"], stiffness.get("torque_on", "pinion"))
            if not _among(t_k, pairs[name], ltca):
                raise GearmeshInputError("ltca.torques_Nm", ltca["torques_Nm"],
                                         f"must include the stiffness LSTE torque ({stiffness['torque_Nm']} N m on "
                                         f"the {stiffness.get('torque_on', 'pinion')}) for the LSTE comparison")
    dyn = config.get("dynamics", {})
    if "dynamics" in config and "ltca" in config and dyn.get("excitation") in (None, "ltca"):
        ltca = config["ltca"]
        torques = dyn.get("torques_Nm", 200.0)
        for name in config["pairs"]:
            for t in torques if isinstance(torques, list) else [torques]:
                t_d = pinion_torque(pairs[name], t, dyn.get("on", "pinion"))
                if not _among(t_d, pairs[name], ltca):
                    raise GearmeshInputError("ltca.torques_Nm", ltca["torques_Nm"],
                                             f"must include the dynamics torque ({t} N m on the "
                                             f"{dyn.get('on', 'pinion')}): the LTCA excites the dynamics")
    if "dynamics" in config and dyn.get("excitation") == "ltca" and "ltca" not in config:
        raise GearmeshInputError("dynamics.excitation", "ltca", "needs an ltca section in the study")
    _check_impact(config.get("impact"))
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


def check_stages(config: Mapping[str, Any], pairs: Mapping[str, GearPair]) -> None:
    """The stage settings the schema cannot judge, checked with each stage's own boundary
    checks and work limits (:mod:`gearmesh.limits`) before any job runs: grid sizes, lead
    slopes, every torque against the contact-stress and deflection limits of every pair it
    loads, helix-sweep size, dynamics comparison couples and the full dynamics and train
    settings with their work estimate (:func:`gearmesh.datasets.dynamics.check_dynamics_settings`)."""
    from .datasets.dynamics import check_dynamics_settings
    from .gear import pair_geometry
    from .limits import (MAX_CONTACT_POINTS, MAX_STIFFNESS_POINTS, MAX_SWEEP_ANGLES, check_grid,
                         check_load, check_speeds)
    from .tca import check_lead_slope

    geoms = {name: pair_geometry(pair) for name, pair in pairs.items()}

    def loads(section: str, key: str, on: str, names: Any) -> None:
        values = config[section][key]
        for k, value in enumerate(values if isinstance(values, list) else [values]):
            field = f"{section}.{key}" + (f"[{k}]" if isinstance(values, list) else "")
            for name in names:
                check_load(geoms[name], pinion_torque(pairs[name], value, on), field, value)

    stiffness = config["stiffness"]
    if not 2 * stiffness["fourier_order"] < stiffness["positions"]:
        raise GearmeshInputError("stiffness.fourier_order", stiffness["fourier_order"],
                                 f"needs more than twice as many positions ({stiffness['positions']})")
    for section in ("stiffness", "stiffness_table", "slice_convergence"):
        if section in config:
            sec = config[section]
            slices = max(sec["slices"]) if isinstance(sec["slices"], list) else sec["slices"]
            check_grid(f"{section}.slices", sec["slices"], slices * sec["positions"], MAX_STIFFNESS_POINTS,
                       "slice-positions")
            if sec.get("torque_Nm") is not None:
                loads(section, "torque_Nm", sec["torque_on"], sec.get("pairs", config["pairs"]))
    for section in ("tca", "ltca"):
        if section in config:
            sec = config[section]
            with _section(section):
                check_lead_slope(sec["lead_slope_um"])
            check_grid(f"{section}.points", sec["points"], (sec["positions"] + 1) * sec["points"],
                       MAX_CONTACT_POINTS, "contact candidates per line")
    if "ltca" in config:
        loads("ltca", "torques_Nm", config["ltca"]["on"], config["pairs"])
    if "impact" in config:
        loads("impact", "torques_Nm", config["impact"]["on"], config["pairs"])
        with _section("impact"):
            check_lead_slope(config["impact"]["lead_slope_um"])
            for name in config["pairs"]:
                check_speeds(geoms[name], config["impact"]["speeds_rpm"], "speeds_rpm")
    for run, section in (config.get("optimise") or {}).items():
        for key in ("speed_rpm", "dynamic_speeds_rpm"):
            for name in config["pairs"] if section.get(key) is not None else ():
                check_speeds(geoms[name], section[key], f"optimise.{run}.{key}")
        for key in ("torque_Nm", "torques_Nm"):
            values = section.get(key)
            for k, value in enumerate(values if isinstance(values, list) else [] if values is None else [values]):
                field = f"optimise.{run}.{key}" + (f"[{k}]" if isinstance(values, list) else "")
                for name in config["pairs"]:
                    check_load(geoms[name], pinion_torque(pairs[name], value, section["on"]), field, value)
    if sweep := config.get("helix_sweep"):
        count = int((sweep["stop_deg"] - sweep["start_deg"]) / sweep["step_deg"]) + 1
        check_grid("helix_sweep.step_deg", sweep["step_deg"], count, MAX_SWEEP_ANGLES, "helix angles per pair")
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
    for section, train in (("dynamics", False), ("train_dynamics", True)):
        if section in config:
            sec = config[section]
            points = config["ltca"]["positions"] if section == "dynamics" and "ltca" in config \
                else config["stiffness"]["positions"]
            key = "torque_Nm" if train else "torques_Nm"
            if sec.get(key) is not None:
                loads(section, key, sec.get("on", "pinion"), config["pairs"])
            elif train and sec.get("static_force_N") is not None:  # normal force -> gear torque F r_b2 cos βb
                force = sec["static_force_N"]
                for name in config["pairs"]:
                    g = geoms[name]
                    t2 = force * float(g.base_radius[1]) * math.cos(g.base_helix_angle)
                    check_load(g, pinion_torque(pairs[name], t2, "gear"), f"{section}.static_force_N", force)
            for name in config["pairs"]:
                with _section(section):
                    check_dynamics_settings(pairs[name], sec, train=train, excitation_points=points)


def _check_impact(impact: Mapping[str, Any] | None) -> None:
    """The impact map's design speed is one of its speeds, its design torque and its simulated torques are
    among its torques."""
    if not impact:
        return
    speeds = impact.get("speeds_rpm", [5000])
    if not any(abs(v - impact.get("design_speed_rpm", 5000)) <= 1e-9 * v for v in speeds):
        raise GearmeshInputError("impact.design_speed_rpm", impact.get("design_speed_rpm", 5000),
                                 f"must be one of impact.speeds_rpm {speeds}")
    torques = impact.get("torques_Nm", [400, 1000, 1600])
    design = impact.get("design_torque_Nm")
    if design is not None and not any(abs(v - design) <= 1e-9 * v for v in torques):
        raise GearmeshInputError("impact.design_torque_Nm", design, f"must be one of impact.torques_Nm {torques}")
    for k, t in enumerate(impact.get("simulate_torques_Nm", [])):
        if not any(abs(v - t) <= 1e-9 * v for v in torques):
            raise GearmeshInputError(f"impact.simulate_torques_Nm[{k}]", t, f"must be one of impact.torques_Nm {torques}")


def _among(t1: float, pair: GearPair, ltca: Mapping[str, Any]) -> bool:
    """Whether pinion torque ``t1`` is one of the LTCA's torques (as pinion torques)."""
    return any(abs(pinion_torque(pair, t, ltca.get("on", "pinion")) - t1) <= 1e-9 * t1 for t in ltca["torques_Nm"])


def lste_comparison_wanted(config: Mapping[str, Any]) -> bool:
    """The study compares the LTCA with F/K: it runs the LTCA on the standard variant and the
    stiffness stage has an LSTE torque."""
    return "ltca" in config and "standard" in config.get("variants", {}) and "torque_Nm" in config.get("stiffness", {})
