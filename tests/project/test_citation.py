"""CITATION.cff names this release and the paper whose models the package implements. The file's schema is checked
by cffconvert in CI (.ci/run, in an environment of its own: cffconvert pins an older jsonschema than Jupyter needs);
this test keeps its version and DOI in step with the package."""
import re
from pathlib import Path

from frictionnoise import package_version

ROOT = Path(__file__).resolve().parents[2]


def test_citation_names_this_version_and_the_paper():
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    version = re.search(r"^version:\s*(\S+)\s*$", text, re.M)
    assert version is not None and version.group(1) == package_version()
    # the paper the README asks users to cite (Xu, Zhou & Persson, Soft Matter 21, 7594 (2025))
    assert "doi: 10.1039/d5sm00617a" in text
    assert "10.1039/d5sm00617a" in (ROOT / "README.md").read_text(encoding="utf-8")
