"""Headless Chromium for the browser tests (tests/project/test_docs_browser.py, tests/compare/test_report_browser.py): Debian's
`chromium` driven through `chromium-driver` with selenium, in a 1280 x 900 window with the console's log kept.

Where no browser or driver is installed a test skips saying what is missing, except under CI (CI=true), where it
fails: .ci/run installs both."""
import os
import shutil

import pytest

WINDOW = (1280, 900)  # pixels: the first screen of a laptop


def missing(reason: str):
    """Skip saying what is missing; under CI (CI=true), which installs the browser, fail instead."""
    if os.environ.get("CI"):
        pytest.fail(f"{reason} (CI=true: the browser tests must run)")
    pytest.skip(reason)


def browser():
    """(chromium, chromedriver) paths, or skip (fail under CI) saying what is missing."""
    try:
        import selenium  # noqa: F401
    except ImportError:
        missing("selenium is not installed (pip install -e '.[test]')")
    chrome = shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")
    driver = shutil.which("chromedriver")
    if not chrome or not driver:
        missing("no headless browser: install Debian's chromium and chromium-driver (apt-get install -y chromium "
                "chromium-driver), as .ci/run does")
    return chrome, driver


def headless_chrome(tmp_path):
    """A selenium Chrome driver on a fresh profile under ``tmp_path`` (the caller quits it), or skip / fail as
    :func:`browser` says."""
    chrome, driver_path = browser()
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = chrome
    for flag in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run",
                 f"--window-size={WINDOW[0]},{WINDOW[1]}", f"--user-data-dir={tmp_path / 'profile'}"):
        opts.add_argument(flag)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(driver_path), options=opts)
