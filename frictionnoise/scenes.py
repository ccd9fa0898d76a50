"""Scenes from Python: load a scenario, run it, render it, compare it with the reduced model that fits it.

A scenario is a TOML file (the shipped ones are listed by :func:`engine_sim.shipped_scenarios`) or a
:class:`engine_sim.Scenario`; a run returns an :class:`engine_sim.EngineTrace` in SI units.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from compare.io.traces import load_trace, save_trace
from engine_sim import EngineTrace, Scenario, load_scenario
from engine_sim import run as _run

__all__ = ["run_scene", "render_scene", "compare_scene", "save_trace", "load_trace", "scenario"]


def scenario(which) -> Scenario:
    """A scenario from a shipped name, a TOML path or a :class:`~engine_sim.Scenario` (returned as is).

    Parameters
    ----------
    which : str, pathlib.Path or Scenario
        A shipped scenario's name (``"pads_friction_patches"``), a path to a scenario TOML file, or a scenario.

    Returns
    -------
    engine_sim.Scenario
        The validated scenario (SI units).
    """
    if isinstance(which, Scenario):
        return which
    return load_scenario(which)


def run_scene(which, duration: float | None = None, seed: int | None = None, **options) -> EngineTrace:
    """Run a scene and return its recorded trace.

    Parameters
    ----------
    which : str, pathlib.Path or Scenario
        A shipped scenario's name, a scenario TOML path or a scenario.
    duration : float, optional
        Recorded simulated time (s); default: the scenario's ``[run] duration``. The warm-up
        (``[run] warmup``) is simulated first and not recorded.
    seed : int, optional
        Seed of the substrate and the scene; default: the scenario's ``[run] seed``.
    **options
        Passed to :func:`engine_sim.run` (``checkpoint``, ``checkpoint_every``, ``epoch``, ``progress``).

    Returns
    -------
    engine_sim.EngineTrace
        ``t`` (s), ``x`` (m), forces (N), energies (J) and ``metadata`` (the scene's parameters for
        :func:`compare_scene`).
    """
    return _run(scenario(which), duration=duration, seed=seed, **options)


def render_scene(which, out=None, *, frames: int = 12, duration: float = 0.6, seed: int | None = None,
                 dpi: int = 90, view: str = "side") -> list[np.ndarray]:
    """Draw frames of a scene, headless.

    Parameters
    ----------
    which : str, pathlib.Path or Scenario
        A shipped scenario's name, a scenario TOML path or a scenario.
    out : str or pathlib.Path, optional
        A folder to write ``frame_000.png``, ``frame_001.png``, ... into (created if needed).
    frames : int, optional
        Number of frames.
    duration : float, optional
        Simulated time spanned by the frames (s).
    seed : int, optional
        Seed of the substrate and the scene; default: the scenario's.
    dpi : int, optional
        Resolution of the frames (dots per inch).
    view : {"side", "tracks"}, optional
        The side view of the block on its spring-mounted pads over the substrate (default), or the map of every
        pad's track.

    Returns
    -------
    list of numpy.ndarray
        The frames as RGBA images, ``(height, width, 4)`` arrays of uint8.
    """
    from engine_sim.frames import draw_frames

    return draw_frames(scenario(which), frames, duration, seed, out=out, dpi=dpi, view=view)


def compare_scene(which, *, trace=None, duration: float | None = None, seed: int | None = None, out=None) -> dict:
    """One scene against the reduced model built from the scene's own measured parameters.

    The model is the one that fits the scene (model I for pads on tracks, model III for the asperity field,
    model II for the wear particles' force, model Ib beside model I for micro-pads), as
    ``frictionnoise compare`` chooses it.

    Parameters
    ----------
    which : str, pathlib.Path or Scenario
        A shipped scenario's name, a scenario TOML path or a scenario.
    trace : engine_sim.EngineTrace, optional
        A trace of this scenario already run (then nothing is simulated but the reduced model).
    duration : float, optional
        Recorded simulated time (s) when the scene is run; default: the scenario's.
    seed : int, optional
        Seed of the scene run and of the model's run; default: the scenario's.
    out : str or pathlib.Path, optional
        A folder to write the HTML report into (``index.html``, ``summary.json``, ``figures/``).

    Returns
    -------
    dict
        The comparison's numbers, as in the report's ``summary.json``: ``gamma`` and ``gamma_err`` (the
        scene's exponent and its 95 % half-width), ``band`` (rad/s), the per-band ratios of the scene's C_x to
        the model's and the extracted model parameters.
    """
    from compare.report.build import build_scene_report

    sc = scenario(which)
    results, summary = build_scene_report(sc, trace=trace, duration=duration, seed=seed)
    if out is not None:
        from compare.report.html import write_report

        write_report(Path(out), results, summary)
    return summary["scenarios"][sc.name]
