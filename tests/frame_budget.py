"""Frame cost against pymunk's own matplotlib drawing of the same space, measured in turns in the same process,
so the check holds on a busy machine (DESIGN.md: pymunk.matplotlib_util takes 0.3-0.4 s a frame, our collections
50-80 ms when the machine is idle)."""
import time
import warnings


def frame_cost_ratio(renderer, turns: int = 2) -> float:
    """Fastest renderer frame / fastest pymunk.matplotlib_util draw of the same scene."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import pymunk.matplotlib_util as mu
    fig = Figure(figsize=(7.0, 5.0), dpi=90)
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ours = theirs = float("inf")
    for _ in range(turns):
        t0 = time.perf_counter()
        renderer.frame()
        ours = min(ours, time.perf_counter() - t0)
        ax.clear()
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            renderer.scene.space.debug_draw(mu.DrawOptions(ax))
        fig.canvas.draw()
        theirs = min(theirs, time.perf_counter() - t0)
    return ours / theirs
