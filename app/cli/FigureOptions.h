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
    bool scaleBar = false;    // --scale-bar
};

inline constexpr int kDefaultDpi = int(model::opt::dpi.defaultValue);

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

/// --figure, --title, --dpi, --print-size, --scale-bar; `shows` says what a figure shows
/// besides the image (default: render's colour bar, variable, region and labelled box).
void addFigureOptions(OptionParser& p, FigureArgs& f, const std::string& shows = "");

/// Refuses (UsageError) an output whose extension is not an image format (io::imageExtensions),
/// before any long work.
void checkImageOutput(const std::string& output);
/// Refuses --title, --print-size or --scale-bar without --figure, and a figure not written as a PNG.
void checkFigureOptions(const FigureArgs& f, const std::string& output);
/// A figure is written as PNG or TIFF (.png, .tif, .tiff, any case); EXR holds linear data, no
/// annotations. UsageError naming `output` otherwise.
void checkFigureFormat(const std::string& output);

/// "WxH" with a unit mm, cm or in (e.g. "180x120mm", "7x5in"), in inches. Throws UsageError.
dvec2 parsePrintSize(const std::string& option, const std::string& text);

/// The figure's layout: print size x dpi pixels, else `width` x `height` (--size) for the
/// whole figure. Throws UsageError when that leaves no room for the plot.
io::FigureLayout figureLayout(const FigureArgs& f, int width, int height, bool colourBar);

/// Whether the figure of a surface coloured by `a` has a colour bar (a colour map or --colour-by).
bool figureHasColourBar(const model::SurfaceSpec& a);

/// What a figure says about the data besides its octree: the field's name, its geographic
/// mapping, the bounds of the grid read (empty for an octree file or a city: the surface's
/// are boxed), the iso value and the world's length unit for the scale bar. A small copy, so
/// that a caller that builds again from the field (the studio) need not keep it still.
struct FigureSubject {
    std::string name;
    ScalarField::Geographic geographic;
    std::optional<Box3> gridBounds;
    double iso = 0.0;
    std::string lengthUnit;  ///< "km" on geographic grids, "m" for cities, else "" (world units)
};
FigureSubject figureSubject(const Surface& s, const std::string& input);

/// Title, subtitle (variable, iso value, colour variable, region), colour bar, the labelled
/// bounding box (longitude, latitude and depth on geographic grids, world x, y, z otherwise)
/// as seen by `camera` (whose image is the plot) and, with --scale-bar, a scale bar measured
/// at the look-at point's distance (exact for an orthographic camera).
io::FigureSpec figureSpec(const FigureArgs& f, const FigureSubject& subject, const Octree& tree, const Camera& camera,
                          const RenderSettings& rs);

/// The figure around `plot` (rendered with `camera` at the layout's plot size), written as a
/// PNG at the layout's dpi to `path` (atomically). What render --figure and the studio's
/// export share. Throws as io::composeFigure and io::writeImage.
void writeFigure(const Frame& plot, const FigureArgs& f, const io::FigureLayout& layout, const FigureSubject& subject,
                 const Octree& tree, const Camera& camera, const RenderSettings& rs, const std::string& path);

}  // namespace octrace::cli
