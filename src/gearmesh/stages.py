"""What a workflow stage is, declared once beside its settings (issue 25 item 4).

A stage's declaration is its settings dataclass in :mod:`gearmesh.settings` (its keys: type,
default, bounds, description) with a ``STAGE`` class attribute, a :class:`Stage`: the function
that computes it, the result it writes, the results of other stages it reads (and when), the
figures it draws and the other config sections it takes whole. From that one declaration come

* the study schema, ``gearmesh validate`` and ``config/README.md`` (the settings fields);
* the stage function's defaults and argument checks (:func:`gearmesh.schema.check_arguments`
  fills every setting the caller leaves out from its field and refuses a signature that
  declares a setting's default a second time);
* the Snakemake rule's ``input`` (the pair file and each :class:`Read`), its netCDF ``output``
  and its ``params`` (function, settings, variant, figures), and the study's targets
  (``workflow/rules/common.smk``);
* the config sections a result depends on, which :mod:`gearmesh.upstream` compares when the
  file is read (:func:`dependencies`).

This module imports only :mod:`gearmesh.choices`: the settings import it, and it imports no
settings, so the declarations form no import circle.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable, Literal, Mapping

from .choices import pair_excitation

#: Where a stage's result lives under ``results/{study}/``: once per pair, per micro-geometry
#: variant of a pair, per named run of a pair (optimise), or once per study.
Scope = Literal["pair", "variant", "run", "study"]
#: A condition on the study config under which a stage reads a result (``config``, the section
#: of the reading stage).
When = Callable[[Mapping[str, Any], str], bool]


def always(config: Mapping[str, Any], section: str) -> bool:
    """Read in every study."""
    return True


def method_fe(of: str | None = None) -> When:
    """Read when the tooth model of section ``of`` (default: the reading stage's own) is the
    finite-element tooth: its tables come from the pair's fe_compliance result, computed once."""

    def when(config: Mapping[str, Any], section: str) -> bool:
        return (config.get(of or section) or {}).get("method") == "fe"

    when.__doc__ = f"the {of or 'stage'}'s method is fe"
    return when


def runs(other: str) -> When:
    """Read when the study runs stage ``other`` (has its section)."""

    def when(config: Mapping[str, Any], section: str) -> bool:
        return other in config

    when.__doc__ = f"the study runs {other}"
    return when


def ltca_drives(config: Mapping[str, Any], section: str) -> bool:
    """Read when the LTCA excites the dynamics (:func:`gearmesh.choices.pair_excitation`: the
    section's excitation, or ltca when the study runs the LTCA)."""
    return pair_excitation((config.get(section) or {}).get("excitation"), "ltca" in config) == "ltca"


@dataclass(frozen=True)
class Read:
    """A result of stage ``stage`` that a stage reads (passed to its function under that name),
    of the reading job's own pair (and variant), or with ``every_variant`` the list of every
    variant's of the pair (a table of the variants), ``when`` the study config says so."""

    stage: str
    when: When = always
    every_variant: bool = False


@dataclass(frozen=True)
class Stage:
    """One stage: ``function`` (``module:name``) computes its dataset from the pair (or the
    study's pairs) and its settings; it ``writes`` one netCDF file (a template under
    ``results/{study}/`` with the wildcards of its ``scope``), ``reads`` other stages'
    results, and ``figures`` (``module:name``) draws its pictures from the written file.
    ``carries``: other config sections the function takes whole (the impact stage's
    tolerances), on which its result therefore depends; ``variant_name``: the function also
    takes the variant's name; ``pair_file``: the job reads the pair file (not a table of
    results). ``wanted``: whether a study with this section gets the result
    (default: whenever the section is in the config)."""

    function: str
    writes: str
    scope: Scope
    reads: tuple[Read, ...] = ()
    figures: str | None = None
    carries: tuple[str, ...] = ()
    variant_name: bool = False
    pair_file: bool = True
    wanted: When | None = None

    @property
    def per_variant(self) -> bool:
        """Whether the result depends on the micro-geometry (a variant's)."""
        return self.scope == "variant"

    def path(self, **wildcards: str) -> str:
        """The result's path, ``results/{study}/...`` with the given wildcards filled (others kept)."""
        keep = {k: "{" + k + "}" for k in ("study", "pair", "variant", "run")}
        return "results/{study}/".format(**{**keep, **wildcards}) + self.writes.format(**{**keep, **wildcards})


def dependencies(stage: Stage | None, section: str, config: Mapping[str, Any]) -> list[str]:
    """The config sections a result of ``stage`` (config ``section``) depends on: its own and
    each section it carries that the study has; :mod:`gearmesh.upstream` compares them with
    the reading run's."""
    own = [section] if section in config else []
    carried = sorted(s for s in (stage.carries if stage else ()) if isinstance(config.get(s), Mapping))
    return own + carried
