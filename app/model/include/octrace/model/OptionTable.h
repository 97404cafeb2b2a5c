#pragma once
/// @file OptionTable.h
/// The options table: every setting that a front end offers, declared once with its key, kind,
/// default, range or choices, unit, help, CLI flag, session member, studio control and what
/// reads it. The CLI's parser and --help, the session files, the studio's widgets and (later)
/// Python's keyword arguments take their names, limits, defaults and help from here, and a
/// setting that the chosen renderer does not read is reported from here (unusedWarning). The
/// pattern of F3D's options.json and of pbrt-v4's ParameterDictionary::ReportUnused.
///
/// Keys are what core and io messages name (util/Parameter.h); sayForCli, sayForSession and
/// sayForStudio turn them into each front end's words.
#include "octrace/octree/Octree.h"
#include "octrace/render/Renderer.h"
#include "octrace/util/Memory.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace octrace::model {

enum class OptionKind {
    Flag,     ///< given or not (CLI flag without a value; a session bool)
    Integer,  ///< a whole number within [min, max]
    Number,   ///< a finite number within min..max, each end closed or open
    Choice,   ///< one word of `choices`
    Text,     ///< free text, checked by the code that reads it
};

/// A renderer capability (Renderer.h): the renderers for which it returns true read the option.
using RendererCapability = bool (Renderer::*)() const;

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

/// One setting. Aggregate, so that the table below reads as a list of designated fields.
struct Option {
    const char* key = "";       ///< snake_case; messages name it as `key`; Python's keyword
    OptionKind kind = OptionKind::Text;
    const char* flag = "";      ///< CLI flag without the dashes ("" none)
    const char* argument = "";  ///< the CLI's name for the value ("N", "DEG"); "" for a flag
    const char* session = "";   ///< member of a studio session file, "group.member" ("" not saved)
    const char* label = "";     ///< the studio control's label ("" no control)
    double defaultValue = 0.0;  ///< Integer, Number; Choice: the index of the default choice
    const char* defaultText = "";  ///< the default as --help says it when it is not defaultValue
    double min = -kUnbounded, max = kUnbounded;
    bool minOpen = false, maxOpen = false;  ///< the end itself is outside
    const char* choices = "";   ///< Choice: the words, separated by '|'
    const char* unit = "";      ///< Integer, Number: "degrees", "pixels"; Text: what defaultValue counts ("" none)
    const char* help = "";      ///< one line, without the range and the default
    const char* commands = "";  ///< the CLI commands that take it, separated by spaces
    RendererCapability renderers = nullptr;  ///< non-null: only renderers with it read the option
    const char* renderersSaid = "";          ///< who reads it, for unusedWarning ("linear and area")
    /// Key of a Flag option that must be on for this one to be read ("" none): the colour
    /// tolerance means nothing without colour coherence.
    const char* needs = "";

    /// The choices as words.
    std::vector<std::string> choiceList() const;
    /// Choice: the default word.
    std::string defaultChoice() const;
    /// Integer or Number: whether `v` lies within the range.
    bool inRange(double v) const;
    /// "[1, 14]", "(0, 180) degrees", "> 0", ">= 0 pixels".
    std::string rangeText() const;
    /// What --help says of the default: defaultText, or the default value or choice.
    std::string defaultSaid() const;
    /// The help line: help, `detail` (what only the running program knows, e.g. the renderers'
    /// names) after "; ", the range of a number, the renderers that read it, "(default ...)".
    std::string helpLine(const std::string& detail = "") const;
    /// The line that docs/user/cli.md shows under the option's heading (generated, and checked
    /// by a test): default, range or choices, who reads it, session member, studio control.
    std::string docLine() const;
    /// The command whose section of docs/user/cli.md documents the option: render when it
    /// takes it, else the first of `commands`.
    std::string docCommand() const;
    /// Whether the CLI command `command` takes the option.
    bool takenBy(std::string_view command) const;
};

