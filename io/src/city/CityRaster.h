#pragma once
// Rasters for city scenes through GDAL: a DEM as terrain, a colour raster as the terrain's
// texture (internal to octrace_io).
#include "octrace/build/CityModel.h"

#include <string>

namespace octrace::io::detail {

/// Whether the extension is one of the raster formats read as a DEM (.tif, .tiff, .dem, .asc,
/// .img, .hgt, .bil, .vrt).
bool isRasterExtension(const std::string& path);

/// Appends the DEM in `path` (band 1, elevations) to `model` as one terrain object of
/// triangles between pixel centres, in the raster's CRS (model.crs is set when empty, and must
/// be the same CRS otherwise: InputError). At most `maxSamples` pixels per edge are read (GDAL
/// averages the rest away). A quad with a nodata corner is left out.
/// @throws InputError (missing), FormatNotSupported (GDAL cannot open it), FileError (no
///         band, no georeferencing, nothing but nodata).
void addDemTerrain(CityModel& model, const std::string& path, int maxSamples);

/// Ground heights from a DEM, for footprints whose base is not given: bilinear between pixel
/// centres, in the DEM's own CRS.
class DemSampler {
public:
    /// Reads band 1 of `path` whole (at most `maxSamples` per edge). Throws as addDemTerrain.
    DemSampler(const std::string& path, int maxSamples);
    /// The DEM's CRS (WKT).
    const std::string& crs() const { return crs_; }
    /// Height at (x, y) in the DEM's CRS; NaN outside or next to nodata.
    double at(double x, double y) const;

private:
    std::string crs_;
    int width_ = 0, height_ = 0;
    double gt_[6] = {};   // pixel (i, j) centre -> x, y: see at()
    double inv_[6] = {};  // x, y -> continuous pixel
    std::vector<double> z_;  // NaN at nodata
};

/// Reads the colour raster in `path` and resamples it (nearest pixel) onto a north-up grid over
/// `bounds` (x, y) in the CRS `crs`, at most `maxPixels` per edge: every grid pixel's centre is
/// transformed into the raster's CRS with OSR. 1 band: grey; 3: RGB; 4: RGBA; a colour table is
/// expanded. Pixels outside the raster or at its nodata get alpha 0.
/// @throws as addDemTerrain; InputError when the raster has no CRS.
CityTexture readTexture(const std::string& path, const std::string& crs, const Box3& bounds, int maxPixels);

}  // namespace octrace::io::detail
