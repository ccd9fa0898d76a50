"""Write reciprocating_force.txt beside this script: a synthetic reciprocating tribometer export with a known exponent.

Model (everything exact by construction, numpy only):

- sliding speed v = 2.5 mm/s, stroke 30 mm (12 s), sampled at 250 Hz; the record starts 7 s into a stroke and
  ends 5 s into the stroke after the last full one, so it holds 8 full strokes and 2 partial ones (5 s each);
- friction force F = s(t) mu0 Fn + r(t) + n(t): s = +-1 the direction of motion, mu0 = 0.5, Fn = 10 N;
  r(t) a reversal transient, a static-friction overshoot 0.8 N (1 + t'/0.02 s) e^{-t'/0.02 s} after each
  reversal (t' the time since it), negligible 0.3 s later;
  n(t) Gaussian noise with C_F(omega) = A omega^-1.2 exactly (Fourier synthesis over the whole record),
  rms 0.05 N: the known force exponent is 1.2;
- normal force Fn(t) = 10 N + 0.01 N white noise; position a triangle wave between 0 and 30 mm; direction +1/-1.

Layout as instrument software writes it: a metadata preamble, a `;`-separated header, a units row, decimal
commas. Run: ``python engine_sim/scenarios/data/make_reciprocating.py`` (seed 2025; the file is rewritten bit for
bit).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

FS = 250.0  # Hz
V = 2.5e-3  # m/s
STROKE_S = 12.0
OFFSET_S = 7.0  # the record starts this far into a stroke
N_FULL = 8
TAIL_S = 5.0  # the record ends this far into the stroke after the last full one
GAMMA_F = 1.2
NOISE_RMS = 0.05  # N
MU0, FN = 0.5, 10.0
SEED = 2025
OUT = Path(__file__).with_name("reciprocating_force.txt")


def power_law_noise(n: int, gamma: float, rms: float, rng) -> np.ndarray:
    """Gaussian series with spectrum ~ omega^-gamma (Fourier synthesis, exact on the record's frequency grid)."""
    f = np.fft.rfftfreq(n)
    amp = np.zeros_like(f)
    amp[1:] = f[1:] ** (-gamma / 2)
    c = (rng.standard_normal(len(f)) + 1j * rng.standard_normal(len(f))) * amp
    y = np.fft.irfft(c, n)
    return y * (rms / y.std())


def make(seed: int = SEED):
    rng = np.random.default_rng(seed)
    dur = (STROKE_S - OFFSET_S) + N_FULL * STROKE_S + TAIL_S
    n = int(round(dur * FS))
    t = np.arange(n) / FS
    tau = t + OFFSET_S  # time since the start of stroke 0
    k = np.floor(tau / STROKE_S).astype(int)
    since = tau - k * STROKE_S
    direction = np.where(k % 2 == 0, 1, -1)
    x = np.where(direction > 0, V * since, V * (STROKE_S - since))
    transient = 0.8 * (1 + since / 0.02) * np.exp(-since / 0.02)
    transient[k == 0] = 0.0  # the record does not see the first reversal
    F = direction * (MU0 * FN + transient) + power_law_noise(n, GAMMA_F, NOISE_RMS, rng)
    Fn = FN + 0.01 * rng.standard_normal(n)
    return t, x, F, Fn, direction


def write(path: Path = OUT, seed: int = SEED) -> Path:
    t, x, F, Fn, d = make(seed)
    lines = ["Tribometer export (synthetic, frictionnoise scenarios/data/make_reciprocating.py)",
             f"Test;reciprocating;speed 2.5 mm/s;stroke 30 mm;seed {seed}",
             "Sample rate;250 Hz",
             "",
             "Time;Position;Ff;Fn;Direction",
             "s;mm;N;N;"]
    for row in zip(t, 1e3 * x, F, Fn, d):
        lines.append(f"{row[0]:.3f};{row[1]:.3f};{row[2]:.5f};{row[3]:.3f};{row[4]:d}".replace(".", ","))
    path.write_text("\n".join(lines) + "\n")
    return path


if __name__ == "__main__":
    p = write()
    print(f"wrote {p} ({p.stat().st_size / 1e3:.0f} kB)")
