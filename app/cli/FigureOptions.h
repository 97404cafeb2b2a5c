#pragma once
// render --figure and slice --figure: the figure options on the command line. The figure itself
// is the pipeline library's (octrace/model/Figure.h).
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/model/Figure.h"

#include <string>

namespace octrace::cli {

using FigureArgs = model::FigureSettings;
using model::checkFigureFormat;
using model::figureHasColourBar;
using model::figureLayout;
using model::FigureSubject;
using model::figureSubject;
using model::GeoAxes;
using model::kDefaultDpi;
using model::latitudeText;
using model::longitudeText;
using model::writeFigure;

/// --figure, --title, --dpi, --print-size, --scale-bar; `shows` says what a figure shows
/// besides the image (default: render's colour bar, variable, region and labelled box).
void addFigureOptions(OptionParser& p, FigureArgs& f, const std::string& shows = "");

/// Refuses (UsageError) an output whose extension is not an image format (io::imageExtensions),
/// before any long work.
void checkImageOutput(const std::string& output);

/// Refuses --title, --print-size or --scale-bar without --figure, and a figure not written as a PNG.
void checkFigureOptions(const FigureArgs& f, const std::string& output);

}  // namespace octrace::cli
