"""Figures for reports (matplotlib's object interface with the Agg canvas: importing this module leaves
pyplot's backend as it was). The only module of compare that imports matplotlib."""
from __future__ import annotations

import io
from pathlib import Path

import numpy as np
from matplotlib import rcParams
from matplotlib.colors import to_rgb
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from ..analysis.fits import flag_mark
from ..analysis.spectra import Spectrum, log_bin

__all__ = ["new_figure", "follow_data", "spectrum_figure", "save_figure", "figure_png_bytes", "episode_histogram_figure", "level_figure",
           "work_precision_figure", "vibration_figure"]

_SLOPE_NAMES = {"x": r"$\gamma$", "F": r"$C_F$ slope", "mu": r"$C_\mu$ slope"}


def new_figure(w, h):
    """A blank figure (w x h inches) on the Agg canvas, for a figure drawn outside this module."""
    fig = Figure(figsize=(w, h), dpi=110)
    FigureCanvasAgg(fig)
    return fig


def follow_data(ax, *curves, margin: float = 3.0, max_ticks: int = 8):
    """A log y axis that spans the positive values of ``curves`` with a factor ``margin`` either side, with at most
    ``max_ticks`` labelled decades (a curve over tens of decades otherwise gets a label on every one, overlapping)."""
    from matplotlib.ticker import LogLocator, NullFormatter

    pos = np.concatenate([np.asarray(c, float)[np.asarray(c, float) > 0] for c in curves] or [np.array([])])
    if pos.size:
        ax.set_ylim(pos.min() / margin, pos.max() * margin)
    ax.yaxis.set_major_locator(LogLocator(base=10, numticks=max_ticks))
    ax.yaxis.set_minor_formatter(NullFormatter())


def _fit_line(ax, fit, label, ls):
    """Draw a fit at its level over its band, on the data (a thin white edge keeps it visible there); return its
    legend handle. The exponent goes into a legend of its own (upper right, where descending spectra leave room)
    rather than beside the line, where a line or a neighbouring curve would cross it."""
    from matplotlib import patheffects

    w = np.logspace(np.log10(fit.band[0]), np.log10(fit.band[1]), 20)
    q = getattr(fit, "quantity", "x") or "x"
    name = _SLOPE_NAMES.get(q, "slope")
    value = f"{fit.gamma:.2f}" if q == "x" else f"{-fit.gamma:.2f}"  # C_F ~ omega^(-gamma): its slope is -gamma
    (line,) = ax.loglog(w, fit.level(w), color="k", ls=ls, lw=1.3, zorder=4,
                        path_effects=[patheffects.withStroke(linewidth=2.6, foreground="w")],
                        label=f"{label}{name} = {value} ± {fit.gamma_err:.2f}{flag_mark(fit)}")
    return line


