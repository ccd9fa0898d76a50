"""The base of every substrate kind: the fields every ``[substrate]`` section has (:class:`SubstrateSpec`), the
class a kind subclasses (:class:`Substrate`) and the registry (:data:`SUBSTRATES`). :mod:`engine_sim.substrates`
re-exports them and imports the shipped kinds, so a kind's module here imports its base from this module (the
tracks the kinds build are :mod:`engine_sim.substrate`'s)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..parts import Part, Registry

__all__ = ["SubstrateSpec", "Substrate", "SUBSTRATES", "substrate_kind"]

SUBSTRATES = Registry("substrate")


@dataclass(frozen=True)
class SubstrateSpec:
    """Fields every substrate has. kind: the registered name; a: the length over which the force on a pad renews
    (m; the fit band is 3-30 v/a); segment_radius: thickness of the track segments (m)."""

    kind: str = "patches"
    a: float = 1e-3
    segment_radius: float = 0.05e-3


class Substrate(Part):
    """One substrate kind. Subclasses set ``name`` (the value of ``[substrate] kind``), ``Spec`` and override what
    differs.

    arrangement: the pad arrangement a scenario gets when its ``[pads]`` section names none (``engine_sim/arrangements``:
    "tracks", one track per pad, or "sole", one track under a flat block on feet, free vertically);
    hosts_wear: flat tracks where wear particles can rest; positive / non_negative / choices: field checks made by
    the loader (names of Spec fields); reduced_model: the key in ``reduced_models.MODELS`` of the model that fits
    a scene on this substrate; quick_duration: the recorded seconds a quick comparison with that model needs (s)."""

    name: ClassVar[str] = ""
    Spec: ClassVar[type] = SubstrateSpec
    arrangement: ClassVar[str] = "tracks"
    hosts_wear: ClassVar[bool] = False
    positive: ClassVar[frozenset] = frozenset({"a", "segment_radius"})
    non_negative: ClassVar[frozenset] = frozenset()
    choices: ClassVar[dict] = {}
    reduced_model: ClassVar[str] = "model_I"  # pads renewing their force every a: model I
    quick_duration: ClassVar[float] = 12.0
    scene_units: ClassVar[dict] = {"a": "length", "segment_radius": "length"}

    @classmethod
    def prepare(cls, spec, where: str = ""):
        """The spec as the scene will use it (e.g. a file name resolved beside the scenario file ``where``)."""
        return spec

    @classmethod
    def validate(cls, spec, scenario, where: str = "") -> None:
        """Raise ValueError (its message names the field) if the spec cannot make a working scene."""

    @property
    def length_scale(self) -> float:
        """The renewal length a (m) that sets the fit band (3-30 v/a) and the correlation window of extract."""
        return self.spec.a

    def notes(self) -> list:
        """One-line statements of what the part did to its input (e.g. a measured profile resampled), for the run
        to print before it starts."""
        return []

    def provenance(self) -> dict:
        """What a trace's metadata records of the part's input (a measured profile's file, checksum and
        resampling); empty for a generated substrate."""
        return {}

    def pad_depth(self, fraction: float, pad_radius: float) -> float:
        """How far below the track's datum (m) the lowest point of a pad of ``pad_radius`` (m) follows the track
        on ``fraction`` of its path (0: a flat track; engine_sim.regime compares it with the pad's deflection)."""
        return 0.0

    def mu_range(self, mu0: float):
        """(lo, hi) of the friction coefficient along the track (a colour bar is drawn when they differ)."""
        return mu0, mu0

    # ------------------------------------------------------------------ scene side (scene units: own, ctx)
    def top(self) -> float:
        """The highest point of the substrate above its datum (mm): feet on a sole start above it."""
        return 0.0

    def floor_depth(self) -> float:
        """How far below its surface a particle may sit on this track (mm; pits)."""
        return 0.0

    def margins(self, scene) -> tuple[float, float]:
        """(ahead, behind) of a pad, in mm, over which its track must exist."""
        r = self.ctx.pad_radius
        return 4 * r + scene.run_ahead, 2 * r

    def build(self, space, y: float, shape_filter, rng, mu: float, x_start: float):
        """A streamed track (scene units) at height y with friction mu, its own generator rng."""
        raise NotImplementedError

    def x_start(self, scene) -> float:
        """Where a track begins (mm)."""
        return -4.0 * self.ctx.pad_radius

    def relief(self, pad_radius: float) -> float:
        """The height range a side view must show (m): the depth the pads follow on 99 % of their path, twice."""
        return 2 * self.pad_depth(0.01, pad_radius)

    def side(self, track, lo: float, hi: float, xs, q_pad: float) -> tuple:
        """The side view of a track within [lo, hi] (scene units): (the surface a pad touches at the points xs,
        the upper envelope of the track's shapes, -inf where none reaches; spans (x0, x1, mu) of the friction
        along it)."""
        from ..side_view import capsule_envelope

        segs = [sh for sh in track.segments if sh.b.x >= lo - 1 and sh.a.x <= hi + 1]
        a = np.array([(sh.a.x, sh.a.y) for sh in segs]).reshape(-1, 2)
        b = np.array([(sh.b.x, sh.b.y) for sh in segs]).reshape(-1, 2)
        r = segs[0].radius if segs else 0.0
        spans = [(sh.a.x, sh.b.x, sh.friction * q_pad) for sh in segs if sh.b.x > sh.a.x]
        return capsule_envelope(a, b, r, xs), spans

    def draw(self, track, lo: float, hi: float, q_pad: float):
        """Polylines (lists of (x, y) points, mm) and their friction coefficients within [lo, hi]."""
        segs, mus = [], []
        for sh in track.segments:
            if sh.b.x >= lo and sh.a.x <= hi:
                segs.append(((sh.a.x, sh.a.y), (sh.b.x, sh.b.y)))
                mus.append(sh.friction * q_pad)
        return segs, mus


def substrate_kind(name: str):
    """The Substrate class registered as ``name`` (KeyError if none)."""
    return SUBSTRATES[name]
