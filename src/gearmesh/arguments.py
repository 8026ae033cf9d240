"""A stage function's arguments checked against its settings' declaration (:mod:`gearmesh.settings`):
the declared defaults filled, every given value checked as the schema checks it, another pair's
upstream dataset refused and the result stamped with its pair (:mod:`gearmesh.upstream`).

Apart from :mod:`gearmesh.schema`, which declares and validates and knows no datasets: the argument
checks reach up to the provenance checks of :mod:`gearmesh.upstream`, which read the pair file.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import inspect
from collections.abc import Mapping
from typing import Any, Callable

from .schema import check_value, default_of, has_default, jsonable, key_of, settings_fields, spec_of
from .upstream import check_dataset_pair, stamp_pair

__all__ = ["check_arguments"]


def check_arguments(cls: type, exclude: tuple[str, ...] = ()) -> Callable[[Callable], Callable]:
    """Decorator of a function whose keyword arguments are the settings of ``cls``: the one
    declaration gives their defaults and their checks.

    * A setting the function names without a default (keyword-only) takes the declared one when the
      caller leaves it out; the function's ``__signature__`` shows it. A default written in the
      signature as well must be the declared one (TypeError at import otherwise), so the two cannot differ.
    * Arguments given are checked against their declarations before the function runs
      (:func:`check_value`), so the API refuses what the schema refuses, with the same bounds.
    * The stage's own function (``cls.STAGE.function``, :mod:`gearmesh.stages`) must take every
      setting, each result it reads and each section it carries (TypeError at import).
    * Another pair's upstream dataset is refused (:mod:`gearmesh.upstream`) and the result is
      stamped with the pair it was computed for.

    Parameters
    ----------
    cls : type
    exclude : tuple of str, default ()
        Keys the function checks itself (a section it parses whole): left to the function.

    Returns
    -------
    callable
        The decorator; the function it returns carries ``__settings__ = cls``.

    Raises
    ------
    GearmeshInputError
        At a call: ``field`` the argument's key, ``rule`` the bound it breaks (:func:`check_value`).
        (TypeError at import: the rules above.)
    """
    fields = {key_of(f): f for f in settings_fields(cls)}
    keys = set(fields) - set(exclude)
    stage = getattr(cls, "STAGE", None)

    def decorate(func: Callable) -> Callable:
        signature = inspect.signature(func)
        params = signature.parameters
        _check_own_stage(cls, stage, func, params, fields)
        filled = {n: _argument_default(fields[n]) for n, p in params.items()
                  if n in fields and p.default is p.empty and has_default(fields[n])}
        for name, p in params.items():
            if name in fields and p.default is not p.empty and not _same_default(fields[name], p.default):
                raise TypeError(f"{func.__qualname__}: {name} = {p.default!r} differs from the declared "
                                f"{cls.__name__}.{name} = {default_of(fields[name])!r}; leave the default to the "
                                "declaration (gearmesh.settings)")
            if name in filled and p.kind is not p.KEYWORD_ONLY:
                raise TypeError(f"{func.__qualname__}: {name} takes its default from {cls.__name__}: make it "
                                "keyword-only (after *)")
        names = [n for n in params if n in keys]
        none = {n for n, p in params.items() if p.default is None} | {n for n, v in filled.items() if v is None}
        extra = next((n for n, p in params.items() if p.kind is p.VAR_KEYWORD), None)

        @functools.wraps(func)
        def checked(*args: Any, **kwargs: Any) -> Any:
            given = signature.bind_partial(*args, **kwargs).arguments
            for name, value in [*((n, given[n]) for n in names if n in given),
                                *((k, v) for k, v in given.get(extra, {}).items() if k in keys)]:
                if value is None and name in none:
                    continue  # the function's own "none" (no mutable default): e.g. no bounds, no constraints
                check_value(cls, name, value)
            kwargs.update({n: copy.deepcopy(v) for n, v in filled.items() if n not in given})
            pair = given.get("pair")
            datasets = {n: v for n, v in given.items() if _is_dataset(v)} if pair is not None else {}
            if datasets:  # another pair's upstream dataset refused (gearmesh.upstream)
                for name, value in datasets.items():
                    check_dataset_pair(name, value, pair)
            out = func(*args, **kwargs)
            if pair is not None and _is_dataset(out) and hasattr(pair, "modification"):
                stamp_pair(out, pair, bool(stage is not None and stage.per_variant))
            return out

        checked.__settings__ = cls
        checked.__signature__ = signature.replace(parameters=[
            p.replace(default=filled[n]) if n in filled else p for n, p in params.items()])
        return checked

    return decorate


def _argument_default(field: dataclasses.Field) -> Any:
    """A setting's default as a function receives it: None where leaving the key out means
    something of its own (``fill=False``), a settings object as its mapping, else the value."""
    if not spec_of(field).fill:
        return None
    value = field.default_factory() if field.default is dataclasses.MISSING else field.default
    return default_of(field) if dataclasses.is_dataclass(value) else value


def _same_default(field: dataclasses.Field, given: Any) -> bool:
    """A default written in a signature is the declared one: equal as JSON data; None stands
    for an empty mapping (no mutable default) and for a key whose absence means none."""
    declared = jsonable(_argument_default(field))
    return declared == jsonable(given) or (given is None and declared in ({}, None))


def _check_own_stage(cls: type, stage: Any, func: Callable, params: Mapping[str, inspect.Parameter],
                     fields: Mapping[str, dataclasses.Field]) -> None:
    """The stage's own function takes every setting, every result the stage reads and every
    section it carries (:class:`gearmesh.stages.Stage`), by name or through ``**``."""
    if stage is None or stage.function != f"{func.__module__}:{func.__name__}":
        return
    if any(p.kind is p.VAR_KEYWORD for p in params.values()):
        return
    wanted = [*fields, *(r.stage for r in stage.reads), *stage.carries, *(["variant"] if stage.variant_name else [])]
    missing = [n for n in wanted if n not in params]
    if missing:
        raise TypeError(f"{stage.function} does not take {missing}, which {cls.__name__}'s stage declares "
                        "(gearmesh.settings)")


def _is_dataset(value: Any) -> bool:
    """Whether ``value`` is an xarray Dataset (without importing xarray)."""
    return type(value).__name__ == "Dataset" and hasattr(value, "data_vars") and hasattr(value, "attrs")
