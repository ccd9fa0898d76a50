"""The side view (engine_sim.side_render, engine_sim.side_view): what a test can see of a frame. Nothing is drawn
inside a body it touches (no pad or foot below the substrate's line), springs and pads are drawn, and the
vertical exaggeration is printed on the frame."""
import numpy as np
import pytest

from engine_sim import Scene, load_scenario, shipped_scenarios
from engine_sim.side_render import SideRenderer
from engine_sim.side_view import capsule_envelope, circle_envelope, zigzag

SLOP = 1e-4  # mm: pymunk's collision slop in the scene (Scene.slop): contacts rest this far into their track


def _frame(name, outputs=150):
    scene = Scene(load_scenario(name), 0)
    r = SideRenderer(scene)
    for k in range(outputs):  # 0.15 s: pads and feet settled on their tracks, grains under way
        if k % 64 == 0:
            scene.maintain()
        scene.advance(scene.n_sub)
        r.observe()
    img = r.frame()
    return r, img


def _lowest_gap(body: np.ndarray, surface) -> float:
    """The least height (display mm) of a body's outline above the surface drawn under it (a polyline, or the
    pieces of one: a sole's caps), over the body's x range; inf where nothing is drawn under it."""
    gap = np.inf
    for piece in surface if isinstance(surface, list) else [surface]:
        xs, ys = piece[:, 0], piece[:, 1]
        inside = (body[:, 0] >= xs.min()) & (body[:, 0] <= xs.max())
        if inside.any():
            gap = min(gap, float(np.min(body[inside, 1] - np.interp(body[inside, 0], xs, ys))))
    return gap


def _surface_under(r, i):
    """The surface drawn under pad i: its own track's piece, or the sole's whole track."""
    surfaces = r.shapes["surface"][1]
    return surfaces if not r.scene.arrangement.guided else surfaces[i]


@pytest.mark.parametrize("name", sorted(shipped_scenarios()))
def test_no_pad_or_foot_is_drawn_below_the_substrate_line(name):
    """Each pad's drawn outline lies on or above the surface drawn under it, to within the contact's slop (the
    pads rest 0.1 um into their tracks) and the surface's sampling (its capsules sampled every few um, 0.1 um at
    most under a crest), both at the frame's exaggeration."""
    r, _ = _frame(name)
    lay, sh = r.layout, r.shapes
    pads = sh["pads"][1]
    assert len(pads) == lay.n_show
    tol = lay.E * 3 * SLOP
    for i, body in enumerate(pads):
        gap = _lowest_gap(body, _surface_under(r, i))
        assert gap >= -tol, f"pad {i + 1}: {gap / lay.E * 1e3:.3f} um below the substrate's line"


def test_asperity_field_feet_stand_on_the_caps_they_touch():
    """The sole's feet: the ones that carry the block touch a cap (gap within the slop), none is drawn inside one;
    the bumps drawn are pymunk's circles (their envelope), with no floor between them."""
    r, _ = _frame("asperity_field")
    lay = r.layout
    gaps = np.array([_lowest_gap(f, _surface_under(r, i)) for i, f in enumerate(r.shapes["pads"][1])]) / lay.E
    assert gaps.min() >= -3 * SLOP
    assert (gaps < 3 * SLOP).sum() >= 3  # the block rests on several feet (measured: 5 of 30 at 0.15 s, seed 0)


@pytest.mark.parametrize("name", ["pads_friction_patches", "pads_rough_profile", "asperity_field", "pads_with_wear",
                                  "pads_multiscale"])
def test_springs_pads_and_block_are_drawn(name):
    r, img = _frame(name, outputs=20)
    lay, sh = r.layout, r.shapes
    assert img.shape[2] == 4 and img.shape[0] > 200
    assert len(sh["pads"][1]) == lay.n_show and len(sh["normal"][1]) == lay.n_show
    for spring, pad in zip(sh["normal"][1], sh["pads"][1]):
        assert len(spring) >= 10  # a zig-zag, not a line
        assert spring[0, 1] == pytest.approx(pad[:, 1].max())  # from the pad's top ...
        assert spring[-1, 1] == pytest.approx(lay.block_bottom)  # ... to the block's underside
    (corner, width, height), _ = sh["block"][1:]
    assert corner[1] == pytest.approx(lay.block_bottom) and width > 0.8 * lay.width and height > 0
    if name != "asperity_field":  # pads on tracks: a tangential spring from a post under the block to each pad
        assert len(sh["tangential"][1]) == lay.n_show
    if name == "pads_multiscale":
        assert len(sh["micro_pads"][1]) == 2 * lay.n_show
    if name == "pads_with_wear":
        assert len(sh["grains"][1]) > 0


@pytest.mark.parametrize("name, E", [("pads_friction_patches", 1), ("pads_rough_profile", 5),
                                     ("asperity_field", 50), ("pads_with_wear", 2)])
