"""The report as a reader meets it: index.html opened in headless Chromium (Debian's `chromium` driven through
`chromium-driver` with selenium). Every image decodes, the console stays free of errors, every section is
reachable from the table of contents, and a screenshot of the first screen is saved beside the test's output.

The report is a quick one restricted to two real studies (model III and the tilted-plane scene), so the test
costs well under a minute. Skipped, with the reason, where no browser or driver is installed (.ci/run installs
them with apt-get); under CI (CI=true) that is a failure."""
import time

import pytest

from compare.report.html import write_report
from compare.report.build import build_report
from tests.browser import headless_chrome

pytestmark = pytest.mark.slow  # a report built (about 7 s) and a browser started (about 4 s)

FIRST_SCREEN_PX = 900  # a 1280 x 900 browser window: the summary table ends above its bottom edge


@pytest.fixture(scope="module")
def small_report(tmp_path_factory):
    from compare.report import studies

    chosen = [s for s in studies.STUDIES if s.key in ("model_III", "scenarios/tilted_plane")]
    assert len(chosen) == 2
    results, summary = build_report(quick=True, seed=0, studies=chosen)
    return write_report(tmp_path_factory.mktemp("browser") / "report", results, summary), results


def test_report_reads_in_a_browser(small_report, tmp_path):
    from selenium.webdriver.common.by import By

    out, results = small_report
    t0 = time.perf_counter()
    drv = headless_chrome(tmp_path)
    try:
        drv.get((out / "index.html").as_uri())
        # every image decodes (a broken data URI leaves naturalWidth at 0)
        imgs = drv.execute_script("return Array.from(document.images).map(i => [i.alt, i.complete, i.naturalWidth]);")
        n_fig = sum(len(r.figures) for r in results)
        assert len(imgs) == n_fig >= 2
        assert all(complete and width > 0 for _, complete, width in imgs), imgs
        # captions numbered 1..n in page order
        caps = [e.text for e in drv.find_elements(By.CSS_SELECTOR, "figcaption")]
        assert [c.split(".")[0] for c in caps] == [f"Figure {k}" for k in range(1, n_fig + 1)], caps
        # every section is linked from the contents, and each link brings its section into view
        sections = [e.get_attribute("id") for e in drv.find_elements(By.CSS_SELECTOR, "section[id]")]
        links = drv.find_elements(By.CSS_SELECTOR, "nav#contents a")
        assert [a.get_attribute("hash").lstrip("#") for a in links] == sections
        assert len(sections) == len([r for r in results if r.title])
        for sid in sections:
            drv.execute_script("window.scrollTo(0, 0);")
            drv.find_element(By.CSS_SELECTOR, f"nav#contents a[href='#{sid}']").click()
            top, height, at_bottom = drv.execute_script(
                f"const r = document.getElementById('{sid}').getBoundingClientRect().top;"
                "const e = document.documentElement;"
                "return [r, window.innerHeight, window.scrollY + window.innerHeight >= e.scrollHeight - 2];")
            # at the top of the window, or in view with the page scrolled to its end (the last sections)
            assert -2 <= top < height and (top < 5 or at_bottom), (sid, top, at_bottom)
        # no console errors
        errors = [e for e in drv.get_log("browser") if e["level"] == "SEVERE"]
        assert not errors, errors
        # the first screen holds the summary table
        drv.execute_script("window.scrollTo(0, 0);")
        bottom = drv.execute_script("return document.getElementById('summary').getBoundingClientRect().bottom;")
        assert bottom <= FIRST_SCREEN_PX, bottom
        # the first screen, for a person to look at
        shot = tmp_path / "report_first_screen.png"
        assert drv.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
        print(f"\nscreenshot of the report's first screen: {shot} (browser part {time.perf_counter() - t0:.1f} s)")
    finally:
        drv.quit()


def test_first_screen_holds_the_summary_of_a_full_report(tmp_path):
    """The full report's contents and summary table (every registered study, each with the verdict rows the full
    report gives it; the longest texts they print) fit the first screen of a 1280 x 900 window."""
    from compare.report import studies
    from compare.report.study import StudyResult
    from compare.report.verdict import gamma_verdict, ratio_verdict

    flagged = {"gamma": 5.98, "gamma_err": 0.02, "band": [1.5, 11.8], "flags": ["band spans 0.90 decades (< 1)",
                                                                                 "log-log residuals curve (2.8 sigma)"]}
    rows = {"model_I": 2, "model_Ib": 2, "model_III": 3, "model_II": 2}  # the scenes: one row each
    results = [StudyResult("model_I_variations", "Model I variations (paper Fig. 2)", {},
                           verdicts=(ratio_verdict("model_I_variations", "C_x level / eq. (6), 5 cases", [0.97, 1.03],
                                                   1.25, "1 (eq. 6)"),))]
    for st in studies.selected(False):
        n = rows.get(st.key, 0 if st.key in ("scenes_method", "engine_work_precision") else 1)
        verdicts = tuple(gamma_verdict(st.key, "gamma, N = 300", flagged, 5.9, "5.90 (exact, over the band)")
                         if k % 2 else ratio_verdict(st.key, "C_F / model III, 2 bands", [0.00135, 0.0187], 1.5,
                                                     "1 (no load sharing)") for k in range(n))
        results.append(StudyResult(st.key, st.label, {}, verdicts=verdicts))
    results.append(StudyResult("scenarios/pads_multiscale_model_Ib", "Scene pads_multiscale against model Ib", {},
                               verdicts=(ratio_verdict("x", "C_x / model Ib", [0.95, 1.06], 1.5, "1 (model Ib)"),)))
    assert sum(len(r.verdicts) for r in results) >= 21
    out = write_report(tmp_path / "report", results, {"version": "0.1.0", "seed": 0, "quick": False})
    drv = headless_chrome(tmp_path)
    try:
        drv.get((out / "index.html").as_uri())
        bottom, width, inner = drv.execute_script(
            "return [document.getElementById('summary').getBoundingClientRect().bottom,"
            " document.documentElement.scrollWidth, window.innerWidth];")
        assert bottom <= FIRST_SCREEN_PX and width <= inner, (bottom, width, inner)  # no sideways scrolling either
    finally:
        drv.quit()
