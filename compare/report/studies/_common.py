"""Small helpers shared by the studies: per-band ratios, timings, balances, the exponent of a time record."""
from __future__ import annotations

import math
import time

import numpy as np

from ..html import esc, num, pct, span
from ...analysis.balances import SAMPLES_PER_PERIOD, balances  # noqa: F401  (balances re-exported for the studies)
from ...analysis.spectra import band_average

__all__ = ["energy_text", "segment_samples", "band_ratios", "ratio_rows", "log_err", "param_rows", "timed", "timing", "balances", "ratio_range",
           "require_band", "whole_run", "run_scene", "record_fit"]


def segment_samples(n: int, dt_out: float, quick: bool) -> int:
    """Samples in a scene study's Welch segment: a power of two of at most 4.1 s (quick) or 8.2 s (2^12 and 2^13
    samples at the shipped scenes' 1 ms output step), and at most a third of the record's ``n`` samples. The cap is
    a time, not a count, so a finer output step resolves the same low frequencies."""
    cap = 1 << int(math.floor(math.log2((4.096 if quick else 8.192) / dt_out) + 1e-9))
    return min(cap, 1 << int(math.floor(math.log2(n / 3))))


def require_band(spec, band, T: float, dt_out: float, nominal_low: float | None = None,
                 what: str = "the fit band 3-30 v/a"):
    """ValueError naming the duration a run needs when its spectrum (segments of 2^floor(log2(n / 3)) samples, as the
    scene studies take them) does not resolve the band's bottom: one line for the CLI, not 'band ... lies outside
    the resolved range'. v / a read from a short run scatters (pads_friction_patches' band bottom: 59 rad/s at 0.2 s,
    28 at 0.5 s, 18.8 at 1 s, against 15 from the law's speed and the patch length), so the advice takes the lower
    of the measured bottom over 1.25 and ``nominal_low`` (the scene's own, when it has one): a run of the length it
    names resolves its band."""
    if band[0] >= spec.omega_min * (1 - 1e-9):
        return
    low = min(band[0] / 1.25, nominal_low or math.inf)
    n_need = 1 << math.ceil(math.log2(2 * math.pi / (low * dt_out)))
    raise ValueError(f"a {T:g} s run is too short for {what} = ({band[0]:.3g}, {band[1]:.3g}) rad/s: it needs at "
                     f"least {math.ceil(3 * n_need * dt_out):.0f} s (--duration)")


def record_fit(t, x, band=None, quantity: str = "x", stationarity: bool = True, integrate: bool = False):
    """The exponent of a time record, as every study quotes it: the record model
    (:func:`compare.analysis.record_model.fit_series`, whose parameters these are), not a straight line through a
    Welch spectrum."""
    from ...analysis.record_model import fit_series

    return fit_series(t, x, band=band, quantity=quantity, stationarity=stationarity, integrate=integrate)


def band_ratios(spec, theory_values, edges) -> list:
    """[{"band": [lo, hi], "ratio": measured / theory}] over consecutive log bands."""
    r = band_average(spec, edges) / band_average(spec, edges, theory_values)
    return [{"band": [float(edges[i]), float(edges[i + 1])], "ratio": float(r[i])} for i in range(len(r))]


def ratio_rows(ratios) -> list:
    """Table rows (band, ratio) of per-band ratios, each ratio to three significant figures."""
    return [[f"{span(b['band'][0], b['band'][1])}", num(b['ratio'])] for b in ratios]


def ratio_range(ratios, fmt=".2f") -> str:
    """"lo-hi" of the per-band ratios, in ``fmt`` when both ends keep two significant figures in it (0.95-1.04),
    else to three significant figures (1.5e-04-6.9e-04, not 0.00-0.00)."""
    r = [b["ratio"] for b in ratios]
    lo, hi = min(r), max(r)
    decimals = int(fmt.strip(".f")) if fmt.endswith("f") else 0
    if fmt.endswith("f") and lo > 0 and math.floor(math.log10(lo)) + decimals >= 1:
        return f"{lo:{fmt}}-{hi:{fmt}}"
    return span(lo, hi, 2 if decimals <= 2 else 3)


def log_err(ratios) -> float:
    """Band-averaged |ln ratio|."""
    return float(np.mean([abs(math.log(b["ratio"])) for b in ratios]))


def param_rows(ex: dict) -> list:
    """Table rows (name, value, unit, provenance) of an extracted-parameter dict."""
    return [[k, f"{v['value']:.4g}", esc(v["unit"]), esc(v["provenance"])] for k, v in ex.items()]


def whole_run(sc, seed=None, progress=None):
    """``engine_sim.run`` for a study: a run that Ctrl-C cut short is not analysed (its partial trace would go on
    into the spectra and end as a misleading error); the interrupt goes on to the caller."""
    import engine_sim

    tr = engine_sim.run(sc, seed=seed, progress=progress)
    if tr.metadata.get("partial"):
        raise KeyboardInterrupt
    return tr


