#pragma once
// What the commands that build a surface (render, export) share: the options that choose the
// field, its isosurface and its colour, with the same names, help and checks, and the
// load-and-build step behind them.
#include "Options.h"
#include "SolidSpec.h"

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

struct SurfaceArgs {
    std::string input;
    io::FieldRequest request;
    std::optional<double> iso;
    std::string isoPreset;  ///< --iso NAME (CtPresets.h): resolved once the field is read
    /// --window: "" (not given: the file's window, if any, unless --colour or --colormap),
    /// "none", a preset name (CtPresets.h), or the centre and width given as numbers.
    std::string windowName;
    ValueWindow window;
    bool colourGiven = false;  ///< --colour / --color given
    bool colours = false;      ///< the command colours the surface (has the colour options)
    int depth = int(model::opt::depth.defaultValue), threads = int(model::opt::threads.defaultValue);
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
    io::CityRequest city;         // --lod-select, --crs, --dem, --texture (city inputs)
    int terrainDepth = 0;         // --terrain-depth (city inputs); 0: --depth
    bool cityGiven = false;       // one of them (or --terrain-depth) was given
    OctreeForm form = OctreeForm::Shell;  // --form
    bool insideBelow = false;             // --inside below
    bool formGiven = false;               // --form or --inside given
    bool keepVolume = false;  // set by the command: buildSurface keeps a volume octree as it is (build, csg)
    std::vector<SolidArgument> cuts;  // --cut, in order (SolidSpec.h: relief:FILE is read once the field is)
    bool clip = false;        // --clip: keep the inside of the cuts instead
    bool extendDown = false;  // --extend-down: water columns extended to the grid's bottom (extendColumnsDown)
    bool bake = false;        // --bake: bake lighting into the shell
    BakeOptions bakeOptions;  // --bake-light, --bake-ao, --bake-ao-distance, --bake-shadows
    bool bakeLightGiven = false;
    enum class Lighting { Auto, Baked, Dynamic } lighting = Lighting::Auto;  // --lighting (render)
    std::optional<float> ambient;  // --ambient (render): diffuse is 1 - ambient, dynamic and baked
    std::optional<bool> shadows;   // --shadows (render); unset: the scene's default (RenderSettings::shadows)
};

/// The window --window TEXT sets: a CT preset, "C,W", or "none" (an invalid window, which
/// stops the file's own). Throws UsageError as --window does.
ValueWindow displayWindow(const std::string& text);
/// "a, b, c".
std::string joinNames(const std::vector<std::string>& names);
/// sRGB display colour (as a user picks it) -> linear, alpha unchanged.
vec4 displayToLinear(vec4 c);

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
/// --colour, --color, --colormap, --window, --colour-range, --masked-colour, --floor-colour.
void addColourOptions(OptionParser& p, SurfaceArgs& a);
/// --window; its help: "grey " + `what` + the presets, and the default `byDefault`.
void addWindowOption(OptionParser& p, SurfaceArgs& a, const std::string& what, const std::string& byDefault);
/// --colormap, --colour-range, --masked-colour, with the help of the first two (after the list
/// of maps) and what the masked colour colours.
void addColourMapOptions(OptionParser& p, SurfaceArgs& a, const std::string& colormapHelp, const std::string& rangeHelp,
                         const std::string& maskedWhat);
/// Refuses (InputError) a CT preset (`option` NAME) for a field whose values are not Hounsfield units.
void requireHounsfield(const ScalarField& f, const std::string& input, const std::string& option);
/// --colour-by, --floor: what is drawn besides the isosurface.
void addLayerOptions(OptionParser& p, SurfaceArgs& a);
/// --region, --depth-range, --time, --vertical-scale.
void addGeographicOptions(OptionParser& p, io::FieldRequest& request);
/// The first option of `request` that chooses part of a field ("--var", "--region", ...), or null.
const char* fieldOptionGiven(const io::FieldRequest& request);
/// --lod-select, --crs, --dem, --texture, --height-attr, --base-attr, --terrain-depth (city inputs).
void addCityOptions(OptionParser& p, SurfaceArgs& a);
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
    /// The display window that colours the surface (invalid: --colour / --colormap), and
    /// whether its grey is inverted (MONOCHROME1); the octree then has voxel values.
    ValueWindow window;
    bool invertedGrey = false;
    std::string windowSource;  ///< where the window comes from, for messages and stats
    BakeReport bake;           ///< when lighting was baked here
    /// A sphere input's spheres (the field is their distance field): the voxels take their
    /// colours (sphereColoursAtVoxels). Shared, so that a rebuild from the same field keeps them.
    std::shared_ptr<const SphereSet> spheres;
};

/// Applies --quiet / --verbose to the log. A city input (CityJSON) is read into one projected
/// CRS and voxelized (CityVoxelizer.h) with its per-voxel colours; --var and --iso are refused.
/// An octree file (.oct) is read as it is (options that
/// choose the field or the depth are refused: UsageError).
/// Otherwise reads a.input, chooses the iso value when none was
/// given (the middle of the valid range, said on stderr) or resolves a preset (--iso skin:
/// InputError unless the field is in HU), chooses the display window (--window, else the
/// file's own unless a colour was given; presets need HU too) and builds the octree in a.form
/// (with voxel values when a window colours it; progress on stderr when it is a terminal),
/// within memoryBudget(a): a read or build that would need more is refused (LimitError). With
/// --cut the volume form is built (an octree file must hold one: InputError otherwise) and
/// each solid is subtracted from it (--clip: intersected with it; the result has no voxel
/// values). A volume octree becomes its shell (extractShell) unless a.keepVolume. With
/// --bake, or --lighting baked on an octree without baked light, the shell's lighting is baked
/// (lighting/Bake.h; UsageError for a kept volume). Then --colour-by's variable, read with the
/// same request (InputError for one on another grid; UsageError beside --window), is sampled
/// at the voxels, and --floor merges in the sea floor and land. Throws as loadField(),
/// buildOctree(), csg() and bakeLighting().
Surface buildSurface(const SurfaceArgs& a);

/// What an interactive caller (the studio) gives a build: progress (instead of the terminal's)
/// and cancellation (BuildOptions::cancelled: CancelledError).
struct BuildHooks {
    std::function<void(double)> progress;
    std::function<bool()> cancelled;
    bool endLine = false;  ///< progress prints on a terminal line: end it after the build
};
/// buildSurface's two steps for a field input (not an octree file or a city), for callers that
/// build again and again from one read: readSurfaceField reads a.input into s.field (s.loadMs);
/// buildFromField does the rest from s.field (iso value or preset, display window, octree in
/// a.form, cuts, shell, baked lighting, --colour-by, --floor) with `hooks`. Throw as buildSurface.
void readSurfaceField(const SurfaceArgs& a, Surface& s);
void buildFromField(const SurfaceArgs& a, Surface& s, const BuildHooks& hooks = {});

/// The colour options as RenderSettings (linear RGB): colour, colour map (by default, with
/// voxel values of a second variable, the one for that variable: defaultColormap in
/// Shading.h), its range, the masked and floor colours, and the surface's display window
/// (RenderSettings::window, invertedGrey).
void applyColour(const SurfaceArgs& a, const Surface& s, RenderSettings& settings);
/// The lighting options as RenderSettings: baked light unless --lighting dynamic, and with
/// --ambient its ambient and diffuse (1 - ambient) shares; --shadows as given.
void applyLighting(const SurfaceArgs& a, RenderSettings& settings);

}  // namespace octrace::cli
