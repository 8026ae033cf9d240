"""The rules of a JSON schema document: the ones gearmesh checks before jsonschema reads a
document (counts in O(1), finite numbers), a jsonschema error as one GearmeshInputError line, and
the rules in words for the type column of the reference tables (:mod:`gearmesh.published`).

Error and table say a rule the same way (``must be at least 1``, ``integer (≥ 1)``), so the
message of a refused value reads like the row of the table that declares it. Knows JSON schema
documents only, not the settings declarations (:mod:`gearmesh.schema` builds the schemas and
imports this module).
"""

from __future__ import annotations

import copy
import functools
import math
from collections.abc import Mapping
from typing import Any

from .errors import GearmeshInputError, unknown_key_rule


def _field(parts: list[Any]) -> str:
    """A key path as the error names it: ``optimise.best.modify[0]``."""
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out


_ARTICLES = {"integer": "an integer", "number": "a number", "string": "a string", "array": "a list",
             "object": "a mapping", "boolean": "true or false", "null": "null"}


def _rule(err) -> str:
    """The rule a jsonschema error says was broken, in the words of the reference tables."""
    kind, limit = err.validator, err.validator_value
    if kind == "type":
        kinds = [limit] if isinstance(limit, str) else list(limit)
        return "must be " + " or ".join(_ARTICLES.get(k, k) for k in kinds)
    words = {"minimum": "at least", "maximum": "at most", "exclusiveMinimum": "above", "exclusiveMaximum": "below"}
    if kind in words:
        return "must be positive" if kind == "exclusiveMinimum" and limit == 0 else f"must be {words[kind]} {_number(limit)}"
    if kind == "multipleOf":
        return f"must be a multiple of {limit}"
    if kind == "enum":
        return f"must be one of {choices_words(limit)}"
    if kind == "minItems":
        return f"must have at least {limit} item{'s' if limit != 1 else ''}"
    if kind == "maxItems":
        return f"must have at most {limit} item{'s' if limit != 1 else ''}"
    if kind == "maxProperties":
        return f"must have at most {limit} keys"
    if kind == "uniqueItems":
        return "must not repeat an item"
    if kind == "pattern":
        return f"{'names ' if 'propertyNames' in err.schema_path else ''}must match {limit}"
    if kind == "maxLength":
        return f"{'names ' if 'propertyNames' in err.schema_path else ''}must be at most {limit} characters"
    if kind == "oneOf":
        return "must be " + choices_words([_alternative(sub) for sub in limit], quote=False)
    message, head = err.message, repr(err.instance)
    return message[len(head):].strip() if message.startswith(head) else message


def choices_words(values: list[Any], quote: bool = True) -> str:
    """``a, b or c``: values as a reader writes them (null, not None).

    Parameters
    ----------
    values : list
        The values, at least one (an ``enum``'s, or words already written).
    quote : bool, default True
        Show strings as their repr (``'pair'``); False writes them as given.

    Returns
    -------
    str
        The values joined by commas, the last by "or".
    """
    words = ["null" if v is None else repr(v) if quote and isinstance(v, str) else str(v) for v in values]
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


def _alternative(schema: Mapping[str, Any]) -> str:
    """One alternative of a ``oneOf`` in words: ``a number ≥ 0``, ``'pair'``, ``null``."""
    if "enum" in schema:
        return choices_words(schema["enum"])
    kind = schema.get("type")
    if not isinstance(kind, str):
        return type_words(schema)
    bounds = _bound_words(schema)
    return _ARTICLES.get(kind, kind) + (" " + bounds.strip(" ()").replace(", ", " and ") if bounds else "")


