#pragma once
// render --figure: the options of a publication figure and what it shows, from the surface,
// its colours and the camera.
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/io/Figure.h"
#include "octrace/render/Camera.h"

#include <optional>
#include <string>

namespace octrace::cli {

struct FigureArgs {
    bool enabled = false;     // --figure
    std::string title;        // --title
    int dpi = 0;              // --dpi; 0: kDefaultDpi for a figure, none recorded for a plain image
    std::optional<dvec2> printInches;  // --print-size, converted to inches
};

inline constexpr int kDefaultDpi = 150;

/// World <-> longitude, latitude (degrees) and depth (metres, positive down) on a geographic
/// grid, by the contract's mapping (ScalarField::Geographic).
struct GeoAxes {
    const ScalarField::Geographic& g;
    double lon(double x) const;
    double lat(double y) const;
    double depthM(double z) const;
    double x(double lonDeg) const;
    double y(double latDeg) const;
    double z(double depthM) const;
};

/// "150°E", "30°W", "0°", rounded to whole degrees.
std::string longitudeText(double lon);
/// "35°N", "10°S", "0°".
std::string latitudeText(double lat);

/// --figure, --title, --dpi, --print-size.
void addFigureOptions(OptionParser& p, FigureArgs& f);

/// Refuses (UsageError) an output whose extension is not an image format (io::imageExtensions),
/// before any long work.
void checkImageOutput(const std::string& output);
/// Refuses --title or --print-size without --figure, and a figure not written as a PNG.
void checkFigureOptions(const FigureArgs& f, const std::string& output);

/// "WxH" with a unit mm, cm or in (e.g. "180x120mm", "7x5in"), in inches. Throws UsageError.
dvec2 parsePrintSize(const std::string& option, const std::string& text);

/// The figure's layout: print size x dpi pixels, else `width` x `height` (--size) for the
/// whole figure. Throws UsageError when that leaves no room for the plot.
io::FigureLayout figureLayout(const FigureArgs& f, int width, int height, bool colourBar);

/// Title, subtitle (variable, iso value, colour variable, region), colour bar and the
/// labelled bounding box (longitude, latitude and depth on geographic grids, world x, y, z
/// otherwise) as seen by `camera` (whose image is the plot).
io::FigureSpec figureSpec(const FigureArgs& f, const Surface& s, const Camera& camera, const RenderSettings& rs);

}  // namespace octrace::cli
