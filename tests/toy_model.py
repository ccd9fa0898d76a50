"""A toy reduced model for the registration tests: a block whose position is a random walk on top of steady
sliding, x = v t + W(t) with <W(t)^2> = 2 D t, so its displacement spectrum is exactly C_x = D / (pi omega^2)
(two-sided, eq. 2) up to the sampling's sinc factor, which is below 0.1 % at omega dt < 0.1. It declares the
registration protocol of reduced_models/__init__.py and nothing else."""
from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from reduced_models.trace import ModelTrace

RESPONSE = "viscous"
SWEEP_SERIES = "x"


@dataclass(frozen=True)
class ToyParams:
    """v: sliding speed (m/s); D: diffusion coefficient of the walk (m^2/s)."""

    v: float = 1e-3
    D: float = 1e-12

    def __post_init__(self):
        for name in ("v", "D"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive (got {getattr(self, name)!r})")

    def to_dict(self) -> dict:
        return asdict(self)


PARAMS = ToyParams


def simulate(params: ToyParams, duration: float, dt_out: float = 1e-3, seed=None) -> ModelTrace:
    n = int(round(duration / dt_out))
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt_out
    walk = np.concatenate([[0.0], np.cumsum(rng.normal(0.0, np.sqrt(2 * params.D * dt_out), n - 1))])
    return ModelTrace(t=t, x=params.v * t + walk, force=np.zeros(n), metadata={"model": "toy"})


def theory_spectrum(params: ToyParams, omega) -> np.ndarray:
    return params.D / (np.pi * np.asarray(omega, dtype=float) ** 2)


def fit_band(params: ToyParams, dt_out: float | None = None):
    return 1.0, 100.0  # rad/s: omega dt_out <= 0.1 at the 1 ms default


def default_duration(params: ToyParams) -> float:
    return 200.0


def default_dt_out(params: ToyParams) -> float:
    return 1e-3
