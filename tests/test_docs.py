"""The user-facing documents stay true (issue 18): the README's Python API block runs,
docs/api.md names only functions that exist, CITATION.cff carries the package version."""

from __future__ import annotations

import importlib
import re

import pytest
import yaml


def _python_block(text: str, heading: str) -> str:
    """The first ```python block after ``heading``."""
    section = text[text.index(heading):]
    return re.search(r"```python\n(.*?)```", section, flags=re.S).group(1)


def test_readme_python_api_block_runs(root, tmp_path, monkeypatch, capsys):
    code = _python_block((root / "README.md").read_text(encoding="utf-8"), "## Python API")
    assert len(code.strip().splitlines()) <= 12
    monkeypatch.chdir(tmp_path)
    exec(compile(code, "README.md (Python API)", "exec"), {})
    out = capsys.readouterr().out
    assert "eps_alpha 1.452" in out  # 29/71 teeth, m_n 5 mm, 27.5°: εα of the case-study pair
    assert (tmp_path / "te_lte.png").stat().st_size > 10_000


def test_api_page_names_only_what_exists(root):
    names = set(re.findall(r"`(gearmesh(?:\.\w+)+)\(", (root / "docs/api.md").read_text(encoding="utf-8")))
    assert len(names) >= 30
    for dotted in sorted(names):
        module, _, attr = dotted.rpartition(".")
        assert callable(getattr(importlib.import_module(module), attr)), dotted


def test_citation_carries_the_package_version(root):
    citation = yaml.safe_load((root / "CITATION.cff").read_text(encoding="utf-8"))
    version = re.search(r'^version = "(.+)"', (root / "pyproject.toml").read_text(), flags=re.M).group(1)
    assert citation["version"] == version and citation["license"] == "MIT"
    assert citation["cff-version"] == "1.2.0" and citation["authors"]


@pytest.mark.parametrize("number", ["000", "001", "002", "003", "004"])
def test_references_name_every_source_document_once(root, number):
    text = (root / "docs/references.md").read_text(encoding="utf-8")
    assert len(re.findall(rf"^\| {number} \| ", text, flags=re.M)) == 1
