"""A Zarr v2 store opens as the NetCDF file it was written from: octrace.open and octrace.surface
take the store's folder like a file, and give the file's samples, mask and pixels."""

import warnings

import numpy as np
import pytest

import octrace

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")

REGION = (120, 180, 10, 60)


@pytest.fixture(scope="module")
def store(tmp_path_factory, levitus):
    path = tmp_path_factory.mktemp("zarr") / "levitus.zarr"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        xr.open_dataset(levitus).to_zarr(path, zarr_format=2, consolidated=True)  # Blosc, zarr-python's default
    return str(path)


def test_open_reads_a_store_as_its_netcdf_file(store, levitus):
    for var in ("TEMP", "SALT"):
        a = octrace.open(levitus, var=var, region=REGION)
        b = octrace.open(store, var=var, region=REGION)
        assert b.shape == a.shape and b.units == a.units and b.notes == a.notes
        assert np.array_equal(b.mask, a.mask)
        assert np.array_equal(np.asarray(b.values)[a.mask == 1], np.asarray(a.values)[a.mask == 1])


def test_a_store_renders_the_netcdf_files_pixels(store, levitus):
    images = [np.asarray(octrace.surface(p, var="TEMP", iso=10, region=REGION, depth=6).render(size=(160, 120)))
              for p in (levitus, store)]
    assert np.array_equal(images[0], images[1])


def test_a_final_v3_store_is_refused_with_how_to_convert_it(tmp_path, levitus):
    path = tmp_path / "v3.zarr"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        xr.open_dataset(levitus).isel(ZAXLEVITR=slice(0, 2)).to_zarr(path)  # zarr-python 3's default layout
    with pytest.raises(octrace.InputError, match=r"final layout.*drop_encoding\(\)\.to_zarr\("):
        octrace.open(str(path), var="TEMP")