// The table. Integer and Number limits are written once, here; code that needs a limit reads
// it from these (opt::depth.max), never writes the number again.
namespace opt {
// Surface.
// `depth` takes the word auto, its default; defaultValue is the number where one is needed before
// the data are read (the studio's first value, a curvilinear grid's lattice under auto).
inline constexpr Option depth{.key = "depth", .kind = OptionKind::Integer, .flag = "depth", .argument = "N|auto",
    .session = "surface.depth", .label = "Depth", .defaultValue = 8,
    .defaultText = "auto: fields, the shallowest depth whose voxel is no larger than the median sample spacing along "
                   "each axis; cities and sphere scenes, a voxel of about one pixel of the default view; capped by "
                   "`max_memory`, said on stderr, listed by `octrace info`",
    .min = 1, .max = Octree::kMaxDepth,
    .help = "octree depth, voxels = 2^N per cube edge, or auto", .commands = "render export build csg animate"};
inline constexpr Option iso{.key = "iso", .kind = OptionKind::Text, .flag = "iso", .argument = "VALUE[UNIT]|NAME",
    .session = "surface.iso", .label = "Iso value",
    .defaultText = "for an image volume (CT, MR, NRRD, ...) Otsu's threshold of its valid samples (what best splits them "
                   "into tissue and background); for an ocean field the middle of its valid samples' range between their 0.5th and "
                   "99.5th percentiles; for an analytic one the middle of the valid range",
    .help = "iso value of the surface in the variable's units, or with a unit converted into them by UDUNITS-2 "
            "(10degC on a field in K), or a CT preset in Hounsfield units", .commands = "render export build csg animate"};
inline constexpr Option variable{.key = "var", .kind = OptionKind::Text, .flag = "var", .argument = "NAME",
    .session = "input.variable", .label = "Variable", .defaultText = "the file's only 3-D variable",
    .help = "variable to draw, by name or CF standard_name; sound_speed is derived from temperature and salinity when "
            "the file has none",
    .commands = "render export build csg slice info animate"};
inline constexpr Option time{.key = "time", .kind = OptionKind::Text, .flag = "time", .argument = "INDEX|DATE",
    .session = "input.time", .label = "Time", .defaultText = "the first",
    .help = "time step, NetCDF only: a 0-based index or a date YYYY-MM-DD[THH:MM[:SS]] in the file's calendar, nearest step",
    .commands = "render export build slice info"};
inline constexpr Option series{.key = "series", .kind = OptionKind::Text, .flag = "series", .argument = "UID|INDEX|DESCRIPTION",
    .session = "input.series", .label = "Series", .defaultText = "the largest",
    .help = "DICOM series to read: its UID, its number in `octrace info`'s list or its description",
    .commands = "render export build slice info"};
inline constexpr Option volume{.key = "volume", .kind = OptionKind::Integer, .flag = "volume", .argument = "N",
    .session = "input.volume", .defaultValue = 0, .defaultText = "0, with a note naming how many there are",
    .min = 0, .max = 100000,
    .help = "volume of a multi-volume DICOM series (time points, echoes, cardiac phases, diffusion directions, magnitude "
            "and phase: `octrace info` lists them) or of a 4-D NIfTI image, 0-based like `time`",
    .commands = "render export build slice info"};
inline constexpr Option form{.key = "form", .kind = OptionKind::Choice, .flag = "form", .argument = "shell|volume",
    .choices = "shell|volume",
    .help = "octree form: the isosurface's boundary voxels (shell), or the solid it bounds with its interior and caps where "
            "the grid ends (volume)",
    .commands = "render export build animate"};
inline constexpr Option surface{.key = "surface", .kind = OptionKind::Choice, .flag = "surface", .argument = "voxel|smooth",
    .session = "surface.mode", .label = "Surface", .defaultText = "smooth for field inputs, except with the papers' renderers (full, linear, area and their variants, "
                   "direct, samet, beam), which draw voxel",
    .choices = "voxel|smooth",
    .help = "how a boundary voxel is drawn: its box, or where the ray crosses the trilinear interpolant of the field's "
            "values at its corners, lit by the field's gradient (8 more bytes per voxel; cities, molecules, cuts and "
            "octree files without corner values draw voxel)",
    .commands = "render export build animate"};
inline constexpr Option inside{.key = "inside", .kind = OptionKind::Choice, .flag = "inside", .argument = "above|below",
    .choices = "above|below", .help = "volume form: the solid is where the value is >= iso (above) or < iso (below)",
    .commands = "render export build csg animate"};
inline constexpr Option threads{.key = "threads", .kind = OptionKind::Integer, .flag = "threads", .argument = "N",
    .defaultValue = 0, .min = 0, .max = 1024, .help = "worker threads, 0 = all cores; the result does not depend on it",
    .commands = "render export build csg animate"};
inline constexpr Option maxMemory{.key = "max_memory", .kind = OptionKind::Text, .flag = "max-memory", .argument = "SIZE",
    .defaultValue = kDefaultMemoryBudgetPercent, .unit = "% of the physical memory", .help = "memory budget for reading the field, building the octree and the output: bytes, K, M, G, T (powers of 1024) "
            "or N% of the physical memory; a larger job is refused up front",
    .commands = "render export build csg slice info animate"};
inline constexpr Option verticalScale{.key = "vertical_scale", .kind = OptionKind::Number, .flag = "vertical-scale",
    .argument = "S", .session = "input.vertical_scale", .label = "Vertical scale", .defaultText = "depth extent = 1/4 of the larger horizontal extent", .min = 0, .minOpen = true,
    .help = "vertical exaggeration of depth, NetCDF only", .commands = "render export build slice info animate"};
inline constexpr Option terrainDepth{.key = "terrain_depth", .kind = OptionKind::Integer, .flag = "terrain-depth",
    .argument = "N", .defaultText = "`depth`", .min = 1, .max = Octree::kMaxDepth,
    .help = "city inputs: per-region depth, terrain to depth N and buildings to `depth` in one octree (nodes that only "
            "terrain crosses stop at level N as coarse leaves; at most `depth`)",
    .commands = "render export build info"};
inline constexpr Option dem{.key = "dem", .kind = OptionKind::Text, .flag = "dem", .argument = "RASTER",
    .defaultText = "none", .help = "city inputs: a DEM raster (GeoTIFF or any GDAL raster, any CRS) added as terrain",
    .commands = "render export build info"};
inline constexpr Option texture{.key = "texture", .kind = OptionKind::Text, .flag = "texture", .argument = "RASTER",
    .defaultText = "none, colours per object type",
    .help = "city inputs: a colour raster (orthophoto, map; any GDAL raster, any CRS) draped on the terrain",
    .commands = "render export build info"};
inline constexpr Option heightAttr{.key = "height_attr", .kind = OptionKind::Text, .flag = "height-attr", .argument = "NAME",
    .defaultText = "the first of height, HEIGHT, hauteur, HAUTEUR, measuredHeight",
    .help = "footprint inputs: the attribute holding each building's height", .commands = "render export build info"};
inline constexpr Option baseAttr{.key = "base_attr", .kind = OptionKind::Text, .flag = "base-attr", .argument = "NAME",
    .defaultText = "the lowest `dem` height under it, else 0",
    .help = "footprint inputs: the attribute holding each building's ground height", .commands = "render export build info"};
inline constexpr Option crs{.key = "crs", .kind = OptionKind::Text, .flag = "crs", .argument = "CRS",
    .defaultText = "the input's own when projected, else the UTM zone of its centre",
    .help = "city inputs: projected coordinate reference system to bring everything into, e.g. EPSG:28992",
    .commands = "render export build info"};
inline constexpr Option cut{.key = "cut", .kind = OptionKind::Text, .flag = "cut", .argument = "SOLID", .session = "surface.cut",
    .label = "Solid", .defaultText = "none",
    .help = "cut a solid away: box:X0,Y0,Z0,X1,Y1,Z1, sphere:X,Y,Z,R, cylinder:X0,Y0,Z0,X1,Y1,Z1,R or halfspace:X,Y,Z,NX,NY,NZ "
            "in world units, or relief:FILE, the ground under a relief raster (e.g. ETOPO; geographic fields only, laid out "
            "in their world); repeatable; builds the volume form",
    .commands = "render export build csg animate"};

inline constexpr Option clip{.key = "clip", .kind = OptionKind::Flag, .flag = "clip", .session = "surface.clip",
    .help = "keep only what lies inside the `cut` solids instead of cutting them away", .commands = "render export build animate"};
inline constexpr Option extendDown{.key = "extend_down", .kind = OptionKind::Flag, .flag = "extend-down",
    .help = "geographic fields: extend each water column's deepest valid value down through the masked samples under it, "
            "so that a finer sea floor (`cut` relief:FILE) bounds the water instead of the grid's own",
    .commands = "render export build csg animate"};
inline constexpr Option region{.key = "region", .kind = OptionKind::Text, .flag = "region", .argument = "LON0,LON1,LAT0,LAT1",
    .session = "input.region", .label = "Region", .defaultText = "the whole grid", .help = "geographic subregion in degrees, NetCDF only",
    .commands = "render export build csg slice info animate"};
inline constexpr Option depthRange{.key = "depth_range", .kind = OptionKind::Text, .flag = "depth-range", .argument = "Z0,Z1",
    .session = "input.depth_range", .label = "Depth range", .defaultText = "every level", .help = "depth levels from Z0 to Z1 metres (positive down), NetCDF only",
    .commands = "render export build slice info animate"};
inline constexpr Option mapProjection{.key = "map_projection", .kind = OptionKind::Choice, .flag = "map-projection",
    .argument = "auto|lonlat|polar", .session = "input.map_projection", .label = "Map projection", .choices = "auto|lonlat|polar",
    .help = "horizontal mapping of a geographic grid: polar stereographic (true scale at 71 degrees) or longitude x "
            "cos(latitude); auto is polar when the region lies in one hemisphere and reaches 75 degrees or beyond, "
            "NetCDF only",
    .commands = "render export build csg slice info animate"};
inline constexpr Option lodSelect{.key = "lod_select", .kind = OptionKind::Text, .flag = "lod-select", .argument = "LOD",
    .defaultText = "each object's highest",
    .help = "city inputs: level of detail to voxelize, e.g. 1, 2 or 2.2 (a prefix takes its sublevels)",
    .commands = "render export build info"};
inline constexpr Option bake{.key = "bake", .kind = OptionKind::Flag, .flag = "bake",
    .help = "bake diffuse lighting, shadows and ambient occlusion into the shell", .commands = "render export build animate"};
inline constexpr Option bakeLight{.key = "bake_light", .kind = OptionKind::Text, .flag = "bake-light",
    .argument = "dir:X,Y,Z[,I]|point:X,Y,Z[,I]", .defaultText = "one dir:0.3,-0.5,1",
    .help = "a light to bake, world direction towards it or position, intensity I (default 1); repeatable",
    .commands = "render export build animate"};

// Colour.
inline constexpr Option colour{.key = "colour", .kind = OptionKind::Text, .flag = "colour", .argument = "R,G,B",
    .session = "shading.colour",
    .defaultText = "by the data: a CT preset's tissue colour (`iso` skin, bone), skin for another patient volume, a "
                   "DICOM file's display window, a city's colours per object and texture, a molecule's per element, "
                   "else the colour map by height",
    .help = "surface colour: sRGB components in [0,1], #RRGGBB or a CSS colour name (steelblue), also over a city's own colours", .commands = "render export animate"};
inline constexpr Option colormap{.key = "colormap", .kind = OptionKind::Text, .flag = "colormap", .argument = "NAME",
    .session = "shading.colormap", .label = "Colour map",
    .defaultText = "viridis by height where nothing else colours the surface (see `colour`)",
    .help = "colour by a colour map", .commands = "render export slice animate"};
inline constexpr Option window{.key = "window", .kind = OptionKind::Text, .flag = "window", .argument = "NAME|C,W|none",
    .session = "shading.window", .label = "Display window", .defaultText = "the window stored in a DICOM file",
    .help = "grey by a display window (a CT preset, a centre and width, or none)", .commands = "render export slice animate"};
inline constexpr Option colourBy{.key = "colour_by", .kind = OptionKind::Text, .flag = "colour-by", .argument = "VAR",
    .session = "surface.colour_by", .label = "Colour by", .defaultText = "none", .help = "colour the isosurface by a second variable of the same file, sampled at each voxel",
    .commands = "render export animate"};
inline constexpr Option colourRange{.key = "colour_range", .kind = OptionKind::Text, .flag = "colour-range",
    .argument = "MIN,MAX", .defaultText = "the range of what is coloured",
    .help = "the values mapped onto the colour map's ends, each in the units of what is coloured or with a unit "
            "(5degC,20degC; a surface coloured by height: heights, in metres above the sea surface on a geographic grid)", .commands = "render export slice animate"};
inline constexpr Option maskedColour{.key = "masked_colour", .kind = OptionKind::Text, .flag = "masked-colour",
    .argument = "R,G,B", .defaultText = "0.6,0.6,0.6", .help = "colour of what is masked: sRGB in [0,1], #RRGGBB or a CSS colour name",
    .commands = "render export slice animate"};
inline constexpr Option floorColour{.key = "floor_colour", .kind = OptionKind::Text, .flag = "floor-colour",
    .argument = "R,G,B", .defaultText = "0.55,0.5,0.45", .help = "colour of the sea floor and land (`floor`): sRGB in [0,1], #RRGGBB or a CSS colour name",
    .commands = "render export animate"};
inline constexpr Option background{.key = "background", .kind = OptionKind::Text, .flag = "background",
    .argument = "R,G,B[,A]", .session = "shading.background",
    .defaultText = "contrasting with the surface: white, or slate 0.32,0.34,0.43 behind a light surface (sphere scenes in "
                   "the object octree: white)",
    .help = "background colour: sRGB components in [0,1], #RRGGBB[AA] or a CSS colour name (black)", .commands = "render animate"};
inline constexpr Option light{.key = "light", .kind = OptionKind::Text, .flag = "light", .argument = "X,Y,Z",
    .session = "shading.light", .defaultText = "0.4,0.6,1",
    .help = "direction towards the light in camera space, x right, y up, z to the viewer", .commands = "render animate"};
inline constexpr Option floor{.key = "floor", .kind = OptionKind::Flag, .flag = "floor", .session = "surface.floor",
    .label = "Sea floor and land",
    .help = "also draw the sea floor and land where the variable is masked, under the isosurface", .commands = "render export animate"};

// Rendering.
inline constexpr Option renderer{.key = "renderer", .kind = OptionKind::Text, .flag = "renderer", .argument = "NAME",
    .session = "renderers.main", .label = "Renderer", .defaultText = "tile",
    .help = "renderer; samet and beam (paper B) draw sphere scenes and voxel octrees alike", .commands = "render animate"};
inline constexpr Option cameraPos{.key = "camera_pos", .kind = OptionKind::Text, .flag = "camera-pos", .argument = "X,Y,Z",
    .session = "camera.position",
    .defaultText = "framing the surface's box tightly: geographic fields north up from the south and above, patient "
                   "volumes from the front (anterior, superior up; a thin sagittal slab from the patient's left), others "
                   "from the south-east and above",
    .help = "camera position, world units", .commands = "render animate"};
inline constexpr Option lookAt{.key = "look_at", .kind = OptionKind::Text, .flag = "look-at", .argument = "X,Y,Z",
    .session = "camera.look_at",
    .defaultText = "the framing's: near the centre of the surface's bounding box, where its projection is centred",
    .help = "point the camera looks at", .commands = "render animate"};
inline constexpr Option up{.key = "up", .kind = OptionKind::Text, .flag = "up", .argument = "X,Y,Z", .session = "camera.up",
    .defaultText = "0,0,1", .help = "camera up direction", .commands = "render animate"};
inline constexpr Option fov{.key = "fov", .kind = OptionKind::Number, .flag = "fov", .argument = "DEG",
    .session = "camera.fov", .label = "Field of view", .defaultValue = 30, .min = 0, .max = 180, .minOpen = true,
    .maxOpen = true, .unit = "degrees", .help = "vertical field of view", .commands = "render animate"};
inline constexpr Option orthoHeight{.key = "ortho_height", .kind = OptionKind::Number, .flag = "ortho-height", .argument = "H",
    .defaultText = "framing the surface", .min = 0, .minOpen = true,
    .help = "height of the orthographic view window in world units", .commands = "render"};
inline constexpr Option projection{.key = "projection", .kind = OptionKind::Choice, .flag = "projection",
    .argument = "perspective|ortho", .choices = "perspective|ortho",
    .help = "camera projection; ortho draws every ray parallel to the view direction", .commands = "render"};
inline constexpr Option lod{.key = "lod", .kind = OptionKind::Number, .flag = "lod", .argument = "PIXELS",
    .defaultText = "0 = exact", .min = 0, .max = 1e6, .unit = "pixels",
    .help = "multi-resolution: stop at octree nodes whose projected size is below PIXELS and draw them whole",
    .commands = "render", .renderers = &Renderer::multiResolution};
inline constexpr Option level{.key = "level", .kind = OptionKind::Integer, .flag = "level", .argument = "L",
    .defaultText = "the voxels", .min = 1, .max = Octree::kMaxDepth,
    .help = "draw the octree at level L (at most `depth`) at the finest, for previews", .commands = "render export",
    .renderers = &Renderer::multiResolution};
inline constexpr Option colourCoherence{.key = "colour_coherence", .kind = OptionKind::Flag, .flag = "colour-coherence",
    .session = "renderers.colour_coherence", .label = "Colour coherence", .help = "colour coherence on the discrete ray casters: a pixel between two neighbours of nearly the same colour gets "
            "their average untraced (a renderer name with +colour, as area+colour, turns it on too)",
    .commands = "render", .renderers = &Renderer::colourCoherence, .renderersSaid = "the discrete ray casters"};
inline constexpr Option colourFillBackground{.key = "colour_fill_background", .kind = OptionKind::Flag,
    .flag = "colour-fill-background", .session = "renderers.colour_fill_background", .label = "Fill background",
    .help = "colour coherence also between two background pixels, as paper A does: the pixel between is taken as "
            "background untraced (off: only between surface pixels)",
    .commands = "render", .renderers = &Renderer::colourCoherence, .renderersSaid = "the discrete ray casters",
    .needs = "colour_coherence"};
inline constexpr Option colourTolerance{.key = "colour_tolerance", .kind = OptionKind::Number, .flag = "colour-tolerance",
    .argument = "T", .session = "renderers.colour_tolerance", .label = "Colour tolerance", .defaultValue = 3, .min = 0,
    .max = 255, .unit = "per 8-bit sRGB channel",
    .help = "largest colour difference of two neighbours for colour coherence", .commands = "render",
    .renderers = &Renderer::colourCoherence, .renderersSaid = "the discrete ray casters", .needs = "colour_coherence"};
inline constexpr Option branchUp{.key = "branch_up", .kind = OptionKind::Integer, .flag = "branch-up", .argument = "N",
    .session = "renderers.branch_up", .label = "Branch up", .defaultValue = 0, .defaultText = "0: paper A, at the branch node",
    .min = 0, .max = Octree::kMaxDepth,
    .help = "trajectory coherence: start a common-path ray N octree levels above its partners' branch node; fewer pixels "
            "differ from full traversal, at some speed",
    .commands = "render", .renderers = &Renderer::trajectoryCoherence,
    .renderersSaid = "linear and area and their variants"};
inline constexpr Option tileSize{.key = "tile_size", .kind = OptionKind::Integer, .flag = "tile-size", .argument = "N",
    .defaultValue = 8, .min = 1, .max = 64, .unit = "pixels",
    .help = "side of the square screen tiles whose rays the tile renderer bounds together (an exact pre-pass per tile); "
            "the image does not depend on it",
    .commands = "render", .renderers = &Renderer::tiled, .renderersSaid = "tile"};
inline constexpr Option missCoherence{.key = "miss_coherence", .kind = OptionKind::Choice, .flag = "miss-coherence",
    .argument = "on|off", .session = "renderers.miss_coherence", .label = "Miss coherence", .defaultValue = 0,
    .choices = "on|off",
    .help = "a common-path pixel whose two partners both missed is taken as background untraced (off: traced from the root)",
    .commands = "render", .renderers = &Renderer::missCoherence,
    .renderersSaid = "the approximate linear and area"};
inline constexpr Option verify{.key = "verify", .kind = OptionKind::Flag, .flag = "verify",
    .help = "also trace every pixel with the reference traversal and report the differences", .commands = "render"};
inline constexpr Option baseline{.key = "baseline", .kind = OptionKind::Text, .flag = "baseline", .argument = "NAME",
    .defaultText = "none",
    .help = "also render with renderer NAME, alternating with the main one `repeat` times, and report baseline_render_ms, "
            "speedup_over_baseline and baseline_differing_pixels (pixels whose colour differs)",
    .commands = "render"};
inline constexpr Option repeat{.key = "repeat", .kind = OptionKind::Integer, .flag = "repeat", .argument = "N",
    .defaultValue = 1, .min = 1, .max = 1000,
    .help = "render N times and report the fastest as render_ms (benchmarks on a noisy machine)", .commands = "render"};
inline constexpr Option size{.key = "size", .kind = OptionKind::Text, .flag = "size", .argument = "WxH",
    .defaultText = "1600x1200", .help = "image size in pixels, `width` x `height`", .commands = "render slice"};
inline constexpr Option width{.key = "width", .kind = OptionKind::Integer, .session = "export.width", .label = "Width",
    .defaultValue = 1600, .min = 1, .max = 16384, .unit = "pixels", .help = "image width, the W of `size`", .commands = "render"};
inline constexpr Option height{.key = "height", .kind = OptionKind::Integer, .session = "export.height", .label = "Height",
    .defaultValue = 1200, .min = 1, .max = 16384, .unit = "pixels", .help = "image height, the H of `size`", .commands = "render"};

// Sphere scenes in the object octree.
inline constexpr Option octree{.key = "octree", .kind = OptionKind::Choice, .flag = "octree", .argument = "object|voxel",
    .defaultText = "object for reference, samet, beam; voxel for the others", .choices = "object|voxel",
    .help = "sphere inputs: trace the spheres in paper B's object octree (renderers reference, samet, beam) or voxelize "
            "them into the voxel octree at `depth` (every voxel renderer)",
    .commands = "render"};
inline constexpr Option leafObjects{.key = "leaf_objects", .kind = OptionKind::Integer, .flag = "leaf-objects",
    .argument = "N", .defaultValue = 8, .min = 1, .max = 100000,
    .help = "object octree: split a node while it holds more than N spheres", .commands = "render"};
inline constexpr Option samples{.key = "samples", .kind = OptionKind::Integer, .flag = "samples", .argument = "N",
    .defaultValue = 1, .min = 1, .max = 256,
    .help = "antialiasing: rays per pixel on a sqrt(N) x sqrt(N) grid in each pixel, averaged; a square number (every "
            "renderer and scene; each sample exact, N times the work)", .commands = "render animate"};
inline constexpr Option bounces{.key = "bounces", .kind = OptionKind::Integer, .flag = "bounces", .argument = "N",
    .defaultValue = 2, .min = 0, .max = 16,
    .help = "object octree: Whitted depth, reflected and transmitted rays at most N deep", .commands = "render"};

// Lighting.
inline constexpr Option ambient{.key = "ambient", .kind = OptionKind::Number, .flag = "ambient", .argument = "A",
    .session = "shading.ambient", .label = "Ambient", .defaultValue = 0.15, .min = 0, .max = 1,
    .help = "share of the light every voxel gets whatever its normal; the light's own share is 1 - A (dynamic shading "
            "and baking)",
    .commands = "render animate"};
inline constexpr Option lighting{.key = "lighting", .kind = OptionKind::Choice, .flag = "lighting", .argument = "baked|dynamic",
    .session = "shading.lighting", .label = "Lighting", .defaultText = "baked when the octree has it, else dynamic",
    .choices = "baked|dynamic",
    .help = "shade by the octree's baked light (baking it first when it has none) or by the normals and the light direction",
    .commands = "render animate"};
inline constexpr Option shadows{.key = "shadows", .kind = OptionKind::Choice, .flag = "shadows", .argument = "on|off",
    .session = "shading.shadows", .label = "Shadow rays",
    .defaultText = "on for sphere scenes in the object octree; off for voxel octrees", .choices = "on|off",
    .help = "shadow rays towards the light: sphere scenes in the object octree and the dynamic shading of voxel octrees "
            "(one more ray per shaded pixel; baked light has its own shadows)",
    .commands = "render animate"};
inline constexpr Option bakeAo{.key = "bake_ao", .kind = OptionKind::Integer, .flag = "bake-ao", .argument = "N",
    .session = "shading.bake_ao", .label = "AO rays", .defaultValue = 8, .min = 0, .max = 1024,
    .help = "ambient-occlusion rays per side of the surface when baking, 0 = none", .commands = "render export build animate"};
inline constexpr Option bakeAoDistance{.key = "bake_ao_distance", .kind = OptionKind::Number, .flag = "bake-ao-distance",
    .argument = "D", .defaultText = "1/8 of the octree's cube", .min = 0, .minOpen = true,
    .help = "how far an occluder darkens when baking, world units", .commands = "render export build animate"};
inline constexpr Option bakeShadows{.key = "bake_shadows", .kind = OptionKind::Choice, .flag = "bake-shadows",
    .argument = "on|off", .session = "shading.bake_shadows", .label = "Baked shadows", .defaultValue = 0,
    .choices = "on|off", .help = "hard shadows from the baked lights", .commands = "render export build animate"};

// Figures and slices.
inline constexpr Option dpi{.key = "dpi", .kind = OptionKind::Integer, .flag = "dpi", .argument = "N", .session = "export.dpi",
    .label = "Resolution", .defaultValue = 150, .defaultText = "150 for a figure, none recorded for a plain image",
    .min = 36, .max = 1200, .unit = "dots per inch",
    .help = "resolution recorded in the PNG or TIFF; a figure's fonts are 9 and 11 pt at it", .commands = "render slice animate"};
inline constexpr Option figure{.key = "figure", .kind = OptionKind::Flag, .flag = "figure", .session = "export.figure",
    .label = "Figure", .defaultText = "off: the plain image",
    .help = "write a publication figure (PNG or TIFF, by the output's extension): the image with a title", .commands = "render slice animate"};
inline constexpr Option title{.key = "title", .kind = OptionKind::Text, .flag = "title", .argument = "TEXT",
    .session = "export.title", .label = "Title", .defaultText = "none", .help = "title of the figure", .commands = "render slice animate"};
inline constexpr Option caption{.key = "caption", .kind = OptionKind::Text, .defaultText = "none; an animation's frame: its date",
    .help = "text at the start of the figure's subtitle, e.g. the date of a time step", .commands = ""};
inline constexpr Option printSize{.key = "print_size", .kind = OptionKind::Text, .flag = "print-size",
    .argument = "WxH(mm|cm|in)", .defaultText = "the figure is `size`",
    .help = "figure size on paper, e.g. 180x120mm, each side at most 100 inches; its pixels are this times `dpi`",
    .commands = "render slice animate"};
inline constexpr Option scaleBar{.key = "scale_bar", .kind = OptionKind::Flag, .flag = "scale-bar", .session = "export.scale_bar",
    .label = "Scale bar",
    .help = "draw a scale bar in the plot's lower left corner, a round length in km (geographic grids), m (cities) or "
            "world units, true at the distance of the look-at point",
    .commands = "render slice animate"};
inline constexpr Option coastline{.key = "coastline", .kind = OptionKind::Text, .flag = "coastline",
    .argument = "auto|none|crude|low|intermediate|high|FILE",
    .defaultText = "auto: GSHHG at a resolution from the region's size, where GSHHG is installed",
    .help = "coastlines on the figure of a geographic field (a depth slice's map; a 3-D view: on the sea surface, hidden "
            "behind the surface): GSHHG at a resolution (Debian gmt-gshhg-low: crude, low; gmt-gshhg-high: intermediate, "
            "high), the lines and polygons of a vector file OGR reads (shapefile, GeoPackage, GeoJSON; reprojected to "
            "longitude/latitude), or none",
    .commands = "render slice animate"};
// Animations (`octrace animate`, model/Animation.h).
inline constexpr Option times{.key = "times", .kind = OptionKind::Text, .flag = "time", .argument = "all|I:J|DATE:DATE",
    .defaultText = "all",
    .help = "time steps to animate: all, 0-based indices I to J (both included, as `time` INDEX) or the steps "
            "dated between two dates YYYY-MM-DD[THH:MM[:SS]] (both included) in the file's calendar; for a multi-volume "
            "DICOM series or a 4-D NIfTI image the steps are its volumes (all or I:J, as `volume`)",
    .commands = "animate"};
inline constexpr Option fps{.key = "fps", .kind = OptionKind::Integer, .flag = "fps", .argument = "N", .defaultValue = 12,
    .min = 1, .max = 240, .unit = "frames a second", .help = "frame rate of the video", .commands = "animate"};
inline constexpr Option orbit{.key = "orbit", .kind = OptionKind::Number, .flag = "orbit", .argument = "DEG",
    .defaultValue = 0, .min = -3600, .max = 3600, .unit = "degrees",
    .help = "turn the camera this many degrees about the vertical axis through the look-at point over the whole animation "
            "(frame i of n at i/n of it; 0: a fixed camera)",
    .commands = "animate"};
inline constexpr Option frames{.key = "frames", .kind = OptionKind::Text, .flag = "frames", .argument = "DIR",
    .defaultText = "none",
    .help = "also write each frame as DIR/frame_NNNN.png (the folder is made if missing)", .commands = "animate"};
inline constexpr Option plane{.key = "plane", .kind = OptionKind::Choice, .flag = "plane", .argument = "NAME",
    .defaultText = "axial for patient volumes, else z; a single image: its own plane", .choices = "axial|coronal|sagittal|x|y|z",
    .help = "slice plane: axial, coronal, sagittal (patient volumes: DICOM, NIfTI, NRRD in LPS space), or x, y, z (normal to "
            "a world axis; on a geographic grid z is a horizontal slice at a depth, x one at a longitude, y at a latitude)",
    .commands = "slice"};
inline constexpr Option at{.key = "at", .kind = OptionKind::Number, .flag = "at", .argument = "POSITION",
    .defaultText = "the middle sample",
    .help = "where the plane lies along its normal: world units (mm for patient volumes: LPS x for sagittal, y for coronal, "
            "z for axial); on a geographic grid the depth in metres (positive down) for z, the longitude or latitude in "
            "degrees for x or y",
    .commands = "slice"};
inline constexpr Option format{.key = "format", .kind = OptionKind::Choice, .flag = "format", .argument = "NAME",
    .defaultText = "from the output's extension", .choices = "ply", .help = "output format of the point cloud",
    .commands = "export"};
inline constexpr Option ascii{.key = "ascii", .kind = OptionKind::Flag, .flag = "ascii",
    .defaultText = "off: binary little-endian", .help = "write the PLY body as ASCII text", .commands = "export"};
inline constexpr Option index{.key = "index", .kind = OptionKind::Integer, .flag = "index", .argument = "N",
    .defaultText = "the middle one, n/2", .min = 0, .max = 1 << 30,
    .help = "where the plane lies: sample N (0-based) of the grid axis across the plane", .commands = "slice"};
inline constexpr Option compression{.key = "compression", .kind = OptionKind::Integer, .flag = "compression",
    .argument = "LEVEL", .defaultValue = 19, .min = 1, .max = 22, .help = "zstd compression level of the file's chunks",
    .commands = "build csg"};
inline constexpr Option sampleCount{.key = "grid_samples", .kind = OptionKind::Integer, .flag = "samples", .argument = "N",
    .defaultValue = 65, .min = 2, .max = 1024, .help = "samples per axis over [-1,1]^3", .commands = "sample"};
inline constexpr Option seed{.key = "seed", .kind = OptionKind::Integer, .flag = "seed", .argument = "S", .defaultValue = 1,
    .min = 0, .max = 1 << 30, .help = "random seed of the 'noise' and 'spheres' fields", .commands = "sample"};
}  // namespace opt

