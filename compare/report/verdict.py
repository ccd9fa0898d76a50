"""A study's verdicts: what is compared, the key number with its interval, and whether it agrees with its
reference and by how much. The report leads with them (one summary table); summary.json and the terminal carry
the same rows.

A verdict that rests on a fit flagged as not a power law (``PowerLawFit.flags``) gives no agree / disagree: its
``agree`` is None and its text says why. The prose states a fit through :func:`fit_text`, which carries the flag.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ..analysis.fits import flag_mark
from .html import fixed, num, span

__all__ = ["Verdict", "fit_text", "flags_of", "gamma_verdict", "interval_verdict", "ratio_verdict", "summary_lines", "prose_flag_problems",
           "NOT_A_POWER_LAW"]

NOT_A_POWER_LAW = "not a power law"


def flags_of(fit) -> tuple:
    """The power-law flags of a :class:`~compare.analysis.fits.PowerLawFit` or of its ``to_dict()``."""
    return tuple(fit.get("flags") or ()) if isinstance(fit, dict) else tuple(getattr(fit, "flags", ()) or ())


def fit_text(fit, digits: int = 2, slope: bool = False) -> str:
    """"3.98 &plusmn; 0.04" (95 %), with " (not a power law)" when the fit is flagged: how prose states a fit.
    ``slope``: the spectrum's log-log slope, -gamma (a force spectrum's exponent)."""
    g = fit["gamma"] if isinstance(fit, dict) else fit.gamma
    e = fit["gamma_err"] if isinstance(fit, dict) else fit.gamma_err
    return f"{fixed(-g if slope else g, digits)} &plusmn; {e:.{digits}f}{flag_mark(fit)}"


def _short(flags) -> str:
    """The flags in a few words: "band under a decade", "curved"."""
    words = {"band spans": "band under a decade", "log-log residuals curve": "curved", "not stationary": "not stationary",
             "the spectrum bends": "bends", "no band of a decade": "no decade of one power law"}
    return ", ".join(dict.fromkeys(next((w for k, w in words.items() if f.startswith(k)), f) for f in flags))


@dataclass(frozen=True)
class Verdict:
    """One row of the report's summary table.

    study : the section's key (the row links to it).
    what : what is compared with what, e.g. "gamma against eq. (6)".
    measured : the key number with its interval, as shown.
    reference : what it is compared with, as shown.
    agree : True, False, or None where no verdict is given (a fit flagged as not a power law; nothing to compare).
    by : how far from the reference, in words and numbers.
    flags : the power-law flags of the fits the verdict rests on (then ``agree`` is None).
    expected : why a disagreement is the expected outcome ("" when it is not): the reference is a counterfactual
        the scene is built to depart from (e.g. model III without load sharing). Shown beside the verdict.
    """
    study: str
    what: str
    measured: str
    reference: str
    agree: bool | None
    by: str
    flags: tuple = ()
    expected: str = ""

    def __post_init__(self):
        if self.flags and self.agree is not None:
            raise ValueError(f"verdict {self.what!r}: agree must be None when a fit it rests on is flagged")

    @property
    def word(self) -> str:
        """"agrees", "disagrees" or "no verdict"."""
        return {True: "agrees", False: "disagrees", None: "no verdict"}[self.agree]

    @property
    def note(self) -> str:
        """"as expected: <why>" for an expected disagreement, "" otherwise."""
        return f"as expected: {self.expected}" if self.expected and self.agree is False else ""

    def to_dict(self) -> dict:
        """The verdict for summary.json: its texts in plain Unicode (the HTML's &plusmn; written as the sign)."""
        def plain(text: str) -> str:
            return text.replace("&plusmn;", "\u00b1")
        return {"study": self.study, "what": plain(self.what), "measured": plain(self.measured),
                "reference": plain(self.reference), "agree": self.agree, "verdict": self.word, "by": plain(self.by),
                "flags": list(self.flags), "expected": plain(self.expected)}


def gamma_verdict(study: str, what: str, fit, expected: float, reference: str, slope: bool = False,
                  tolerance: float = 0.0) -> Verdict:
    """A fitted exponent against an expected one: agrees when the 95 % interval, widened by ``tolerance`` (a
    stated model tolerance, in exponent units), holds the expected value. A flagged fit gives no verdict."""
    g = fit["gamma"] if isinstance(fit, dict) else fit.gamma
    e = fit["gamma_err"] if isinstance(fit, dict) else fit.gamma_err
    value = -g if slope else g
    flags = flags_of(fit)
    d = value - expected
    if flags:
        return Verdict(study, what, fit_text(fit, slope=slope), reference, None,
                       f"{fixed(d, 2, sign=True)}; {NOT_A_POWER_LAW} ({_short(flags)})", flags)
    ok = abs(d) <= e + tolerance
    return Verdict(study, what, fit_text(fit, slope=slope), reference, ok,
                   f"{fixed(d, 2, sign=True)} ({abs(d) / e:.1f} half-widths{f', tolerance {tolerance:g}' if tolerance else ''})")


def interval_verdict(study: str, what: str, value: float, err: float, expected: float, reference: str,
                     digits: int = 2, flags: tuple = (), direction: str = "equal") -> Verdict:
    """A number with its 95 % half-width against a reference value. ``direction``: "equal" (the interval holds
    it), "above" (the interval lies above it: a target met beyond the uncertainty)."""
    shown = f"{fixed(value, digits, sign=direction == 'above')} &plusmn; {err:.{digits}f}"
    d = value - expected
    if flags:
        return Verdict(study, what, shown + f" ({NOT_A_POWER_LAW})", reference, None,
                       f"{fixed(d, digits, sign=True)}; fits {NOT_A_POWER_LAW} ({_short(flags)})", tuple(flags))
    ok = (value - err >= expected) if direction == "above" else abs(d) <= err
    return Verdict(study, what, shown, reference, ok, f"{fixed(d, digits, sign=True)} ({abs(d) / err:.1f} half-widths)"
                   if err > 0 else f"{fixed(d, digits, sign=True)}")


def ratio_verdict(study: str, what: str, ratios, factor: float, reference: str, expected: str = "") -> Verdict:
    """Per-band ratios measured / reference (a list of numbers or of {"ratio": r}) against a stated factor: agrees
    when every band lies within it; "by" names the worst band's factor. ``expected``: why a disagreement is the
    expected outcome (see :class:`Verdict`)."""
    r = [b["ratio"] if isinstance(b, dict) else float(b) for b in ratios]
    worst = max(max(r), 1 / min(r))
    return Verdict(study, what, f"{span(min(r), max(r))} per band", reference, worst <= factor,
                   f"worst band x{num(worst)} (limit x{factor:g})", expected=expected)


def summary_lines(summary: dict) -> list:
    """The terminal's summary of a report: one line per verdict of summary.json (plain text, flags included), so
    what the terminal says is what the page's summary table says."""
    import html
    import re

    def plain(text: str) -> str:
        return html.unescape(re.sub(r"<[^>]+>", "", text))

    out = []
    for v in summary.get("verdicts", []):
        note = f" ({plain(v['expected'])}: as expected)" if v.get("expected") and v.get("agree") is False else ""
        out.append(f"  {v['verdict']:10s} {v['study']}: {plain(v['what'])} = {plain(v['measured'])} against "
                   f"{plain(v['reference'])}: {plain(v['by'])}{note}")
    return out


_VERDICT_WORDS = ("is met", "agrees", "disagrees", "confirm", "beyond the uncertainty", "within a factor")


def _flagged_fits(numbers, path=""):
    """(path, fit dict) of every fit in a study's numbers that carries flags."""
    if isinstance(numbers, dict):
        if "gamma" in numbers and "gamma_err" in numbers and numbers.get("flags"):
            yield path or "(top)", numbers
        for k, v in numbers.items():
            yield from _flagged_fits(v, f"{path}/{k}")
    elif isinstance(numbers, (list, tuple)):
        for i, v in enumerate(numbers):
            yield from _flagged_fits(v, f"{path}[{i}]")


def _sentences(fragment: str) -> list:
    """The prose of an HTML fragment cut into sentences and table cells (tags dropped, entities kept)."""
    import re

    text = re.sub(r"</(p|td|th|caption|li)>|<br\s*/?>", "\n", fragment)
    text = re.sub(r"<[^>]+>", "", text)
    return [s.strip() for s in re.split(r"\n|(?<=[.;])\s+(?=[A-Z(])", text) if s.strip()]


def prose_flag_problems(result) -> list:
    """What a study's prose says wrongly about its flagged fits (an empty list when it is honest): every
    sentence that states a flagged fit's exponent with its interval carries "not a power law" and no agree /
    disagree wording, and every verdict resting on a flagged fit gives no verdict."""
    problems = []
    sentences = _sentences(result.html)
    for path, fit in _flagged_fits(result.numbers):
        g, e = fit["gamma"], fit["gamma_err"]
        stated = {f"{sign * g:.{d}f} &plusmn; {e:.{d}f}" for d in (2, 3) for sign in (1, -1)}
        for s in sentences:
            if any(x in s for x in stated):
                if NOT_A_POWER_LAW not in s:
                    problems.append(f"{result.key}{path}: a flagged fit stated without its flag: {s!r}")
                if any(w in s for w in _VERDICT_WORDS):
                    problems.append(f"{result.key}{path}: a verdict on a flagged fit: {s!r}")
    for v in getattr(result, "verdicts", ()):
        if v.flags and v.agree is not None:
            problems.append(f"{result.key}: verdict {v.what!r} rests on a flagged fit")
        if v.flags:
            for s in sentences:
                if v.measured.split(" (")[0] in s and any(w in s for w in _VERDICT_WORDS):
                    problems.append(f"{result.key}: the prose gives a verdict on {v.what!r}: {s!r}")
    return problems
