"""The xarray accessor: a DataArray goes to the NetCDF reader's own CF interpretation, so the
same settings give the CLI's pixels; times (decoded, undecodable, cftime calendars), uneven
depth, ``positive``, NaN masks and Dask-backed arrays."""

import numpy as np
import pytest

import octrace
from conftest import read_png, run_cli

xr = pytest.importorskip("xarray")


def test_the_accessor_gives_the_clis_pixels(tmp_path, octrace_exe, levitus):
    cli_png = tmp_path / "cli.png"
    run_cli(octrace_exe, "render", levitus, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "7",
            "--colormap", "viridis", "--size", "320x240", "-o", cli_png)
    expected = read_png(cli_png)
    # Masked and scaled by xarray (NaN where the file has its fill value) ...
    da = xr.open_dataset(levitus)["TEMP"]
    img = da.octrace.render(iso=10, region=(120, 180, 10, 60), depth=7, colormap="viridis", size=(320, 240))
    assert np.array_equal(np.asarray(img), expected)
    # ... or raw, with the fill value in the attributes, as the file stores it.
    raw = xr.open_dataset(levitus, mask_and_scale=False, decode_times=False)["TEMP"]
    img = raw.octrace.render(iso=10, region=(120, 180, 10, 60), depth=7, colormap="viridis", size=(320, 240))
    assert np.array_equal(np.asarray(img), expected)


def test_the_field_equals_the_files(levitus):
    from_file = octrace.open(levitus, var="SALT", region=(140, 220, -20, 30), depth_range=(0, 1000))
    da = xr.open_dataset(levitus)["SALT"]
    from_array = da.octrace.volume(region=(140, 220, -20, 30), depth_range=(0, 1000))
    assert from_array.shape == from_file.shape
    assert from_array.bounds == from_file.bounds and from_array.coords == from_file.coords
    assert np.array_equal(from_array.values, from_file.values) and np.array_equal(from_array.mask, from_file.mask)
    assert "Lon" in da.octrace.describe() or "lon" in da.octrace.describe().lower()


def ocean(times, calendar=None, depth_positive="down"):
    """A small ocean field: temperature falling with depth, warmer to the east, over uneven
    depth levels, with a masked corner (land) and a time axis."""
    lon = np.arange(140.0, 160.0, 1.0)
    lat = np.arange(10.0, 30.0, 1.0)
    depth = np.array([0.0, 10, 30, 60, 100, 200, 400, 700, 1000])
    z = depth if depth_positive == "down" else -depth
    t = np.arange(len(times), dtype=float)
    values = (25.0 - depth[None, :, None, None] / 50.0 + (lon - 140.0)[None, None, None, :] / 4.0
              + t[:, None, None, None] + 0 * lat[None, None, :, None]).astype(np.float32)
    values[:, :, :3, :3] = np.nan
    coords = {"time": times, "depth": ("depth", z, {"units": "m", "positive": depth_positive}),
              "lat": ("lat", lat, {"units": "degrees_north"}), "lon": ("lon", lon, {"units": "degrees_east"})}
    da = xr.DataArray(values, dims=("time", "depth", "lat", "lon"), coords=coords, name="temp",
                      attrs={"units": "degC", "standard_name": "sea_water_temperature"})
    if calendar:
        da["time"].encoding.update({"units": "days since 2000-01-01", "calendar": calendar})
    return da


def test_a_time_step_chosen_with_sel_or_time_gives_the_same_surface():
    times = xr.date_range("2001-01-01", periods=3, freq="MS", calendar="noleap", use_cftime=True)
    da = ocean(times, calendar="noleap")
    by_sel = da.sel(time=times[2]).octrace.volume()
    by_index = da.octrace.volume(time=2)
    by_date = da.octrace.volume(time="2001-03-01")
    assert np.array_equal(by_sel.values, by_index.values) and np.array_equal(by_index.values, by_date.values)
    assert not np.array_equal(by_index.values, da.octrace.volume(time=0).values)


def test_decoded_numpy_datetimes():
    da = ocean(np.array(["2010-01-01", "2010-02-01"], dtype="datetime64[ns]"))
    assert np.array_equal(da.octrace.volume(time="2010-02-01").values, da.isel(time=1).octrace.volume().values)


def test_uneven_depth_positive_up_and_the_mask():
    down = ocean(np.array(["2010-01-01"], dtype="datetime64[ns]")).isel(time=0)
    up = ocean(np.array(["2010-01-01"], dtype="datetime64[ns]"), depth_positive="up").isel(time=0)
    a, b = down.octrace.volume(), up.octrace.volume()
    assert np.allclose(np.array(a.bounds), np.array(b.bounds)) and np.array_equal(a.values, b.values)
    assert len(a.coords[2]) == 9  # the uneven depth levels are kept
    assert a.mask is not None and a.mask.sum() < a.mask.size
    shell = down.octrace.surface(iso=20, depth=6)
    assert shell.boundary_voxels > 0


def test_dask_backed_arrays_are_computed():
    pytest.importorskip("dask")
    da = ocean(np.array(["2010-01-01"], dtype="datetime64[ns]")).isel(time=0)
    chunked = da.chunk({"depth": 3})
    assert np.array_equal(chunked.octrace.volume().values, da.octrace.volume().values)


def test_bad_arrays_are_refused_with_the_readers_messages():
    da = ocean(np.array(["2010-01-01"], dtype="datetime64[ns]")).isel(time=0)
    with pytest.raises(octrace.InputError):
        da.isel(depth=0).octrace.volume()  # 2-D: no volume
    bad = da.copy()
    bad["lat"] = bad["lat"].copy(data=np.full(bad.sizes["lat"], np.nan))
    with pytest.raises(octrace.InputError, match="lat"):
        bad.octrace.volume()
    with pytest.raises(TypeError, match="'regoin'.*'region'"):
        da.octrace.volume(regoin=(0, 1, 0, 1))


def test_the_package_functions_take_a_dataarray(levitus):
    da = xr.open_dataset(levitus)["TEMP"].sel(XAXLEVITR=slice(120, 180), YAXLEVITR=slice(10, 60))
    a = octrace.surface(da, iso=10, depth=5).render(size=(96, 72))
    b = da.octrace.surface(iso=10, depth=5).render(size=(96, 72))
    assert np.array_equal(np.asarray(a), np.asarray(b))
    with pytest.raises(octrace.UsageError, match="Dataset holds several variables"):
        octrace.surface(da.to_dataset(name="TEMP"), iso=10)
    with pytest.warns(octrace.OctraceWarning, match="da.octrace.volume"):
        octrace.Volume(da.fillna(0).astype(np.float32))
