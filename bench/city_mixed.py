#!/usr/bin/env python3
"""Generates docs/benchmarks/city-mixed.md: per-region depth (--terrain-depth) against uniform
depth on the city scenes: build time, boundary voxels (coarse leaves counted once), octree
size and peak resident memory.

Scenes: Delft (`delft.json`, its own terrain) and the Lyon footprints over a ground DEM. No DEM
of the shared data covers Lyon, so the script makes one from the footprints themselves: the
ground height of each footprint (Z_MIN_SOL) at its first vertex, interpolated by inverse
distance weighting onto a 65 x 65 grid over their extent (an ESRI ASCII grid wrapped in a GDAL
VRT that states EPSG:3946). Each row is one `octrace render` run (a 160x120 frame) with
--stats; raw JSON per run, with its command, in docs/benchmarks/city-mixed/.

Usage: bench/city_mixed.py [--bin PATH] [--data DIR] [--threads N]
"""
import json
import os
import tempfile

from city import arguments, run  # shared with bench/city.py: options, the run with its peak RSS

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LYON = ["--height-attr", "HAUTEUR", "--base-attr", "Z_MIN_SOL"]
# (scene, input, options, depth, terrain depth or None)
RUNS = [
    ("delft", "city/delft.json", [], 12, None),
    ("delft", "city/delft.json", [], 12, 9),
    ("delft", "city/delft.json", [], 10, 7),
    ("lyon+dem", "city/buildings_lyon1.geojson", LYON + ["--dem", "DEM"], 12, None),
    ("lyon+dem", "city/buildings_lyon1.geojson", LYON + ["--dem", "DEM"], 12, 9),
    ("lyon+dem", "city/buildings_lyon1.geojson", LYON + ["--dem", "DEM"], 10, 7),
]


def lyon_ground_dem(footprints, tmp):
    """Writes the Lyon ground DEM (see the docstring); returns the VRT's path."""
    with open(footprints) as f:
        fc = json.load(f)
    pts = []
    for feat in fc["features"]:
        z = feat["properties"].get("Z_MIN_SOL")
        g = feat.get("geometry")
        if z is None or not g:
            continue
        ring = g["coordinates"][0][0] if g["type"] == "MultiPolygon" else g["coordinates"][0]
        pts.append((ring[0][0], ring[0][1], float(z)))
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    n = 65
    x0, x1, y0, y1 = min(xs) - 20, max(xs) + 20, min(ys) - 20, max(ys) + 20
    cell = max(x1 - x0, y1 - y0) / (n - 1)
    rows = []
    for j in range(n):
        y = y1 - j * cell
        row = []
        for i in range(n):
            x = x0 + i * cell
            num = den = 0.0
            for px, py, pz in pts:
                d2 = (px - x) ** 2 + (py - y) ** 2 + 1.0
                w = 1.0 / (d2 * d2)
                num += w * pz
                den += w
            row.append("%.2f" % (num / den))
        rows.append(" ".join(row))
    asc = os.path.join(tmp, "lyon_ground.asc")
    with open(asc, "w") as f:
        f.write("ncols %d\nnrows %d\nxllcorner %.3f\nyllcorner %.3f\ncellsize %.6f\n" %
                (n, n, x0 - cell / 2, y1 - (n - 1) * cell - cell / 2, cell))
        f.write("\n".join(rows) + "\n")
    vrt = os.path.join(tmp, "lyon_ground.vrt")
    with open(vrt, "w") as f:
        f.write('<VRTDataset rasterXSize="%d" rasterYSize="%d">\n <SRS>EPSG:3946</SRS>\n'
                ' <GeoTransform>%.6f, %.6f, 0, %.6f, 0, %.6f</GeoTransform>\n'
                ' <VRTRasterBand dataType="Float32" band="1">\n  <SimpleSource>\n'
                '   <SourceFilename relativeToVRT="1">lyon_ground.asc</SourceFilename>\n'
                '   <SourceBand>1</SourceBand>\n  </SimpleSource>\n </VRTRasterBand>\n</VRTDataset>\n' %
                (n, n, x0 - cell / 2, cell, y1 + cell / 2, -cell))
    return vrt


def main():
    args, outdir = arguments(__doc__, "city-mixed")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        dem = lyon_ground_dem(os.path.join(args.data, "city/buildings_lyon1.geojson"), tmp)
        for scene, rel, extra, depth, terrain in RUNS:
            stats = os.path.join(tmp, "stats.json")
            opts = [dem if o == "DEM" else o for o in extra] + ["--depth", str(depth)]
            if terrain:
                opts += ["--terrain-depth", str(terrain)]
            cmd = [args.bin, "render", os.path.join(args.data, rel)] + opts + [
                "--renderer", "full", "--size", "160x120", "--threads", str(args.threads), "--quiet", "--stats", stats,
                "-o", os.path.join(tmp, "frame.png")]
            rss = run(cmd)
            with open(stats) as f:
                res = json.load(f)
            res["scene"] = scene
            res["terrain_depth"] = terrain or depth
            res["peak_rss_bytes"] = rss
            shown = ["octrace", "render", "../shared/data/" + rel] + [
                "LYON_GROUND.vrt" if o == dem else o for o in opts] + cmd[len(cmd) - 11:-4] + [
                "--stats", "STATS.json", "-o", "FRAME.png"]
            res["command"] = " ".join(shown)
            name = "%s_d%d_t%d.json" % (scene.replace("+", "_"), depth, terrain or depth)
            with open(os.path.join(outdir, name), "w") as f:
                json.dump(res, f, indent=1)
            rows.append(res)
            print("%s depth %d terrain %d: build %.0f ms, %d voxels, peak RSS %.0f MiB" %
                  (scene, depth, terrain or depth, res["build_ms"], res["boundary_voxels"], rss / 2**20))

    md = ["# Per-region depth: terrain shallower than the buildings", "",
          "Generated by `bench/city_mixed.py` (do not edit by hand); raw JSON per run, with its command,",
          "in [`city-mixed/`](city-mixed/). Each row is one `octrace render` process reading the scene,",
          "voxelizing it top-down (no dense grid) and drawing a 160x120 frame; `threads` = %s." %
          (args.threads or "all cores"),
          "`--terrain-depth T --depth D`: nodes only terrain crosses stop at level T as coarse leaves",
          "(one leaf each in the voxel count); buildings, and the terrain in nodes they share, go to D.", "",
          "| scene | buildings depth | terrain depth | load ms | build ms | boundary leaves | octree nodes | octree MiB | peak RSS MiB |",
          "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        md.append("| %s | %d | %d | %.0f | %.0f | %d | %d | %.1f | %.0f |" % (
            r["scene"], r["depth"], r["terrain_depth"], r["load_ms"], r["build_ms"], r["boundary_voxels"],
            r["octree_nodes"], r["octree_bytes"] / 2**20, r["peak_rss_bytes"] / 2**20))
    md += ["", "Delft is `delft.json` (160 LoD1 buildings; its terrain objects: relief, roads, water, land",
           "use, plant cover). Lyon+DEM is `buildings_lyon1.geojson` (extruded from `Z_MIN_SOL` by",
           "`HAUTEUR`) over the ground DEM the script interpolates from the footprints' own `Z_MIN_SOL`",
           "(no shared DEM covers Lyon). With uniform depth the DEM is read at up to 2^depth + 1 samples per",
           "edge, with a terrain depth at 2^T + 1.", ""]
    with open(os.path.join(ROOT, "docs", "benchmarks", "city-mixed.md"), "w") as f:
        f.write("\n".join(md))


if __name__ == "__main__":
    main()
