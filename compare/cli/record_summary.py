"""The terminal's account of an analysed measured record: the breaks of its time stamps and the blocks of its
export as they are read, then the lines that close ``frictionnoise analyze`` (strokes, pieces, per-block means,
fits; everything is also in summary.json)."""
from __future__ import annotations

__all__ = ["print_breaks", "force_lines", "displacement_lines"]


def print_breaks(timeline, most: int = 10):
    """The breaks of a record's time stamps, one line each (at most ``most``), and its uniform segments."""
    if timeline is None or not timeline.events:
        return
    for e in timeline.events[:most]:
        print(f"{'export' if e.kind == 'block' else 'time stamps'}: {e.describe()}")
    if len(timeline.events) > most:
        print(f"time stamps: ... and {len(timeline.events) - most} more breaks (all in summary.json)")
    used = timeline.usable()
    what = "segments" if all(e.kind == "block" for e in timeline.events) else "time stamps"
    print(f"{what}: {len(timeline.segments)} uniform segments, {len(used)} long enough to analyse (steps "
          f"{', '.join(f'{s.dt:.4g}' for s in used)} s)")


def _fit_text(f: dict) -> str:
    """A fit as the terminal shows it: exponent, 95 % interval, method, band, the floor (record model), flags."""
    ci = (f"+-: 95 % half-width; interval [{f['gamma_interval'][0]:.3f}, {f['gamma_interval'][1]:.3f}]"
          if "gamma_interval" in f else "+-: 95 % half-width")
    return (f"{f['gamma']:.3f} +- {f['gamma_err']:.3f} ({ci}, {f['method']}) over {f['band'][0]:.3g}-{f['band'][1]:.3g} "
            f"rad/s{_floor_text(f)}{_flags_text(f)}")


def _floor_text(f: dict) -> str:
    """The record model's white floor and what ends its band, in words
    (:func:`compare.analysis.record_model.band_end_words`): no floor detected, a floor below the power law over the
    whole band, a floor that ends the band at its crossover, or a band cut where the spectrum departs from the power
    law in another shape (a resonance's approach, a corner), named as such and not as a floor."""
    if "floor" not in f:
        return ""
    from compare.analysis.record_model import band_end_words  # here: the CLI starts without scipy.stats

    rms, cross = f.get("floor_rms") or 0.0, f.get("crossover")
    end = f.get("band_end") or ("floor" if rms > 0 and cross is not None and cross <= f["band"][1] * (1 + 1e-9)
                                else "last frequency")
    segments = [(s["band"][0], s["band"][1], s["gamma"]) for s in f.get("segments") or []]
    unit = f.get("record_unit", "m")  # the fitted record's unit (a force fitted through its sum: N s)
    return band_end_words(end, rms, cross, f["band"][1], f["gamma"], segments, f" {unit}" if unit else "")


def _flags_text(f: dict) -> str:
    return "" if f["power_law"] else f" [not a power law: {'; '.join(f['flags'])}]"


def force_lines(summary: dict, index, most: int = 10) -> list:
    st = summary["strokes"]
    lines = [f"strokes ({st['method']}): {st['found']} found, {st['used']} used, {len(st['dropped'])} dropped; "
             f"{st['cut_each_end_s']:.4g} s cut at each end"]
    pieces = summary.get("pieces") or []
    if pieces:
        lines.append(f"uniform pieces (strokes cut at the breaks): {len(pieces)}, "
                     f"{sum(p['in_combined'] for p in pieces)} in the combined spectrum (common window "
                     f"{summary['piece_window_s']:.4g} s)")
    for i, p in enumerate(pieces[:most]):
        lines.append(f"  piece {i + 1}: stroke {p['stroke']}, rows {p['start_row'] + 1}-{p['stop_row']}, t = "
                     f"{p['t_start_s']:.6g}-{p['t_stop_s']:.6g} s, step {p['dt_s']:.4g} s, "
                     + ("in the combined spectrum" if p["in_combined"] else "not in the combined spectrum"))
    if len(pieces) > most:
        lines.append(f"  ... and {len(pieces) - most} more pieces (all in summary.json)")
    lines += _block_lines(summary, most)
    if "fit_mu" in summary:
        lines.append(f"C_mu of {summary['mu_source']}: exponent {_fit_text(summary['fit_mu'])}; mean |mu| = "
                     f"{summary['mean_abs_mu']:.4g}")
    return lines + [f"wrote {index}: force exponent {_fit_text(summary['fit_F'])}"] + [
        f"  {n}" for n in summary["fit_F"].get("notes", [])]


def _block_lines(summary: dict, most: int = 10) -> list:
    """The pooled mean |F| (and |mu|) of a multi-block export, then each block's own (blocks run at different
    loads): one line each, at most ``most`` blocks."""
    blocks = summary.get("blocks") or []
    if not blocks:
        return []
    mu = "mean_abs_mu" in summary
    pooled = f"mean |F| = {summary['mean_abs_F_N']:.4g} N" + (f", mean |mu| = {summary['mean_abs_mu']:.4g}" if mu else "")
    lines = [f"{pooled} pooled over {len(blocks)} blocks; by block:"]
    for b in blocks[:most]:
        lines.append(f"  block {b['block']}{' (' + b['title'] + ')' if b['title'] else ''}, from {b['place']}, t = "
                     f"{b['t_start_s']:.6g}-{b['t_stop_s']:.6g} s: mean |F| = {b['mean_abs_F_N']:.4g} N"
                     + (f", mean |mu| = {b['mean_abs_mu']:.4g}" if "mean_abs_mu" in b else "")
                     + (f", mean |N| = {b['mean_abs_N_N']:.4g} N" if "mean_abs_N_N" in b else ""))
    if len(blocks) > most:
        lines.append(f"  ... and {len(blocks) - most} more blocks (all in summary.json)")
    return lines


def displacement_lines(summary: dict, index) -> list:
    lines = [f"wrote {index}",
             f"  C_x ~ omega^-gamma, gamma = {_fit_text(summary['fit'])}",
             f"  mean velocity {summary['mean_velocity']:.4g} m/s; zeta_rms = {summary['zeta_rms_m']:.4g} m over "
             f"{summary['zeta_rms_band'][0]:.3g}-{summary['zeta_rms_band'][1]:.4g} rad/s (eq. 4), mu_rms = "
             f"{summary['mu_rms']:.4g} over {summary['mu_rms_band'][0]:.3g}-{summary['mu_rms_band'][1]:.4g} rad/s, the "
             f"fitted band within the Welch spectrum's (C_mu = omega^4 C_x / g^2; a white floor above the band is the sensor's, not friction)"]
    if "fit_F" in summary:
        lines.append(f"  C_F = M^2 omega^4 C_x (M = {summary['mass_kg']:g} kg, eq. 3): force exponent "
                     f"{_fit_text(summary['fit_F'])}; F_rms = {summary['F_rms_N']:.4g} N")
    return lines + [f"  {n}" for n in ([] if "fit_F" in summary else summary["notes"]) + summary["fit"].get("notes", [])]
