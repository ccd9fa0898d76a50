"""The base of every friction law: the fields every ``[friction]`` section has (:class:`FrictionSpec`), the
class a law subclasses (:class:`Law`) and the registry (:data:`LAWS`). :mod:`engine_sim.laws` re-exports them and
imports the shipped laws, so a law module here imports its base from this module."""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..parts import Part, Registry

__all__ = ["FrictionSpec", "Law", "LAWS", "law_kind"]

LAWS = Registry("friction law", key="law")


@dataclass(frozen=True)
class FrictionSpec:
    """Fields every law has: law, its registered name; mu0: the Coulomb coefficient (the substrate's local value
    varies about it); c: viscous slope (N s/m per sliding body)."""

    law: str = "linear"
    mu0: float = 0.6
    c: float = 10.0


class Law(Part):
    """One friction law. ``spec`` is its section; ``sc`` the scenario it belongs to."""

    name: ClassVar[str] = ""
    Spec: ClassVar[type] = FrictionSpec
    positive: ClassVar[frozenset] = frozenset()
    non_negative: ClassVar[frozenset] = frozenset({"mu0", "c"})
    choices: ClassVar[dict] = {}
    reduced_model = None  # a key of reduced_models.MODELS fitting a scene with this law (None: the substrate's)
    quick_duration = None  # recorded seconds of a quick comparison with that model (s)

    @classmethod
    def validate(cls, spec, sc) -> None:
        """Raise ValueError (naming the field) if the law cannot slide the scene steadily."""

    def force(self, v: float, load: float, c: float) -> float:
        """Steady friction force (N) of one sliding body under ``load`` (N) at speed v >= 0, viscous slope c."""
        raise NotImplementedError

    def slope(self, v: float, load: float, c: float) -> float:
        """dF/dv (N s/m) of one sliding body at speed v."""
        raise NotImplementedError

    def drag_terms(self, load: float, c: float) -> tuple[float, float, float]:
        """(c [N s/m], b N_pad [N], v_c [m/s]) of the velocity part in the recorder's form (b N_pad = 0: none)."""
        return c, 0.0, 1.0

    def recorded_drag(self, scene) -> tuple | None:
        """The law's velocity part beyond the form of :meth:`drag_terms`, at a sample, as the recorder computes it:
        ``(kernel, rows)``, with ``kernel(v, rows, out)`` a numba-compiled function that writes that part g_own(v[i])
        (x force, scene units) of sliding body i (``scene.sliders`` order) at its velocity v[i] into ``out[i]``, and
        ``rows`` its parameters, one row per sliding body (scene units). The recorder adds it to the drag_terms form
        in F_drag and counts its power in the dissipated energy. None (the shipped laws): the drag_terms form is the
        whole velocity part, and the recorder calls no kernel of the law's."""
        return None

    def describe(self, load: float, c: float) -> dict:
        """The law's parameters for one sliding body (``metadata["scene"]["friction_law"]``)."""
        return {"law": self.name, "c": c, "b": 0.0, "v_c": None, "load_per_pad": load}

    @classmethod
    def described_slope(cls, law: dict, v: float) -> float:
        """dF/dv (N s/m) of one sliding body at speed v (m/s), from the law's :meth:`describe` (what a trace
        carries, so an analysis needs no scenario): ``compare`` asks the law registered as ``law["law"]``."""
        return law["c"]

    def build(self, scene, body, c: float) -> None:
        """Add the velocity part of the law on ``body`` (viscous slope ``c``, scene units) to ``scene.space``."""

    # the law applies impulses per step outside pymunk's constraints (impulse_totals), and they act after pymunk's
    # step (written as velocities), not inside it as forces
    per_step_impulses: ClassVar[bool] = False
    impulses_after_step: ClassVar[bool] = False

    def impulse_totals(self, scene) -> np.ndarray:
        """The impulses (x, scene units) the law has applied to each sliding body (``scene.sliders`` order) outside
        pymunk's constraints since the scene was built, summed per step; zeros for a law whose velocity part is its
        dampers alone (the recorder's means read those from the bodies' motion)."""
        tot = getattr(self, "_impulses", None)
        if tot is None or tot.shape[0] != len(scene.sliders):
            tot = self._impulses = np.zeros(len(scene.sliders))
        return tot

    def _add_impulses(self, scene, idx, acc):
        """Add ``acc`` (per body of the batch, in its order; ``idx``: each one's slider index or -1) to the totals
        :meth:`impulse_totals` hands over."""
        tot = self.impulse_totals(scene)
        mine = idx >= 0
        tot[idx[mine]] += acc[mine]

    def advance(self, scene, n: int) -> None:
        """n pymunk steps of the scene (a law that writes forces each step overrides this)."""
        step, dt = scene.space.step, scene.dt
        for _ in range(n):
            step(dt)


def law_kind(name: str):
    """The Law class registered as ``name`` (KeyError if none)."""
    return LAWS[name]
