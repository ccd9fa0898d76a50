"""Randomly rough self-affine tracks (streamed FIR-filtered white noise), uniform friction."""
from __future__ import annotations

from dataclasses import dataclass
from statistics import NormalDist

import numpy as np

from .. import units as U
from ..substrate import SelfAffineTrack, self_affine_kernel
from . import SUBSTRATES, Substrate, SubstrateSpec


@dataclass(frozen=True)
class SelfAffineSpec(SubstrateSpec):
    """A randomly rough profile by Fourier synthesis: Hurst exponent ``hurst`` of the *line* (its 1D spectrum
    falls as q^-(1+2H), as a line scan across an isotropic surface of the same H), roll-off wavelength
    ``lambda_r`` (flat spectrum above it), short cut-off ``lambda_s``, rms slope ``rms_slope`` (m, m, -); grid
    spacing lambda_s / 4; friction mu0 everywhere. ``a`` is the renewal length used for the fit band (set it to
    lambda_r)."""

    kind: str = "self_affine"
    a: float = 2e-3
    hurst: float = 0.8
    lambda_r: float = 2e-3
    lambda_s: float = 0.1e-3
    rms_slope: float = 0.1


def sliding_limit(mu0: float) -> float:
    """Largest rms slope a pad slides over: 1/(6 mu0) (the steepest flanks, ~4 rms slopes, near the locking
    slope 1/mu0 pin the pads; measured on pads_rough_profile)."""
    return 1.0 / (6.0 * max(mu0, 1e-9))


@SUBSTRATES.register
class SelfAffine(Substrate):
    name = "self_affine"
    Spec = SelfAffineSpec
    positive = Substrate.positive | {"lambda_r", "lambda_s", "rms_slope"}
    quick_duration = 8.0  # streaming its short segments costs about 1 wall s per simulated s

    @classmethod
    def validate(cls, s, sc, where=""):
        if not 0 < s.hurst < 1:
            raise ValueError(f"substrate.hurst must lie in (0, 1) (got {s.hurst!r})")
        if not s.lambda_s < s.lambda_r:
            raise ValueError(f"substrate.lambda_s = {s.lambda_s!r} m must be shorter than lambda_r = {s.lambda_r!r} m")
        limit = sliding_limit(sc.friction.mu0)
        if s.rms_slope > limit:
            raise ValueError(f"substrate.rms_slope = {s.rms_slope!r} exceeds the sliding limit {limit:.3g} = 1/(6 mu0): "
                             "the steepest flanks (~4 rms slopes) near the locking slope 1/mu0 pin the pads "
                             "(measured on pads_rough_profile: rms slope 0.4 pins the block, 0.3 slides unsteadily)")

    def __init__(self, spec, scenario):
        super().__init__(spec, scenario)
        s = spec
        self.dx = s.lambda_s * U.LENGTH / 4
        self.kernel = self_affine_kernel(s.hurst, s.lambda_r * U.LENGTH, s.lambda_s * U.LENGTH, self.dx, s.rms_slope)

    def pad_depth(self, fraction, pad_radius):
        """The Gaussian heights' depth exceeded on ``fraction`` of the track, z h_rms (m; h_rms of the kernel on unit
        white noise). A pad's path over this profile has the profile's rms within 1 % (radius 0.3 mm over
        pads_rough_profile's, 50 m of track), so the profile's quantile stands for the path's."""
        h_rms = float(np.sqrt(np.sum(self.kernel**2))) / U.LENGTH
        return NormalDist().inv_cdf(1 - fraction) * h_rms

    def build(self, space, y, shape_filter, rng, mu, x_start):
        return SelfAffineTrack(space, y, self.kernel, self.dx, mu, self.spec.segment_radius * U.LENGTH, shape_filter,
                               rng, x_start=x_start, chunk_points=64)
