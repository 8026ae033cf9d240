"""The study's registry: what the declarations of :mod:`gearmesh.settings` add up to.

The study schema (published by :mod:`gearmesh.published`, validated against by
:mod:`gearmesh.config`), the sections of a study, its stages by config section (the workflow's
rules, :mod:`gearmesh.plan`, :mod:`gearmesh.pipeline`) and every key path. Each is derived from
the settings classes (:class:`gearmesh.settings.Study` and the sections it holds), never declared
again here. Split out of :mod:`gearmesh.settings` so that module stays the declarations only; it
imports :mod:`gearmesh.settings`, :mod:`gearmesh.schema` and :mod:`gearmesh.stages`, and none of
them imports it.
"""

from __future__ import annotations

from typing import Any

from .schema import all_keys, nested_sections, object_schema
from .settings import Study
from .stages import Stage, Table


def study_schema() -> dict[str, Any]:
    """The JSON schema of a study config (:class:`gearmesh.settings.Study`).

    Returns
    -------
    dict
        A JSON Schema (draft 2020-12) object: ``$schema``, ``title`` and the properties, defaults,
        bounds and descriptions of every key, as ``gearmesh schema study`` prints them.
    """
    return {"$schema": "https://json-schema.org/draft/2020-12/schema", "title": "gearmesh study config",
            **object_schema(Study)}


def stage_sections() -> list[tuple[str, type]]:
    """(key path, settings class) of every section of a study.

    Returns
    -------
    list of (str, type)
        Key path (``dynamics``, ``dynamics.speeds_rpm``; named entries as ``optimise.NAME``) and the
        settings class declaring that section, in the order of :class:`gearmesh.settings.Study`.
    """
    return nested_sections(Study)


def stages() -> dict[str, Stage]:
    """Every stage of a study by its config section (and rule name): the declaration
    (:class:`gearmesh.stages.Stage`) of each settings class that has one.

    Returns
    -------
    dict of str to Stage
        Top-level config section (``stiffness``, ``optimise``) to its ``STAGE``, in the order of
        :class:`gearmesh.settings.Study`.
    """
    return {path.removesuffix(".NAME"): cls.STAGE for path, cls in stage_sections()
            if "." not in path.removesuffix(".NAME") and isinstance(getattr(cls, "STAGE", None), Stage)}


def stage_of(section: str) -> Stage | None:
    """The stage of config ``section`` (a rule's name), or None (a table, a figure).

    Parameters
    ----------
    section : str
        A top-level config section, which is also the name of its rule (``ltca``).

    Returns
    -------
    Stage or None
        Its declaration; None for a name that is no stage's section.
    """
    return stages().get(section)


def job_of(name: str) -> Stage | Table | None:
    """The job whose rule is ``name``: the stage of that config section, or the table of that name.

    Parameters
    ----------
    name : str
        A rule's name: a stage's config section (``dynamics``) or a table's name (``engagement_table``).

    Returns
    -------
    Stage or Table or None
        The declaration that rule runs; None for a name no stage or table declares.
    """
    declared = stages()
    if name in declared:
        return declared[name]
    return next((t for stage in declared.values() for t in stage.tables if t.name == name), None)


def study_keys() -> list[str]:
    """Every key path of a study config (``dynamics.speeds_rpm.start``; named entries as ``NAME``).

    Returns
    -------
    list of str
        Dotted key paths of every setting, sections and their fields, as the schema declares them.
    """
    return all_keys(Study)
