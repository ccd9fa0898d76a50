"""A synthetic stylus-profilometer export, written the way such instruments write line scans: a scan-parameter
preamble, a "Scan Data" header, latin-1 text (the micro sign, the angstrom sign), CRLF line ends and two empty
trailing columns on every data row. The surface is made here (seeded), not measured: a self-affine line (Hurst
0.8, roll-off 0.25 mm, cut-off 1 um) of 1.5 um rms, a 2 nm noise floor, a 0.2 % tilt and an offset.

``python -m tests.stylus_export`` rewrites the shipped copy,
engine_sim/scenarios/profiles/synthetic_stylus_export.csv."""
from __future__ import annotations

from pathlib import Path

import numpy as np

SHIPPED = Path(__file__).resolve().parent.parent / "engine_sim" / "scenarios" / "profiles" / \
    "synthetic_stylus_export.csv"
SPACING_UM = 0.156
POINTS = 12821  # 2 mm


def stylus_heights(n: int = POINTS, dx: float = SPACING_UM * 1e-6, seed: int = 2026, rms: float = 1.5e-6):
    """Heights (m) of the synthetic surface, before tilt and offset: Fourier-filtered white noise."""
    rng = np.random.default_rng(seed)
    m = 2 * n
    q = 2 * np.pi * np.fft.rfftfreq(m, dx)
    qr, qs = 2 * np.pi / 0.25e-3, 2 * np.pi / 1e-6
    amp = (np.maximum(q, qr) / qr) ** -1.3  # |amp|^2 ~ q^-(1 + 2H), H = 0.8
    amp[q > qs] = 0.0
    amp[0] = 0.0
    h = np.fft.irfft(np.fft.rfft(rng.standard_normal(m)) * amp, m)[:n]
    return h * (rms / h.std()) + 2e-9 * rng.standard_normal(n)


def stylus_export(n: int = POINTS, newline: str = "\r\n", heights=None, rows=None) -> bytes:
    """The export as bytes (latin-1). ``heights`` (m) replaces the surface; ``rows`` (a list of data-row strings)
    replaces the data rows as written."""
    x_um = SPACING_UM * np.arange(n)
    h = stylus_heights(n) if heights is None else np.asarray(heights, float)
    h_A = 1e10 * (h + 2e-3 * x_um * 1e-6 + 0.8e-6)  # tilt 0.2 %, offset 0.8 um, in angstrom
    pre = ["Scan Parameters,,,", "Instrument,Synthetic stylus profilometer (frictionnoise test file),,",
           "Date,2026-11-25 10:30:00,,", "Scan Type,Standard Scan,,", f"Scan Length,{SPACING_UM * (n - 1):.3f},µm,",
           "Scan Duration,60,s,", f"Resolution,{SPACING_UM:.3f},µm/pt,", "Stylus Radius,2,µm,",
           "Stylus Force,3,mg,", "Measurement Range,65.5,µm,", "Profile,Hills and Valleys,,", f"Data Points,{n},,",
           "Scan Data,,,", "", "Lateral (µm),Total Profile (Å),,"]
    data = rows if rows is not None else [f"{a:.3f},{b:.1f},," for a, b in zip(x_um, h_A)]
    return newline.join(pre + data + [""]).encode("latin-1")


if __name__ == "__main__":
    SHIPPED.write_bytes(stylus_export())
    print(f"wrote {SHIPPED} ({SHIPPED.stat().st_size} bytes)")
