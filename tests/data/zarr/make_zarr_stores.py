#!/usr/bin/env python3
"""Zarr stores for octrace's tests, made from the Levitus atlas (a NetCDF file).

  make_zarr_stores.py levitus LEVITUS.cdf OUTDIR   the stores the tests compare with the NetCDF
                                                   file (about 40 MB; written at test time into
                                                   the build tree by tests/ZarrStores.h)
  make_zarr_stores.py corpus LEVITUS.cdf OUTDIR    the small broken stores of tests/data/invalid
                                                   (run once; their outputs are committed)
  make_zarr_stores.py seeds LEVITUS.cdf OUTDIR     the seeds of tests/fuzz/fuzz_zarr_metadata.cpp:
                                                   a tiny store's files joined by the byte 0x1E

Needs xarray and zarr (app/python/requirements.txt) and GDAL's gdalmdimtranslate (gdal-bin).
Exits with 77 when one of them is missing, so that the tests can say what to install.
"""
import os
import shutil
import subprocess
import sys
import warnings

MISSING = 77

try:
    import numcodecs
    import numpy as np
    import xarray as xr
    import zarr
except ImportError as e:  # pragma: no cover - reported to the test
    print(f"make_zarr_stores: {e}; install app/python/requirements.txt", file=sys.stderr)
    sys.exit(MISSING)

warnings.filterwarnings("ignore", category=UserWarning)  # zarr's notes on consolidated metadata
VARIABLES = ("TEMP", "SALT")


def gdal_translate(source, store, *options):
    if shutil.which("gdalmdimtranslate") is None:
        print("make_zarr_stores: gdalmdimtranslate not found; install gdal-bin", file=sys.stderr)
        sys.exit(MISSING)
    subprocess.run(["gdalmdimtranslate", "-q", "-of", "ZARR", *options, source, store], check=True)


def chunked(ds, chunks, compressor=None):
    """`ds` with TEMP and SALT written in `chunks` (and `compressor`), their _FillValue and
    missing_value kept (an `encoding=` argument would replace them)."""
    ds = ds.copy()
    for name in VARIABLES:
        ds[name].encoding["chunks"] = chunks
        if compressor is not None:
            ds[name].encoding["compressors"] = (compressor,)
    return ds


def require_blosc(store):
    for name in VARIABLES:
        compressor = zarr.open_array(os.path.join(store, name), mode="r", zarr_format=2).metadata.compressor
        if compressor is None or compressor.codec_id != "blosc":
            sys.exit(f"make_zarr_stores: {store}/{name} is not Blosc-compressed ({compressor})")


