#pragma once
// What the commands that build a surface (render, export) share: the options that choose the
// field, its isosurface and its colour, with the same names, help and checks, and the
// load-and-build step behind them.
#include "Options.h"
#include "octrace/model/Input.h"
#include "octrace/model/Surface.h"

#include "octrace/build/CtPresets.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/ScalarField.h"
#include "octrace/io/CityReader.h"
#include "octrace/csg/Solid.h"
#include "octrace/lighting/Bake.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/scene/Spheres.h"

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace octrace::cli {

/// What only the command line has: --help, --quiet, --verbose.
struct MessageArgs {
    bool help = false, quiet = false, verbose = false;
};

/// The surface commands' options: the pipeline's spec (model/Surface.h) and what only the
/// command line has.
struct SurfaceArgs : model::SurfaceSpec, MessageArgs {};

// The pipeline's names, as the commands use them.
using model::applyColour;
using model::applyLighting;
using model::BuildHooks;
using model::buildFromField;
using model::displayToLinear;
using model::displayWindow;
using model::fieldOptionGiven;
using model::memoryBudget;
using model::readSurfaceField;
using model::requireHounsfield;
using model::Surface;
using model::checkSolidArgument;
using model::describe;
using model::isOctreeInput;
using model::isSolidArgument;
using model::isSphereInput;
using model::loadField;
using model::loadOctree;
using model::loadSpheres;
using model::resolveSolid;
using model::SolidArgument;

/// "a, b, c".
std::string joinNames(const std::vector<std::string>& names);

// Each adds its options to `p`, writing into `a`; the help lines state the defaults of SurfaceArgs.
/// --var.
void addVariableOption(OptionParser& p, io::FieldRequest& request);
/// --var, --iso, --depth.
void addSurfaceOptions(OptionParser& p, SurfaceArgs& a);
/// --inside above|below; `applies` says to what ("volume form").
void addInsideOption(OptionParser& p, SurfaceArgs& a, const std::string& applies);
/// --form shell|volume, --inside above|below, --cut SOLID, --clip, --extend-down.
void addFormOptions(OptionParser& p, SurfaceArgs& a);
/// --extend-down (geographic fields).
void addExtendDownOption(OptionParser& p, SurfaceArgs& a);
/// --bake, --bake-light, --bake-ao, --bake-ao-distance, --bake-shadows.
void addBakeOptions(OptionParser& p, SurfaceArgs& a);
/// --lighting baked|dynamic, --ambient A, --shadows on|off.
void addLightingOption(OptionParser& p, SurfaceArgs& a);
/// --threads; `result` names what does not depend on it ("the image").
void addThreadsOption(OptionParser& p, SurfaceArgs& a, const std::string& result);
void addThreadsOption(OptionParser& p, const model::SettingTargets& into, const std::string& result);
/// --colour, --color, --colormap, --window, --colour-range, --masked-colour, --floor-colour.
void addColourOptions(OptionParser& p, SurfaceArgs& a);
/// --window (the options table's), its help followed by `what` (what it greys here), the presets,
/// and what is drawn without it (`byDefault`).
void addWindowOption(OptionParser& p, const model::SettingTargets& into, const std::string& what, const std::string& byDefault);
/// --colormap, --colour-range, --masked-colour (the options table's), with what the first two mean
/// for the command (after the list of maps) and what the masked colour colours.
void addColourMapOptions(OptionParser& p, const model::SettingTargets& into, const std::string& colormapHelp,
                         const std::string& rangeHelp, const std::string& maskedWhat);
/// --colour-by, --floor: what is drawn besides the isosurface.
void addLayerOptions(OptionParser& p, SurfaceArgs& a);
/// --region, --depth-range, --time (unless `timeStep` is false: animate's --time is its `times`), --vertical-scale.
void addGeographicOptions(OptionParser& p, io::FieldRequest& request, bool timeStep = true);
/// --lod-select, --crs, --dem, --texture, --height-attr, --base-attr, --terrain-depth (city inputs).
void addCityOptions(OptionParser& p, SurfaceArgs& a);
/// --series and --volume (DICOM; --volume also 4-D NIfTI).
void addSeriesOption(OptionParser& p, io::FieldRequest& request);
/// --max-memory (landing in `budget`), --quiet, --verbose, --help.
void addMessageOptions(OptionParser& p, SurfaceArgs& a);
void addMessageOptions(OptionParser& p, MessageArgs& a, const model::SettingTargets& budget);

/// The start of every surface command: parses `args` with `p` (which writes into `a`). With
/// --help, prints the help on stdout and returns false. Otherwise checks that there is exactly
/// one INPUT (stored in a.input) and that `output` (filled by the parse) is not empty, else
/// throws UsageError "<command> needs " + `missingOutput`; returns true.
bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, SurfaceArgs& a,
                      const std::string& output, const std::string& missingOutput);
/// The same for a command whose spec is not a surface's: the INPUT lands in `input`.
bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, MessageArgs& a, std::string& input,
                      const std::string& output, const std::string& missingOutput);


/// Applies --quiet / --verbose to the log and builds with progress on stderr when it is a
/// terminal (reading a DICOM or NIfTI input, then building the octree): model::buildSurface
/// (the pipeline's first steps), which see.
Surface buildSurface(const SurfaceArgs& a);
/// The progress of a read on stderr ("octrace: reading N%"), as buildSurface shows it: only
/// when stderr is a terminal and not `quiet` (else empty), for io::FieldRequest::hooks.
std::function<void(double)> readProgressPrinter(bool quiet);



}  // namespace octrace::cli
