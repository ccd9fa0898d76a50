"""Frames of a scene as it slides, drawn headless at output steps of the one stepping loop
(:class:`engine_sim.loop.Loop`), for ``frictionnoise render`` and :func:`frictionnoise.render_scene`."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from frictionnoise.base import check_seconds

from .loop import Loop
from .scene import Scene

__all__ = ["draw_frames", "VIEWS"]

# view name -> (module, renderer class): the side view of the block on its pads over the substrate, or the per-pad
# track map; imported when drawn (matplotlib stays out of the engine until then)
VIEWS = {"side": ("engine_sim.side_render", "SideRenderer"), "tracks": ("engine_sim.render", "SceneRenderer")}


class _Drawer:
    """The loop's sampler while drawing: the renderer observes every output step (its grains' states are the
    recorder's, judged on their mean speed over the output step) and draws every ``every``-th."""

    def __init__(self, renderer, every: int, out, images: list):
        self.renderer, self.every, self.out, self.images, self.k = renderer, every, out, images, 0

    def sample(self):
        r = self.renderer
        r.observe()
        if self.k % self.every == 0:
            self.images.append(np.array(r.frame(), copy=True))
            if self.out is not None:
                r.save_png(self.out / f"frame_{len(self.images) - 1:03d}.png")
        self.k += 1


def draw_frames(sc, frames: int, duration: float, seed: int | None = None, *, out=None,
                dpi: int = 90, view: str = "side") -> list[np.ndarray]:
    """Draw ``frames`` frames of a scenario's scene spanning ``duration`` simulated seconds.

    Frame j is drawn at output step j n, n = max(1, round(duration / (frames dt_out))) output steps apart, from the
    scene's first state (no warm-up).

    Parameters
    ----------
    sc : Scenario
        The scenario.
    frames : int
        Number of frames, >= 1.
    duration : float
        Simulated time spanned by the frames (Units: s), > 0.
    seed : int, optional
        Default the scenario's ``run.seed``.
    out : str or pathlib.Path, optional
        Where ``frame_000.png``, ``frame_001.png``, ... go (the folder is created if needed).
    dpi : int, optional
        Dots per inch of every frame.
    view : {"side", "tracks"}, optional
        The side view of the block on its spring-mounted pads over the substrate (default), or the map of every
        pad's track (:data:`VIEWS`).

    Returns
    -------
    list of numpy.ndarray
        RGBA images of uint8, one per frame.
    """
    from importlib import import_module

    if view not in VIEWS:
        raise ValueError(f"view must be one of {sorted(VIEWS)} (got {view!r})")
    if frames < 1:
        raise ValueError(f"frames must be at least 1 (got {frames!r})")
    check_seconds("duration", duration)
    if out is not None:
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
    scene = Scene(sc, seed)
    module, name = VIEWS[view]
    renderer = getattr(import_module(module), name)(scene, dpi=dpi)
    every = max(1, int(round(duration / sc.run.dt_out / frames)))  # output steps between frames
    images = []
    n_out = (frames - 1) * every + 1  # the last frame ends the loop, as a last sample ends a recording
    try:
        Loop(scene, _Drawer(renderer, every, out, images), n_out).run(n_out)
    finally:
        renderer.close()
    return images
