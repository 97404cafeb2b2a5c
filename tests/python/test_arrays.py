"""NumPy in and out: volumes from arrays, images as views of the frame, bad arrays refused with
the CLI's messages, never a crash."""

import math
import threading
import time
import warnings

import numpy as np
import pytest

import octrace


def sphere(n=48, radius=0.6, dtype=np.float32):
    """A signed distance field of a sphere on n^3 samples over [-1, 1]^3, axes (z, y, x)."""
    axis = np.linspace(-1.0, 1.0, n)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    return (np.sqrt(x * x + y * y + z * z) - radius).astype(dtype)


def test_a_volume_from_a_float32_array_renders_a_sphere():
    vol = octrace.Volume(sphere(), spacing=(2 / 47,) * 3, origin=(-1, -1, -1))
    assert vol.shape == (48, 48, 48)
    assert vol.spacing == pytest.approx((2 / 47,) * 3)
    shell = vol.surface(iso=0.0, depth=6)
    img = shell.render(size=(96, 96), background=(0, 0, 0))
    a = np.asarray(img)
    hit = np.isfinite(img.depth)
    # The sphere of radius 0.6 covers a disc in the middle of the framed image.
    assert hit[48, 48] and not hit[0, 0]
    assert 0.15 < hit.mean() < 0.95
    assert (a[hit][:, :3].sum(axis=1) > 0).all()
    assert img.stats["boundary_voxels"] == shell.boundary_voxels > 0


def test_the_image_is_a_view_without_a_copy():
    img = octrace.Volume(sphere(24)).surface(iso=0, depth=5).render(size=(40, 30))
    a = np.asarray(img)
    b = np.asarray(img)
    assert a.shape == (30, 40, 4) and a.dtype == np.uint8
    assert np.shares_memory(a, b) and np.shares_memory(a, img.rgba)
    assert not a.flags.writeable
    depth = img.depth
    assert depth.shape == (30, 40) and depth.dtype == np.float32
    del img  # the arrays keep the frame alive
    assert int(a.sum()) > 0 and np.isfinite(depth).any()


def test_the_volume_values_are_a_view_of_the_field():
    vol = octrace.Volume(sphere(16))
    v1, v2 = vol.values, vol.values
    assert np.shares_memory(v1, v2) and v1.shape == (16, 16, 16)
    assert np.array_equal(v1, sphere(16))


def test_a_float32_array_is_read_in_place():
    a = sphere(24)
    vol = octrace.Volume(a)
    assert vol.in_place and np.shares_memory(vol.values, a)
    shell = vol.surface(iso=0.0, depth=5)
    assert shell._shell.field_in_place  # the surface reads the same memory: no copy anywhere
    del a
    import gc

    gc.collect()  # the Volume keeps the array alive
    assert shell.render(size=(32, 32)).stats["hits"] > 0 and np.array_equal(vol.values, sphere(24))


def test_an_array_with_nan_is_copied_and_left_as_it_was():
    a = sphere(16)
    a[0, 0, 0] = np.nan
    vol = octrace.Volume(a)
    assert not vol.in_place and not np.shares_memory(vol.values, a)
    assert np.isnan(a[0, 0, 0]) and vol.values[0, 0, 0] == 0.0


def test_a_converted_array_is_not_in_place():
    a = sphere(16, dtype=np.float64)
    with pytest.warns(octrace.OctraceWarning, match="float64"):
        vol = octrace.Volume(a)
    assert not vol.in_place and not np.shares_memory(vol.values, a)
    with pytest.raises(ValueError, match="real numbers"):
        octrace.Volume(sphere(8).astype(np.complex64))


def test_a_setting_of_another_call_names_it():
    shell = octrace.Volume(sphere(16)).surface(iso=0, depth=4)
    with pytest.raises(TypeError, match=r"'threads' is a setting of octrace.surface\(\)"):
        shell.render(size=(32, 32), threads=1)


