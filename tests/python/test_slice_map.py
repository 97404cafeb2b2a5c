"""2-D fields drawn as maps from Python (model/Slice.h, as `octrace slice` draws them): a 2-D
DataArray through the in-memory CF interpretation gives the file path's pixels (the real ETOPO20
relief, the Levitus top level as a 2-D file and as OISST lays it out, made by
tests/data/netcdf/make_maps.py), and a surface of a 2-D field is refused saying to use slice."""

import pathlib

import numpy as np
import pytest

import octrace
from conftest import read_png, run_cli, shared

DATA = pathlib.Path(__file__).parents[1] / "data" / "netcdf"
KEYWORDS = dict(colour_range=(-2, 30), masked_colour=(1, 0, 1))


def test_etopo20_dataarray_map_is_the_files(tmp_path, octrace_exe):
    xr = pytest.importorskip("xarray")
    etopo = shared("ocean/etopo20.cdf")
    run_cli(octrace_exe, "slice", etopo, "--colour-range", "-6000,4000", "-o", tmp_path / "cli.png")
    expected = read_png(tmp_path / "cli.png")
    da = xr.open_dataset(etopo)["ROSE"]
    by_array = np.asarray(octrace.slice(da, colour_range=(-6000, 4000)))
    assert np.array_equal(by_array, expected)
    assert np.array_equal(np.asarray(da.octrace.slice(colour_range=(-6000, 4000))), expected)
    assert np.array_equal(np.asarray(octrace.slice(etopo, colour_range=(-6000, 4000))), expected)


@pytest.mark.parametrize("name, tolerance", [("levitus_sst_2d.nc", 0), ("oisst_like_zlev.nc", 1)])
def test_two_dimensional_dataarray_map_is_the_files(tmp_path, octrace_exe, name, tolerance):
    xr = pytest.importorskip("xarray")
    path = DATA / name
    run_cli(octrace_exe, "slice", path, "--colour-range", "-2,30", "--masked-colour", "1,0,1", "--figure", "--size", "900x600",
            "-o", tmp_path / "cli.png")
    expected = read_png(tmp_path / "cli.png")
    # Decoded by xarray (OISST's int16 unpacked to float, _FillValue to NaN) or not: the same map.
    for decode in (True, False):
        da = xr.open_dataset(path, mask_and_scale=decode)["sst"]
        img = np.asarray(da.octrace.slice(figure=True, size=(900, 600), **KEYWORDS)).astype(int)
        assert img.shape == expected.shape
        assert np.abs(img - expected).max() <= tolerance, (name, decode)


def test_map_of_the_atlas_top_level_from_a_dataarray_level(levitus):
    xr = pytest.importorskip("xarray")
    top = xr.open_dataset(levitus)["TEMP"].isel(ZAXLEVITR=0)  # a 2-D DataArray with a scalar depth coordinate
    from_level = np.asarray(top.octrace.slice(**KEYWORDS))
    from_file = np.asarray(octrace.slice(str(DATA / "levitus_sst_2d.nc"), **KEYWORDS))
    assert np.array_equal(from_level, from_file)


def test_surface_of_a_two_dimensional_field_is_refused_saying_to_slice():
    xr = pytest.importorskip("xarray")
    da = xr.open_dataset(DATA / "levitus_sst_2d.nc")["sst"]
    with pytest.raises(octrace.InputError, match="a surface needs a 3-D field; draw the 2-D sst with slice"):
        da.octrace.render(iso=10)
    with pytest.raises(octrace.InputError, match="draw the 2-D sst with slice"):
        octrace.surface(str(DATA / "levitus_sst_2d.nc"), iso=10)
    with pytest.raises(octrace.InputError, match="only its z plane, the map itself, can be drawn"):
        da.octrace.slice(plane="x")
