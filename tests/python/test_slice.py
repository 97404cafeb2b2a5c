"""Slices from Python (model/Slice.h, as `octrace slice` draws them): a DataArray, a file opened
with octrace.open and a path give the CLI's pixels and stats; a NumPy volume in patient
coordinates is sliced as a radiology workstation shows it; bad arguments raise the CLI's
messages, worded for Python."""

import json
import subprocess

import numpy as np
import pytest

import octrace
from conftest import read_png, run_cli, shared


def cli_slice(exe, tmp_path, name, source, *args):
    """The CLI's slice of `source`: its pixels and its stats (without load_ms)."""
    png, stats = tmp_path / f"{name}.png", tmp_path / f"{name}.json"
    run_cli(exe, "slice", source, *args, "--stats", stats, "-o", png)
    expected = json.loads(stats.read_text())
    expected.pop("load_ms")
    return read_png(png), expected


def python_words(text):
    """A CLI text as Python words it: the flags as keywords in quotes."""
    for flag in ("--plane", "--at", "--index", "--window", "--colormap", "--colour-range"):
        text = text.replace(flag, "'" + flag[2:].replace("-", "_") + "'")
    return text


def same_stats(img, expected, input_differs=False):
    got = dict(img.stats)
    got.pop("load_ms")
    if input_differs:
        got.pop("input"), expected.pop("input")
    assert list(got) == list(expected)
    for key, value in expected.items():  # the JSON's numbers have 10 significant digits
        value = python_words(value) if isinstance(value, str) else pytest.approx(value, rel=1e-9) if isinstance(value, float) else value
        assert got[key] == value, key


@pytest.mark.parametrize("args, keywords", [
    (("--plane", "z", "--at", "500"), dict(plane="z", at=500)),
    (("--plane", "x", "--index", "50", "--colormap", "viridis", "--colour-range", "0,25"),
     dict(plane="x", index=50, colormap="viridis", colour_range=(0, 25))),
    (("--plane", "y", "--at", "30", "--figure", "--size", "600x400", "--title", "Section"),
     dict(plane="y", at=30, figure=True, size=(600, 400), title="Section")),
    (("--plane", "z", "--at", "0", "--figure", "--size", "600x400", "--coastline", "low"),
     dict(plane="z", at=0, figure=True, size=(600, 400), coastline="low")),
])
def test_levitus_slices_are_the_clis(tmp_path, octrace_exe, levitus, args, keywords):
    expected, stats = cli_slice(octrace_exe, tmp_path, "cli", levitus, "--var", "TEMP", *args)
    opened = octrace.open(levitus, var="TEMP").slice(**keywords)
    assert np.array_equal(np.asarray(opened), expected)
    same_stats(opened, dict(stats))
    by_path = octrace.slice(levitus, var="TEMP", **keywords)
    assert np.array_equal(np.asarray(by_path), expected)
    # The saved file is the CLI's, byte for byte.
    by_path.save(tmp_path / "py.png")
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    xr = pytest.importorskip("xarray")
    da = xr.open_dataset(levitus)["TEMP"]
    img = da.octrace.slice(**keywords)
    assert np.array_equal(np.asarray(img), expected)
    same_stats(img, dict(stats), input_differs=True)


def test_the_accessor_takes_the_readers_settings(tmp_path, octrace_exe, levitus):
    xr = pytest.importorskip("xarray")
    expected, _ = cli_slice(octrace_exe, tmp_path, "cli", levitus, "--var", "TEMP", "--region", "120,180,10,60", "--at", "100",
                            "--masked-colour", "1,0,0")
    img = xr.open_dataset(levitus)["TEMP"].octrace.slice(region=(120, 180, 10, 60), at=100, masked_colour=(1, 0, 0))
    assert np.array_equal(np.asarray(img), expected)
    assert img.stats["masked_pixels"] > 0 and img.stats["plane"] == "z"