def timed(fn, *a, **k):
    """(fn(*a, **k), wall seconds)."""
    t0 = time.perf_counter()
    out = fn(*a, **k)
    return out, time.perf_counter() - t0


def timing(model: str, run: str, wall, err) -> dict:
    """A row of the report's speed table: wall time (s) and error as numbers (None for n/a), so summary.json holds
    numbers; the table shows them as given."""
    def num(v):
        try:
            return float(v)
        except (TypeError, ValueError):
            return None
    return {"model": model, "run": run, "wall_s": num(wall), "mean_abs_log_ratio": num(err)}


def energy_text(d: dict, digits: int = 4) -> str:
    """"energy balance X %" as the report states it; in a shaken trace sampled too coarsely to resolve the
    vibration (:func:`compare.analysis.balances.balances`), what the residual then holds."""
    text = f"energy balance {pct(d['energy_balance_rel'], digits)}"
    if d.get("energy_balance_resolved") is False:
        text += (f" (the sampled powers hold {d['samples_per_vibration_period']:.3g} samples per vibration period; "
                 f"past the pads' onset of reversal it closes within 1e-3 from {SAMPLES_PER_PERIOD}, so this "
                 "residual is stated, not bounded)")
    return text


def run_scene(sc, quick, seed, trace, duration, progress):
    """The scene's trace (run now unless given), its wall time and duration. A shaken scene's line at the
    vibration's frequency and its harmonics below the output's Nyquist frequency are fitted and removed from x(t)
    (:func:`compare.analysis.harmonics.remove_harmonics`), the fit kept in ``metadata["line_removed"]``. The pads'
    forces lose the vibration too, or its period would pass for the renewal length (past the onset of reversal at
    1 kHz: 1.5 um for the patches' 1 mm, and the fit band 3-30 v/a above the Nyquist frequency): a vibration whose
    period is under a tenth of the scene's length scale in sliding distance is averaged out over one period (a
    boxcar of the samples nearest one period); a slower one has its line and harmonics removed as x(t) has. What
    was done is in ``metadata["force_filter"]``."""
    if trace is None:
        T = duration or (sc.substrate_part.quick_duration if quick else sc.run.duration)
        tr, wall = timed(whole_run, sc.with_run(duration=T), seed=seed, progress=progress)
    else:
        tr, wall = trace, float(trace.metadata.get("wall_s", float("nan")))
        T = float(tr.t[-1])
    vib = getattr(sc, "vibration", None)
    if vib is not None and vib.amplitude > 0:
        from dataclasses import replace

        from scipy.ndimage import uniform_filter1d

        from ...analysis.harmonics import remove_harmonics

        w_v = 2 * math.pi * vib.frequency
        x, line = remove_harmonics(tr.t, tr.x, w_v, harmonics=4, order=2)
        dt_out = float(tr.t[1] - tr.t[0])
        ell = tr.metadata.get("scene", {}).get("length_scale") or getattr(sc.substrate, "a", None) or 0.0
        f = tr.pad_force
        if f.size and sc.steady_velocity / vib.frequency < 0.1 * ell:
            n = max(1, round(1.0 / (vib.frequency * dt_out)))
            f = uniform_filter1d(f, n, axis=0, mode="nearest")
            how = f"averaged over {n} samples ({1e3 * n * dt_out:.3g} ms, one vibration period)"
        elif f.size:  # a force's spectrum is flatter than a position's (omega^-2 above v/a): one difference
            f = np.column_stack([remove_harmonics(tr.t, f[:, i], w_v, harmonics=4, order=1)[0]
                                 for i in range(f.shape[1])])
            how = "with the line and its harmonics removed, as x(t)"
        else:
            how = ""
        tr = replace(tr, x=x, pad_force=f,
                     metadata={**tr.metadata, "line_removed": line.to_dict(), "force_filter": how})
    return tr, wall, T


def line_text(tr) -> str:
    """The sentence that says a shaken scene's line was removed from x(t) before its spectrum ("" if none was)."""
    line = tr.metadata.get("line_removed")
    if not line:
        return ""
    f = line["omega"] / (2 * math.pi)
    kept = [f"{1e6 * a:.3g} um at {k + 1} f_v" for k, a in enumerate(line["amplitude"]) if a == a]
    return (f"The scene is shaken at f_v = {f:g} Hz: the line and its harmonics below the output's Nyquist frequency "
            f"were fitted and removed from x(t) before the spectrum ({', '.join(kept) or 'none resolved'}); the "
            "spectra, fits and ratios here hold the noise alone. The in-band effect of the vibration is read against "
            "the unshaken twin (the same scene with amplitude 0 and the same seed), not against model I."
            + (f" The pads' forces were {tr.metadata['force_filter']} before the renewal length and alpha were "
               "measured." if tr.metadata.get("force_filter") else ""))
