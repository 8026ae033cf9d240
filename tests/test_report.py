"""The report's landing page and captions, rendered as ``snakemake --report`` renders them (Jinja,
then reStructuredText) for every study config: no markup error, tables as tables, and the
reader's language (documents by title or subject, no "seed 00x", no "withheld", no raw
sub- or superscript markup such as K_s·δ^n)."""

from __future__ import annotations

import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr
from docutils.core import publish_parts
from jinja2 import Environment

from gearmesh import plan
from gearmesh.config import load_study
from gearmesh.io import variable
from gearmesh.tables import write_csv

# Snakemake renders captions with docutils' publish_parts(writer_name="html"), deprecated in docutils 0.22
pytestmark = pytest.mark.filterwarnings("ignore:Argument \"writer_name\":PendingDeprecationWarning")

ROOT = Path(__file__).resolve().parents[1]
CAPTIONS = sorted((ROOT / "workflow/report").glob("*.rst"))
STUDIES = [ROOT / "config/config.yaml", *sorted((ROOT / "config/studies").glob("*.yaml"))]

@pytest.fixture(scope="module")
def csv_file(tmp_path_factory) -> str:
    """A table as the workflow writes it (a flag variable and a float), for the csv-table captions."""
    scenario = variable(("variant",), np.array([2, 1], dtype=np.int8), "1", "scenario")
    scenario.attrs.update(flag_values=np.array([0, 1, 2], dtype=np.int8), flag_meanings="none surface edge")
    ds = xr.Dataset({"scenario": scenario, "impact_force": variable(("variant",), [13639.36, 6864.9], "N", "F_s")},
                    coords={"variant": variable(("variant",), ["standard", "relief"], "1", "variant")})
    path = tmp_path_factory.mktemp("table") / "table.csv"
    write_csv(ds, path)
    return str(path)


def _render(caption: Path, config: dict, output: SimpleNamespace, files=()) -> str:
    wildcards = SimpleNamespace(pair=config["pairs"][0], variant=next(iter(config.get("variants") or {"standard": 0})),
                                run=next(iter(config.get("optimise") or {"run": 0})), study=config["study"])
    snakemake = SimpleNamespace(config=config, wildcards=wildcards, output=output)
    template = Environment(trim_blocks=True, lstrip_blocks=True).from_string(caption.read_text())
    text = template.render(snakemake=snakemake, files=list(files))  # files: the report's, as Snakemake passes them
    # halt on any warning: a markup error would show as a "System Message" in the report
    return publish_parts(text, writer_name="html", settings_overrides={"halt_level": 2, "report_level": 2})["body"]


def _cases():
    """Every caption of every study's report items (the study's rules, from the stage declarations)."""
    for study in STUDIES:
        config = load_study(study)
        used = {o.caption for rule in plan.rules(config) for o in rule.outputs.values() if o.caption}
        for caption in CAPTIONS:
            if caption.stem in used:
                yield pytest.param(study, caption, id=f"{config['study']}-{caption.stem}")


@pytest.mark.parametrize("study, caption", list(_cases()))
def test_captions_render_in_the_readers_language(study, caption, csv_file):
    config = load_study(study)
    uses_csv = "snakemake.output.csv" in caption.read_text()
    outputs = [SimpleNamespace(csv=csv_file)] + ([SimpleNamespace()] if "is defined" in caption.read_text() else [])
    for output in outputs if uses_csv else [SimpleNamespace()]:
        html = _render(caption, config, output)
        # names, file names, links and the tables (whose columns are the variables' names) left out
        text = re.sub(r"<(tt|strong|em|a|table)\b[^>]*>.*?</\1>", " ", html, flags=re.S)
        text = re.sub(r"<[^>]+>", " ", text)
        assert not re.search(r"\b[Ss]eed 00\d", text), text
        assert "withheld" not in text and "System Message" not in html
        assert not re.search(r"\w_\w|\^", text), re.findall(r".{20}(?:\w_\w|\^).{20}", text)
        if getattr(output, "csv", None):
            assert "<table" in html and "<td>edge</td>" in html and "13639.4" in html  # the table itself


def test_the_landing_page_names_its_source_document_by_title():
    config = load_study(ROOT / "config/config.yaml")
    html = _render(ROOT / "workflow/report/workflow.rst", config, SimpleNamespace())
    assert "Comprehensive Analysis and Optimization of Mesh-in Impact in Helical Gears" in html
    assert 'href="docs/references.md"' in html
    assert "Where our results differ from the source document" in html
    for section in ("how-to-read-this-report", "where-our-results-differ-from-the-source-document-and-why"):
        assert f'id="{section}"' in html  # headings, not text run into a paragraph


def test_the_landing_page_takes_its_numbers_from_the_results(csv_file):
    """The LTE the landing page quotes is the run's lte_table.csv, shown as a table (no number
    copied into the text by hand, which went stale when the default tooth model changed); before
    the run has made it, the page says so."""
    config = load_study(ROOT / "config/config.yaml")
    page = ROOT / "workflow/report/workflow.rst"
    html = _render(page, config, SimpleNamespace(), [SimpleNamespace(name="lte_table.csv", path=csv_file)])
    assert "<caption>Loaded transmission error</caption>" in html and "13639.4" in html  # the file's rows
    assert "lte_table.csv appears here when the study has run" in _render(page, config, SimpleNamespace())
    # the page of the default study cut down to the stages every pair gets (as the browser test runs it)
    bare = {key: config[key] for key in ("study", "description", "source", "pairs")} | {"variants": {"standard": {}}}
    assert "Where our results differ" in _render(page, bare, SimpleNamespace())
    # no result in µm, N/µm or % written into any study's text by hand (config values come by Jinja)
    source = page.read_text()
    assert not re.search(r"\d\s*(µm|N/µm|%)", source), re.findall(r".{30}\d\s*(?:µm|N/µm|%)", source)
