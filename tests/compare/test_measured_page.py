"""The page of a measured displacement record (analyze's index.html): the sensor floor and what ends the band, the
exponent's 95 % interval stated as the terminal states it, and a spectrum figure that reaches the fitted band's low
end with the fitted record model drawn over it."""
import html
import math
import re
from pathlib import Path

import numpy as np
import pytest

from compare.analysis.displacement import analyze_displacement
from compare.analysis.synthetic import power_law_record
from compare.cli.record_summary import _fit_text
from compare.report.measured_report import build_measured_report, displacement_figure

DT = 1e-3
N = 4096
DOCS = Path(__file__).resolve().parents[2] / "docs"


class _Record:
    """The attributes build_measured_report reads of a measured record."""

    def __init__(self, t, x):
        self.t, self.x, self.source = t, x, "synthetic.csv"
        self.resampled, self.warning, self.layout, self.timeline = False, None, {}, None


def _analysed(floor_rms: float, seed: int = 5):
    t = np.arange(N) * DT
    x = 1e-4 * t + power_law_record(N, DT, 4.0, floor_rms=floor_rms, seed=seed)
    return analyze_displacement(t, x), _Record(t, x)


def _floor_crossing_mid_band() -> float:
    """A white floor meeting A omega^-4 (A = 1) at the geometric middle of the Fourier frequencies (rms, m)."""
    w1, wn = 2 * math.pi / (N * DT), math.pi / DT
    return math.sqrt(2 * math.pi * math.sqrt(w1 * wn) ** -4.0 / DT)


@pytest.fixture(scope="module")
def floored():
    an, rec = _analysed(_floor_crossing_mid_band())
    results, summary = build_measured_report(an, rec)
    return an, html.unescape(results[0].html), results[0].figures[0].caption, summary


def test_the_page_names_the_floor_with_its_unit_and_that_it_ends_the_band(floored):
    an, text, _, _ = floored
    fit = an.fit
    assert fit.band_end == "floor"  # the floor was built to cross the power law inside the record's band
    assert f"white floor {fit.floor_rms:.3g} m rms (level B = {fit.floor:.3g} m^2 s of C_x)" in text
    assert f"over the power law above {fit.crossover:.3g} rad/s: the floor ends the band" in text


def test_a_record_without_a_resolved_floor_says_so_and_why_the_band_ends():
    an, rec = _analysed(0.0)
    text = html.unescape(build_measured_report(an, rec)[0][0].html)
    fit = an.fit
    assert fit.band_end == "last frequency"
    if fit.floor > 0:  # a floor term below the power law everywhere: named with its level
        assert f"a floor term of {fit.floor_rms:.3g} m rms fitted" in text and "no floor resolved" in text
        assert "below the power law over the whole band" in text
    else:
        assert "no white floor resolved" in text
    assert f"the band reaches the record's highest frequency, {fit.band[1]:.4g} rad/s (Nyquist)" in text


def test_a_given_band_is_said_to_end_where_it_was_given():
    t = np.arange(N) * DT
    x = power_law_record(N, DT, 4.0, seed=2)
    an = analyze_displacement(t, x, band=(1.0, 300.0))
    text = html.unescape(build_measured_report(an, _Record(t, x))[0][0].html)
    assert an.fit.band_end == "given"
    assert "the band given (--band)" in text


def _stated(text: str) -> tuple:
    """(gamma, +-, lo, hi) as the page or the terminal states the exponent."""
    m = re.search(r"gamma = ([\d.]+) (?:&plusmn;|±|\+-) ([\d.]+) \((?:95 % |\+-: 95 % half-width; interval )"
                  r"\[([\d.]+), ([\d.]+)\]", text)
    assert m, text[:400]
    return tuple(float(v) for v in m.groups())