def test_other_dtypes_are_converted_and_said():
    with pytest.warns(octrace.OctraceWarning, match="float64"):
        vol = octrace.Volume(sphere(16, dtype=np.float64))
    assert vol.values.dtype == np.float32
    with pytest.warns(octrace.OctraceWarning, match="non-contiguous"):
        octrace.Volume(np.asfortranarray(sphere(16)))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        octrace.Volume(sphere(16))  # float32, C order: taken as it is


def test_nan_samples_are_masked():
    a = sphere(24)
    a[:, :, :4] = np.nan
    vol = octrace.Volume(a)
    assert vol.mask is not None and vol.mask[:, :, :4].sum() == 0 and vol.mask[:, :, 4:].all()


@pytest.mark.parametrize("array, spacing, message", [
    (np.zeros((4, 4)), (1, 1, 1), "3-D array"),
    (np.zeros((0, 4, 4), np.float32), (1, 1, 1), "empty"),
    (np.zeros((4, 4, 4, 4), np.float32), (1, 1, 1), "3-D array"),
    (np.array([["a"]]), (1, 1, 1), "3-D array"),
    (np.zeros((4, 4, 4), np.float32), (1, math.inf, 1), "spacing"),
    (np.zeros((4, 4, 4), np.float32), (1, 0, 1), "spacing"),
    (np.zeros((4, 4, 4), np.float32), (1, 1), "spacing"),
])
def test_bad_arrays_raise_value_errors(array, spacing, message):
    with pytest.raises(ValueError, match=message):
        octrace.Volume(array, spacing=spacing)


def test_an_all_nan_array_is_refused():
    with pytest.raises(octrace.InputError, match="NaN"):
        octrace.Volume(np.full((4, 4, 4), np.nan, np.float32))


def test_too_large_for_max_memory_raises_memory_error():
    vol = octrace.Volume(sphere(32))
    with pytest.raises(MemoryError, match="'max_memory'|'depth'"):
        vol.surface(iso=0, depth=7, max_memory="64K")


def test_a_surface_round_trips_through_an_octree_file(tmp_path):
    shell = octrace.Volume(sphere(32)).surface(iso=0, depth=6)
    path = tmp_path / "sphere.oct"
    shell.save(path)
    back = octrace.load(path)
    assert back.depth == shell.depth and back.boundary_voxels == shell.boundary_voxels
    a = np.asarray(shell.render(size=(64, 48)))
    b = np.asarray(back.render(size=(64, 48)))
    assert np.array_equal(a, b)


def test_progress_is_reported_and_an_interrupt_cancels_the_build():
    vol = octrace.Volume(sphere(96))
    seen = []
    vol.surface(iso=0, depth=7, progress=seen.append)
    assert seen and seen[-1] == 1.0 and all(0.0 <= f <= 1.0 for f in seen)

    def interrupt(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        vol.surface(iso=0, depth=8, progress=interrupt)


def test_ctrl_c_cancels_a_build():
    """A real SIGINT while the build runs (the handler is Python's own) ends it with
    KeyboardInterrupt, and the interpreter goes on."""
    import os
    import signal

    vol = octrace.Volume(sphere(160))
    timer = threading.Timer(0.05, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            vol.surface(iso=0, depth=9)
    finally:
        timer.cancel()
    assert vol.surface(iso=0, depth=5).boundary_voxels > 0


def test_the_gil_is_released_while_building():
    """A Python thread keeps running while the octree is built."""
    vol = octrace.Volume(sphere(128))
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    start = time.perf_counter()
    t.start()
    vol.surface(iso=0, depth=8)
    end = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    assert len(during) >= 5, f"{len(during)} ticks in {end - start:.3f} s of building"


def test_an_image_is_made_by_octrace_only():
    with pytest.raises(TypeError, match="comes from Surface.render"):
        octrace.Image(np.zeros((4, 4, 4), np.uint8))