def schema_error(err, prefix: str = "") -> GearmeshInputError:
    """One jsonschema error as the field it is about (``a.b[0]``, an unknown or missing key
    named itself) and the rule it breaks (:func:`_rule`). A value that fails every alternative of
    a ``oneOf`` but has the type of exactly one is judged by that one (``speeds_rpm.start``
    must be positive, not "must be a mapping or a list").

    Parameters
    ----------
    err : jsonschema.exceptions.ValidationError
        The error, as ``Validator.iter_errors`` yields it.
    prefix : str, default ""
        The key path of the validated document inside its file (``optimise``), put before
        the error's own path.

    Returns
    -------
    GearmeshInputError
        ``field``: the key path (``config`` for the document itself); ``value``: the value
        refused (None for a missing key); ``rule``: "is required", "unknown key; ..." or the
        broken keyword in words (``must be at least 1``).

    References
    ----------
    .. [1] A. Wright, H. Andrews, B. Hutton, "JSON Schema Validation: A Vocabulary for
       Structural Validation of JSON", draft-bhutton-json-schema-validation-00 (JSON Schema
       draft 2020-12), IETF Internet-Draft, 2020, section 6 (the keywords put in words).
    .. [2] A. Wright, H. Andrews, B. Hutton, G. Dennis, "JSON Schema: A Media Type for
       Describing JSON Documents", draft-bhutton-json-schema-00 (JSON Schema draft 2020-12),
       IETF Internet-Draft, 2020, section 10 (``oneOf``, ``properties``,
       ``additionalProperties``).
    .. [3] jsonschema (Python package) documentation, "Handling Validation Errors"
       (``ValidationError``: ``validator``, ``validator_value``, ``absolute_path``,
       ``context``), https://python-jsonschema.readthedocs.io.
    """
    alternative = _matching_alternative(err)
    if alternative is not None:
        return schema_error(alternative, prefix)
    path = ([prefix] if prefix else []) + list(err.absolute_path)
    instance = err.instance
    if err.validator == "additionalProperties" and err.validator_value is False and isinstance(instance, Mapping):
        extra = sorted((k for k in instance if k not in err.schema.get("properties", {})), key=str)
        if extra:
            rule = unknown_key_rule(extra[0], err.schema.get("properties", {}), "gearmesh schema study --format markdown")
            if isinstance(extra[0], bool):
                rule = rule.replace("unknown key", "unknown key (YAML 1.1 reads on/off/yes/no as true/false: quote the "
                                                   "key, e.g. \"on\")", 1)
            return GearmeshInputError(_field(path + [str(extra[0])]), instance[extra[0]], rule)
    if err.validator == "required" and isinstance(instance, Mapping):
        missing = [k for k in err.validator_value if k not in instance]
        if missing:
            return GearmeshInputError(_field(path + [missing[0]]), None, "is required")
    return GearmeshInputError(_field(path) or "config", instance if path else None, _rule(err))


def _matching_alternative(err):
    """The first error of the one ``oneOf`` alternative whose type the value has, or None."""
    if err.validator != "oneOf" or not err.context:
        return None
    by_alternative: dict[int, list] = {}
    for sub in err.context:
        by_alternative.setdefault(sub.relative_schema_path[0], []).append(sub)
    typed = [subs for subs in by_alternative.values()
             if not any(e.validator in ("type", "enum") and not e.relative_path for e in subs)]
    if len(typed) != 1:
        return None
    return sorted(typed[0], key=lambda e: (len(e.relative_path), list(map(str, e.relative_path))))[0]


@functools.lru_cache(maxsize=None)
def filling_validator(validator_class):
    """A validator that fills ``default`` values while it validates (jsonschema FAQ recipe); the
    class made once per validator class (making one costs a millisecond, and every setting checked
    made one).

    Parameters
    ----------
    validator_class : type
        A jsonschema validator class (``jsonschema.Draft202012Validator``).

    Returns
    -------
    type
        The class extended so that ``properties`` first sets each absent key that has a
        ``default`` (a deep copy), then validates.

    References
    ----------
    .. [1] jsonschema (Python package) documentation, FAQ: "Why doesn't my schema's default property set
       the default on my instance?", https://python-jsonschema.readthedocs.io.
    .. [2] A. Wright, H. Andrews, B. Hutton, "JSON Schema Validation: A Vocabulary for Structural Validation
       of JSON", IETF draft-bhutton-json-schema-validation-00 (JSON Schema 2020-12), 2020, section 9.2
       (``default`` is an annotation: a validator leaves the instance alone unless extended).
    """
    validate_properties = validator_class.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, schema):
        if isinstance(instance, dict):
            for name, sub in properties.items():
                if "default" in sub and name not in instance:
                    instance[name] = copy.deepcopy(sub["default"])
        yield from validate_properties(validator, properties, instance, schema)

    import jsonschema

    return jsonschema.validators.extend(validator_class, {"properties": set_defaults})


def first_non_finite(data: Any, path: str = "") -> tuple[str, float] | None:
    """The path and value of the first NaN or infinite number in nested data (JSON schema
    numbers accept both; no setting may be either).

    Parameters
    ----------
    data : object
        Nested mappings, lists and numbers.
    path : str, default ""
        The key path of ``data`` (``optimise``).

    Returns
    -------
    tuple of (str, float) or None
        The key path (``config`` for ``data`` itself) and the number; None if every number is finite.
    """
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


def _alternatives(schema: Mapping[str, Any]) -> list[Mapping[str, Any]]:
    return [schema, *schema.get("oneOf", ()), *schema.get("anyOf", ())]


