"""Study configs: schema validation with defaults, and resolving pair names to pair files.

The schema (``schemas/config.schema.yaml``, linked as ``workflow/schemas/``) is the one
source of truth; Snakemake validates with it through ``snakemake.utils.validate`` and the
CLI through :func:`validate_study`, both filling the defaults it declares.
"""

from __future__ import annotations

import copy
from importlib.resources import files
from pathlib import Path
from typing import Any, Mapping

import jsonschema
import yaml

from .errors import GearmeshInputError
from .gear import GearPair, load_pair, pinion_torque, read_yaml

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


def validate_study(config: Mapping[str, Any]) -> dict[str, Any]:
    """A copy of ``config`` with defaults filled; GearmeshInputError naming the first bad field."""
    schema = load_schema()
    data = copy.deepcopy(dict(config))
    validator = _with_defaults(jsonschema.Draft202012Validator)(schema)
    errors = sorted(validator.iter_errors(data), key=lambda e: (len(e.path), list(map(str, e.path))))
    if errors:
        err = errors[0]
        field = ".".join(str(p) for p in err.path) or "config"
        raise GearmeshInputError(field, err.instance if err.path else None, err.message)
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
        pair = load_pair(path)
        if pair.name != name:
            raise GearmeshInputError(f"{path}: name", pair.name, f"must equal the file name {name!r}")
        out[name] = pair
    return out


def variant_pair(pair: GearPair, variant: str, spec: Mapping[str, Any]) -> GearPair:
    """``pair`` carrying the modification of micro-geometry ``variant`` (none for 'standard'
    or a variant without one); the variant's modification replaces the pair file's."""
    from .gear import pair_from_dict, pair_to_dict

    data = pair_to_dict(pair)
    data.pop("modification", None)
    if spec.get("modification"):
        data["modification"] = spec["modification"]
    return pair_from_dict(data, source=pair.source)


def check_study(config: Mapping[str, Any], root: str | Path = ".") -> dict[str, GearPair]:
    """Everything a study will need, checked before any job runs (one error, naming the field):
    every pair loads and works, has the material and bore the always-run stiffness stage
    needs, every micro-geometry variant and every stiffness-table variant gives a working
    pair, and sweep ranges are not empty. Returns the pairs."""
    from .datasets.stiffness import apply_variant
    from .gear import pair_geometry
    from .stiffness import require_stiffness_data

    pairs = study_pairs(config, root)
    for name, pair in pairs.items():
        geom = pair_geometry(pair)
        if name in config["pairs"]:
            require_stiffness_data(geom)
        for variant, spec in config.get("variants", {}).items():
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
    if "dynamics" in config and "ltca" in config:
        dyn, ltca = config["dynamics"], config["ltca"]
        for name in config["pairs"]:
            t_d = pinion_torque(pairs[name], dyn.get("torque_Nm", 200.0), dyn.get("on", "gear"))
            if not _among(t_d, pairs[name], ltca):
                raise GearmeshInputError("ltca.torques_Nm", ltca["torques_Nm"],
                                         f"must include the dynamics torque ({dyn.get('torque_Nm', 200.0)} N m on "
                                         f"the {dyn.get('on', 'gear')}): the LTCA excites the dynamics")
    sweep = config.get("helix_sweep")
    if sweep and sweep["stop_deg"] < sweep["start_deg"]:
        raise GearmeshInputError("helix_sweep.stop_deg", sweep["stop_deg"],
                                 f"must not be below start_deg ({sweep['start_deg']})")
    return pairs


def _among(t1: float, pair: GearPair, ltca: Mapping[str, Any]) -> bool:
    """Whether pinion torque ``t1`` is one of the LTCA's torques (as pinion torques)."""
    return any(abs(pinion_torque(pair, t, ltca.get("on", "pinion")) - t1) <= 1e-9 * t1 for t in ltca["torques_Nm"])


def lste_comparison_wanted(config: Mapping[str, Any]) -> bool:
    """The study compares the LTCA with F/K: it runs the LTCA on the standard variant and the
    stiffness stage has an LSTE torque."""
    return "ltca" in config and "standard" in config.get("variants", {}) and "torque_Nm" in config.get("stiffness", {})
