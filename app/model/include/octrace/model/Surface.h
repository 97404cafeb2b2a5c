#pragma once
/// @file Surface.h
/// The pipeline's first steps, for every front end: a typed spec of what to read and how to
/// build it (SurfaceSpec, filled by the CLI from argv, by the studio from its state, later by
/// Python from keyword arguments, with the limits of the options table), and the steps that
/// turn it into a field and a shell octree (read -> build -> cut -> bake -> colour), with
/// progress and cancellation. No argv, no Qt; messages name settings by their keys
/// (util/Parameter.h), which each front end says in its own words.
#include "octrace/model/OptionTable.h"
#include "octrace/model/SolidSpec.h"

#include "octrace/build/AutoDepth.h"
#include "octrace/build/CtPresets.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/ScalarField.h"
#include "octrace/csg/Solid.h"
#include "octrace/io/CityReader.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/lighting/Bake.h"
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

namespace octrace::model {

/// What to read and how to build its surface. Defaults are the options table's.
struct SurfaceSpec {
    std::string input;
    io::FieldRequest request;
    std::optional<double> iso;
    std::string isoUnit;    ///< the unit `iso` was given in ("" the field's own): converted once the field is read
    std::string isoPreset;  ///< --iso NAME (CtPresets.h): resolved once the field is read
    /// --window: "" (not given: the file's window, if any, unless --colour or --colormap),
    /// "none", a preset name (CtPresets.h), or the centre and width given as numbers.
    std::string windowName;
    ValueWindow window;
    bool colourGiven = false;  ///< --colour / --color given
    bool colours = false;      ///< the command colours the surface (has the colour options)
    /// `depth`; unset: auto (chooseDepth), the table's default.
    std::optional<int> depth;
    int threads = int(opt::threads.defaultValue);
    bool depthGiven = false;  // --depth given (an octree file input fixes the depth)
    /// The view that `depth` auto aims a geometry input's voxels at (about one pixel of it):
    /// render's image size and field of view; the table's for the other commands.
    int viewWidth = int(opt::width.defaultValue), viewHeight = int(opt::height.defaultValue);
    double viewFov = opt::fov.defaultValue;
    vec3 colour{0.85f, 0.62f, 0.35f};  // sRGB display values, as the user gives them
    std::string colormap;              // empty: uniform colour, or the colour-by variable's default
    std::string colourBy;              // --colour-by: second variable sampled at the voxels
    float colourMin = std::numeric_limits<float>::quiet_NaN(), colourMax = std::numeric_limits<float>::quiet_NaN();
    Quantity colourMinGiven, colourMaxGiven;  // `colour_range`'s ends as given, with their units ("" those coloured)
    vec3 maskedColour{0.6f, 0.6f, 0.6f};      // sRGB
    vec3 floorColour{0.55f, 0.5f, 0.45f};     // sRGB
    bool floor = false;                // --floor: sea floor / land from the validity mask
    std::uint64_t maxMemory = 0;  // --max-memory; 0: defaultMemoryBudget()
    io::CityRequest city;         // --lod-select, --crs, --dem, --texture (city inputs)
    int terrainDepth = 0;         // --terrain-depth (city inputs); 0: --depth
    bool cityGiven = false;       // one of them (or --terrain-depth) was given
    OctreeForm form = OctreeForm::Shell;  // --form
    bool insideBelow = false;             // --inside below
    bool formGiven = false;               // --form or --inside given
    /// --surface; unset: surfaceModeFor's default (smooth, voxel with the papers' renderers). A
    /// build stores corner values (BuildOptions::corners) unless it is voxel.
    std::optional<SurfaceMode> surface;
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

/// The window `text` names: a CT preset, "C,W", or "none" (an invalid window, which stops the
/// file's own). Throws UsageError naming `window`.
ValueWindow displayWindow(const std::string& text);
/// sRGB display colour (as a user picks it) -> linear, alpha unchanged.
vec4 displayToLinear(vec4 c);
/// The iso value a surface of `field` (read from `input`) gets when none is given, and why (a
/// clause for the log: "Otsu's threshold of ..."): for an image volume (any field not on a
/// longitude/latitude grid and not analytic: CT, MR, NRRD, ...), Otsu's threshold of its valid
/// samples (256 bins over their range: the value that best splits them into two classes, the
/// tissue from the background, as a radiologist's first threshold does); for a field on a
/// longitude/latitude grid, the middle of its valid samples' range between their 0.5th and
/// 99.5th percentiles (a few extreme samples would put the plain middle where no cell crosses
/// it); for an analytic field, the middle of the valid range. Throws as ScalarField::validRange.
std::pair<double, std::string> defaultIso(const ScalarField& field, const std::string& input);
/// Refuses (InputError) a CT preset (`what`, e.g. "`iso` bone") for a field whose values are not
/// Hounsfield units.
void requireHounsfield(const ScalarField& f, const std::string& input, const std::string& what);
/// `colour_range` as given (its ends `min`, `max`) in `units`, the units of `subject`
/// ("FILE: variable 'TEMP'"), as quantityIn converts each end.
/// @throws InputError as quantityIn, and when the converted MIN is not below MAX.
std::pair<float, float> colourRangeIn(const Quantity& min, const Quantity& max, const std::string& units,
                                      const std::string& subject);
/// The surface mode a frame of `renderer` (a name or an alias) draws: `given`, else voxel for
/// the papers' renderers (RendererTraits::paper) and smooth for the others. Smooth draws voxel
/// where the octree has no corner values (SmoothSurface.h).
SurfaceMode surfaceModeFor(const std::optional<SurfaceMode>& given, const std::string& renderer);
/// The memory budget in bytes: spec.maxMemory, or the default share of physical memory.
std::uint64_t memoryBudget(const SurfaceSpec& a);
/// The first setting of `request` that chooses part of a field, as a message names it
/// ("`var`", "`region`", ...), or null.
const char* fieldOptionGiven(const io::FieldRequest& request);

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
    /// The octree's depth and why: `depth` as given, or what auto chose (chooseDepth).
    DepthChoice depth;
    /// A sphere input's spheres (the field is their distance field): the voxels take their
    /// colours (sphereColoursAtVoxels). Shared, so that a rebuild from the same field keeps them.
    std::shared_ptr<const SphereSet> spheres;
};

/// What an interactive caller gives a build: progress (0..1, from the builder's threads) and
/// cancellation (BuildOptions::cancelled: CancelledError). Reading the input is a stage of its
/// own before the build: `readProgress` (0..1, from the reading thread; DICOM per file, NIfTI
/// per slice, io::ReadHooks) and the same `cancelled`, asked between files or slices.
struct BuildHooks {
    std::function<void(double)> progress;
    std::function<bool()> cancelled;
    std::function<void(double)> readProgress;

