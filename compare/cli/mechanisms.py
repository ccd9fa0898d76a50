"""The mechanism ranking of ``frictionnoise analyze``: :func:`compare.analysis.identify.identify` on a displacement
record, as summary.json's ``mechanisms`` and the terminal's first lines."""
from __future__ import annotations

import numpy as np

__all__ = ["mechanisms_of", "ranking_lines", "ranking_section", "stationarity_line", "SPLIT_HALF", "BAND_TEST"]


SPLIT_HALF = "split-half likelihood ratio of the record model"
BAND_TEST = "band levels of the two halves (compare.analysis.band_stationarity)"


def mechanisms_of(data, v: float, flags=(), progress=None, *, stationarity_p: float | None = None,
                  speed: float | None = None) -> dict:
    """summary.json's ``mechanisms`` (best first, each :meth:`Mechanism.to_dict`) and ``stationarity`` of a
    measured displacement record at mean speed ``v`` (m/s); ``mechanisms_note`` says why there are none.

    One stationarity verdict: the exponent fit's split-half likelihood-ratio test
    (:mod:`compare.analysis.record_model`, flagged below p = 0.01) when it ran, so the ranking and the exponent's
    flag never disagree; only a fit without that test (``--method whittle`` or ``lsq``) leaves the verdict to the
    band test of :func:`compare.analysis.identify.stationarity`. ``stationarity`` names the test that decided.

    Parameters
    ----------
    data : compare.io.measured.MeasuredData
        The record (``t`` in s, ``x`` in m).
    v : float
        Its mean sliding speed (Units: m/s).
    flags : iterable of str, optional
        The exponent fit's flags; one starting "not stationary" (the record model's split-half test) names no
        mechanism.
    progress : callable, optional
        Called with one line per family fitted (:func:`compare.analysis.identify.identify`'s ``progress``).
    stationarity_p : float, optional
        The exponent fit's split-half p-value (:attr:`~compare.analysis.record_model.RecordFit.stationarity_p`);
        None or NaN when the test did not run.
    speed : float, optional
        The sliding speed the user states (``--speed``, m/s): the families use it instead of ``v``.

    Returns
    -------
    dict
        ``mechanisms`` (list), ``stationarity`` (dict or None: ``test``, ``stationary``, and ``p_value`` with
        ``level`` for the split-half test), ``mechanisms_note`` (str) and ``speed`` (``value`` in m/s, ``source``,
        and ``halves``, the mean speeds of the record's two halves; ``note`` when they differ by more than a factor
        :data:`SPEED_RATIO` and no speed was stated: the families assume one steady speed).
    """
    used = _speed(data, v, speed)
    if speed is not None:
        v = speed
    out = _mechanisms(data, v, flags, progress, stationarity_p)
    out["speed"] = used
    return out


SPEED_RATIO = 2.0  # halves' mean speeds further apart than this factor: the record is not one steady slide


def _speed(data, v: float, speed: float | None) -> dict:
    """summary.json's ``speed``: the speed the families use, where it came from, the halves' mean speeds and, where
    they disagree and the user stated none, a note saying what to do."""
    x, t = (np.asarray(getattr(data, k, ()), float) for k in ("x", "t"))
    h = len(x) // 2 if len(x) == len(t) else 0
    halves = [float((x[h] - x[0]) / (t[h] - t[0])), float((x[-1] - x[h]) / (t[-1] - t[h]))] if h >= 1 else []
    out = {"value": float(speed if speed is not None else v),
           "source": "--speed" if speed is not None else "the record's mean speed (its ends)", "halves": halves}
    if speed is None and len(halves) == 2:
        a, b = halves
        if a * b <= 0 or max(abs(a), abs(b)) > SPEED_RATIO * min(abs(a), abs(b)):
            out["note"] = (f"the record's mean speed is {a:.3g} m/s over its first half and {b:.3g} m/s over its "
                           "second: the families assume one steady sliding speed; give the drive's with --speed")
    return out


def _mechanisms(data, v, flags, progress, stationarity_p) -> dict:
    from ..analysis.identify import MIN_SAMPLES, identify, record_stationarity, too_short
    from ..analysis.record_model import TEST_LEVEL

    if getattr(data, "segmented", False):
        return {"mechanisms": [], "stationarity": None,
                "mechanisms_note": "no mechanism named: the time stamps break into segments (identification needs "
                                   "one uniform record; --resample makes one)"}
    if not v > 0:
        return {"mechanisms": [], "stationarity": None,
                "mechanisms_note": _backward(v)}
    if len(data.x) < MIN_SAMPLES:
        return {"mechanisms": [], "stationarity": None, "mechanisms_note": f"no mechanism named: {too_short(len(data.x))}"}
    split = [f for f in flags if f.startswith("not stationary")]
    ran = stationarity_p is not None and stationarity_p == stationarity_p
    if split or ran:
        st = {"test": SPLIT_HALF, "stationary": not split, "p_value": stationarity_p if ran else None,
              "level": TEST_LEVEL}
        if split:
            return {"mechanisms": [], "stationarity": st, "mechanisms_note": f"no mechanism named: {split[0]}"}
    else:
        dt = float(np.median(np.diff(data.t)))
        st = {"test": BAND_TEST, **record_stationarity(data.x, dt)}
        if not st["stationary"]:
            return {"mechanisms": [], "stationarity": st,
                    "mechanisms_note": "no mechanism named: the record's two halves have different spectra (not "
                                       "stationary by the band test of the halves' levels, eight bands, Bonferroni at "
                                       "1 %; the exponent's fit ran no stationarity test of its own)"}
    dt = float(np.median(np.diff(data.t)))
    ranking = identify(x=data.x, dt=dt, v=v, stationary=True, progress=progress)
    return {"mechanisms": [m.to_dict() for m in ranking], "stationarity": st, "mechanisms_note": ""}


