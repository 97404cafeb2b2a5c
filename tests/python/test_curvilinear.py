"""A DataArray on a curvilinear grid (2-D lat/lon coordinates) goes through the same resampling
as the file (docs/dev/ocean.md, "Curvilinear grids")."""

import os

import numpy as np
import pytest

import octrace

xr = pytest.importorskip("xarray")

ROTATED = os.path.join(os.path.dirname(__file__), "..", "data", "netcdf", "rotated_natl.nc")
REGION = (-70, -10, 20, 55)


def test_a_dataarray_with_2d_coordinates_is_resampled_as_the_file_is():
    from_file = octrace.open(ROTATED, var="temp", region=REGION)
    da = xr.open_dataset(ROTATED)["temp"]
    assert da.coords["lat"].ndim == 2  # xarray made the `coordinates` attribute into coordinates
    from_array = da.octrace.volume(region=REGION)
    assert from_array.shape == from_file.shape
    assert from_array.bounds == from_file.bounds and from_array.coords == from_file.coords
    assert np.array_equal(from_array.mask, from_file.mask)
    # xarray unpacks the int16 in float32, the reader in double: a rounding apart at most.
    assert np.allclose(from_array.values, from_file.values, rtol=0, atol=1e-5)
    assert "curvilinear" in da.octrace.describe()
