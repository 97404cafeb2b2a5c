"""Keyword arguments come from the options table and are checked by the CLI's code."""

import numpy as np
import pytest

import octrace


@pytest.fixture(scope="module")
def shell():
    axis = np.linspace(-1, 1, 24)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    return octrace.Volume((x * x + y * y + z * z - 0.36).astype(np.float32)).surface(iso=0, depth=5)


def test_the_table_is_the_clis():
    table = {o["key"]: o for o in octrace.options()}
    assert table["depth"]["flag"] == "--depth" and table["depth"]["kind"] == "integer"
    assert table["depth"]["min"] == 1 and table["depth"]["max"] >= 12
    assert "viridis" not in table["colormap"]["choices"]  # a text setting, checked when used
    assert table["size"]["separator"] == "x" and table["colour_range"]["separator"] == ","
    assert table["iso"]["part"] == "surface" and table["fov"]["part"] == "render" and table["title"]["part"] == "figure"


def test_an_unknown_keyword_names_the_nearest(shell):
    with pytest.raises(TypeError, match="'colourmap'.*did you mean 'colormap'"):
        shell.render(size=(16, 16), colourmap="viridis")
    with pytest.raises(TypeError, match="'deph'.*'depth'"):
        octrace.surface(octrace.Volume(np.zeros((4, 4, 4), np.float32)), iso=0, deph=5)


def test_a_setting_of_another_call_is_refused(shell):
    with pytest.raises(TypeError, match="'depth'"):
        shell.render(size=(16, 16), depth=5)


def test_values_are_checked_by_the_table(shell):
    with pytest.raises(octrace.UsageError, match=r"'fov': 180 is outside \(0, 180\) degrees"):
        shell.render(size=(16, 16), fov=180)
    with pytest.raises(octrace.UsageError, match="'size'"):
        shell.render(size=(0, 16))
    with pytest.raises(octrace.UsageError, match="'colour_range'"):
        shell.render(size=(16, 16), colour_range=(5, 1))
    with pytest.raises(octrace.UsageError, match="'background'"):
        shell.render(size=(16, 16), background=(2, 0, 0))
    with pytest.raises(octrace.UsageError, match="unknown renderer 'nonsense'"):
        shell.render(size=(16, 16), renderer="nonsense")


def test_a_setting_the_renderer_ignores_warns(shell):
    with pytest.warns(octrace.OctraceWarning, match="'branch_up' has no effect on renderer tile"):
        shell.render(size=(16, 16), branch_up=2)
    with pytest.warns(octrace.OctraceWarning, match="'colour_tolerance' has no effect without 'colour_coherence'"):
        shell.render(size=(16, 16), renderer="area", colour_tolerance=4)


def test_render_settings_change_the_frame(shell):
    white = np.asarray(shell.render(size=(32, 32)))
    black = np.asarray(shell.render(size=(32, 32), background=(0, 0, 0)))
    assert tuple(white[0, 0]) == (255, 255, 255, 255) and tuple(black[0, 0]) == (0, 0, 0, 255)
    red = np.asarray(shell.render(size=(32, 32), colour=(1, 0, 0)))
    centre = red[16, 16]
    assert centre[0] > 0 and centre[1] == 0 and centre[2] == 0
    ortho = shell.render(size=(32, 32), camera={"projection": "ortho"})
    assert ortho.stats["projection"] == "orthographic" or ortho.stats.get("projection") == "ortho"


def test_every_renderer_draws_the_same_surface(shell):
    # The papers' renderers draw the field's voxels, the others its smooth surface (`surface`'s
    # default): each group draws the same image.
    voxel = np.asarray(shell.render(size=(48, 40), renderer="full"))
    for name in ("linear-exact", "area-exact"):
        assert np.array_equal(np.asarray(shell.render(size=(48, 40), renderer=name)), voxel), name
    smooth = np.asarray(shell.render(size=(48, 40), renderer="reference"))
    assert np.array_equal(np.asarray(shell.render(size=(48, 40), renderer="tile")), smooth)
    assert not np.array_equal(smooth, voxel)


def test_corner_values_are_built_only_for_smooth_frames(tmp_path):
    # Smooth frames need 8 bytes of corner values per boundary voxel. A surface built without
    # `surface` does not know its renderers yet: it gets them with its first smooth frame (a
    # renderer that is not a paper's, as the default, tile), not with the build, so the papers'
    # voxel frames (full, ...) never pay for them.
    axis = np.linspace(-1, 1, 24)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    vol = octrace.Volume((0.6 - np.sqrt(x * x + y * y + z * z)).astype(np.float32))
    later = vol.surface(iso=0, depth=5)
    voxel = vol.surface(iso=0, depth=5, surface="voxel")
    smooth = vol.surface(iso=0, depth=5, surface="smooth")
    corners = 8 * later.boundary_voxels
    assert later.nbytes == voxel.nbytes and smooth.nbytes == voxel.nbytes + corners
    frame = later.render(size=(48, 40), renderer="full")
    assert frame.stats["renderer"] == "full" and frame.stats["surface"] == "voxel"
    assert frame.stats["corner_bytes_per_voxel"] == 0 and later.nbytes == voxel.nbytes
    assert np.array_equal(np.asarray(frame), np.asarray(voxel.render(size=(48, 40), renderer="full")))
    tile = later.render(size=(48, 40))
    assert tile.stats["renderer"] == "tile" and tile.stats["surface"] == "smooth" and later.nbytes == smooth.nbytes
    assert np.array_equal(np.asarray(tile), np.asarray(smooth.render(size=(48, 40), renderer="tile")))
    assert voxel.render(size=(48, 40), renderer="tile").stats["surface"] == "voxel" and voxel.nbytes + corners == smooth.nbytes
    # Saved, they are there whatever frames were drawn, as `octrace build` writes them.
    vol.surface(iso=0, depth=5).save(tmp_path / "s.oct")
    assert octrace.load(tmp_path / "s.oct").render(size=(48, 40), renderer="tile").stats["surface"] == "smooth"


def test_a_figure(shell):
    img = shell.render(size=(400, 300), figure=True, title="A sphere", colormap="viridis")
    assert img.size == (400, 300) and img.dpi > 0
    assert np.asarray(img).shape == (300, 400, 4)


def test_the_image_shows_itself_in_a_notebook(shell):
    png = shell.render(size=(16, 12))._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