def test_the_exaggeration_is_printed_on_the_frame(name, E):
    """The title states the exaggeration the drawing uses; the vertical scale bar says what it spans."""
    r, _ = _frame(name, outputs=5)
    assert r.layout.E == E
    title = r.ax.get_title(loc="left")
    assert f"vertical exaggeration x{E} " in title and "schematic" in title
    bars = [t.get_text() for t in r.ax.texts if t.get_text().endswith(("um", f"(drawn x{E})"))]
    assert len(bars) == 1 and (E == 1 or f"drawn x{E}" in bars[0])


def test_capsule_envelope_is_the_union_of_discs():
    """Closed form: a segment from (0, 0) to (1, 0.5) thickened by 0.2 has its top at y = 0.5 x + 0.2 / cos(a)
    along its straight part (a its slope angle) and the end discs beyond."""
    xs = np.linspace(-0.3, 1.3, 1601)
    top = capsule_envelope(np.array([[0.0, 0.0]]), np.array([[1.0, 0.5]]), 0.2, xs)
    a = np.arctan(0.5)
    mid = (xs > 0.2) & (xs < 0.8)
    assert np.allclose(top[mid], 0.5 * xs[mid] + 0.2 / np.cos(a), atol=1e-12)
    # brute force: the highest point of 2001 discs along the segment
    t = np.linspace(0, 1, 2001)
    brute = np.max(0.5 * t[:, None] + np.sqrt(np.maximum(0.04 - (xs[None, :] - t[:, None]) ** 2, 0))
                   - np.where(np.abs(xs[None, :] - t[:, None]) > 0.2, np.inf, 0), axis=0)
    ok = np.isfinite(brute)
    assert np.allclose(top[ok], brute[ok], atol=1e-6)  # the brute force's own grid error is below 1e-6
    assert np.allclose(circle_envelope(np.array([[0.0, -1.0]]), 1.0, np.array([0.0, 0.6])), [0.0, -0.2])


def test_zigzag_runs_from_end_to_end():
    z = zigzag((0.0, 0.0), (0.0, 2.0), coils=5, width=0.1)
    assert np.allclose(z[0], (0, 0)) and np.allclose(z[-1], (0, 2)) and len(z) == 2 * 5 + 4
    assert np.allclose(np.abs(z[2:-2, 0]), 0.1)


@pytest.mark.parametrize("name", ["pads_friction_patches", "pads_with_wear", "pads_rough_profile", "asperity_field"])
def test_pads_and_feet_are_drawn_in_their_true_shape_with_heights_exaggerated(name):
    """Only heights are exaggerated: a body drawn h display mm tall (flat top) is as wide as the true body at the
    true height h / E above its lowest point, 2 sqrt(R^2 - (R - h/E)^2) plus the foot's flat length, and as wide
    as the true body (2R, or the foot's length) once h / E reaches R. Drawn as the exaggerated contact cap with
    vertical sides, pads_with_wear's pads were 0.5 mm wide for 0.6 mm and asperity_field's feet 0.3 mm for 0.4."""
    r, _ = _frame(name, outputs=20)
    sc, E = r.scene.sc, r.layout.E
    R = sc.pads.radius * 1e3  # mm
    # a sole's foot: pymunk's segment (its axis a -> b, scene mm) thickened by R; a pad: a circle
    shape = next(iter(r.scene.pads[0].shapes))
    flat = abs(shape.b.x - shape.a.x) if r.scene.arrangement.name == "sole" else 0.0
    assert f"heights x{E}" in r.shapes["pads"][2]["label"]
    for body in r.shapes["pads"][1]:
        h = min((body[:, 1].max() - body[:, 1].min()) / E, R)
        want = flat + 2 * np.sqrt(R * R - (R - h) ** 2)
        # the outline samples the arc at 41 points and cuts it exactly at the top: float arithmetic only
        assert body[:, 0].max() - body[:, 0].min() == pytest.approx(want, rel=1e-9)
    if E <= 2:  # these reach their equator: the full width
        assert all(b[:, 0].max() - b[:, 0].min() == pytest.approx(flat + 2 * R) for b in r.shapes["pads"][1])


def test_the_patch_friction_has_a_labelled_colour_scale():
    r, _ = _frame("pads_friction_patches", outputs=5)
    cbar = r.cbar
    assert "friction coefficient" in cbar.ax.get_title()
    lo, hi = r.scene.substrate.mu_range(r.scene.sc.friction.mu0)
    assert cbar.mappable.norm.vmin == pytest.approx(lo) and cbar.mappable.norm.vmax == pytest.approx(hi, abs=1e-9)


def test_a_scene_without_patches_draws_no_colour_scale():
    r, _ = _frame("asperity_field", outputs=5)
    assert getattr(r, "cbar", None) is None
