"""The report's figures: what the reader is told is what is drawn (exponent names, the reference point, axis
ranges). That importing them leaves matplotlib's backend alone is in test_backend.py (every project module)."""
import numpy as np
import pytest

from compare.report import plots
from compare.analysis.fits import fit_power_law
from compare.analysis.spectra import displacement_spectrum, force_series_spectrum


@pytest.fixture(scope="module")
def walk():
    """A random walk (C_x ~ omega^-2) and its steps (white force), 2^14 samples."""
    t = np.arange(2**14) * 1e-3
    f = np.random.default_rng(1).standard_normal(t.size)
    return t, np.cumsum(f) * 1e-9, f


def _legend_texts(fig):
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    for art in ax.artists:  # the fits' legend is added as an artist
        texts += [t.get_text() for t in art.get_texts()]
    return texts


def test_force_slopes_are_not_called_gamma(walk):
    t, x, f = walk
    sx, sF = displacement_spectrum(t, x), force_series_spectrum(t, f)
    fx, fF = fit_power_law(sx, band=(10.0, 300.0)), fit_power_law(sF, band=(10.0, 300.0))
    tx = _legend_texts(plots.spectrum_figure([(sx, "x")], fits=[(fx, "")]))
    tF = _legend_texts(plots.spectrum_figure([(sF, "F")], fits=[(fF, "")], ylabel="C_F"))
    assert any(r"$\gamma$ = " in s and f"{fx.gamma:.2f}" in s for s in tx), tx
    assert not any("gamma" in s for s in tF) and any("$C_F$ slope = " in s and f"{-fF.gamma:.2f}" in s for s in tF), tF


def test_axis_follows_the_data_not_a_closed_form_zero(walk):
    # a theory curve with a zero (a sinc^2 factor) must not stretch the axis over tens of decades
    t, x, _ = walk
    s = displacement_spectrum(t, x)
    w = np.logspace(0, 3, 300)
    dip = 1e-16 * w**-2.0
    dip[150] = 1e-40
    lo, hi = plots.spectrum_figure([(s, "walk")], [(w, dip, "theory with a zero")]).axes[0].get_ylim()
    data = s.C[s.omega > 0]
    assert lo >= data.min() / 1e3 and hi <= data.max() * 1e3, (lo, hi, data.min(), data.max())


def test_work_precision_draws_every_setting_and_the_reference():
    rows = [{"dt": 2.5e-5, "iterations": 20, "cost": 0.9, "error": 0.0, "pareto": None, "default": False},
            {"dt": 1e-4, "iterations": 2, "cost": 0.2, "error": 0.004, "pareto": True, "default": True},
            {"dt": 5e-5, "iterations": 2, "cost": 0.4, "error": 0.0015, "pareto": True, "default": False},
            {"dt": 1e-4, "iterations": 10, "cost": 0.3, "error": 0.004, "pareto": False, "default": False}]
    fig = plots.work_precision_figure(rows)
    ax = fig.axes[0]
    pts = [l for l in ax.get_lines() if l.get_marker() in ("o", "*")]
    assert len(pts) == len(rows)
    labels = [t.get_text() for t in ax.texts]
    assert any("(reference)" in s for s in labels) and any("(default)" in s for s in labels)
    # every label inside the figure (none clipped at an edge)
    fig.canvas.draw()
    W, H = fig.canvas.get_width_height()
    for txt in ax.texts:
        bb = txt.get_window_extent()
        assert bb.x0 >= 0 and bb.x1 <= W and bb.y0 >= 0 and bb.y1 <= H, (txt.get_text(), bb, W, H)



def test_fit_line_is_drawn_on_the_data_at_its_level(walk):
    # the line is the fitted power law itself (prefactor * omega^-gamma), not an offset copy, and the legend says
    # what it is without naming an offset
    t, x, _ = walk
    s = displacement_spectrum(t, x)
    fit = fit_power_law(s, band=(10.0, 300.0))
    fig = plots.spectrum_figure([(s, "walk")], fits=[(fit, "")], band=fit.band)
    ax = fig.axes[0]
    line = next(ln for ln in ax.get_lines() if r"$\gamma$" in ln.get_label())
    w, c = line.get_data()
    np.testing.assert_allclose(c, fit.level(w), rtol=1e-12)
    titles = [a.get_title().get_text() for a in ax.artists] + [ax.get_legend().get_title().get_text()]
    assert not any("3x" in s or "above its level" in s for s in titles), titles


def test_an_axis_over_many_decades_keeps_its_labels_apart():
    # a closed form from 1e-8 down to 1e-58 (the wide-band sensor figure): at most 8 labelled decades, the range
    # the data's, and no two tick labels overlapping
    fig = plots.new_figure(5.0, 4.6)
    ax = fig.add_subplot()
    w = np.geomspace(0.1, 3e7, 400)
    C = 1e-8 * (1 + (w / 10.0) ** 2) ** -3.5
    ax.loglog(w, C)
    plots.follow_data(ax, C)
    lo, hi = ax.get_ylim()
    assert C.min() / 10 <= lo <= C.min() and C.max() <= hi <= C.max() * 10
    fig.canvas.draw()
    boxes = [t.get_window_extent() for t in ax.get_yticklabels() if t.get_visible() and t.get_text()
             and lo <= t.get_position()[1] <= hi]
    assert 2 <= len(boxes) <= 8 and not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:]), len(boxes)
