"""The rendered frame's layout (engine_sim.render): the time line and the key lie outside every axes' data
region, the key names what is drawn, and pads_multiscale shows the whole block (all 30 columns) and column 1 enlarged so that its micro-pads can be
seen, with a key, and no track under the caption."""
import numpy as np
import pytest
from matplotlib.text import Text

from engine_sim import Scene, load_scenario
from engine_sim.render import SceneRenderer


def _rendered(name):
    r = SceneRenderer(Scene(load_scenario(name), 0))
    r.frame()
    return r, r.fig.canvas.get_renderer()


@pytest.mark.parametrize("name", ["pads_multiscale", "pads_friction_patches", "pads_with_wear", "asperity_field",
                                  "pads_rough_profile", "leonardo_slider"])
def test_caption_and_key_lie_outside_the_scene_and_inside_the_figure(name):
    r, rend = _rendered(name)
    fig_bb = r.fig.bbox
    texts = [r.text, r._legend] + [pn["ax"].title for pn in r.panels[1:]]
    for art in texts:
        bb = art.get_window_extent(rend)
        assert fig_bb.x0 <= bb.x0 and bb.x1 <= fig_bb.x1 and fig_bb.y0 <= bb.y0 and bb.y1 <= fig_bb.y1, art
        for pn in r.panels:
            assert not bb.overlaps(pn["ax"].get_window_extent(rend)), (art, pn["view"]["ylabel"])
    # no part writes its numbers over the scene (a label such as Leonardo's "hanging mass" would cover the tracks)
    for pn in r.panels:
        for shape, art in pn["artists"].items():
            assert not (isinstance(art, Text) and art.get_text()), (shape, art.get_text())
    if name == "leonardo_slider":
        assert "hanging mass" in r.text.get_text()
    # axis labels (the colour bar's among them) are not cut off at the figure's edge
    for ax in r.fig.axes + [c for pn in r.panels for c in pn["ax"].child_axes]:
        bb = ax.get_tightbbox(rend)
        assert fig_bb.x0 - 1 <= bb.x0 and bb.x1 <= fig_bb.x1 + 1, ax
    labels = [t.get_text() for t in r._legend.get_texts()]
    assert "block" in labels and any("track" in lab for lab in labels), labels
    # the key speaks of a colour only where the tracks are coloured (one friction coefficient: grey, no colour bar)
    colour_bars = sum(len(pn["ax"].child_axes) for pn in r.panels)
    assert any("colour" in lab for lab in labels) == r.coloured == (colour_bars == 1), labels


def test_multiscale_shows_the_whole_block_and_an_enlarged_column_with_a_key():
    r, _ = _rendered("pads_multiscale")
    s = r.scene
    labels = [t.get_text() for t in r._legend.get_texts()]
    for want in ("pad (macro contact)", "micro-pad (micro contact)",
                 "pad track / micro-track (colour: patch friction)"):
        assert want in labels, labels
    assert len(r.panels) == 2
    whole, zoom = (pn["ax"] for pn in r.panels)
    pads = np.array([(p.position.x, p.position.y) for p in s.pads])
    lo, hi = whole.get_ylim()
    assert np.all((pads[:, 1] > lo) & (pads[:, 1] < hi)) and len(pads) == 30  # every column, not 3 of 30
    n = s.sc.pads.n_micro
    col1 = np.array([(b.position.x, b.position.y) for b in s.arrangement.micro_pads[:n]] + [tuple(pads[0])])
    (x0, x1), (y0, y1) = zoom.get_xlim(), zoom.get_ylim()
    assert np.all((col1[:, 0] > x0) & (col1[:, 0] < x1) & (col1[:, 1] > y0) & (col1[:, 1] < y1))
    # enlarged: a micro spacing spans at least a tenth of the zoom's height, against under 1 % of the whole
    ms = s.sc.pads.micro_spacing * 1e3
    assert ms / (y1 - y0) > 0.1 and ms / (hi - lo) < 0.015
    assert "column 1 of 30" in zoom.get_title(loc="left")
