"""The files published from the declarations of :mod:`gearmesh.settings` and
:mod:`gearmesh.pair_keys`: the study schema (``schemas/config.schema.yaml``), the pair-file
schema (``schemas/pair.schema.json``) and the Markdown reference of every key
(``config/README.md``; the pair file's printed by ``gearmesh schema pair --format markdown``).
``tests/test_settings.py`` checks the published files are these texts.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping
from typing import Any

import yaml

from .pair_keys import PairFile, pair_schema
from .schema import (default_of, description_of, field_schema, has_default, holds_section, key_of, nested_sections,
                     section_type, settings_fields, spec_of, units_of)
from .schema_rules import choices_words, type_words
from .registry import study_schema
from .settings import Study

#: The header of a published file: the module whose declarations it renders (``{source}``) and the command.
_GENERATED = "generated from {source} by `gearmesh schema {what}`: edit the settings, not this file"


def _source(root: type) -> str:
    """The file that declares settings class ``root`` (``gearmesh/settings.py``)."""
    return root.__module__.replace(".", "/") + ".py"


def study_schema_text() -> str:
    """The study schema as published in ``schemas/config.schema.yaml``.

    Returns
    -------
    str
        YAML: a generated-file header comment and the JSON schema of a study config
        (:func:`gearmesh.registry.study_schema`).
    """
    head = f"# The JSON schema of a study config, {_GENERATED.format(source=_source(Study), what='study')}.\n"
    return head + yaml.safe_dump(study_schema(), sort_keys=False, allow_unicode=True, width=110, default_flow_style=None)


def pair_schema_text() -> str:
    """The pair-file schema as published in ``schemas/pair.schema.json``.

    Returns
    -------
    str
        JSON (2-space indent, newline at the end) of :func:`gearmesh.pair_keys.pair_schema`.
    """
    return json.dumps(pair_schema(), indent=2, ensure_ascii=False) + "\n"


def study_reference() -> str:
    """``config/README.md``: every study key, section by section (the Snakemake workflow
    catalog's convention of a config README).

    Returns
    -------
    str
        Markdown: title, introduction, the table of top-level keys and one per nested section.

    References
    ----------
    .. [1] Snakemake workflow catalog, "Standardized usage" rules: a workflow documents its
       configuration in ``config/README.md``. https://snakemake.github.io/snakemake-workflow-catalog/
    """
    return _reference(Study, "Configuration", "study --format markdown", [
        "A study config (`config/config.yaml`, the default study, or one of `config/studies/*.yaml`",
        "with `--configfile`) says which gear pairs to run, which stages and how finely. Run",
        "`gearmesh validate FILE` to check one: it fills the defaults below and refuses a bad key",
        "or value with one line naming it. Gear pairs are files `config/pairs/NAME.yaml`",
        "(`gearmesh schema pair --format markdown` lists their keys). Units are in the key names; a",
        "value left out takes its default; a section left out is a stage that does not run, except",
        "`geometry`, `contact_lines`, `stiffness` and `variants`, which every study has.",
        "",
        "Editors complete and check a config with the schema `workflow/schemas/config.schema.yaml`",
        "(for the YAML language server: `# yaml-language-server: $schema=../workflow/schemas/config.schema.yaml`",
        "as the first line of `config/config.yaml`).",
    ])


def pair_reference() -> str:
    """Every key of a pair file as Markdown tables.

    Returns
    -------
    str
        Markdown: title, introduction, the table of top-level pair keys and one per nested section.
    """
    return _reference(PairFile, "Gear pair files", "pair --format markdown", [
        "A pair file `NAME.yaml` describes one helical gear pair as designed. `gearmesh validate FILE`",
        "checks it, the physics included (contact ratio, interference, centre distance), which no",
        "schema can; editors complete and check its form with `gearmesh schema pair` (JSON schema).",
    ])


def _reference(root: type, title: str, command: str, intro: list[str]) -> str:
    """Markdown: a title, ``intro``, the keys of ``root`` and of each nested section."""
    lines = [f"# {title}", "", f"<!-- {_GENERATED.format(source=_source(root), what=command)} -->", "", *intro, "",
             f"## {'Study' if root is Study else 'Pair'}", "", *markdown_table(root)]
    for path, cls in nested_sections(root):
        lines += ["", f"## `{path}`", "", description_of(cls), "", *markdown_table(cls, prefix=f"{path}.")]
    return "\n".join(lines) + "\n"


# The reference tables of config/README.md (and of the pair file's keys)


def _default_words(field: dataclasses.Field) -> str:
    if not has_default(field):
        return "required"
    if not spec_of(field).fill:
        return "—"
    value = default_of(field)
    return "`" + _flow(value) + "`"


def _flow(value: Any) -> str:
    """A value as YAML flow text."""
    if value is None:
        return "null"
    if value == "":
        return '""'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{k}: {_flow(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    return str(value)


def markdown_table(cls: type, prefix: str = "") -> list[str]:
    """Markdown rows ``| key | type | units | default | description |`` of the settings of ``cls``.

    Nested sections get a row that links to their own table (:func:`gearmesh.schema.nested_sections`
    lists them).

    Parameters
    ----------
    cls : type
        A settings dataclass (:mod:`gearmesh.settings`, :mod:`gearmesh.pair_keys`).
    prefix : str, default ""
        The key path of ``cls`` in its study or pair file, with its trailing dot (``"impact."``).

    Returns
    -------
    list of str
        The table's lines, header first, then "At most one of …" for each group of alternative keys.
    """
    rows = ["| key | type | units | default | description |", "| --- | --- | --- | --- | --- |"]
    for f in settings_fields(cls):
        schema = field_schema(cls, f)
        section = section_type(cls, f)
        kind = "section" if section else type_words(schema).replace("|", "\\|")
        text = spec_of(f).description
        if section:  # its own table follows: a link and its first sentence here
            path = f"{prefix}{key_of(f)}" + ("" if holds_section(cls, f) else ".NAME")
            anchor = "".join(c for c in path.lower() if c.isalnum() or c in "_-")
            text = f"[`{path}`](#{anchor}): " + (text or description_of(section).split(". ")[0].rstrip("."))
        text = text.replace("|", "\\|")
        rows.append(f"| `{prefix}{key_of(f)}` | {kind} | {units_of(f)} | {_default_words(f)} | {text} |")
    for group in getattr(cls, "ALTERNATIVES", ()):
        rows += ["", "At most one of " + choices_words([f"`{prefix}{k}`" for k in group], quote=False) + "."]
    return rows
