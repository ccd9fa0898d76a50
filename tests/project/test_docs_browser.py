"""The documentation as a reader meets it: every page of the built site (docs/_build/html, which .ci/run builds with
``python -m sphinx -W --keep-going -b html docs docs/_build/html`` before the tests) opened in headless Chromium
(Debian's `chromium` driven through `chromium-driver` with selenium). Every page loads with a title and a heading,
every image decodes, every link inside the site resolves to a page that exists (and to an element of that page
when it names one), and the browser's console holds no error.

Where the site is not built or no browser is installed the test skips saying what is missing, except under CI
(CI=true), where it fails: CI installs both and builds the site first.
"""
import re
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

from tests.browser import headless_chrome, missing

pytestmark = pytest.mark.slow  # a browser started (about 4 s) and some 50 pages loaded

SITE = Path(__file__).resolve().parents[2] / "docs" / "_build" / "html"


def _ids(page: Path) -> set:
    return set(re.findall(r'\bid="([^"]+)"', page.read_text(encoding="utf-8")))


def test_docs_site_reads_in_a_browser(tmp_path):
    if not (SITE / "index.html").exists():
        missing(f"the documentation is not built ({SITE / 'index.html'} missing): python -m sphinx -W --keep-going "
                "-b html docs docs/_build/html")
    pages = sorted(p for p in SITE.rglob("*.html") if not {"_static", "_sources", "_images"} & set(p.parts))
    # the site holds the four parts and the results, each with its pages (the toctrees' targets)
    names = {p.relative_to(SITE).as_posix() for p in pages}
    for part in ("tutorials", "howto", "reference", "explanation", "results"):
        assert f"{part}/index.html" in names, part
    assert {"tutorials/first_report.html", "reference/cli.html", "reference/api.html"} <= names
    drv = headless_chrome(tmp_path)
    problems, links, n_images = [], {}, 0
    try:
        for page in pages:
            rel = page.relative_to(SITE).as_posix()
            drv.get(page.as_uri())
            title, h1, imgs, hrefs = drv.execute_script(
                "return [document.title, document.querySelectorAll('h1').length,"
                " Array.from(document.images).map(i => [i.src, i.complete, i.naturalWidth]),"
                " Array.from(document.querySelectorAll('a[href]')).map(a => a.href)];")
            if not title.strip():
                problems.append(f"{rel}: no title")
            if rel not in ("genindex.html", "search.html", "py-modindex.html") and h1 < 1:
                problems.append(f"{rel}: no heading")
            for src, complete, width in imgs:
                n_images += 1
                if not (complete and width > 0):
                    problems.append(f"{rel}: image does not decode: {src}")
            for href in hrefs:
                links.setdefault(href, rel)
            for entry in drv.get_log("browser"):
                if entry["level"] == "SEVERE":
                    problems.append(f"{rel}: console: {entry['message']}")
    finally:
        drv.quit()
    # internal links: the file exists; a fragment names an element of the target page
    root = SITE.resolve()
    checked = 0
    for href, rel in links.items():
        u = urlsplit(href)
        if u.scheme != "file":
            continue
        target = Path(unquote(u.path))
        if root not in target.parents and target != root:
            problems.append(f"{rel}: link leaves the site: {href}")
            continue
        checked += 1
        if not target.exists():
            problems.append(f"{rel}: broken link: {target.relative_to(root)}")
        elif u.fragment and target.suffix == ".html" and unquote(u.fragment) not in _ids(target):
            problems.append(f"{rel}: no #{u.fragment} in {target.relative_to(root)}")
    assert not problems, "\n".join(problems)
    # the tutorials' figures and the CLI reference are there (images counted over the whole site)
    assert n_images >= 4 and checked > 100, (n_images, checked)
