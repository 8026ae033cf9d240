"""The report as a reader sees it: ``snakemake --report`` of the default study's landing page,
opened in headless Chromium at two common window sizes. Snakemake's page centres its content in
a full-height box, and content taller than the window used to overflow above the box, where it
cannot be scrolled to (issue 25): the title, description and source document were lost.

Needs Chromium and Playwright (the ``test`` extra): ``apt-get install chromium`` or
``playwright install chromium``. Without a browser the test is skipped, unless
GEARMESH_REQUIRE_BROWSER=1 (CI's ``.ci/run`` sets it), where it fails instead."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest
import yaml

from test_workflow import _scratch_workflow, _snakemake

pytestmark = [pytest.mark.workflow, pytest.mark.browser,
              pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake not installed")]

#: Common laptop and desktop windows (CSS pixels).
WINDOWS = ((1366, 768), (1920, 1080))
#: Browsers launched in this order: the system's, then Playwright's own download.
SYSTEM_BROWSERS = ("chromium", "chromium-browser", "google-chrome")


def _browser(playwright):
    """Headless Chromium, or skip (fail when GEARMESH_REQUIRE_BROWSER=1)."""
    errors = []
    # --no-sandbox: CI runs as root, where Chromium's sandbox refuses to start; the page is our own file
    for path in [shutil.which(name) for name in SYSTEM_BROWSERS if shutil.which(name)] + [None]:
        try:
            return playwright.chromium.launch(executable_path=path, args=["--no-sandbox"])
        except Exception as exc:  # noqa: BLE001 (any launch failure means: try the next browser)
            errors.append(f"{path or 'playwright chromium'}: {str(exc).splitlines()[0]}")
    if os.environ.get("GEARMESH_REQUIRE_BROWSER") == "1":
        pytest.fail("no headless Chromium: " + "; ".join(errors))
    pytest.skip("no headless Chromium: " + "; ".join(errors))


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    """report.html of the default study's landing page: its config with the stages every pair gets
    (geometry, contact lines, stiffness) and what its verdict reads (the standard and relief
    variants' TCA, LTCA, impact and rating, and the sign-off, on nominal gears), on small grids, so
    the run takes seconds."""
    root = Path(__file__).resolve().parents[1]
    tmp = tmp_path_factory.mktemp("report")
    default = yaml.safe_load((root / "config/config.yaml").read_text())
    config = {key: default[key] for key in ("study", "description", "source", "pairs")}
    torques = [400, 1000, 1600]
    config.update(geometry={"involute_points": 20, "fillet_points": 10, "face_points": 5},
                  contact_lines={"positions": 24}, stiffness={"method": "transition", "slices": 20, "positions": 24},
                  variants={"standard": {}, "relief": default["variants"]["relief"]},
                  tca={"positions": 16, "points": 12},
                  ltca={"torques_Nm": list(torques), "on": "pinion", "positions": 16, "points": 12, "method": "transition"},
                  impact={"torques_Nm": list(torques), "on": "pinion", "speeds_rpm": [5000], "design_speed_rpm": 5000,
                          "simulate_torques_Nm": [], "method": "transition", "points": 12, "window_positions": 16,
                          "face_samples": 33},
                  rating={"speed_rpm": 5000, "method": "ltca"},
                  signoff={**default["signoff"], "basis": "nominal"})
    work = _scratch_workflow(root, tmp, config)
    (work / "profiles").symlink_to("workflow/profiles")  # the workflow profile (report-stylesheet), as in the repository
    for args in ((), ("--report", "report.html")):
        proc = _snakemake(work, *args)
        assert proc.returncode == 0, proc.stderr[-3000:]
    return work / "report.html"


@pytest.mark.parametrize("width, height", WINDOWS, ids=[f"{w}x{h}" for w, h in WINDOWS])
def test_the_landing_page_scrolls_to_its_title(report, width, height, tmp_path):
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as playwright:
        browser = _browser(playwright)
        try:
            page = browser.new_page(viewport={"width": width, "height": height})
            page.goto(report.as_uri())
            title = page.locator(".prose h1").first
            title.wait_for(timeout=60_000)
            # every scrolling box around the title at its start, as a reader scrolling up leaves it
            box = page.evaluate("""() => {
                const title = document.querySelector('.prose h1');
                for (let el = title.parentElement; el; el = el.parentElement) { el.scrollTop = 0; el.scrollLeft = 0; }
                window.scrollTo(0, 0);
                const r = title.getBoundingClientRect(), page = title.closest('.prose').getBoundingClientRect();
                return {text: title.textContent, top: r.top, bottom: r.bottom, left: r.left,
                        pageHeight: page.height}; }""")
            page.screenshot(path=str(tmp_path / f"landing_{width}x{height}.png"))
        finally:
            browser.close()
    assert box["text"] == "gearmesh study impact_case"
    # the case the fix is for: the landing page is taller than the window
    assert box["pageHeight"] > height, box
    assert 0 <= box["top"] and box["bottom"] <= height and box["left"] >= 0, box


def test_the_verdict_fits_the_page_and_says_what_a_reader_needs(report, tmp_path):
    """At 1366 px no table of the landing page is wider than its text column (the sign-off table of
    34 columns used to be 5049 px wide in a 490 px column), and its first table is the verdict:
    variant, torque, the verdict, and per criterion meets or fails with its margin and the gear it
    was judged on."""
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as playwright:
        browser = _browser(playwright)
        try:
            page = browser.new_page(viewport={"width": 1366, "height": 768})
            page.goto(report.as_uri())
            page.locator(".prose table").first.wait_for(timeout=60_000)
            found = page.evaluate("""() => {
                const prose = document.querySelector('.prose');
                const style = getComputedStyle(prose);
                const column = prose.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
                const tables = [...prose.querySelectorAll('table')].map(t => ({
                    caption: (t.querySelector('caption') || {}).textContent || '',
                    width: t.getBoundingClientRect().width, scroll: t.scrollWidth,
                    header: [...t.querySelectorAll('thead th')].map(th => th.textContent.trim()),
                    rows: [...t.querySelectorAll('tbody tr')].map(tr => [...tr.children].map(td => td.textContent.trim()))}));
                return {column, tables, window: document.documentElement.scrollWidth};
            }""")
            page.screenshot(path=str(tmp_path / "landing_1366x768.png"))
        finally:
            browser.close()
    assert found["window"] <= 1366
    wide = [(t["caption"], t["width"]) for t in found["tables"] if max(t["width"], t["scroll"]) > found["column"] + 0.5]
    assert len(found["tables"]) >= 2 and not wide, (found["column"], wide)
    verdict = found["tables"][0]
    assert verdict["caption"] == "Sign-off verdict"
    assert verdict["header"][:3] == ["variant", "torque [N m]", "verdict"]
    criteria = verdict["header"][3:]
    assert "pressure (nominal)" in criteria and "F_s (nominal)" in criteria and len(criteria) >= 5
    assert {row[0] for row in verdict["rows"]} == {"relief"} and {row[1] for row in verdict["rows"]} == \
        {"400", "1000", "1600"}
    for row in verdict["rows"]:
        assert row[2] in ("meets", "fails")
        for cell in row[3:]:  # ✓ or ✗ and the margin in percent of the limit
            assert re.fullmatch(r"[✓✗]\s[+−]\d+\s%", cell), cell
        assert (row[2] == "meets") == all(cell.startswith("✓") for cell in row[3:])