def test_a_ct_from_numpy_in_patient_coordinates_is_the_clis(tmp_path, octrace_exe):
    path = shared("medical/lidc2_chest_ct.nrrd")
    ct = octrace.open(path)
    volume = octrace.Volume(np.array(ct.values), spacing=ct.spacing, origin=ct.origin, direction=ct.direction, name=ct.name,
                            units=ct.units, patient_lps=True)
    for name, args, keywords in [
        ("axial", (), {}),  # axial by default, greyed over the volume's value range
        ("coronal", ("--plane", "coronal", "--window", "100,150", "--figure", "--size", "500x400"),
         dict(plane="coronal", window=(100, 150), figure=True, size=(500, 400))),
        ("sagittal", ("--plane", "sagittal", "--at", "100", "--window", "120,240"), dict(plane="sagittal", at=100, window="120,240")),
    ]:
        expected, stats = cli_slice(octrace_exe, tmp_path, name, path, *args)
        img = volume.slice(**keywords)
        assert np.array_equal(np.asarray(img), expected), name
        same_stats(img, dict(stats), input_differs=True)
    assert img.stats["patient_lps"] and (img.stats["screen_right"], img.stats["screen_up"]) == ("P", "S")


def test_a_numpy_volume_is_sliced_in_radiology_orientation():
    z, y, x = np.mgrid[0:6, 0:8, 0:10].astype(np.float32)
    values = x + 10 * y + 100 * z
    patient = octrace.Volume(values, spacing=(1, 1, 2), patient_lps=True)
    img = patient.slice(index=2, colormap="grey", colour_range=(200, 300))
    assert img.stats["plane"] == "axial" and img.stats["grid_index"] == 2
    assert (img.stats["screen_right"], img.stats["screen_up"]) == ("L", "A")  # seen from the feet, anterior up
    assert (img.width, img.height) == (10, 8)
    grey = np.asarray(img)[..., 0].astype(int)
    assert np.all(np.diff(grey, axis=1) >= 0) and np.all(np.diff(grey, axis=0) >= 0)  # left and posterior grow
    assert grey[0, 0] == 0 and grey[-1, -1] > 128  # 200 at the top left, 279 at the bottom right
    plain = octrace.Volume(values)
    assert plain.slice().stats["plane"] == "z"
    with pytest.raises(octrace.UsageError, match="'plane' sagittal: .* not in patient coordinates"):
        plain.slice(plane="sagittal")


def cli_error(exe, *args):
    r = subprocess.run([exe, "slice", *map(str, args)], capture_output=True, text=True)
    assert r.returncode != 0
    return r.stderr.splitlines()[0].removeprefix("octrace: ").removeprefix("error: ")


@pytest.mark.parametrize("args, keywords, error", [
    (("--plane", "oblique"), dict(plane="oblique"), octrace.UsageError),
    (("--at", "6000"), dict(at=6000), octrace.InputError),  # below the deepest level: outside the grid
    (("--at", "0", "--index", "1"), dict(at=0, index=1), octrace.UsageError),
    (("--window", "40,400", "--colormap", "viridis"), dict(window=(40, 400), colormap="viridis"), octrace.UsageError),
])
def test_bad_arguments_raise_the_clis_messages(tmp_path, octrace_exe, levitus, args, keywords, error):
    message = python_words(cli_error(octrace_exe, levitus, "--var", "TEMP", *args, "-o", tmp_path / "x.png"))
    with pytest.raises(error) as raised:
        octrace.slice(levitus, var="TEMP", **keywords)
    assert str(raised.value) == message
    with pytest.raises(error) as raised:
        octrace.open(levitus, var="TEMP").slice(**keywords)
    assert str(raised.value) == message


def test_unknown_keywords_name_the_nearest(levitus):
    volume = octrace.open(levitus, var="TEMP")
    with pytest.raises(TypeError, match="'plnae'.*'plane'"):
        volume.slice(plnae="z")
    with pytest.raises(TypeError, match="'colourmap'.*'colormap'"):
        octrace.slice(levitus, var="TEMP", colourmap="viridis")
    with pytest.raises(TypeError, match="'iso'"):
        volume.slice(iso=10)  # a surface's setting
    with pytest.raises(octrace.UsageError, match="slice samples a field"):
        octrace.slice(octrace.Input("shell.oct", []))
