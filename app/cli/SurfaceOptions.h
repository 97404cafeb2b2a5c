#pragma once
// What the commands that build a surface (render, export) share: the options that choose the
// field, its isosurface and its colour, with the same names, help and checks, and the
// load-and-build step behind them.
#include "Options.h"

#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/RenderSettings.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace octrace::cli {

struct SurfaceArgs {
    std::string input;
    io::FieldRequest request;
    std::optional<double> iso;
    int depth = 8, threads = 0;
    bool depthGiven = false;  // --depth given (an octree file input fixes the depth)
    vec3 colour{0.85f, 0.62f, 0.35f};  // sRGB display values, as the user gives them
    std::string colormap;              // empty: uniform colour, or the colour-by variable's default
    std::string colourBy;              // --colour-by: second variable sampled at the voxels
    float colourMin = std::numeric_limits<float>::quiet_NaN(), colourMax = std::numeric_limits<float>::quiet_NaN();
    vec3 maskedColour{0.6f, 0.6f, 0.6f};      // sRGB
    vec3 floorColour{0.55f, 0.5f, 0.45f};     // sRGB
    bool floor = false;                // --floor: sea floor / land from the validity mask
    bool help = false, quiet = false, verbose = false;
    std::uint64_t maxMemory = 0;  // --max-memory; 0: defaultMemoryBudget()
};

/// "a, b, c".
std::string joinNames(const std::vector<std::string>& names);
/// sRGB display colour (as a user picks it) -> linear, alpha unchanged.
vec4 displayToLinear(vec4 c);

// Each adds its options to `p`, writing into `a`; the help lines state the defaults of SurfaceArgs.
/// --var, --iso, --depth.
void addSurfaceOptions(OptionParser& p, SurfaceArgs& a);
/// --threads; `result` names what does not depend on it ("the image").
void addThreadsOption(OptionParser& p, SurfaceArgs& a, const std::string& result);
/// --colour, --color, --colormap, --colour-range, --masked-colour, --floor-colour.
void addColourOptions(OptionParser& p, SurfaceArgs& a);
/// --colour-by, --floor: what is drawn besides the isosurface.
void addLayerOptions(OptionParser& p, SurfaceArgs& a);
/// --region, --vertical-scale.
void addGeographicOptions(OptionParser& p, SurfaceArgs& a);
/// --series (DICOM).
void addSeriesOption(OptionParser& p, io::FieldRequest& request);
/// --max-memory, --quiet, --verbose, --help.
void addMessageOptions(OptionParser& p, SurfaceArgs& a);
/// The memory budget in bytes: --max-memory, or the default share of physical memory.
std::uint64_t memoryBudget(const SurfaceArgs& a);

/// The start of every surface command: parses `args` with `p` (which writes into `a`). With
/// --help, prints the help on stdout and returns false. Otherwise checks that there is exactly
/// one INPUT (stored in a.input) and that `output` (filled by the parse) is not empty, else
/// throws UsageError "<command> needs " + `missingOutput`; returns true.
bool parseCommandLine(const OptionParser& p, const std::vector<std::string>& args, SurfaceArgs& a,
                      const std::string& output, const std::string& missingOutput);

/// A field and the shell octree of its isosurface (with --colour-by its voxels' values, with
/// --floor the sea floor / land merged in as VoxelMaterial::Floor).
struct Surface {
    ScalarField field;
    double iso = 0.0;
    Octree tree;
    BuildReport report;
    double loadMs = 0.0;
};

/// Applies --quiet / --verbose to the log. An octree file (.oct) is read as it is (options that
/// choose the field or the depth are refused: UsageError; a volume octree gives its shell).
/// Otherwise reads a.input, chooses the iso value when none was
/// given (the middle of the valid range, said on stderr) and builds the shell octree (progress
/// on stderr when it is a terminal), within memoryBudget(a): a read or build that would need
/// more is refused (LimitError). --colour-by reads the second variable with the same request
/// and refuses (InputError) one on another grid. Throws as loadField() and buildShellOctree().
Surface buildSurface(const SurfaceArgs& a);

/// The colour options as RenderSettings (linear RGB); the colour map by default, with values
/// on `tree`, is the one for their variable (defaultColormap in Shading.h).
void applyColour(const SurfaceArgs& a, const Octree& tree, RenderSettings& settings);

}  // namespace octrace::cli
