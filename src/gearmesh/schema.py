"""Typed settings → JSON schema, argument checks and reference tables: one declaration each.

A setting is a field of a frozen dataclass declared with :func:`setting`: its Python type,
default, bounds and description. From that one declaration come

* the JSON schema (:func:`object_schema`) that validates a document and fills its defaults
  (``gearmesh validate``, the Snakefile and editors through the published schema files);
* the refusal of a bad argument of a stage function (:func:`gearmesh.arguments.check_arguments`), with the same
  bounds, so the Python API, the CLI and a study config refuse the same values;
* the reference table of every key (:func:`gearmesh.published.markdown_table`, ``config/README.md``).

The checks gearmesh makes before jsonschema (counts, finite numbers) and the words of a rule (a
refused value's message, the reference tables' type column) live in
:mod:`gearmesh.schema_rules`.

Types map to JSON schema as: ``int`` → integer, ``float`` → number, ``bool`` → boolean,
``str`` → string, ``Literal[...]`` → enum, ``tuple[X, ...]`` → array of X, ``tuple[X, X]``
→ array of exactly two X, ``dict[str, X]`` → object of X, a dataclass → object, ``X | None``
→ X or null, ``X | Y`` → one of X, Y. Numeric bounds apply to every number inside the type
(the items of an array too), item counts to the outermost array, key patterns to the outermost
mapping.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import inspect
import types
import typing
from collections.abc import Mapping
from typing import Any, Literal, Union

from .errors import GearmeshInputError
from .limits import MAX_LIST_ITEMS
from .schema_rules import check_counts, filling_validator, first_non_finite, schema_error

#: Key of a field's :class:`Spec` in ``dataclasses.field(metadata=...)``.
SPEC = "gearmesh"
#: Default of a setting that must be given.
REQUIRED = dataclasses.MISSING

#: Units of a key from its suffix (the convention of config and pair files: the unit is in the name).
UNIT_SUFFIXES = (
    ("_Ns_per_m", "N s/m"), ("_N_per_m", "N/m"), ("_kg_m2", "kg m²"), ("_kg_m3", "kg/m³"), ("_Nm", "N m"),
    ("_rpm", "r/min"), ("_um", "µm"), ("_mm", "mm"), ("_deg", "°"), ("_Hz", "Hz"), ("_GPa", "GPa"),
    ("_percent", "%"), ("_N", "N"),
)


@dataclasses.dataclass(frozen=True)
class Spec:
    """What a setting declares beyond its type and default (:func:`setting`)."""

    description: str
    units: str | None = None
    minimum: float | None = None
    maximum: float | None = None
    exclusive_minimum: float | None = None
    exclusive_maximum: float | None = None
    multiple_of: int | None = None
    min_items: int | None = None
    max_items: int | None = None
    unique: bool = False
    pattern: str | None = None
    max_length: int | None = None
    key_pattern: str | None = None
    key_max_length: int | None = None
    key: str | None = None
    fill: bool = True


def setting(default: Any = REQUIRED, description: str = "", **spec: Any) -> Any:
    """A dataclass field declaring one setting: its default, description and :class:`Spec`.

    Parameters
    ----------
    default : object, default REQUIRED
        :data:`REQUIRED`: must be given; a dict, list or set is copied for each instance.
    description : str, default ""
        A sentence fragment: what it is, what null or a special value means.
    **spec
        The keywords of :class:`Spec`. ``units``: shown in the reference table; by default from the
        key's suffix (:data:`UNIT_SUFFIXES`). ``minimum``, ``maximum``, ``exclusive_minimum``,
        ``exclusive_maximum``, ``multiple_of``: numeric bounds. ``min_items``, ``max_items``,
        ``unique``: of the outermost array. ``pattern``, ``max_length``: of the strings;
        ``key_pattern``, ``key_max_length``: of a mapping's keys. ``key``: the key in the document
        when it is not a Python name (``from``). ``fill``: False when leaving the key out means
        something of its own (no default filled, null not accepted; the Python default is None).

    Returns
    -------
    dataclasses.Field
        The field, its :class:`Spec` in ``metadata[SPEC]``.
    """
    meta = {SPEC: Spec(description=" ".join(description.split()), **spec)}
    if default is REQUIRED:
        return dataclasses.field(metadata=meta)
    if isinstance(default, (dict, list, set)):
        return dataclasses.field(default_factory=lambda: copy.deepcopy(default), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


# --------------------------------------------------------------------------------------
# Reading a declaration
# --------------------------------------------------------------------------------------


def spec_of(field: dataclasses.Field) -> Spec:
    """What a setting declares beyond its type and default.

    Parameters
    ----------
    field : dataclasses.Field
        A setting (:func:`setting`).

    Returns
    -------
    Spec
    """
    return field.metadata[SPEC]


def key_of(field: dataclasses.Field) -> str:
    """The field's key in the document.

    Parameters
    ----------
    field : dataclasses.Field

    Returns
    -------
    str
        ``Spec.key``, else the field's name.
    """
    return spec_of(field).key or field.name


def settings_fields(cls: type) -> list[dataclasses.Field]:
    """The settings of dataclass ``cls``, in declaration order.

    Parameters
    ----------
    cls : type
        A settings dataclass.

    Returns
    -------
    list of dataclasses.Field
    """
    return [f for f in dataclasses.fields(cls) if SPEC in f.metadata]


@functools.cache
def type_hints(cls: type) -> dict[str, Any]:
    """The resolved annotations of ``cls`` (``typing.get_type_hints``), once per class.

    Parameters
    ----------
    cls : type

    Returns
    -------
    dict
        Field name → Python type.
    """
    return typing.get_type_hints(cls)


def has_default(field: dataclasses.Field) -> bool:
    """Whether a setting has a default (a value or a factory), i.e. may be left out.

    Parameters
    ----------
    field : dataclasses.Field

    Returns
    -------
    bool
    """
    return field.default is not dataclasses.MISSING or field.default_factory is not dataclasses.MISSING


def default_of(field: dataclasses.Field) -> Any:
    """The field's default as a document value: tuples as lists, a settings object that is all
    its own defaults as ``{}`` (they are filled inside it), any other in full.

    Parameters
    ----------
    field : dataclasses.Field
        A setting with a default (:func:`has_default`).

    Returns
    -------
    object
        JSON data (:func:`jsonable`).
    """
    value = field.default_factory() if field.default is dataclasses.MISSING else field.default
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        try:
            plain = type(value)()
        except TypeError:  # it has keys that must be given
            plain = None
        return {} if value == plain else jsonable(value)
    return jsonable(value)


def jsonable(value: Any) -> Any:
    """``value`` as JSON data: tuples and arrays as lists, numpy scalars as Python numbers,
    mappings as dicts, a settings object as the mapping of its keys.

    Parameters
    ----------
    value : object
        Any value of a document or of an API call.

    Returns
    -------
    object
        The same value of JSON types (dict, list, str, int, float, bool, None).
    """
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return {key_of(f): jsonable(getattr(value, f.name)) for f in settings_fields(type(value))}
    if isinstance(value, Mapping):
        return {k: jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):  # numpy arrays and scalars
        return jsonable(value.tolist())
    return value


def units_of(field: dataclasses.Field) -> str:
    """The units of a setting: declared, or from its key's suffix, else '' (a count, a name or
    a dimensionless number).

    Parameters
    ----------
    field : dataclasses.Field

    Returns
    -------
    str
        The units as the reference table shows them (``N m``, ``µm``, ``°``).
    """
    spec = spec_of(field)
    if spec.units is not None:
        return spec.units
    key = key_of(field)
    return next((units for suffix, units in UNIT_SUFFIXES if key.endswith(suffix)), "")


# --------------------------------------------------------------------------------------
# JSON schema
# --------------------------------------------------------------------------------------

_SCALARS = {bool: "boolean", int: "integer", float: "number", str: "string"}


def _numeric(spec: Spec) -> dict[str, Any]:
    out = {}
    for attr, word in (("minimum", "minimum"), ("maximum", "maximum"), ("exclusive_minimum", "exclusiveMinimum"),
                       ("exclusive_maximum", "exclusiveMaximum"), ("multiple_of", "multipleOf")):
        if getattr(spec, attr) is not None:
            out[word] = getattr(spec, attr)
    return out


def type_schema(tp: Any, spec: Spec, outer: bool = True) -> dict[str, Any]:
    """JSON schema of Python type ``tp`` with the constraints of ``spec`` (module docstring).

    Parameters
    ----------
    tp : type
        A setting's annotation (``float``, ``tuple[float, ...]``, ``X | None``, a dataclass ...).
    spec : Spec
        Its declaration: bounds, counts, patterns.
    outer : bool, default True
        Whether ``tp`` is the setting's own type (item counts and key patterns apply there only).

    Returns
    -------
    dict
        The schema; every list and mapping capped at ``MAX_LIST_ITEMS`` (:mod:`gearmesh.limits`).

    Raises
    ------
    TypeError
        A type with no JSON schema, or a fixed-length tuple of mixed item types.

    References
    ----------
    .. [1] A. Wright, H. Andrews, B. Hutton, "JSON Schema Validation: A Vocabulary for Structural Validation
       of JSON", IETF draft-bhutton-json-schema-validation-00 (JSON Schema 2020-12), 2020, section 6.
    .. [2] A. Wright, H. Andrews, B. Hutton, G. Dennis, "JSON Schema: A Media Type for Describing JSON
       Documents", IETF draft-bhutton-json-schema-00 (JSON Schema 2020-12), 2020, section 10.
    """
    origin, args = typing.get_origin(tp), typing.get_args(tp)
    if tp is Any:
        return {}
    if tp is type(None):
        return {"type": "null"}
    if origin in (Union, types.UnionType):
        members = [a for a in args if a is not type(None)]
        nullable = len(members) < len(args)
        parts = [type_schema(a, spec, outer) for a in members]
        if len(parts) == 1:
            return _with_null(parts[0]) if nullable else parts[0]
        return {"oneOf": parts + ([{"type": "null"}] if nullable else [])}
    if origin is Literal:
        return {"type": "string", "enum": list(args)}
    if tp in _SCALARS:
        out: dict[str, Any] = {"type": _SCALARS[tp]}
        if tp in (int, float):
            out.update(_numeric(spec))
        if tp is str:
            out.update({k: v for k, v in (("pattern", spec.pattern), ("maxLength", spec.max_length)) if v is not None})
        return out
    if origin in (tuple, list):
        variadic = origin is list or (len(args) == 2 and args[1] is Ellipsis)
        item = args[0]
        if not variadic and any(a != item for a in args):
            raise TypeError(f"{tp}: arrays of one item type only")
        out = {"type": "array", "items": type_schema(item, spec, outer=False)}
        if not variadic:
            out["minItems"] = out["maxItems"] = len(args)
        elif outer:
            for attr, word in (("min_items", "minItems"), ("max_items", "maxItems")):
                if getattr(spec, attr) is not None:
                    out[word] = getattr(spec, attr)
            if spec.unique:
                out["uniqueItems"] = True
        if variadic:  # every list has a length limit (gearmesh.limits)
            out.setdefault("maxItems", MAX_LIST_ITEMS)
        return out
    if origin in (dict, Mapping, typing.Mapping) or tp is dict:
        value = args[1] if args else Any
        out = {"type": "object", "maxProperties": MAX_LIST_ITEMS}
        if value is not Any:
            out["additionalProperties"] = type_schema(value, spec, outer=False)
        names = {k: v for k, v in (("pattern", spec.key_pattern), ("maxLength", spec.key_max_length)) if v is not None}
        if names and outer:
            out["propertyNames"] = names
        return out
    if dataclasses.is_dataclass(tp):
        return object_schema(tp)
    raise TypeError(f"no JSON schema for the type {tp!r}")


def _with_null(schema: dict[str, Any]) -> dict[str, Any]:
    out = dict(schema)
    if "enum" in out:
        out["enum"] = out["enum"] + [None]
    kind = out.get("type")
    if kind is None:
        return {"oneOf": [schema, {"type": "null"}]}
    out["type"] = [kind, "null"] if isinstance(kind, str) else [*kind, "null"]
    return out


def field_schema(cls: type, field: dataclasses.Field) -> dict[str, Any]:
    """JSON schema of one setting of ``cls``: type, bounds, description and default.

    Parameters
    ----------
    cls : type
    field : dataclasses.Field

    Returns
    -------
    dict
        Its :func:`type_schema`, ``description`` and ``default`` (:func:`default_of`; none where ``fill`` is False).
    """
    spec = spec_of(field)
    tp = type_hints(cls)[field.name]
    if not spec.fill:  # absent means "not given": the key may be left out, not set to null
        args = typing.get_args(tp)
        if typing.get_origin(tp) in (Union, types.UnionType) and type(None) in args:
            members = tuple(a for a in args if a is not type(None))
            tp = members[0] if len(members) == 1 else Union[members]
    out = type_schema(tp, spec)
    if spec.description:
        out = {**out, "description": spec.description}
    if spec.fill and has_default(field):
        out["default"] = default_of(field)
    return out


def object_schema(cls: type) -> dict[str, Any]:
    """JSON schema of settings dataclass ``cls``: no unknown key, its required keys, each
    setting's :func:`field_schema`, and at most one key of each group of its ``ALTERNATIVES``
    (keys that give the same quantity) other than null; described by the first paragraph of its
    docstring.

    Parameters
    ----------
    cls : type

    Returns
    -------
    dict
        An ``object`` schema: ``additionalProperties`` false, ``required``, ``properties``, ``allOf``.
    """
    fields = settings_fields(cls)
    out: dict[str, Any] = {"type": "object", "additionalProperties": False}
    doc = description_of(cls)
    if doc:
        out["description"] = doc
    required = [key_of(f) for f in fields if not has_default(f)]
    if required:
        out["required"] = required
    out["properties"] = {key_of(f): field_schema(cls, f) for f in fields}
    exclusive = [(a, b) for group in getattr(cls, "ALTERNATIVES", ()) for i, a in enumerate(group) for b in group[i + 1:]]
    if exclusive:  # two keys of one group both given (not null): refused
        out["allOf"] = [{"not": {"required": [a, b], "properties": {a: {"not": {"type": "null"}},
                                                                     b: {"not": {"type": "null"}}}}}
                        for a, b in exclusive]
    return out


def description_of(cls: type) -> str:
    """The first paragraph of ``cls``'s own docstring, on one line.

    Parameters
    ----------
    cls : type
        A class (its own docstring: none inherited).

    Returns
    -------
    str
    """
    doc = cls.__dict__.get("__doc__") or ""
    return " ".join(inspect.cleandoc(doc).split("\n\n")[0].split())


# --------------------------------------------------------------------------------------
# Validation with defaults, and the refusal of one bad value
# --------------------------------------------------------------------------------------


def validate(data: Mapping[str, Any], schema: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """A copy of ``data`` with the defaults of ``schema`` filled; GearmeshInputError naming the
    first bad field (a NaN or infinite number anywhere, then the schema's first error).

    Parameters
    ----------
    data : Mapping
        The document (a config section, a pair file, an API call's keywords).
    schema : Mapping
        Its JSON schema (:func:`object_schema`).
    prefix : str, default ""
        The key path of ``data`` in its file: bad fields are named ``prefix.KEY``.

    Returns
    -------
    dict
        The validated copy as JSON data, defaults filled at every depth
        (:func:`gearmesh.schema_rules.filling_validator`).

    Raises
    ------
    GearmeshInputError
        ``field`` the key path of the first bad value: a list or mapping over its count
        (:func:`gearmesh.schema_rules.check_counts`), a NaN or infinite number ("must be a finite
        number"), then the first schema error, shallowest first (:func:`gearmesh.schema_rules.schema_error`).
    """
    import jsonschema

    check_counts(data, schema, prefix)  # O(1) per list before any list is read through
    bad = first_non_finite(data, prefix)
    if bad:
        raise GearmeshInputError(bad[0], bad[1], "must be a finite number")
    out = copy.deepcopy(jsonable(dict(data)))
    validator = filling_validator(jsonschema.Draft202012Validator)(schema)
    errors = sorted(validator.iter_errors(out), key=lambda e: (len(e.path), list(map(str, e.path))))
    if errors:
        raise schema_error(errors[0], prefix)
    for _ in validator.iter_errors(out):  # fill a second time: nested defaults of objects the first pass created
        pass
    return out


def section_keys(cls: type) -> tuple[str, ...]:
    """The config keys of settings class ``cls``'s section (its fields' names in the config).

    Parameters
    ----------
    cls : type

    Returns
    -------
    tuple of str
    """
    return tuple(key_of(f) for f in settings_fields(cls))


def settings_object(cls: type, data: Mapping[str, Any] | None, prefix: str = "") -> Any:
    """``data`` (a study's section, or the keywords of an API call) as the frozen settings object
    ``cls``: validated against its declaration with its defaults filled (:func:`validate`; a bad
    value named ``prefix.KEY``), lists as tuples, a nested section as its own object. The one parse
    of a section that every door shares.

    Parameters
    ----------
    cls : type
    data : Mapping or None
        The section (None: all defaults).
    prefix : str, default ""
        The section's key path in its file (``optimise``).

    Returns
    -------
    cls

    Raises
    ------
    GearmeshInputError
        ``field`` ``prefix.KEY`` of the first bad value (:func:`validate`).
    """
    return _settings_instance(cls, validate(data or {}, object_schema(cls), prefix))


def _settings_instance(cls: type, values: Mapping[str, Any]) -> Any:
    """The settings object ``cls`` of validated ``values`` (keys left out: the field's default)."""
    given = {}
    for f in settings_fields(cls):
        if key_of(f) not in values:
            continue
        value, inner = values[key_of(f)], section_type(cls, f)
        if inner is not None and isinstance(value, Mapping):
            held = type_hints(cls)[f.name]
            named = any(typing.get_origin(t) in (dict, Mapping) for t in (held, *typing.get_args(held)))
            value = {k: _settings_instance(inner, v) for k, v in value.items()} if named else \
                _settings_instance(inner, value)
        given[f.name] = _frozen(value)
    return cls(**given)


def _frozen(value: Any) -> Any:
    """Lists as tuples, at every depth (mappings stay mappings)."""
    if isinstance(value, list):
        return tuple(_frozen(v) for v in value)
    if isinstance(value, dict):
        return {k: _frozen(v) for k, v in value.items()}
    return value


def check_value(cls: type, key: str, value: Any) -> None:
    """Refuse ``value`` of setting ``key`` of ``cls`` unless its declaration accepts it
    (GearmeshInputError naming the key).

    Parameters
    ----------
    cls : type
    key : str
        The setting's key in the document (:func:`key_of`).
    value : object
        The value given.

    Raises
    ------
    GearmeshInputError
        ``field`` ``key`` (or a path inside it), ``rule`` the bound it breaks (:func:`validate`).
    """
    field = next(f for f in settings_fields(cls) if key_of(f) == key)
    schema = {"type": "object", "properties": {key: field_schema(cls, field)}}
    validate({key: value}, schema)


def defaults(cls: type) -> dict[str, Any]:
    """The filled defaults of settings dataclass ``cls`` as a document (keys that must be given
    and keys without a default are left out).

    Parameters
    ----------
    cls : type

    Returns
    -------
    dict
        Key → default as JSON data; a nested section as its own defaults.
    """
    out = {}
    for f in settings_fields(cls):
        if has_default(f) and spec_of(f).fill:
            value = f.default_factory() if f.default is dataclasses.MISSING else f.default
            out[key_of(f)] = defaults(type(value)) if dataclasses.is_dataclass(value) else jsonable(value)
    return out


def holds_section(cls: type, field: dataclasses.Field) -> bool:
    """Whether a field holds one settings object (directly or optionally), not a mapping of them.

    Parameters
    ----------
    cls : type
    field : dataclasses.Field

    Returns
    -------
    bool
        True for ``X`` or ``X | None`` with ``X`` a dataclass.
    """
    tp = type_hints(cls)[field.name]
    members = typing.get_args(tp) if typing.get_origin(tp) in (Union, types.UnionType) else (tp,)
    return any(dataclasses.is_dataclass(m) for m in members)


def section_type(cls: type, field: dataclasses.Field) -> type | None:
    """The settings dataclass a field holds (directly, optionally, or as the values of a
    mapping of named entries), else None.

    Parameters
    ----------
    cls : type
    field : dataclasses.Field

    Returns
    -------
    type or None
    """
    tp = type_hints(cls)[field.name]
    for candidate in (tp, *typing.get_args(tp)):
        if dataclasses.is_dataclass(candidate):
            return candidate
        inner = typing.get_args(candidate)
        if typing.get_origin(candidate) in (dict, Mapping, typing.Mapping) and inner and dataclasses.is_dataclass(inner[-1]):
            return inner[-1]
    return None


def nested_sections(cls: type, prefix: str = "") -> list[tuple[str, type]]:
    """(key path, dataclass) of every settings object inside ``cls``, depth first; a mapping of
    named entries appears as ``KEY.NAME``.

    Parameters
    ----------
    cls : type
    prefix : str, default ""
        Put before every path (``KEY.``).

    Returns
    -------
    list of (str, type)
        Key path and settings dataclass of each section.
    """
    out = []
    for f in settings_fields(cls):
        sub = section_type(cls, f)
        if sub is None:
            continue
        path = f"{prefix}{key_of(f)}" + ("" if holds_section(cls, f) else ".NAME")
        out.append((path, sub))
        out += nested_sections(sub, path + ".")
    return out


def all_keys(cls: type, prefix: str = "") -> list[str]:
    """Every key path of ``cls`` and its nested settings (``a.b.c``; named entries as ``NAME``).

    Parameters
    ----------
    cls : type
    prefix : str, default ""
        Put before every path.

    Returns
    -------
    list of str
        The key paths, ``cls``'s own first.
    """
    keys = [f"{prefix}{key_of(f)}" for f in settings_fields(cls)]
    for path, sub in nested_sections(cls, prefix):
        keys += [f"{path}.{key_of(f)}" for f in settings_fields(sub)]
    return keys
