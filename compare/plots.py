"""Figures for reports (matplotlib, Agg). The only module of compare that imports matplotlib.

Figures are ``matplotlib.figure.Figure`` objects with their own Agg canvas: importing this module never changes
the program's matplotlib backend, and no figure is registered with pyplot."""
from __future__ import annotations

import io
from pathlib import Path

import matplotlib
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .spectra import Spectrum, log_bin


def _subplots(*grid, figsize, dpi, **kw):
    """A Figure on its own Agg canvas and its axes (pyplot's subplots without pyplot's backend or registry)."""
    fig = Figure(figsize=figsize, dpi=dpi)
    FigureCanvasAgg(fig)
    return fig, fig.subplots(*grid, **kw)

__all__ = ["spectrum_figure", "save_figure", "figure_png_bytes", "episode_histogram_figure"]


def spectrum_figure(measured: list, theory: list = (), *, title: str = "", ylabel: str = r"$C_x$ (m$^2$ s)",
                    fits: list = (), band: tuple | None = None):
    """Log-log overlay.

    measured : list of (Spectrum, label) -- drawn log-binned (20 per decade) as lines with markers.
    theory : list of (omega, C, label) -- drawn as dashed lines.
    fits : list of (PowerLawFit, label) -- drawn as thin lines over their band.
    band : shaded frequency band (rad/s), e.g. the fit band.
    """
    fig, ax = _subplots(figsize=(6.4, 4.6), dpi=110)
    colors = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (spec, label) in enumerate(measured):
        b = log_bin(spec, 20) if isinstance(spec, Spectrum) else spec
        ax.loglog(b.omega, b.C, "-", marker=".", ms=3, lw=1.2, color=colors[i % len(colors)], label=label)
    for j, (w, C, label) in enumerate(theory):
        ax.loglog(w, C, "--", lw=1.4, color=colors[(len(measured) + j) % len(colors)] if len(theory) > len(measured)
                  else colors[j % len(colors)], alpha=0.9, label=label)
    for fit, label in fits:
        w = np.logspace(np.log10(fit.band[0]), np.log10(fit.band[1]), 20)
        ax.loglog(w, fit.level(w) * 3.0, "k-", lw=0.8)
        ax.text(np.sqrt(fit.band[0] * fit.band[1]), fit.level(np.sqrt(fit.band[0] * fit.band[1])) * 4.5,
                f"{label}$\\gamma$ = {fit.gamma:.2f} ± {fit.gamma_err:.2f}", fontsize=8, ha="center")
    if band is not None:
        ax.axvspan(band[0], band[1], color="0.9", zorder=-1)
    ax.set_xlabel(r"$\omega$ (rad/s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
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
    fig, ax = _subplots(figsize=(5.4, 4.0), dpi=110)
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


def work_precision_figure(rows):
    """Cost against error, log-log; Pareto front in red, the default labelled."""
    fig, ax = _subplots(figsize=(5.5, 4.0), dpi=110)
    for r in rows:
        if r["pareto"] is None:
            continue
        e = max(r["error"], 1e-4)
        ax.plot(r["cost"], e, "o", color="tab:red" if r["pareto"] else "0.5")
        ax.annotate(f"dt={r['dt']:g}, it={r['iterations']}{' (default)' if r['default'] else ''}", (r["cost"], e), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall s per simulated s")
    ax.set_ylabel(r"band-averaged $|\ln C_x / C_{x,\mathrm{ref}}|$ (floor 1e-4)")
    ax.set_title("Engine work-precision (red: Pareto front)", fontsize=9)
    fig.tight_layout()
    return fig


def episode_histogram_figure(ep: dict, title: str = ""):
    """Trap/release episode durations (log bins) and episode forces, by state."""
    fig, (a1, a2) = _subplots(1, 2, figsize=(8.0, 3.6), dpi=110)
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
