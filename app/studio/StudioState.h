#pragma once
// Everything the studio shows, as plain data: the input and how it is read, the surface, the
// renderers, the camera, the shading and the export. A session file is this state as JSON
// (Session.h); renderArguments() is the same state as the `octrace render` command line that
// draws the same image, so that the studio and the CLI can be checked against each other.
#include "octrace/model/Figure.h"
#include "octrace/model/Render.h"
#include "octrace/model/Surface.h"

#include "octrace/model/OptionTable.h"
#include "octrace/render/Camera.h"
#include "octrace/render/RenderSettings.h"
#include "octrace/util/Math.h"

#include <array>
#include <map>
#include <optional>
#include <span>
#include <variant>
#include <string>
#include <string_view>
#include <vector>

namespace octrace::studio {

struct StudioState {
    // Input (what `octrace render INPUT --var --time --series` reads).
    std::string input;
    std::string variable;  ///< empty: the file's only 3-D variable
    std::string time;      ///< NetCDF time step (index or ISO date); empty: the first
    std::string series;    ///< DICOM series; empty: the largest
    /// The settings of textSettings() that are given, by option key, as the CLI takes their
    /// text ("region" -> "-80,0,0,60", "volume" -> "2", a Flag as "on"); absent: the table's
    /// default. They land in the specs through model::applySetting, as the CLI's flags do.
    std::map<std::string, std::string> settings;
    // Surface.
    std::optional<double> iso;  ///< empty: the middle of the valid range
    /// `depth`; unset: auto, the table's default, chosen by the build as render chooses it
    /// (model::chooseDepth, chooseGeometryDepth).
    std::optional<int> depth;
    // Renderers: the main view's, and the second one of the split view.
    std::string renderer = model::opt::renderer.defaultText;
    std::string secondRenderer = "direct";  ///< a renderer's name, or kOpenGlPane
    bool split = false;
    // Coherence of the renderers that have it (the CLI's --colour-tolerance, --branch-up,
    // --miss-coherence; Renderer::colourCoherence, trajectoryCoherence, missCoherence).
    bool colourCoherence = false;  ///< on full, linear, area and their exact variants (a pane named X+colour has it anyway)
    float colourTolerance = float(model::opt::colourTolerance.defaultValue);  ///< 8-bit sRGB units
    bool colourFillsBackground = false;  ///< colour coherence between background pixels too
    int branchUp = int(model::opt::branchUp.defaultValue);
    bool missCoherence = model::opt::missCoherence.defaultChoice() == "on";
    // Camera; unset: framing the surface as `octrace render` does without camera options.
    bool cameraSet = false;
    dvec3 position{0.0, 0.0, 1.0}, lookAt{0.0}, up{0.0, 0.0, 1.0};
    double fov = model::opt::fov.defaultValue;
    // Shading (RenderSettings, display values as a user picks them).
    dvec3 light{0.4, 0.6, 1.0};
    vec3 colour{0.85f, 0.62f, 0.35f};  ///< sRGB
    std::string colormap;               ///< empty: uniform colour
    /// --window: "" (the file's own display window, if any, unless a colour map is chosen),
    /// "none", or a CT preset (CtPresets.h).
    std::string window;
    /// sRGB, alpha; unset: the CLI's default, the background contrasting with the surface
    /// (model::contrastingBackground), white behind a transparent export.
    std::optional<vec4> background;
    // Lighting (the CLI's --ambient, --lighting, --bake-ao, --bake-shadows, --shadows).
    double ambient = model::opt::ambient.defaultValue;  ///< share of light independent of the normal; the light's is 1 - ambient
    /// "" (baked light when the octree has it, else dynamic), "baked" (baked at build when the
    /// octree has none), "dynamic" (from the normals and `light`).
    std::string lighting;
    int bakeAo = int(model::opt::bakeAo.defaultValue);
    bool bakeShadows = model::opt::bakeShadows.defaultChoice() == "on";
    bool shadows = false;  ///< --shadows: shadow rays of the dynamic light (not with baked light)
    // CSG: a cut-away solid (the CLI's --cut syntax: box:..., sphere:..., halfspace:...,
    // cylinder:...; empty: none) and --clip.
    std::string cut;
    bool clip = false;
    // Export.
    int exportWidth = int(model::opt::width.defaultValue), exportHeight = int(model::opt::height.defaultValue);
    bool transparent = false;  ///< export with a transparent background (alpha 0)
    // Export as a figure (render --figure, PNG): title, dpi (fonts scale with it), scale bar;
    // the colour bar comes with a colour map.
    bool figure = false;
    std::string title;
    int dpi = model::kDefaultDpi;
    bool scaleBar = false;
    // Layout (View > Four-Up Layout) and the slice panes (SliceViews.h): the crosshair's sample
    // (i, j, k; unset: the middle sample, as the CLI's `index`), each pane's `at` when placed
    // by its position box (axial/z, coronal/y, sagittal/x; the user's terms, as the CLI's
    // `at`), and the slices' window ("" automatic, a CT preset's name, or "C,W").
    bool fourUp = false;
    std::optional<ivec3> crosshair;
    std::array<std::optional<double>, 3> sliceAt;
    std::string sliceWindow;
};

/// A setting of the options table held in a plain member of StudioState: sessions read and
/// write it under the table's member (with its range), and the studio's bound controls
/// (MainWindow::addBoundControls) show it with the table's label, range and tooltip. A new
/// setting of this kind is a table entry, a member and a line of bindings().
struct Binding {
    /// What a change of the value asks for: a new frame, or a new surface (built again).
    enum class Effect { Render, Rebuild };
    const model::Option* option;
    std::variant<bool StudioState::*, int StudioState::*, float StudioState::*, double StudioState::*> member;
    Effect effect;
    /// Made by addBoundControls in the Rendering panel (false: the control is made by hand
    /// where it is laid out, and only the session is generic).
    bool renderingControl = false;
};
/// Every bound setting, in the order the Rendering panel shows its controls.
std::span<const Binding> bindings();

/// The settings StudioState::settings holds as text: what to read of an ocean field (`region`,
/// `depth_range`, `vertical_scale`, `map_projection`), the volume of a 4-D series (`volume`) and
/// the surface's `colour_by`, `floor` and `surface` (voxel or smooth). Sessions keep each under
/// its table member.
std::span<const model::Option* const> textSettings();
/// What a change of a setting asks for, from where model::applySetting puts it: a new read
/// (what to read), a new build (the surface), or a new frame (shading only).
enum class SettingEffect { Render, Rebuild, Reload };
SettingEffect settingEffect(const model::Option& o);
/// Checks `text` for option `o` as model::applySetting parses it. @throws UsageError naming `o.key`.
void checkSetting(const model::Option& o, const std::string& text);

/// The split view's right pane as the OpenGL surfel view instead of a CPU renderer.
inline constexpr const char* kOpenGlPane = "opengl";

/// The largest export side in pixels.
inline constexpr int kMaxExportSide = int(model::opt::width.max);

/// Whether the state's surface colour is not the default one (the CLI's --colour given: it
/// then replaces an input's own voxel colours).
bool colourGiven(const StudioState& state);

/// The pipeline's render spec of `state` at width x height (renderer, camera when set, field of
/// view, background, light, coherence).
model::RenderSpec renderSpec(const StudioState& state, int width, int height);

/// The camera of `state` at width x height: its own when set, else the CLI's default framing of
/// `surfaceBounds` seen as `view` says (model::frameCamera; `view` is model::sceneView of the
/// surface's field, Engine::view()).
Camera cameraFor(const StudioState& state, const Box3& surfaceBounds, model::SceneView view, int width, int height);

/// The CLI's surface options for `state` (input, variable, time, series, iso, depth, colour,
/// colour map, display window).
model::SurfaceSpec surfaceArgs(const StudioState& state);

/// The render settings of `state` for `surface`, the surface built (its display window, its
/// octree's colours and values, its field's kind: what the default look reads), by the CLI's
/// conversion of the same options (model::renderSettings); `transparent` makes the
/// background's alpha 0 (white unless state.background is set).
/// `background`: where the contrasting background comes from (model::renderSettings).
RenderSettings renderSettingsFor(const StudioState& state, bool transparent, const model::Surface& surface,
                                 const model::BackgroundSource& background = {});

/// The figure options of `state` (render --figure, --title, --dpi, --scale-bar).
model::FigureSettings figureArgs(const StudioState& state);
/// The figure's layout for an export of width x height (state.figure), else nothing; throws
/// UsageError as model::figureLayout when the size leaves no room for the plot.
std::optional<io::FigureLayout> figureLayoutFor(const StudioState& state, int width, int height);

/// The input and what to read of it as `octrace COMMAND` takes them: INPUT, then --var,
/// --time, --series and the text settings given that COMMAND takes (Option::takenBy), so that
/// `render` and `slice` read the field the studio read.
std::vector<std::string> inputArguments(const StudioState& state, std::string_view command);

/// `octrace render` arguments (without the program and command names) that draw what the studio
/// exports for `state` at width x height with `camera` (Engine::exportView): input options,
/// surface, cut, lighting, renderer, camera (its position, look-at point and up vector only when
/// state.cameraSet: else render's default framing, which the studio's is), shading, size,
/// background, figure, -o `output`. Numbers
/// are written with 17 significant digits (exact round trip). `iso` is the value in use (the
/// state's may be unset).
std::vector<std::string> renderArguments(const StudioState& state, const Camera& camera, double iso,
                                         const std::string& output, int width, int height);

}  // namespace octrace::studio
