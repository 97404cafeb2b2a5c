#!/usr/bin/env python3
"""Writes the small coastline files of the coastline tests (tests/io/CoastlineTest.cpp,
tests/cli/CoastlineCliTest.cpp) and the coastline files of the invalid corpus. Plain JSON, no
dependencies: run it from anywhere, it writes beside itself and into ../invalid/.

- island.geojson: a polygon ring (a square 'island' 10..12°E, 40..41°N) and a line that crosses
  the dateline (179.5°E to 179.5°W at 5°S, as a file cut at ±180 would not have it).
- island_3857.geojson: the same square in Web Mercator (EPSG:3857, named by the GeoJSON 2008
  `crs` member GDAL reads), to test the reprojection to longitude/latitude.
- ../invalid/invalid_coastline_not_vector.geojson: text that is no vector data.
- ../invalid/invalid_coastline_points_only.geojson: valid GeoJSON holding only points.
"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
INVALID = os.path.join(HERE, "..", "invalid")

SQUARE = [[10.0, 40.0], [12.0, 40.0], [12.0, 41.0], [10.0, 41.0], [10.0, 40.0]]
DATELINE = [[179.5, -5.0], [-179.5, -5.0]]


def feature(geometry, name):
    return {"type": "Feature", "properties": {"name": name}, "geometry": geometry}


def write(path, obj):
    with open(path, "w") as f:
        json.dump(obj, f, indent=1)
        f.write("\n")


def mercator(lon, lat):
    r = 6378137.0
    return [r * math.radians(lon), r * math.log(math.tan(math.pi / 4 + math.radians(lat) / 2))]


write(os.path.join(HERE, "island.geojson"), {
    "type": "FeatureCollection",
    "features": [feature({"type": "Polygon", "coordinates": [SQUARE]}, "square island"),
                 feature({"type": "LineString", "coordinates": DATELINE}, "dateline crossing")]})

write(os.path.join(HERE, "island_3857.geojson"), {
    "type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::3857"}},
    "features": [feature({"type": "Polygon", "coordinates": [[mercator(*p) for p in SQUARE]]}, "square island")]})

with open(os.path.join(INVALID, "invalid_coastline_not_vector.geojson"), "w") as f:
    f.write("this is not a vector file, only text with a .geojson extension\n")

write(os.path.join(INVALID, "invalid_coastline_points_only.geojson"), {
    "type": "FeatureCollection",
    "features": [feature({"type": "Point", "coordinates": [10.0, 40.0]}, "a lighthouse")]})