/// Every option of the table, in the order of the declarations above.
std::span<const Option* const> allOptions();
/// The option of `key`, or null.
const Option* findOption(std::string_view key);
/// The option that the CLI command `command` takes as --`flag`, or null.
const Option* findFlag(std::string_view command, std::string_view flag);

/// What is wrong with `value` for the option ("180 is outside (0, 180) degrees", "2.5 is not a
/// whole number"), or nothing.
std::optional<std::string> valueProblem(const Option& o, double value);
/// The last part of the option's session member ("renderers.branch_up" -> "branch_up").
std::string sessionMember(const Option& o);

/// Checks a value against the option's range (and, for an Integer, that it is whole).
/// @returns the value. @throws UsageError naming the option as `key`, e.g.
/// "`fov`: 180 is outside (0, 180) degrees".
double checkNumber(const Option& o, double value);
int checkInteger(const Option& o, double value);
/// Parses `text` as a finite number (strtod rules, the whole text) without the option's range:
/// a part of a value with several parts. @throws UsageError "`key`: 'x' is not a finite number".
double parseFinite(const Option& o, const std::string& text);
/// Parses `text` as the option's number (strtod/strtol rules, the whole text) and checks it.
/// @throws UsageError "`key`: 'x' is not a number" and as checkNumber.
double parseNumber(const Option& o, const std::string& text);
int parseInteger(const Option& o, const std::string& text);
/// A number with an optional unit, as `iso` and `colour_range` take it: "10", "10degC",
/// "283.15 K", "-2km". Without a unit the number is in the units of what it applies to.
struct Quantity {
    double value = 0.0;
    std::string unit;  ///< as given, "" for a plain number
    std::string text;  ///< the whole text as given, for messages
};
/// Parses `text` as a finite number (strtod rules) followed by an optional unit that UDUNITS-2
/// knows (io/Units.h), checks the number against the option's range when no unit is given.
/// @throws UsageError "`key`: 'x' is not a number ..." or "`key`: unknown unit 'u' in '10u' ...".
Quantity parseQuantity(const Option& o, const std::string& text);
/// q's value in `units`, the units of `subject` (e.g. "levitus.nc: variable 'TEMP'"); `what`
/// names the setting ("`iso`"). A plain number is returned as it is. @throws InputError
/// saying what was given, `units` and what to do, when subject has no units, UDUNITS-2 does
/// not know them, or q's unit does not convert to them.
double quantityIn(const Quantity& q, const std::string& units, const std::string& what, const std::string& subject);
/// Parses one of the option's choices. @throws UsageError "`key`: choose on or off, got 'x'".
std::string parseChoice(const Option& o, const std::string& text);

/// The warning for an option given although `rendererName` does not read it, e.g. "`branch_up`
/// has no effect on renderer full (only on linear and area and their variants)", or although
/// the option it `needs` is off (isOn(key) says which Flag options are on): "`colour_tolerance`
/// has no effect without `colour_coherence`"; or nothing.
std::optional<std::string> unusedWarning(const Option& o, const Renderer& renderer, const std::string& rendererName,
                                         const std::function<bool(std::string_view key)>& isOn = {});

/// Each front end's words for the parameters that core and io messages name (Parameter.h):
/// the CLI's flag ("--max-memory"), a session file's member ("renderers.branch_up"), the
/// studio control's label ("'Depth'"), Python's keyword. A key without such a word is left as it is.
std::string sayForCli(std::string_view text);
std::string sayForSession(std::string_view text);
std::string sayForStudio(std::string_view text);
/// Python's keyword in quotes ("'max_memory'"; `width` and `height` are 'size').
std::string sayForPython(std::string_view text);

}  // namespace octrace::model