def spectrum_figure(measured: list, theory: list = (), *, title: str = "", ylabel: str = r"$C_x$ (m$^2$ s)",
                    fits: list = (), band: tuple | None = None, theory_on_top: bool = False):
    """Log-log overlay.

    measured : list of (Spectrum, label) -- drawn log-binned (20 per decade) as lines with markers.
    theory : list of (omega, C, label) -- dashed lines over the measured ones, in colours after theirs. With
        ``theory_on_top`` theory j belongs to measured j: drawn thinner, dashed, in its colour and above it, and
        the legend has one entry for all of them (the first label up to its comma).
    fits : list of (PowerLawFit, label) -- thin black lines over their band (solid, dash-dot, dotted), their
        exponents in a legend of their own (gamma for C_x; the slope for a force or friction spectrum).
    band : shaded frequency band (rad/s), e.g. the fit band.

    The y axis spans the measured data with a margin; a closed form that dips far below it (a zero of a sinc
    factor) is clipped rather than stretching the axis over tens of decades.
    """
    fig = new_figure(6.4, 4.6)
    ax = fig.add_subplot()
    colors = rcParams["axes.prop_cycle"].by_key()["color"]
    lo, hi = np.inf, -np.inf
    for i, (spec, label) in enumerate(measured):
        b = log_bin(spec, 20) if isinstance(spec, Spectrum) else spec
        ax.loglog(b.omega, b.C, "-", marker=".", ms=3, lw=1.2, color=colors[i % len(colors)], label=label, zorder=2)
        pos = np.asarray(b.C)[np.asarray(b.C) > 0]
        if pos.size:
            lo, hi = min(lo, pos.min()), max(hi, pos.max())
    handles = []
    for j, (w, C, label) in enumerate(theory):
        if theory_on_top:
            dark = tuple(0.5 * c for c in to_rgb(colors[j % len(colors)]))  # its curve's colour, darkened
            ax.loglog(w, C, "--", lw=1.0, color=dark, zorder=3)
        else:
            ax.loglog(w, C, "--", lw=1.2, color=colors[(len(measured) + j) % len(colors)], label=label, zorder=3)
    if theory_on_top and len(theory):
        handles = [Line2D([], [], color="k", ls="--", lw=0.9, label=theory[0][2].split(",")[0] + " (dashed, darker shade of each colour)")]
    fit_lines = [_fit_line(ax, fit, label, ("-", "-.", ":")[k % 3]) for k, (fit, label) in enumerate(fits)]
    if band is not None:
        ax.axvspan(band[0], band[1], color="0.9", zorder=-1)
    if np.isfinite(lo):
        tv = np.concatenate([np.asarray(C, float)[np.asarray(C, float) > 0] for _, C, _ in theory] or [np.array([])])
        if tv.size:  # theory may widen the axis, but by two decades at most
            lo, hi = max(min(lo, tv.min()), lo / 100), min(max(hi, tv.max()), hi * 100)
        ax.set_ylim(lo / 3, hi * 3)
        follow_data(ax, [lo, hi], margin=3.0)
    ax.set_xlabel(r"$\omega$ (rad/s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    h = [x for x in ax.get_legend_handles_labels()[0] if x not in fit_lines]
    if fit_lines:
        ax.add_artist(ax.legend(handles=fit_lines, fontsize=8, loc="upper right", title="power-law fit (95 %); shaded: the frequencies fitted",
                                title_fontsize=7))
    ax.legend(handles=h + handles, fontsize=7, loc="lower left")
    fig.tight_layout()
    return fig


def figure_png_bytes(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


def save_figure(fig, path: Path) -> bytes:
    """Write a PNG and return its bytes (for embedding)."""
    data = figure_png_bytes(fig)
    Path(path).write_bytes(data)
    return data


def level_figure(v, C, exponent, err, omega_ref):
    """C_x at fixed omega against v, log-log, with the fitted power law."""
    fig = new_figure(5.4, 4.0)
    ax = fig.add_subplot()
    ax.loglog(v * 1e3, C, "o", label="runs")
    A = np.exp(np.mean(np.log(C) - exponent * np.log(v)))
    vv = np.logspace(np.log10(v.min()), np.log10(v.max()), 20)
    ax.loglog(vv * 1e3, A * vv**exponent, "-", label=f"fit: $v^{{{exponent:.2f} \\pm {err:.2f}}}$")
    ax.set_xlabel("v (mm/s)")
    ax.set_ylabel(rf"$C_x$, {omega_ref[0]:g}-{omega_ref[1]:g} rad/s (m$^2$ s)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def work_precision_figure(rows, floor: float = 1e-4):
    """Cost against error, log-log: every setting (red: Pareto front), the reference (error 0, drawn on the
    floor as a black star), each labelled at the first of four places beside its point that overlaps no other
    label and stays inside the figure."""
    fig = new_figure(6.0, 4.2)
    ax = fig.add_subplot()
    for r in rows:
        ref = r["pareto"] is None
        ax.plot(r["cost"], max(r["error"], floor), "*" if ref else "o", ms=10 if ref else 6,
                color="k" if ref else ("tab:red" if r["pareto"] else "0.5"), zorder=3)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.margins(x=0.15, y=0.2)
    ax.axhline(floor, color="0.7", lw=0.8, ls=":", zorder=1)
    ax.set_xlabel("wall s per simulated s")
    ax.set_ylabel(r"band-averaged $|\ln C_x / C_{x,\mathrm{ref}}|$" + f" (floor {floor:g})")
    ax.set_title("Engine work-precision (red: Pareto front; star: reference)", fontsize=9)
    ax.grid(True, which="major", alpha=0.3)
    fig.tight_layout()
    fig.canvas.draw()
    W, H = fig.canvas.get_width_height()
    boxes = []
    places = [((6, 4), "left", "bottom"), ((6, -5), "left", "top"), ((-6, 4), "right", "bottom"), ((-6, -5), "right", "top")]
    for r in rows:
        ref = r["pareto"] is None
        text = f"dt={r['dt']:g}, it={r['iterations']}" + (" (reference)" if ref else " (default)" if r["default"] else "")
        for k, (off, ha, va) in enumerate(places):
            a = ax.annotate(text, (r["cost"], max(r["error"], floor)), xytext=off, textcoords="offset points",
                            ha=ha, va=va, fontsize=7)
            bb = a.get_window_extent(fig.canvas.get_renderer())
            inside = bb.x0 >= 2 and bb.x1 <= W - 2 and bb.y0 >= 2 and bb.y1 <= H - 2
            if (inside and not any(bb.overlaps(b) for b in boxes)) or k == len(places) - 1:
                boxes.append(bb)
                break
            a.remove()
    return fig


def episode_histogram_figure(ep: dict, title: str = ""):
    """Trap/release episode durations (log bins) and episode forces, by state."""
    fig = new_figure(8.0, 3.6)
    a1, a2 = fig.subplots(1, 2)
    tau = ep["tau"]
    bins = np.logspace(np.log10(max(tau.min(), 1e-4)), np.log10(tau.max() * 1.01), 30) if tau.size else 10
    for code, name, col in ((1, "trapped", "tab:blue"), (2, "moving", "tab:red"), (0, "idle", "0.5")):
        sel = ep["state"] == code
        if not np.any(sel):
            continue
        a1.hist(tau[sel], bins=bins, histtype="step", lw=1.4, color=col, label=f"{name} ({sel.sum()})")
        if code:
            a2.hist(ep["force"][sel] * 1e3, bins=40, histtype="step", lw=1.4, color=col, label=name)
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("episode duration (s)")
    a1.set_ylabel("count")
    a1.legend(fontsize=7)
    a2.set_yscale("log")
    a2.set_xlabel("mean force on the pad in the episode (mN)")
    a2.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def velocity_series_figure(spectra: list, v, C, exponent: float, err: float, omega: float):
    """The paper's Fig. 15 for measured records: C_x against omega for each speed (left) and C_x(omega) against v
    with the fitted power law v^exponent (right), log-log; ``spectra`` is a list of (omega, C, label)."""
    fig = new_figure(10.0, 4.0)
    ax, bx = fig.subplots(1, 2)
    for w, c, label in spectra:
        ax.loglog(w, c, lw=1, label=label)
    ax.axvline(omega, color="k", ls=":", lw=1, label=rf"$\omega^*$ = {omega:.3g} rad/s")
    ax.set_xlabel(r"$\omega$ (rad/s)")
    ax.set_ylabel(r"$C_x$ (m$^2$ s)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    v, C = np.asarray(v), np.asarray(C)
    bx.loglog(v * 1e3, C, "o", label="records")
    A = np.exp(np.mean(np.log(C) - exponent * np.log(v)))
    vv = np.logspace(np.log10(v.min()), np.log10(v.max()), 20)
    bx.loglog(vv * 1e3, A * vv**exponent, "-", label=f"fit: $v^{{{exponent:.2f} \\pm {err:.2f}}}$")
    bx.set_xlabel("v (mm/s)")
    bx.set_ylabel(rf"$C_x(\omega^*)$ (m$^2$ s)")
    bx.grid(True, alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    return fig


def collapse_figure(curves: list):
    """Spectra in the distance domain: v C_x(omega = q v) against q = omega / v (section 2); (q, C_s, label) each."""
    fig = new_figure(5.4, 4.0)
    ax = fig.add_subplot()
    for q, c, label in curves:
        ax.loglog(q, c, lw=1, label=label)
    ax.set_xlabel(r"$q = \omega / v$ (rad/m)")
    ax.set_ylabel(r"$v\,C_x(\omega = q v)$ (m$^3$)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def vibration_figure(rows: list):
    """The vibration sweep against xi = v / (A omega_v), one curve per frequency (colour) and drive (marker: o
    constant force, s constant velocity): in-band C_x over the unshaken twin, gamma, the mean Coulomb part over the
    twin's, and the mean speed (force drive) or drive force (velocity drive) over the twin's, with 95 % intervals
    and the rigid (dashed) and compliant (dotted) contact predictions (first panel, dashed: the square of the
    measured Coulomb part's ratio); a thin vertical line per frequency at the onset of reversal of the linear pads
    (xi = the pads' slip share, A = A_onset)."""
    fig = new_figure(10.0, 7.4)
    axs = fig.subplots(2, 2, sharex=True).ravel()
    freqs = sorted({r["frequency"] for r in rows})
    colours = dict(zip(freqs, rcParams["axes.prop_cycle"].by_key()["color"]))
    panels = (("C_ratio", r"in-band $C_x$ / twin", None), ("gamma", r"$\gamma$ (fit)", None),
              ("coulomb", "mean Coulomb part / twin", "coulomb"), ("motion", "speed (o) or drive force (s) / twin",
                                                                    "motion"))
    for f in freqs:
        for cf, mk in ((True, "o"), (False, "s")):
            rr = sorted((r for r in rows if r["frequency"] == f and r["constant_force"] == cf), key=lambda r: r["xi"])
            if not rr:
                continue
            xi = np.array([r["xi"] for r in rr])
            lab = f"{f:g} Hz, {'force' if cf else 'velocity'}"
            for ax, (key, _, pred) in zip(axs, panels):
                k = key if key != "motion" else ("speed" if cf else "drive")
                y, e = np.array([r[k] for r in rr]), np.array([r[k + "_ci"] for r in rr])
                ax.errorbar(xi, y, yerr=e, fmt=mk + "-", color=colours[f], ms=4, lw=0.8, capsize=2,
                            mfc="none" if not cf else colours[f], label=lab)
                if key == "C_ratio":  # the square of the measured Coulomb part's ratio
                    ax.plot(xi, [r["coulomb_sq"] for r in rr], "--", color=colours[f], lw=1.0)
                if pred is not None:
                    base = {"coulomb": "coulomb", "motion": "speed" if cf else "drive"}[pred]
                    for suffix, ls in (("_rigid", "--"), ("_compliant", ":"), ("_pads", "-.")):
                        if base + suffix in rr[0]:
                            ax.plot(xi, [r[base + suffix] for r in rr], ls, color=colours[f], lw=1.0)
        onset = [r["pad_share"] for r in rows if r["frequency"] == f]
        for ax in axs:
            ax.axvline(onset[0], color=colours[f], lw=0.6, ls=(0, (1, 3)))
    axs[0].set_yscale("log")
    axs[0].axhline(1.0, color="k", lw=0.6)
    measured = [r["C_ratio"] for r in rows if r["C_ratio"] > 0]
    if measured:  # the measured levels set the axis; the squared Coulomb ratio may run far below them
        axs[0].set_ylim(min(measured) / 5, max(max(measured), 1.0) * 3)
    twin = [r["gamma_twin"] for r in rows]
    if twin:
        axs[1].axhline(float(np.nanmean(twin)), color="k", lw=0.6, label="unshaken twins")
    from matplotlib.ticker import NullFormatter

    for ax, (_, ylab, _) in zip(axs, panels):
        ax.set_xscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.set_ylabel(ylab)
        ax.grid(True, alpha=0.3)
    for ax in axs[2:]:
        ax.set_xlabel(r"$\xi = v / (A\,\omega_v)$")
    h, _ = axs[0].get_legend_handles_labels()
    axs[0].legend(handles=h + [Line2D([], [], color="k", ls="--", label="(measured Coulomb part / twin)$^2$")],
                  fontsize=7)
    axs[2].legend(handles=[Line2D([], [], color="k", ls="--", label="rigid contacts (arcsin, held share)"),
                           Line2D([], [], color="k", ls=":", label="compliant pads (Jenkins element)"),
                           Line2D([], [], color="k", ls="-.", label="arcsin with the linear pads' slip share")],
                   fontsize=7)
    fig.tight_layout()
    return fig
