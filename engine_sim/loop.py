"""The one stepping loop of a scene: output step by output step, the recorder's sample, the maintenance and the
pymunk steps. Everything that steps a scene steps it here: a run and its warm-up (:mod:`engine_sim.run`), the
forecast's probe (:mod:`engine_sim.forecast`), the step costs (:mod:`engine_sim.timing`), the drawn frames
(:mod:`engine_sim.frames`), the benchmarks and the studies. The few places that time or observe something inside
an output step (a bare pymunk step, a part's stepping alone, each body before and after a step) step a scene
themselves; tests/project/test_one_loop.py lists them, each with its reason.
"""
from __future__ import annotations

import math

__all__ = ["Loop", "MAINTAIN_EVERY", "warm_up"]

MAINTAIN_EVERY = 64  # output steps between substrate maintenance (the margin ahead covers 200 outputs)


class Loop:
    """Steps a :class:`~engine_sim.scene.Scene` by output steps of ``scene.n_sub`` pymunk steps.

    Output step k (counted from ``k``): the recorder's sample, if there is one (``recorder.sample()``); every
    MAINTAIN_EVERY-th output step (k = 0, 64, ...), right after the sample, the scene's maintenance
    (:meth:`~engine_sim.scene.Scene.maintain`: the substrate streamed, the grains recycled), then ``on_maintain(k)``
    if given; then the ``n_sub`` pymunk steps to output step k + 1 (:meth:`~engine_sim.scene.Scene.advance`), but
    after output step ``n_out - 1``, which ends a recording on its sample. Maintenance comes right after a sample and
    before the steps: pymunk recomputes a cached arbiter's contact points from the bodies' current positions, so a
    particle moved between a step and a sample would report a bogus overlap.

    ``scene`` and ``recorder`` are attributes that may be replaced between output steps (a run continues from a
    restored copy at every epoch, :func:`engine_sim.checkpoint.round_trip`); ``recorder`` is any object with a
    ``sample()`` method (:class:`~engine_sim.record.Recorder`, or the frames' drawer).

    Parameters
    ----------
    scene : Scene
        The scene to step.
    recorder : object, optional
        Sampled at the start of every output step.
    n_out : int, optional
        Output steps of the recording: no pymunk step follows output step ``n_out - 1`` (None: every output step
        steps on).
    k : int, optional
        The first output step's index (a resumed recording's).
    on_maintain : callable, optional
        ``on_maintain(k)`` after each maintenance.
    n_sub : int, optional
        Pymunk steps per output step, a divisor of ``scene.n_sub`` (None: ``scene.n_sub``); with it the loop samples
        ``scene.n_sub / n_sub`` times per output step of the scene (a study's fine recording, every step at 1) and
        maintains every ``MAINTAIN_EVERY * scene.n_sub`` pymunk steps still, as a run does.
    """

    def __init__(self, scene, recorder=None, n_out: int | None = None, k: int = 0, on_maintain=None,
                 n_sub: int | None = None):
        if n_sub is not None and (n_sub < 1 or scene.n_sub % n_sub):
            raise ValueError(f"n_sub = {n_sub!r} does not divide the scene's {scene.n_sub} steps per output step")
        self.scene, self.recorder, self.n_out, self.k, self.on_maintain = scene, recorder, n_out, k, on_maintain
        self.n_sub = n_sub

    def step(self) -> None:
        """One output step (class docstring)."""
        self.run(1)

    def run(self, n: int, check=None) -> None:
        """``n`` output steps (class docstring); ``k`` counts the output steps done.

        Parameters
        ----------
        n : int
            Output steps to take.
        check : callable, optional
            Called before each output step; it raises to stop the loop there, where the scene and the recorder
            agree (a deferred SIGINT or SIGTERM in :func:`engine_sim.run`).
        """
        scene, on_maintain = self.scene, self.on_maintain
        advance, n_sub = scene.advance, scene.n_sub
        every = MAINTAIN_EVERY  # output steps between maintenances
        if self.n_sub is not None:
            every, n_sub = MAINTAIN_EVERY * n_sub // self.n_sub, self.n_sub
        sample = None if self.recorder is None else self.recorder.sample
        last = math.inf if self.n_out is None else self.n_out - 1  # the output step no pymunk step follows
        for k in range(self.k, self.k + n):
            if check is not None:
                check()
            if sample is not None:
                sample()
            if k % every == 0:
                scene.maintain()
                if on_maintain is not None:
                    on_maintain(k)
            if k < last:
                advance(n_sub)
            self.k = k + 1


def warm_up(scene, n_out: int, interrupts=None) -> None:
    """``n_out`` output steps unrecorded, maintained as a recording is (``interrupts.check()`` before each)."""
    Loop(scene).run(n_out, None if interrupts is None else interrupts.check)
