"""octrace.animate: a DataArray with a time axis (the Levitus field, warmed step by step) to an
MP4 with one frame per step, in order, rendered on local threads and on a 2-worker Dask
LocalCluster; the date in each figure's caption."""

import json
import shutil
import subprocess

import numpy as np
import pytest

import octrace
from conftest import read_png

xr = pytest.importorskip("xarray")


@pytest.fixture(scope="module")
def series(levitus):
    """TEMP over the Northwest Pacific with four monthly steps, each 1.5 degC warmer: the 10 degC
    isotherm deepens step by step."""
    temp = xr.open_dataset(levitus)["TEMP"].sel(XAXLEVITR=slice(120, 180), YAXLEVITR=slice(10, 60)).load()
    times = np.array(["2001-01-01", "2001-02-01", "2001-03-01", "2001-04-01"], dtype="datetime64[ns]")
    return xr.concat([temp + 1.5 * i for i in range(len(times))], dim=xr.DataArray(times, dims="time", name="time"))


def probe(path):
    if not shutil.which("ffprobe"):
        pytest.skip("needs ffprobe (scripts/setup.sh installs ffmpeg)")
    out = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                          "stream=codec_name,width,height,nb_read_frames", "-of", "json", str(path)],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)["streams"][0]


def decoded(path, width, height):
    raw = subprocess.run(["ffmpeg", "-v", "error", "-i", str(path), "-f", "rawvideo", "-pix_fmt", "rgb24", "-"],
                         capture_output=True, check=True).stdout
    return np.frombuffer(raw, np.uint8).reshape(-1, height, width, 3).astype(np.int32)


def check_order(video, pngs, width, height):
    """Each decoded video frame is nearest to the PNG of its own step."""
    frames = decoded(video, width, height)
    assert len(frames) == len(pngs)
    originals = [read_png(p)[..., :3].astype(np.int32) for p in pngs]
    for i, frame in enumerate(frames):
        errors = [np.abs(frame - o).mean() for o in originals]
        assert int(np.argmin(errors)) == i, errors


def test_local_threads(tmp_path, series):
    video = octrace.animate(series, "time", tmp_path / "warming.mp4", frames=tmp_path / "frames", iso=10, depth=7,
                            colormap="viridis", size=(320, 240), progress=False)
    info = probe(video)
    assert info["codec_name"] in ("h264", "mpeg4") and int(info["nb_read_frames"]) == 4
    pngs = sorted((tmp_path / "frames").glob("frame_*.png"))
    assert len(pngs) == 4
    check_order(video, pngs, 320, 240)
    assert not np.array_equal(read_png(pngs[0]), read_png(pngs[3]))


def test_colours_by_height_over_the_grid_in_every_frame(tmp_path, series):
    """Coloured by height, every frame maps the grid's heights (0 .. the deepest level, in metres)
    onto the colour map, as octrace animate does: frame i is the step's render with that range."""
    octrace.animate(series, "time", frames=tmp_path / "frames", iso=10, depth=6, colormap="viridis", size=(160, 120),
                    workers=1, progress=False)
    grid = series.isel(time=0).octrace.volume()
    low, high = octrace._octrace.height_range(grid._field)
    assert high == pytest.approx(0.0) and low == pytest.approx(-float(series["ZAXLEVITR"].max()), rel=1e-6)
    camera = octrace._octrace.box_camera(grid.bounds, [("size", "160x120")], 0.0)
    for i in (0, 3):
        step = series.isel(time=i).octrace.surface(iso=10, depth=6)
        fixed = step.render(size=(160, 120), camera=camera, colormap="viridis", colour_range=(low, high))
        own = step.render(size=(160, 120), camera=camera, colormap="viridis")
        frame = read_png(tmp_path / "frames" / f"frame_{i:04d}.png")
        assert np.array_equal(frame, np.asarray(fixed))
        assert not np.array_equal(frame, np.asarray(own))


def test_dask_local_cluster_with_captions(tmp_path, series):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        video = octrace.animate(series, "time", tmp_path / "warming.mp4", frames=tmp_path / "frames", client=client,
                                iso=10, depth=6, threads=1, figure=True, title="Warming", size=(480, 360), progress=False)
    info = probe(video)
    assert int(info["nb_read_frames"]) == 4 and int(info["width"]) == 480
    pngs = sorted((tmp_path / "frames").glob("frame_*.png"))
    check_order(video, pngs, 480, 360)
    # The caption (the date) is in the subtitle: frames differ there even where the plot is alike.
    tops = [read_png(p)[:60] for p in pngs]
    assert all(not np.array_equal(tops[0], t) for t in tops[1:])


def test_bad_calls(tmp_path, series):
    with pytest.raises(octrace.UsageError, match="'depth' is not a dimension|not a dimension"):
        octrace.animate(series, "depth", tmp_path / "x.mp4", iso=10)
    with pytest.raises(octrace.UsageError, match=".mp4"):
        octrace.animate(series, "time", tmp_path / "x.avi", iso=10)
    with pytest.raises(octrace.UsageError, match="'fps'"):
        octrace.animate(series, "time", tmp_path / "x.mp4", iso=10, fps=1000)
    with pytest.raises(TypeError, match="'isoo'"):
        octrace.animate(series, "time", tmp_path / "x.mp4", isoo=10)


def test_a_progress_callable_sees_the_frames_and_can_cancel(tmp_path, series):
    seen = []
    octrace.animate(series.isel(time=slice(0, 2)), "time", frames=tmp_path / "ok", iso=10, depth=5, size=(64, 48),
                    workers=1, progress=seen.append)
    assert seen == [0.5, 1.0]

    def stop(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        octrace.animate(series, "time", tmp_path / "x.mp4", iso=10, depth=5, size=(64, 48), workers=1, progress=stop)
    assert not (tmp_path / "x.mp4").exists()
    with pytest.raises(octrace.UsageError, match="Dataset holds several variables"):
        octrace.animate(series.to_dataset(name="TEMP"), "time", tmp_path / "x.mp4", iso=10)


def test_undecoded_cf_times_are_captioned_with_their_dates():
    """A year-0 noleap climatology that xarray leaves as numbers (decode_times=False) is dated
    by the NetCDF reader's calendars; a coordinate without time units keeps its numbers."""
    from octrace._animate import captions

    da = xr.DataArray(np.zeros((3, 2, 2, 2), np.float32), dims=("time", "z", "y", "x"),
                      coords={"time": ("time", [15.0, 45.0, 74.0], {"units": "days since 0000-01-01", "calendar": "noleap"})})
    assert captions(da, "time") == ["0000-01-16", "0000-02-15", "0000-03-16"]
    plain = da.assign_coords(time=("time", [1.0, 2.0, 3.0]))
    assert captions(plain, "time") == ["1", "2", "3"]
    assert captions(da.drop_vars("time"), "time") == ["step 0", "step 1", "step 2"]
