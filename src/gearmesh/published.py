"""The files published from the declarations of :mod:`gearmesh.settings` and
:mod:`gearmesh.pair_keys`: the study schema (``schemas/config.schema.yaml``), the pair-file
schema (``schemas/pair.schema.json``) and the Markdown reference of every key
(``config/README.md``; the pair file's printed by ``gearmesh schema pair --format markdown``).
``tests/test_settings.py`` checks the published files are these texts.
"""

from __future__ import annotations

import json

import yaml

from .pair_keys import PairFile, pair_schema
from .schema import description_of, markdown_table, nested_sections
from .settings import Study, study_schema

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
        (:func:`gearmesh.settings.study_schema`).
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
