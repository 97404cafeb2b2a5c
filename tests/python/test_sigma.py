"""Parametric vertical coordinates from xarray (docs/dev/ocean.md, "Parametric vertical
coordinates"): a DataArray of the ROMS-like test file opened with decode_coords="all" carries
the formula terms as coordinates and gives the file's field; without them it is refused
naming the missing term."""

import pathlib

import numpy as np
import pytest

import octrace

xr = pytest.importorskip("xarray")
ROMS = pathlib.Path(__file__).resolve().parents[1] / "data" / "netcdf" / "roms_g2_nwatlantic.nc"


def test_a_roms_dataarray_gives_the_files_field():
    from_file = octrace.open(ROMS, var="temp", time="1", region=(-76, -60, 33, 44))
    da = xr.open_dataset(ROMS, decode_coords="all")["temp"]
    assert {"h", "zeta", "Cs_r", "hc"} <= set(da.coords)
    from_array = da.octrace.volume(time="1", region=(-76, -60, 33, 44))
    assert from_array.shape == from_file.shape and from_array.coords == from_file.coords
    assert np.array_equal(from_array.values, from_file.values) and np.array_equal(from_array.mask, from_file.mask)
    # a step chosen with isel: zeta(lat, lon) then has no time, as the field
    one = da.isel(ocean_time=1).octrace.volume(region=(-76, -60, 33, 44))
    assert np.array_equal(one.values, from_file.values)
    assert "ocean_s_coordinate_g2" in da.octrace.describe(time="1")


def test_without_its_terms_the_dataarray_is_refused_naming_them():
    da = xr.open_dataset(ROMS)["temp"]  # the terms are data variables of the Dataset, not coordinates
    with pytest.raises(octrace.InputError, match="name variable 'Cs_r' for term 'C'"):
        da.octrace.volume(time="0")
