"""The release notes: CHANGELOG.md in the Keep a Changelog form, an "Unreleased" section first (where new entries
go), a section for the package's version, short entries a user reads (no issue numbers), the file under 20 KB.
The version in CITATION.cff: tests/project/test_citation.py; the build and twine's checks: .ci/run."""
import re
from pathlib import Path

from frictionnoise import package_version

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")


def _sections() -> list:
    return re.findall(r"^## (.+)$", TEXT, re.M)


def test_unreleased_first_then_the_packages_version():
    sections = _sections()
    assert sections[0] == "Unreleased", sections
    assert re.fullmatch(rf"{re.escape(package_version())} - \d{{4}}-\d\d-\d\d", sections[1]), sections
    versions = [s.split(" - ")[0] for s in sections[1:]]
    as_tuples = [tuple(int(x) for x in v.split(".")) for v in versions]
    assert as_tuples == sorted(as_tuples, reverse=True), versions  # newest first


def test_short_user_entries_under_20_kb():
    assert len(TEXT.encode("utf-8")) < 20_000
    headings = set(re.findall(r"^### (.+)$", TEXT, re.M))
    assert headings <= {"Added", "Changed", "Deprecated", "Removed", "Fixed", "Security"}, headings
    entries = re.split(r"\n(?=- )", TEXT)
    long = [e[:60] for e in entries if e.startswith("- ") and len(e) > 400]
    assert not long, long  # an entry says what changed for a user in a few lines, not how it was found
    assert not re.search(r"\bissue \d+|#\d+\b", TEXT, re.I)
