# compare/study.py
from dataclasses import dataclass
from typing import Callable
@dataclass(frozen=True)
class Figure:
    name: str        # file stem under figures/
    png: bytes
    caption: str     # what is compared and the verdict in numbers
@dataclass(frozen=True)
class StudyResult:
    key: str
    title: str
    numbers: dict    # JSON-able
    figures: tuple = ()
    html: str = ""   # HTML fragment
@dataclass(frozen=True)
class Study:
    key: str
    label: str
    run: Callable[[bool, int], "StudyResult"]