def check_counts(data: Any, schema: Mapping[str, Any], prefix: str = "") -> None:
    """Refuse a list with more items (a mapping with more keys) than ``schema`` allows anywhere
    in ``data``, measuring each by its length before reading any item (GearmeshInputError naming
    the field and the count), so a list of 10⁷ values costs no more to refuse than one of 10³.
    Items are visited only inside lists already within their limit.

    Parameters
    ----------
    data : object
        The document.
    schema : Mapping
        Its JSON schema (``maxItems``, ``maxProperties``, inside ``oneOf``/``anyOf`` too).
    prefix : str, default ""
        The key path of ``data`` in its file.

    Raises
    ------
    GearmeshInputError
        ``field`` the list's or mapping's key path (``config`` for ``data`` itself), ``value``
        its count, ``rule`` "must have at most N items" (or keys).
    """
    stack = [(prefix, data, schema)]
    while stack:
        where, value, sub = stack.pop()
        if not isinstance(sub, Mapping):
            continue
        field = where or "config"
        if isinstance(value, Mapping):
            limits = [a["maxProperties"] for a in _alternatives(sub) if "maxProperties" in a]
            if limits and len(value) > max(limits):
                raise GearmeshInputError(field, f"{len(value)} keys", f"must have at most {max(limits)} keys "
                                         "(gearmesh.limits)")
            for alt in _alternatives(sub):
                props, extra = alt.get("properties", {}), alt.get("additionalProperties")
                for key, item in value.items():
                    inner = props.get(key, extra if isinstance(extra, Mapping) else None)
                    if inner is not None:
                        stack.append((f"{where}.{key}" if where else str(key), item, inner))
        elif isinstance(value, (list, tuple)) or (hasattr(value, "__len__") and hasattr(value, "shape")):
            limits = [a["maxItems"] for a in _alternatives(sub) if "maxItems" in a]
            if limits and len(value) > max(limits):
                raise GearmeshInputError(field, f"{len(value)} items", f"must have at most {max(limits)} items "
                                         "(gearmesh.limits)")
            items = next((a["items"] for a in _alternatives(sub) if isinstance(a.get("items"), Mapping)), None)
            if items is not None and isinstance(value, (list, tuple)):
                stack += [(f"{where}[{k}]", v, items) for k, v in enumerate(value)]


def type_words(schema: Mapping[str, Any]) -> str:
    """A short reader's description of a schema's type and bounds: ``integer (≥ 1)``,
    ``list of 2 numbers``, ``mapping of number``, `` `a` / `b` / null``.

    Parameters
    ----------
    schema : Mapping
        A JSON schema (``type``, ``enum``, ``oneOf``, bounds, ``items``,
        ``additionalProperties``).

    Returns
    -------
    str
        The words, "any" for a schema without a type.

    References
    ----------
    .. [1] A. Wright, H. Andrews, B. Hutton, "JSON Schema Validation: A Vocabulary for
       Structural Validation of JSON", draft-bhutton-json-schema-validation-00 (JSON Schema
       draft 2020-12), IETF Internet-Draft, 2020, section 6.
    """
    if "oneOf" in schema:
        return " or ".join(type_words(s) for s in schema["oneOf"])
    kind = schema.get("type")
    kinds = [kind] if isinstance(kind, str) else list(kind or [])
    words = []
    if "enum" in schema:
        words.append(" / ".join("null" if v is None else f"`{v}`" for v in schema["enum"]))
    else:
        for k in kinds:
            if k == "array":
                words.append(_array_words(schema))
            elif k == "object":
                values = schema.get("additionalProperties")
                words.append("mapping" + (f" of {type_words(values)}" if isinstance(values, Mapping) else ""))
            elif k == "null":
                words.append("null")
            else:
                words.append(k + _bound_words(schema))
    return " or ".join(words) if words else "any"


def _number(value: float) -> str:
    """A bound as written: integers whole, other numbers short."""
    return str(value) if isinstance(value, int) else f"{value:g}"


def _bound_words(schema: Mapping[str, Any]) -> str:
    lo = (f"≥ {_number(schema['minimum'])}" if "minimum" in schema else
          f"> {_number(schema['exclusiveMinimum'])}" if "exclusiveMinimum" in schema else "")
    hi = (f"≤ {_number(schema['maximum'])}" if "maximum" in schema else
          f"< {_number(schema['exclusiveMaximum'])}" if "exclusiveMaximum" in schema else "")
    parts = [p for p in (lo, hi) if p]
    if "multipleOf" in schema:
        parts.append(f"multiple of {schema['multipleOf']}")
    if "pattern" in schema:
        parts.append(f"matching `{schema['pattern']}`")
    if "maxLength" in schema:
        parts.append(f"at most {schema['maxLength']} characters")
    return f" ({', '.join(parts)})" if parts else ""


def _array_words(schema: Mapping[str, Any]) -> str:
    lo, hi = schema.get("minItems"), schema.get("maxItems")
    count = (f"{lo}" if lo is not None and lo == hi else f"{lo}–{hi}" if lo is not None and hi is not None
             else f"≥ {lo}" if lo is not None else f"≤ {hi}" if hi is not None else "")
    item = type_words(schema.get("items", {}))
    head, _, rest = item.partition(" ")
    if head in ("integer", "number", "string", "list", "mapping"):
        item = f"{head}s{' ' + rest if rest else ''}"
    unique = ", distinct" if schema.get("uniqueItems") else ""
    return f"list of {count + ' ' if count else ''}{item}{unique}"