    /// The read's share of these hooks, for io::FieldRequest::hooks.
    io::ReadHooks forRead() const { return {readProgress, cancelled}; }
};

/// A city input (CityJSON, CityGML, footprints, DEM) is read into one projected CRS and
/// voxelized (CityVoxelizer.h) with its per-voxel colours; `iso` and `var` are refused.
/// An octree file (.oct) is read as it is (settings that choose the field or the depth are
/// refused: UsageError). Otherwise reads a.input, chooses the iso value when none was given
/// (the middle of the valid range, said in the log) or resolves a preset (`iso` skin:
/// InputError unless the field is in HU), chooses the display window (`window`, else the file's
/// own unless a colour was given; presets need HU too) and builds the octree in a.form (with
/// voxel values when a window colours it), within memoryBudget(a): a read or build that would
/// need more is refused (LimitError). With cuts the volume form is built (an octree file must
/// hold one: InputError otherwise) and each solid is subtracted from it (clip: intersected
/// with it). A volume octree becomes its shell (extractShell) unless a.keepVolume. With bake,
/// or baked lighting on an octree without baked light, the shell's lighting is baked
/// (lighting/Bake.h; UsageError for a kept volume). Then `colour_by`'s variable, read with the
/// same request (InputError for one on another grid; UsageError beside a window), is sampled
/// at the voxels, and `floor` merges in the sea floor and land. Throws as loadField(),
/// buildOctree(), csg() and bakeLighting().
Surface buildSurface(const SurfaceSpec& a, const BuildHooks& hooks = {});

/// The depth a read needs before the field is known (a curvilinear grid's lattice, readField):
/// `depth` when given, else the table's number (opt::depth.defaultValue).
int readDepth(const SurfaceSpec& a);
/// `depth` for a field input: as given, or auto, the shallowest depth whose voxel is no larger
/// than the field's median sample spacing along each axis (depthForField), capped by the memory
/// budget (the deepest whose estimateBuildMemory at `iso` fits it). Said on stderr (log::info)
/// when auto chose it. Throws as estimateBuildMemory.
DepthChoice chooseDepth(const SurfaceSpec& a, const ScalarField& field, double iso);
/// The depth whose voxel is nearest one pixel of the default view (frameCamera, Render.h) of
/// `bounds` at `width` x `height` and `fov` degrees (depthForPixel), without the memory cap.
DepthChoice viewDepth(const Box3& bounds, int width, int height, double fov, const std::string& unit);
/// `depth` for geometry (a city's or a sphere scene's box `bounds`, its cube the box's largest
/// extent): as given, or auto, the voxel nearest one pixel of the default view of the box at
/// a's view size and field of view (depthForPixel), capped so that `bytesAtDepth(d)` fits the
/// memory budget. `unit` names the world unit in the reason. Said on stderr when auto chose it.
DepthChoice chooseGeometryDepth(const SurfaceSpec& a, const Box3& bounds, const std::string& unit,
                                const std::function<double(int)>& bytesAtDepth);

/// buildSurface's two steps for a field input (not an octree file or a city), for callers that
/// build again and again from one read: readSurfaceField reads a.input into s.field (s.loadMs),
/// reporting to hooks.readProgress and stopping when hooks.cancelled says so (CancelledError);
/// buildFromField does the rest from s.field with `hooks`. Throw as buildSurface.
void readSurfaceField(const SurfaceSpec& a, Surface& s, const BuildHooks& hooks = {});
void buildFromField(const SurfaceSpec& a, Surface& s, const BuildHooks& hooks = {});

/// The colour map of a surface coloured by height by default.
inline constexpr const char* kHeightColormap = "viridis";

/// The colour settings as RenderSettings (linear RGB): colour, colour map (by default, with
/// voxel values of a second variable, the one for that variable: defaultColormap in
/// Shading.h), its range, the masked and floor colours, and the surface's display window.
/// With none of these given and no colours of its own (a city's, a molecule's) nor a display
/// window, the surface gets its default look: a CT preset's tissue colour (CtPresets.h), skin
/// for another patient volume, else kHeightColormap by height.
void applyColour(const SurfaceSpec& a, const Surface& s, RenderSettings& settings);
/// The lighting settings as RenderSettings: baked light unless dynamic, the ambient share and
/// the diffuse (1 - ambient), shadows as given.
void applyLighting(const SurfaceSpec& a, RenderSettings& settings);

}  // namespace octrace::model
