"""Write a still of every shipped scene's side view into docs/results/scenes/NAME.png (the pictures of
docs/results/scene_stills.md): each scene built with seed 0, run 0.15 s so that its pads have settled on their
tracks, and drawn by engine_sim.side_render. About 1-2 s a scene.

    python docs/make_stills.py [NAME ...]
"""
import sys
from pathlib import Path

from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.run import MAINTAIN_EVERY
from engine_sim.side_render import SideRenderer

OUT = Path(__file__).parent / "results" / "scenes"
SETTLE = 150  # output steps before the still (0.15 s at dt_out = 1 ms)


def still(name: str, out: Path = OUT) -> Path:
    scene = Scene(load_scenario(name), 0)
    r = SideRenderer(scene, dpi=80)
    for k in range(SETTLE):
        if k % MAINTAIN_EVERY == 0:
            scene.maintain()
        scene.advance(scene.n_sub)
        r.observe()
    r.frame()
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{name}.png"
    r.save_png(path)
    r.close()
    return path


if __name__ == "__main__":
    for name in sys.argv[1:] or shipped_scenarios():
        print(still(name))