def stationarity_line(summary: dict) -> str:
    """The stationarity verdict the ranking rests on, in one line: which test, its p-value and level."""
    st = summary.get("stationarity")
    if not st:
        return ""
    if st["test"] == SPLIT_HALF:
        p = st.get("p_value")
        return (f"stationarity: {'stationary' if st['stationary'] else 'NOT stationary'} by the {SPLIT_HALF} "
                + (f"(p = {p:.2g}; flagged below {st['level']:g}), the test of the exponent's flags" if p is not None
                   else f"(flagged below {st['level']:g}), the test of the exponent's flags"))
    return (f"stationarity: {'stationary' if st['stationary'] else 'NOT stationary'} by the {BAND_TEST}; the "
            "exponent's fit ran no stationarity test of its own")


def _backward(v: float) -> str:
    """Why a record whose displacement does not grow gets no mechanism, in words a user can act on."""
    if v == 0 or v != v:
        return "no mechanism named: the displacement does not advance over the record (no sliding speed to refer to)"
    return (f"no mechanism named: the displacement falls over the record ({v:.3g} m/s on average); the families "
            "describe a block sliding forward at the drive's speed (negate x for a record sliding backward; a record "
            "of a driven slide's fluctuation alone takes the drive's speed from --speed; a free block that wanders is "
            "not a driven slide)")


def _value(p) -> str:
    value, half, unit = p
    return f"{value:.3g} +- {half:.2g}" + (f" {unit}" if unit else "")


def _params(m: dict) -> str:
    """The identified parameters as value +- 95 % half-width, then the names of those not identified."""
    shown = [f"{k} = {_value(v)}" for k, v in m["parameters"].items() if not isinstance(v, str)]
    unseen = [k for k, v in m["parameters"].items() if isinstance(v, str)]
    return "; ".join(([", ".join(shown)] if shown else []) + ([f"not identified: {', '.join(unseen)}"] if unseen else []))


def ranking_lines(summary: dict) -> list:
    """The ranking as the terminal shows it, best first: model, verdict, p-value, parameters (identified ones as
    value +- 95 % half-width, then those not identified; a rejected model's in summary.json only); the models coinciding with the best on the record's band
    under it as one family, with what would separate each; then the others, with what would separate an
    indistinguishable one."""
    mechs = summary.get("mechanisms") or []
    st = stationarity_line(summary)
    sp = summary.get("speed") or {}
    speed = ([f"sliding speed {sp['value']:.3g} m/s ({sp['source']})"] if sp else []) + (
        [f"NOTE: {sp['note']}"] if sp.get("note") else [])
    if not mechs:
        return [f"mechanism: {summary.get('mechanisms_note') or 'none named'}"] + speed + ([st] if st else [])
    lines = ["mechanisms (best first; p: Holm-adjusted, against the best; +-: 95 % half-width, the larger side of "
             "an asymmetric interval):"]
    best = mechs[0]["model"]
    same = [m for m in mechs[1:] if m.get("coincides_with") == best]
    for m in [mechs[0]] + [m for m in mechs[1:] if m not in same]:
        # a rejected family's best fit is no estimate of anything the record holds: its parameters stay in
        # summary.json, out of the terminal's reading
        params = "parameters of its best fit in summary.json" if m["verdict"] == "rejected" else _params(m)
        lines.append(f"  {m['model']:13s} {m['verdict']:17s} p = {m['p_value']:.2g}" + (f"; {params}" if params else ""))
        if m is mechs[0] and same:
            lines.append(f"      {', '.join(c['model'] for c in same)} coincide with it on this band (one family "
                         "here); to separate them:")
            lines.extend(f"        {c['model']}: {c['separate']}" for c in same)
        elif m["separate"]:
            lines.append(f"      to separate: {m['separate']}")
    return lines + speed + ([st] if st else [])


def ranking_section(summary: dict):
    """The ranking as the first section of analyze's index.html: the terminal's lines, verbatim, and where
    "indistinguishable" is explained."""
    from ..report.html import esc
    from ..report.study import StudyResult

    text = ("<pre>" + esc("\n".join(ranking_lines(summary))) + "</pre>"
            "<p>Which of the paper's models explains this record (every registered model's spectral family fitted "
            "and compared with the best; summary.json's <code>mechanisms</code> holds the same, best first). "
            "Reading the ranking and what \"indistinguishable\" means: the documentation's explanation page "
            "<i>Which mechanism? Reading the ranking</i> (docs/explanation/identification.md).</p>")
    return StudyResult("mechanism_ranking", "Mechanisms: which model explains the record", {}, (), text)
