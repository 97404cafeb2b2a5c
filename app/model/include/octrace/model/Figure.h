#pragma once
/// @file Figure.h
/// A publication figure: the rendered image (the plot) with a title, a colour bar, the labelled
/// bounding box and a scale bar, from the surface, its colours and the camera. What `octrace
/// render --figure`, `octrace slice --figure` and the studio's export share.
#include "octrace/model/OptionTable.h"
#include "octrace/model/Render.h"
#include "octrace/model/Surface.h"

#include "octrace/io/Coastline.h"
#include "octrace/io/Figure.h"
#include "octrace/render/Camera.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderSettings.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace octrace::model {

/// The figure settings (options table: `figure`, `title`, `dpi`, `print_size`, `scale_bar`).
struct FigureSettings {
    bool enabled = false;     ///< `figure`
    std::string title;        ///< `title`
    std::string caption;      ///< `caption`: first in the subtitle (an animation frame's date)
    int dpi = 0;              ///< `dpi`; 0: kDefaultDpi for a figure, none recorded for a plain image
    std::optional<dvec2> printInches;  ///< `print_size`, in inches
    bool scaleBar = false;    ///< `scale_bar`
    /// `coastline`: "" (auto: GSHHG at the region's resolution if installed), "none", a GSHHG
    /// resolution (crude, low, intermediate, high) or a vector file's path.
    std::string coastline;
};

inline constexpr int kDefaultDpi = int(opt::dpi.defaultValue);

/// World <-> longitude, latitude (degrees) and depth (metres, positive down) on a geographic
/// grid, by the contract's mapping (ScalarField::Geographic). lon, lat, x and y alone hold on
/// the lon/lat mapping only; world and lonLat on the polar one too.
struct GeoAxes {
    const ScalarField::Geographic& g;
    dvec2 world(double lonDeg, double latDeg) const;
    dvec2 lonLat(double x, double y) const;
    double lon(double x) const;
    double lat(double y) const;
    double depthM(double z) const;
    double x(double lonDeg) const;
    double y(double latDeg) const;
    double z(double depthM) const;
};

/// `coastline`'s text as FigureSettings keeps it: "" for auto, "none", "crude", "low",
/// "intermediate", "high", else a vector file's path. @throws UsageError when empty.
std::string parseCoastline(const std::string& text);

/// The longitude/latitude box of a world box on a geographic grid (longitudes unwrapped).
io::LonLatBox lonLatBox(const ScalarField::Geographic& g, const Box3& box);

/// The coastlines `coastline` (FigureSettings::coastline) asks for over `region`: none for
/// "none"; GSHHG at the resolution given or, for auto, at io::gshhgResolutionFor(region), and
/// for auto only a warning (once) and none when GSHHG is not installed; else the vector file.
/// The last result is kept, so an animation's frames read the file once. Thread-safe.
/// @throws as io::readGshhg and io::readVectorCoastlines.
std::shared_ptr<const io::Coastlines> figureCoastlines(const std::string& coastline, const io::LonLatBox& region);

/// Warns (once a process) that `coastline`, given (not auto, not none), is not drawn, and `why`.
void warnCoastlineUnused(const std::string& coastline, const std::string& why);

/// Appends to `out` the parts of the polyline `points` inside the rectangle [lo, hi].
void clipPolyline(const std::vector<dvec2>& points, dvec2 lo, dvec2 hi, std::vector<std::vector<dvec2>>& out);

/// `v` at `precision` significant digits, -0 as 0: how figures and summaries print a number.
std::string numberText(double v, int precision = 6);

/// "150°E", "30°W", "0°", rounded to whole degrees.
std::string longitudeText(double lon);
/// "35°N", "10°S", "0°".
std::string latitudeText(double lat);


/// The extension of `path`, lower case, with its dot ("" when none).
std::string lowerExtension(const std::string& path);
/// A figure is written as PNG or TIFF (.png, .tif, .tiff, any case); EXR holds linear data, no
/// annotations. UsageError naming `output` otherwise.
void checkFigureFormat(const std::string& output);


/// The figure's layout: print size x dpi pixels, else `width` x `height` (`size`) for the
/// whole figure. Throws UsageError when that leaves no room for the plot.
io::FigureLayout figureLayout(const FigureSettings& f, int width, int height, bool colourBar);

/// The layout, from `first` (figureLayout: the same size, dpi and colour bar), whose margins
/// hold the figure's text as io::figureRoom measures it: `specFor(layout)` makes the figure's
/// spec for a plot of that layout (its camera framed for the plot's size). The room found for
/// one layout makes the next; the margins only grow, and a few rounds settle them.
/// @throws UsageError as io::layoutFigure when the text leaves no room for the plot.
io::FigureLayout fitFigureLayout(const io::FigureLayout& first, const std::function<io::FigureSpec(const io::FigureLayout&)>& specFor);

/// Whether the figure of a surface coloured by `a` has a colour bar (a colour map or `colour_by`).
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
    bool patientLps = false;  ///< world is patient LPS in mm: ticks in mm and the patient's letters
    std::string time;         ///< the field's ScalarField::timeLabel ("" without time)
};
FigureSubject figureSubject(const Surface& s, const std::string& input);

/// fitFigureLayout for a 3-D figure of `tree` (figureSpec without coastlines, which do not
/// change the text), its camera frameCamera(`view` at the plot's size, `bounds`, `sceneView`).
io::FigureLayout fitFigureLayout(const io::FigureLayout& first, const FigureSettings& f, const FigureSubject& subject, const Octree& tree,
                                 const RenderSettings& rs, const RenderSpec& view, const Box3& bounds,
                                 SceneView sceneView = SceneView::Oblique);


/// The heights a grid spans, bottom and top, in the units a colour bar of height uses and
/// `colour_range` takes for a surface coloured by height: metres above the sea surface on a
/// geographic field (negative below it), else world z.
std::pair<double, double> gridHeightRange(const ScalarField& grid);

/// Title, subtitle (caption or time step, variable, iso value, colour variable, region), colour
/// bar (a bar over heights below the sea surface reads depth, positive down), the labelled
/// bounding box (longitude, latitude and depth on geographic grids, mm and the patient's
/// letters L/R, A/P, S/I on patient volumes, world x, y, z otherwise)
/// as seen by `camera` (whose image is the plot) and, with `scale_bar`, a scale bar measured
/// at the look-at point's distance (exact for an orthographic camera). On a geographic field,
/// the coastlines (`coastline`) on the sea surface (or the top of the grid read when it lies
/// deeper) over the grid's region, hidden where `plot`'s depth shows the surface in front.
io::FigureSpec figureSpec(const Frame& plot, const FigureSettings& f, const FigureSubject& subject, const Octree& tree, const Camera& camera,
                          const RenderSettings& rs);

/// The figure around `plot` (rendered with `camera` at the layout's plot size), written as a
/// PNG at the layout's dpi to `path` (atomically). What render --figure and the studio's
/// export share. Throws as io::composeFigure and io::writeImage.
void writeFigure(const Frame& plot, const FigureSettings& f, const io::FigureLayout& layout, const FigureSubject& subject,
                 const Octree& tree, const Camera& camera, const RenderSettings& rs, const std::string& path);

}  // namespace octrace::model
