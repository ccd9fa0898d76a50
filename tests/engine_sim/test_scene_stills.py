"""Every shipped scene has its still in the docs (docs/results/scene_stills.md), made by the one documented
command (docs/make_stills.py)."""
import importlib.util
from pathlib import Path

from PIL import Image

from engine_sim import shipped_scenarios

DOCS = Path(__file__).resolve().parents[2] / "docs"


def test_every_shipped_scene_has_a_still_on_the_page():
    page = (DOCS / "results" / "scene_stills.md").read_text()
    for name in shipped_scenarios():
        png = DOCS / "results" / "scenes" / f"{name}.png"
        assert png.is_file(), f"no still of {name}: python docs/make_stills.py {name}"
        assert f"## {name}\n" in page and f"(scenes/{name}.png)" in page, name
        w, h = Image.open(png).size
        assert w > 600 and h > 200


def test_the_documented_command_writes_a_still(tmp_path):
    spec = importlib.util.spec_from_file_location("make_stills", DOCS / "make_stills.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    path = mod.still("pads_friction_patches", tmp_path)
    assert path == tmp_path / "pads_friction_patches.png" and Image.open(path).size[0] > 600
