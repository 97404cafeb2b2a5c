// octrace slice: a planar slice through a field's samples (no octree), greyed by a display
// window (CT, MR) or coloured by a colour map, as a radiology workstation or a map shows it.
// The slice itself is the pipeline library's (octrace/model/Slice.h); this parses, reads and writes.
#include "Commands.h"
#include "FigureOptions.h"
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/model/Input.h"
#include "octrace/model/Slice.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/util/Log.h"
#include "octrace/util/Timer.h"

#include <string>
#include <string_view>
#include <vector>

namespace octrace::cli {
namespace {

/// The slice's spec (model/Slice.h) and what only the command line has.
struct SliceArgs : model::SliceSpec, MessageArgs {
    std::string output, statsPath;
};

OptionParser makeParser(SliceArgs& a) {
    const model::SettingTargets into{.slice = &a};
    OptionParser p("slice", "octrace slice INPUT -o OUT.(png|exr|tif) [options]");
    p.add({"o", "FILE", "output image; format from the extension: " + joinNames(io::imageExtensions()) + " (required)",
           [&](const std::string& v) { a.output = v; }});
    addVariableOption(p, a.request);
    for (const model::Option* o : {&model::opt::plane, &model::opt::at, &model::opt::index}) p.add(settingOption(*o, into));
    p.add({"size", "WxH", "image size in pixels, the slice fitted and centred, its aspect kept (default: one pixel per sample of "
           "the finer in-plane spacing, so anisotropic voxels keep their shape; with --figure the whole figure, 1200x1000)",
           [into](const std::string& v) { model::applySetting(model::opt::size, v, into); }});
    addWindowOption(p, into, "here the slice",
                    "the window stored in a DICOM file; else for a patient volume its whole value range in grey; else the colour map");
    addColourMapOptions(p, into,
                        "here the slice's, when no window greys it; by default the variable's map from its standard_name or name, "
                        "thermal/haline/speed/viridis",
                        "here the slice's values, by default their range",
                        "masked samples (land, missing values, outside a resampled gantry-tilted stack)");
    p.add({"background", "R,G,B[,A]", "colour outside the grid: sRGB components in [0,1], #RRGGBB[AA] or a CSS colour name (default 0,0,0,1; with --figure 0,0,0,0: the paper)",
           [into](const std::string& v) { model::applySetting(model::opt::background, v, into); }});
    addGeographicOptions(p, a.request);
    addSeriesOption(p, a.request);
    p.add({"stats", "FILE.json", "write the slice's geometry and colouring as JSON (keys: docs/user/cli.md)",
           [&](const std::string& v) { a.statsPath = v; }});
    addThreadsOption(p, into, "the image");
    addFigureOptions(p, a.figure, "the grey or colour bar with units, the variable, the plane and window, and the A/P, R/L, "
                     "S/I letters with a scale bar (patient volumes) or labelled longitude/latitude/depth ticks");
    addMessageOptions(p, a, into);
    return p;
}

}  // namespace

int runSlice(const std::vector<std::string>& args) {
    SliceArgs a;
    if (!parseCommandLine(makeParser(a), args, a, a.input, a.output, "an output image: -o OUT.png, -o OUT.exr or -o OUT.tif")) return 0;
    checkImageOutput(a.output);
    checkFigureOptions(a.figure, a.output);
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    model::checkSliceSpec(a);
    io::FieldRequest request = a.request;
    request.memoryBudget = model::memoryBudget(a);
    request.acceptPlanar = true;  // a 2-D field is drawn as a map
    request.hooks.progress = readProgressPrinter(a.quiet);

    Timer loadTimer;
    const ScalarField field = loadField(a.input, request, 8);
    const double loadMs = loadTimer.ms();
    const model::SliceResult r = model::renderSlice(field, a);
    io::ImageWriteOptions options;
    options.dpi = r.dpi;
    io::writeImage(r.image, a.output, options);
    log::info(model::sliceSummary(field, r, a.output));
    if (!a.statsPath.empty())
        io::writeFileAtomically(a.statsPath, std::string_view(model::sliceStats(field, r, a.input, loadMs).json(model::sayForCli)));
    return 0;
}

}  // namespace octrace::cli