def test_the_page_prints_the_interval_and_its_half_width_as_the_terminal_and_the_docs_do(floored):
    an, text, caption, summary = floored
    page = _stated(text)
    assert page == _stated(caption)
    assert page == _stated("gamma = " + _fit_text(summary["fit"]))  # analyze's terminal line, the same numbers
    g, pm, lo, hi = page
    assert lo < g < hi
    assert abs(pm - (hi - lo) / 2) <= 1.5e-3  # +- is half the interval's width (each printed to 3 decimals)
    doc = " ".join((DOCS / "explanation" / "identification.md").read_text().split())
    rule = doc[doc.index("The exponent's +-"):][:400]
    assert "half its interval's width" in rule and "interval itself beside it" in rule
    assert _stated("gamma = " + rule.split("(\"")[1]) == (3.988, 0.052, 3.937, 4.041)  # the terminal's form, quoted
    assert _stated("gamma = " + rule.split("index.html (\"")[1]) == (3.988, 0.052, 3.937, 4.041)  # the page's


def test_the_figure_reaches_the_band_and_draws_the_fitted_model(floored):
    an, _, caption, _ = floored
    fig, cap = displacement_figure(an)
    ax = fig.axes[0]
    fit = an.fit
    lo, hi = ax.get_xlim()
    assert lo <= fit.band[0] and hi >= fit.band[1]
    assert an.C_x.omega_min > 4 * fit.band[0]  # the Welch average alone starts above the band: the periodogram fills it
    curves = [(np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float)) for ln in ax.get_lines()]
    assert min(w.min() for w, _ in curves if len(w) > 1) <= fit.band[0] * 1.5  # a measured curve at the band's low end
    model = [(w, c) for w, c in curves if len(w) > 10 and np.allclose(c, fit.level(w) + fit.floor, rtol=1e-9)]
    assert model and model[0][0].min() <= fit.band[0] * 1.001  # power law + floor over the fitted ordinates
    shaded = [(p.get_x(), p.get_x() + p.get_width()) for p in ax.patches if hasattr(p, "get_width")]
    top = (math.ceil((N - fit.order) / 2) - 1) * 2 * math.pi / ((N - fit.order) * DT)  # highest fitted ordinate
    assert any(np.isclose(a, fit.band[0]) and np.isclose(b, top) for a, b in shaded)
    assert "periodogram of the whole record" in cap and f"{an.C_x.periodogram_omega[0]:.3g} rad/s" in cap
    assert lo <= an.C_x.periodogram_omega[0] and "as the fit does" in cap  # the fit starts at the lowest ordinate


def test_the_figure_shows_the_periodogram_below_a_band_that_starts_higher():
    # a band given above the record's lowest frequencies: the periodogram drawn to its lowest ordinate, in view, and
    # the caption does not say the fit reaches it
    t = np.arange(N) * DT
    an = analyze_displacement(t, power_law_record(N, DT, 4.0, seed=3), band=(20.0, 300.0))
    fig, cap = displacement_figure(an)
    lo, _ = fig.axes[0].get_xlim()
    w0 = an.C_x.periodogram_omega[0]
    assert an.fit.band[0] > 10 * w0 and lo <= w0
    assert f"lowest Fourier frequency {w0:.3g} rad/s" in cap and "as the fit does" not in cap


def test_a_band_fit_of_the_welch_spectrum_says_it_fits_no_floor_and_draws_only_its_band():
    t = np.arange(N) * DT
    x = power_law_record(N, DT, 4.0, seed=3)
    an = analyze_displacement(t, x, method="whittle")
    text = html.unescape(build_measured_report(an, _Record(t, x))[0][0].html)
    assert "No floor term: the whittle fit takes a power law alone" in text
    g, pm, lo, hi = _stated(text)
    assert abs(pm - (hi - lo) / 2) <= 1.5e-3
    fig, cap = displacement_figure(an)
    assert "periodogram" not in cap and "record model" not in cap  # the band fit reads neither
    shaded = [(p.get_x(), p.get_x() + p.get_width()) for p in fig.axes[0].patches if hasattr(p, "get_width")]
    assert any(np.isclose(a, an.fit.band[0]) and np.isclose(b, an.fit.band[1]) for a, b in shaded)
