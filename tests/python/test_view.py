"""The Jupyter view, driven headless through its event handler: the pointer orbits, the wheel
zooms, the iso slider rebuilds, and each frame is a render of the surface."""

import numpy as np
import pytest

import octrace

pytest.importorskip("jupyter_rfb")


def sphere(n=32):
    axis = np.linspace(-1, 1, n)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    # An ellipsoid, so that an orbit changes the picture.
    return (np.sqrt((x / 0.9) ** 2 + (y / 0.5) ** 2 + (z / 0.3) ** 2) - 1.0).astype(np.float32)


def test_the_view_draws_the_surface_and_orbits():
    shell = octrace.Volume(sphere()).surface(iso=0, depth=5)
    v = octrace.view(shell, size=(64, 48))
    first = np.array(v.get_frame())
    assert first.shape == (48, 64, 4)
    assert np.array_equal(first, np.asarray(shell.render(size=(64, 48))))
    v.handle_event({"event_type": "pointer_down", "x": 10, "y": 10, "button": 1, "buttons": (1,), "modifiers": ()})
    v.handle_event({"event_type": "pointer_move", "x": 60, "y": 10, "button": 1, "buttons": (1,), "modifiers": ()})
    v.handle_event({"event_type": "pointer_up", "x": 60, "y": 10, "button": 1, "buttons": (), "modifiers": ()})
    orbited = np.array(v.get_frame())
    assert not np.array_equal(orbited, first)
    # The frame is the surface rendered from the view's camera, which render() takes back.
    assert np.array_equal(orbited, np.asarray(shell.render(size=(64, 48), camera=v.camera)))
    before = v.camera["camera_pos"]
    v.handle_event({"event_type": "wheel", "dx": 0, "dy": -300, "x": 32, "y": 24, "buttons": (), "modifiers": ()})
    look = np.array(v.camera["look_at"])
    assert np.linalg.norm(np.array(v.camera["camera_pos"]) - look) < np.linalg.norm(np.array(before) - look)
    v.handle_event({"event_type": "resize", "width": 80, "height": 40, "pixel_ratio": 1})
    assert np.array(v.get_frame()).shape == (40, 80, 4)


def test_the_iso_slider_rebuilds():
    box = octrace.view(octrace.Volume(sphere()), size=(48, 48), iso_range=(-0.5, 0.5), iso=0.0, depth=5)
    before = box.frame.surface
    box.slider.value = 0.4
    after = box.frame.surface
    assert before.iso == pytest.approx(0.0) and after.iso == pytest.approx(0.4)
    (lo0, hi0), (lo1, hi1) = before.bounds, after.bounds
    assert hi1[0] - lo1[0] > hi0[0] - lo0[0]  # the larger iso surface encloses the smaller
    assert np.array(box.frame.get_frame()).shape == (48, 48, 4)


@pytest.mark.filterwarnings("ignore:.*grid indices used as world units")
def test_the_time_slider_steps_through_a_dataarray():
    xr = pytest.importorskip("xarray")
    times = np.array(["2001-01-01", "2001-02-01", "2001-03-01"], dtype="datetime64[ns]")
    base = sphere(24)
    # The ellipsoid grows step by step: the surface at iso 0 is larger each month.
    da = xr.DataArray(np.stack([base - 0.2 * i for i in range(3)]), dims=("time", "z", "y", "x"),
                      coords={"time": times}, name="v")
    box = octrace.view(da, size=(48, 40), iso=0.0, depth=5)
    assert box.step_slider.max == 2 and box.step_label.value == "2001-01-01"
    first = np.array(box.frame.get_frame())
    assert np.array_equal(first, np.asarray(octrace.Volume(base).surface(iso=0.0, depth=5).render(size=(48, 40))))
    box.step_slider.value = 2
    assert box.step_label.value == "2001-03-01"
    assert box.frame.camera is not None  # the first step's framing, kept
    stepped = np.array(box.frame.get_frame())
    expected = octrace.Volume(base - 0.4).surface(iso=0.0, depth=5).render(size=(48, 40), camera=box.frame.camera)
    assert np.array_equal(stepped, np.asarray(expected))
    assert (np.isfinite(expected.depth).sum() > np.isfinite(np.asarray(
        octrace.Volume(base).surface(iso=0.0, depth=5).render(size=(48, 40), camera=box.frame.camera).depth)).sum())
    box.slider.value = 0.1  # the iso slider rebuilds the current step
    assert box.frame.surface.iso == pytest.approx(0.1)
    with pytest.raises(octrace.UsageError, match="'depth' is not a dimension"):
        octrace.view(da, dim="depth")
    with pytest.raises(octrace.UsageError, match="no dimension to step through"):
        octrace.view(da.isel(time=0))
