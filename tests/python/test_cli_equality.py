"""The package gives the CLI's pixels: the same settings through octrace.open/surface/render and
through `octrace render` produce the same image, on the real Levitus atlas."""

import numpy as np

import octrace
from conftest import read_png, run_cli

REGION = (120, 180, 10, 60)


def test_levitus_isotherm_equals_the_cli(tmp_path, octrace_exe, levitus):
    cli_png = tmp_path / "cli.png"
    run_cli(octrace_exe, "render", levitus, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "7",
            "--colormap", "viridis", "--size", "320x240", "-o", cli_png)
    temp = octrace.open(levitus, var="TEMP", region=REGION)
    shell = octrace.surface(temp, iso=10, depth=7, colormap="viridis")
    img = shell.render(size=(320, 240))
    pixels = np.asarray(img)
    assert pixels.shape == (240, 320, 4) and pixels.dtype == np.uint8
    expected = read_png(cli_png)
    differing = int(np.count_nonzero(np.any(pixels != expected, axis=2)))
    assert differing == 0, f"{differing} pixels differ from the CLI's"
    # The package's writer is the CLI's: the same file, byte for byte.
    img.save(tmp_path / "py.png")
    assert (tmp_path / "py.png").read_bytes() == cli_png.read_bytes()


def test_a_path_builds_as_the_cli_does(tmp_path, octrace_exe, levitus):
    """octrace.surface(PATH, ...) reads and builds in one step with the reader's settings."""
    cli_png = tmp_path / "cli.png"
    run_cli(octrace_exe, "render", levitus, "--var", "SALT", "--iso", "34.5", "--region", "120,180,10,60", "--depth", "6",
            "--size", "200x150", "--background", "0,0,0", "-o", cli_png)
    img = octrace.surface(levitus, var="SALT", iso=34.5, region=REGION, depth=6).render(size=(200, 150), background=(0, 0, 0))
    assert np.array_equal(np.asarray(img), read_png(cli_png))


def test_stats_are_the_clis_keys(tmp_path, octrace_exe, levitus):
    stats_json = tmp_path / "s.json"
    run_cli(octrace_exe, "render", levitus, "--var", "TEMP", "--iso", "10", "--depth", "6", "--size", "160x120",
            "-o", tmp_path / "x.png", "--stats", stats_json)
    import json

    cli = json.loads(stats_json.read_text())
    img = octrace.surface(levitus, var="TEMP", iso=10, depth=6).render(size=(160, 120))
    assert list(img.stats)[:5] == list(cli)[:5]
    for key in ("renderer", "width", "height", "boundary_voxels", "octree_depth", "iso", "rays"):
        if key in cli:
            assert img.stats[key] == cli[key], key


def test_values_with_units_are_the_clis(tmp_path, octrace_exe):
    """iso="10degC" on a field in kelvin and colour_range=("5degC", "20degC") go through the
    options table's parser (one parser for both front ends) and give the CLI's pixels."""
    import pathlib

    kelvin = str(pathlib.Path(__file__).parents[1] / "data" / "netcdf" / "levitus_kelvin.nc")
    cli_png = tmp_path / "cli.png"
    run_cli(octrace_exe, "render", kelvin, "--var", "TEMP", "--iso", "10degC", "--depth", "7",
            "--colour-by", "TEMP", "--colour-range", "5degC,20degC", "--size", "200x150", "-o", cli_png)
    shell = octrace.surface(kelvin, var="TEMP", iso="10degC", depth=7, colour_by="TEMP")
    assert abs(shell.iso - 283.15) < 1e-9
    img = shell.render(size=(200, 150), colour_range=("5degC", "20degC"))
    assert np.array_equal(np.asarray(img), read_png(cli_png))
    # The same errors as the CLI's, as the package's exceptions.
    import pytest

    with pytest.raises(octrace.UsageError, match="unknown unit 'degx'"):
        octrace.surface(kelvin, var="TEMP", iso="10degx")
    with pytest.raises(octrace.InputError, match="10m does not convert to K"):
        octrace.surface(kelvin, var="TEMP", iso="10m")