def delete_masked_chunks(store, ds, chunks):
    """Deletes every chunk of TEMP and SALT whose samples are all _FillValue (all land), as ocean
    stores leave them out; returns how many are gone."""
    gone = 0
    for name in VARIABLES:
        masked = ds[name].isnull().values  # xarray decodes _FillValue to NaN
        for index in np.ndindex(*[-(-n // c) for n, c in zip(masked.shape, chunks)]):
            block = tuple(slice(i * c, (i + 1) * c) for i, c in zip(index, chunks))
            if masked[block].all():
                path = os.path.join(store, name, ".".join(str(i) for i in index))
                if os.path.exists(path):
                    os.remove(path)  # zarr-python may not have written it at all
                gone += 1
    if gone == 0:
        sys.exit("make_zarr_stores: no all-masked chunk to leave out; choose smaller chunks")
    return gone


def levitus(source, out):
    ds = xr.open_dataset(source)
    # GDAL's own writer (uncompressed: GDAL 3.6's gdalmdimtranslate passes -co to the dataset,
    # and COMPRESS is an option of each array), and the pre-final v3 draft GDAL 3.6 writes.
    gdal_translate(source, os.path.join(out, "levitus_gdal.zarr"))
    gdal_translate(source, os.path.join(out, "levitus_gdal_v3draft.zarr"), "-co", "FORMAT=ZARR_V3")
    # xarray (zarr-python), format 2, consolidated or not; Blosc zstd with bit shuffle, and
    # zarr-python's default (Blosc lz4).
    blosc = numcodecs.Blosc(cname="zstd", clevel=3, shuffle=numcodecs.Blosc.BITSHUFFLE)
    consolidated = os.path.join(out, "levitus_xr_consolidated.zarr")
    chunked(ds, (5, 90, 180), blosc).to_zarr(consolidated, zarr_format=2, consolidated=True, mode="w")
    plain = os.path.join(out, "levitus_xr_unconsolidated.zarr")
    chunked(ds, (4, 60, 120)).to_zarr(plain, zarr_format=2, consolidated=False, mode="w")
    require_blosc(consolidated)
    require_blosc(plain)
    if os.path.exists(os.path.join(plain, ".zmetadata")):
        sys.exit(f"make_zarr_stores: {plain} has consolidated metadata")
    # Small chunks (5 levels x 30 x 30 degrees), the all-land ones left out.
    missing = os.path.join(out, "levitus_missing_chunks.zarr")
    chunked(ds, (5, 30, 30), blosc).to_zarr(missing, zarr_format=2, consolidated=True, mode="w")
    gone = delete_masked_chunks(missing, ds, (5, 30, 30))
    with open(os.path.join(missing, "MISSING_CHUNKS"), "w") as f:
        f.write(f"{gone}\n")
    # A monthly series (TEMP over the North Pacific, 1 degree cooler each month), as a NetCDF
    # file and as a store, for `octrace animate`.
    pacific = ds["TEMP"].sel(XAXLEVITR=slice(120, 180), YAXLEVITR=slice(10, 60))
    series = xr.concat([pacific - k for k in range(3)], dim="time").to_dataset(name="TEMP")
    series["time"] = ("time", np.array([0.0, 31.0, 59.0]),
                      {"units": "days since 2001-01-01", "calendar": "noleap", "standard_name": "time"})
    series["TEMP"].encoding = {"_FillValue": np.float32(-1e10), "dtype": "float32"}
    series.to_netcdf(os.path.join(out, "pacific_monthly.nc"))
    series.to_zarr(os.path.join(out, "pacific_monthly.zarr"), zarr_format=2, consolidated=True, mode="w")
    # zarr-python 3's default, the final v3 layout (refused), and its conversion to v2 as
    # octrace's refusal says to do it.
    v3 = os.path.join(out, "levitus_v3.zarr")
    ds.to_zarr(v3, mode="w")
    xr.open_zarr(v3).drop_encoding().to_zarr(os.path.join(out, "levitus_v3_v2.zarr"), zarr_format=2)


def corpus(source, out):
    # A corner of the atlas (4 levels x 6 x 8 degrees in the North Atlantic) in two chunks.
    ds = xr.open_dataset(source).isel(ZAXLEVITR=slice(0, 4), YAXLEVITR=slice(120, 126), XAXLEVITR=slice(300, 308))
    ds = ds.drop_vars("ZAXLEVITRedges")
    broken = os.path.join(out, "invalid_corrupt_chunk.zarr")
    chunked(ds, (2, 6, 8)).to_zarr(broken, zarr_format=2, consolidated=True, mode="w")
    require_blosc(broken)
    # The second chunk of TEMP: bytes that are no Blosc frame.
    with open(os.path.join(broken, "TEMP", "1.0.0"), "wb") as f:
        f.write(b"these bytes are not a Blosc-compressed chunk\n")
    ds.to_zarr(os.path.join(out, "invalid_zarr_v3.zarr"), mode="w")  # zarr-python 3's default layout


def seeds(source, out):
    """Tiny stores for fuzz_zarr_metadata: .zgroup, .zmetadata, zarr.json, then the array v's
    .zarray, .zattrs and chunk 0.0.0, joined by 0x1E (empty parts: the file is absent)."""
    import json
    import tempfile

    ds = xr.open_dataset(source).isel(ZAXLEVITR=slice(0, 3), YAXLEVITR=slice(120, 124), XAXLEVITR=slice(300, 305))
    temp = ds["TEMP"].rename("v").to_dataset().drop_vars(["ZAXLEVITR", "YAXLEVITR", "XAXLEVITR"])

    def read(path):
        if not os.path.exists(path):
            return b""
        with open(path, "rb") as f:
            return f.read()

    def seed(name, store, zarr_json=b""):
        files = [read(os.path.join(store, ".zgroup")), read(os.path.join(store, ".zmetadata")), zarr_json,
                 read(os.path.join(store, "v", ".zarray")), read(os.path.join(store, "v", ".zattrs")),
                 read(os.path.join(store, "v", "0.0.0"))]
        with open(os.path.join(out, name), "wb") as f:
            f.write(b"\x1e".join(files))

    with tempfile.TemporaryDirectory() as tmp:
        for name, chunks, compressor, consolidated in (
                ("blosc_consolidated", (3, 4, 5), None, True),
                ("blosc_zstd_two_chunks", (2, 4, 5), numcodecs.Blosc(cname="zstd", shuffle=numcodecs.Blosc.BITSHUFFLE), False),
                ("zlib", (3, 4, 5), numcodecs.Zlib(level=1), True),
                ("uncompressed", (3, 4, 5), "none", False)):
            store = os.path.join(tmp, name + ".zarr")
            data = temp.copy()
            data["v"].encoding["chunks"] = chunks
            data["v"].encoding["compressors"] = None if compressor == "none" else (compressor,) if compressor else None
            if compressor is None:
                del data["v"].encoding["compressors"]
            data.to_zarr(store, zarr_format=2, consolidated=consolidated, mode="w")
            seed(name, store)
        draft = {"zarr_format": "https://purl.org/zarr/spec/protocol/core/3.0",
                 "metadata_encoding": "https://purl.org/zarr/spec/protocol/core/3.0",
                 "metadata_key_suffix": ".json", "extensions": []}
        with open(os.path.join(out, "v3_draft_root"), "wb") as f:
            f.write(b"\x1e\x1e" + json.dumps(draft).encode() + b"\x1e\x1e\x1e")
        final = {"zarr_format": 3, "node_type": "group", "attributes": {}}
        with open(os.path.join(out, "v3_final_root"), "wb") as f:
            f.write(b"\x1e\x1e" + json.dumps(final).encode() + b"\x1e\x1e\x1e")


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("levitus", "corpus", "seeds"):
        sys.exit(__doc__)
    what, source, out = sys.argv[1:]
    os.makedirs(out, exist_ok=True)
    {"levitus": levitus, "corpus": corpus, "seeds": seeds}[what](source, out)


if __name__ == "__main__":
    main()
