#pragma once
/// @file Animation.h
/// An animation over the time steps of an input: one surface per step, drawn from a fixed
/// camera (or one that orbits), in one colour range, captioned with the step's date. Split so
/// that any process can draw any frame: planAnimation reads the time axis and does the one
/// pass over all steps that a fixed colour range needs, once; renderAnimationFrame(plan, i) is
/// then a pure function of the plan and i (what `octrace animate` runs in parallel, and Python
/// will distribute over Dask); VideoWriter (io/VideoWriter.h) joins the frames into an MP4.
/// No argv, no Qt; messages name settings by their keys (`times`, `orbit`, `fps`).
#include "octrace/model/Figure.h"
#include "octrace/model/Render.h"
#include "octrace/model/Surface.h"

#include "octrace/io/Figure.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/render/Frame.h"
#include "octrace/render/RenderStats.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace octrace::model {

/// Which steps of the input's time axis an animation draws (`times`, the CLI's `--time` of
/// `animate`), as parsed from text:
///   all           every step;
///   I:J, I        steps I to J, 0-based like `time` INDEX, both ends included (I <= J);
///   DATE:DATE     the steps whose date lies between the two, both included, ISO dates
///                 YYYY-MM-DD[THH:MM[:SS]] in the file's calendar (as `time` DATE).
struct TimeSelection {
    enum class Kind { All, Indices, Dates };
    Kind kind = Kind::All;
    std::size_t first = 0, last = 0;  ///< Indices
    std::string from, to;             ///< Dates
};

/// Parses the text of `times`. @throws UsageError naming `times` for anything else (an
/// empty text, J < I, a malformed date, a date range that ends before it starts).
TimeSelection parseTimeSelection(const std::string& text);

/// The steps of `axis` that `selection` chooses, in increasing order. @throws InputError: the
/// field has no time axis, an index beyond the last step, dates on an axis without CF time
/// units or not in its calendar, a date range with no step in it.
std::vector<std::size_t> selectSteps(const TimeSelection& selection, const io::TimeAxis& axis);

/// What to animate: the surface and how it is drawn (as `octrace render` takes them; the
/// surface's request.time is set per frame), the figure around each frame (optional), and the
/// animation's own settings. Defaults from the options table.
struct AnimationSpec {
    SurfaceSpec surface;
    RenderSpec render;
    FigureSettings figure;  ///< figure.enabled: each frame is a figure whose subtitle starts with its date
    std::string times = opt::times.defaultText;  ///< `times` (TimeSelection's text)
    double orbitDegrees = 0.0;                     ///< `orbit`: the camera's turn over the whole animation
    int fps = int(opt::fps.defaultValue);          ///< `fps`
};

/// One frame: which input slice it draws, from where, and what its caption says.
struct AnimationFrame {
    /// The step of the input's time axis, and the same as FieldRequest::time text (its index),
    /// which is what a frame changes in the request; or, when the steps are the volumes of a
    /// DICOM series or a 4-D NIfTI image (TimeAxis::volumes), FieldRequest::volume (`time` "").
    std::size_t step = 0;
    std::string time;
    int volume = -1;
    std::string date;     ///< as the file gives it ("1990-01-15"); "" on an axis without dates
    std::string caption;  ///< the date, or "step 3" on an axis without dates, or "volume 2: temporal position 3"
    double orbitDegrees = 0.0;  ///< the camera's turn about the vertical (up) axis, from the spec's camera
};

/// Everything a frame needs, decided once: a value that can be copied to another process.
struct AnimationPlan {
    AnimationSpec spec;
    std::string timeAxis;  ///< the time dimension's name
    std::string calendar;  ///< the axis's CF calendar ("" without dates)
    std::vector<AnimationFrame> frames;
    /// What the camera frames (unless the spec places it): the world bounds of the grid read,
    /// which every step shares, so that the view does not follow each step's surface.
    Box3 bounds;
    SceneView view = SceneView::Oblique;  ///< how the grid is seen (sceneView of the grid)
    /// The values (or, coloured by height, the heights in a colour bar's units) mapped onto
    /// the colour map's ends in every frame (NaN: no colour map; see colourRangeSource).
    float colourMin = std::numeric_limits<float>::quiet_NaN(), colourMax = std::numeric_limits<float>::quiet_NaN();
    /// How the range was chosen, for messages and stats: "`colour_range`", "`colour_by` <VAR>
    /// over the N steps", "height over the grid: [LO, HI] m", or "" without a colour map.
    std::string colourRangeSource;
    /// The image's size (the whole figure's with a figure; the plot's otherwise).
    int width = 0, height = 0;
    std::optional<io::FigureLayout> figureLayout;
    std::vector<std::string> notes;  ///< what the plan decided that a user should know
};

/// Progress of the planning pass (0..1) and cancellation, as BuildHooks.
using AnimationHooks = BuildHooks;

/// The plan of `spec`: reads the time axis of the input's field (no samples), selects the
/// steps (`times`), reads the first step's grid for the camera's bounds, and, when the surface
/// is coloured by a second variable (`colour_by`) and no `colour_range` was given, reads that
/// variable at every selected step (only it: no octree is built) and fixes the colour range to
/// the union of its valid ranges over the grid read. That range holds every frame's surface
/// values and is the same whatever the iso value; it can be wider than the values on the
/// surfaces themselves, which would cost building every surface twice. A surface coloured by
/// height (a colour map, no values) is coloured over the grid's heights (gridHeightRange,
/// Figure.h) in every frame, unless `colour_range` gives them; a window keeps its window.
/// @throws UsageError (bad `times`, a camera the spec cannot frame, a figure that does not
///         fit), InputError (no time axis: an animation needs one; steps out of range), and as
///         loadField.
AnimationPlan planAnimation(const AnimationSpec& spec, const AnimationHooks& hooks = {});

/// The camera of frame `i` of `plan`: frameCamera of the plan's bounds, turned about its up
/// axis through the look-at point by frames[i].orbitDegrees.
Camera animationCamera(const AnimationPlan& plan, std::size_t i);

/// One drawn frame: the image (the figure with a figure, else the plot; linear RGBA) and the
/// render's counters.
struct AnimationImage {
    Frame image;
    RenderStats stats;
    /// The image as 8-bit sRGB RGBA, row 0 at the top (what a video or a PNG holds).
    std::vector<std::uint8_t> rgba8() const;
};

/// Frame `i` of `plan`: builds the surface of its step (with the plan's colour range),
/// renders it with the plan's renderer and its camera, and with a figure composes it with the
/// caption at the start of the subtitle. A pure function of (plan, i): the same bytes in any
/// process, in any order, on any number of threads. `hooks` report the build's progress.
/// @throws UsageError (i out of range) and as buildSurface and renderFrame.
AnimationImage renderAnimationFrame(const AnimationPlan& plan, std::size_t i, const BuildHooks& hooks = {});

}  // namespace octrace::model
