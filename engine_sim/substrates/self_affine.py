"""Randomly rough self-affine tracks (streamed FIR-filtered white noise), uniform friction."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from statistics import NormalDist

import numpy as np

from ..substrate import SelfAffineTrack, self_affine_kernel
from .substrate import SUBSTRATES, Substrate, SubstrateSpec


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

    scene_units = {**Substrate.scene_units, "lambda_r": "length", "lambda_s": "length"}

    @staticmethod
    def _kernel(s, lambda_r, lambda_s):
        """(the FIR kernel, its grid spacing dx = lambda_s / 4) in the units of the lengths given."""
        dx = lambda_s / 4
        return self_affine_kernel(s.hurst, lambda_r, lambda_s, dx, s.rms_slope), dx

    @cached_property
    def kernel_si(self):
        """The kernel in metres (the scenario side's depths)."""
        return self._kernel(self.spec, self.spec.lambda_r, self.spec.lambda_s)[0]

    @cached_property
    def scene_kernel(self):
        """(kernel, dx) in scene units (mm), computed once per scene."""
        return self._kernel(self.spec, self.own.lambda_r, self.own.lambda_s)

    def pad_depth(self, fraction, pad_radius):
        """The Gaussian heights' depth exceeded on ``fraction`` of the track, z h_rms (m; h_rms of the kernel on unit
        white noise). A pad's path over this profile has the profile's rms within 1 % (radius 0.3 mm over
        pads_rough_profile's, 50 m of track), so the profile's quantile stands for the path's."""
        h_rms = float(np.sqrt(np.sum(self.kernel_si**2)))
        return NormalDist().inv_cdf(1 - fraction) * h_rms

    def build(self, space, y, shape_filter, rng, mu, x_start):
        kernel, dx = self.scene_kernel
        return SelfAffineTrack(space, y, kernel, dx, mu, self.own.segment_radius, shape_filter, rng, x_start=x_start,
                               chunk_points=64)
