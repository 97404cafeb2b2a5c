#pragma once
/// @file Slice.h
/// A planar slice through a field's samples (no octree), greyed by a display window (CT, MR)
/// or coloured by a colour map, as a radiology workstation or a map shows it, optionally inside
/// a figure. What `octrace slice`, Python (`Volume.slice`, `da.octrace.slice`) and the studio's
/// slice views share: each fills a SliceSpec from its own words and calls renderSlice. No argv,
/// no Qt; messages name settings by their keys (`plane`, `at`, `window`, ...), which each front
/// end says in its own words.
#include "octrace/model/Figure.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Stats.h"

#include "octrace/build/ScalarField.h"
#include "octrace/io/Figure.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/render/Frame.h"
#include "octrace/render/SliceView.h"
#include "octrace/util/Math.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace octrace::model {

/// What to slice and how to show it. Defaults are the options table's (a setting lands here
/// through applySetting with SettingTargets::slice).
struct SliceSpec {
    std::string input;         ///< as given, for messages and stats (a path, or the field's source)
    io::FieldRequest request;  ///< what to read from `input` (`var`, `region`, `time`, ...)
    std::optional<SlicePlane> plane;  ///< `plane`; unset: axial for patient volumes, else z
    std::optional<double> at;         ///< `at`, along the plane's normal (geographic grids: depth m, lon, lat)
    std::optional<int> index;         ///< `index`, the sample across the plane; unset with `at` unset: n/2
    /// `size`: the image (with a figure: the whole figure, by default 1200x1000); 0: one
    /// pixel per sample of the finer in-plane spacing.
    int width = 0, height = 0;
    /// `window`: "" (not given: the file's window, else a patient volume's value range, else
    /// the colour map), "none", a preset name (CtPresets.h), or "C,W"; `window` its value.
    std::string windowName;
    ValueWindow window;
    std::string colormap;  ///< `colormap`; empty: the variable's (defaultColormap, Shading.h)
    float colourMin = std::numeric_limits<float>::quiet_NaN(), colourMax = std::numeric_limits<float>::quiet_NaN();  ///< `colour_range`
    Quantity colourMinGiven, colourMaxGiven;  ///< `colour_range`'s ends as given, with their units ("" the field's)
    vec3 maskedColour{0.6f, 0.6f, 0.6f};  ///< `masked_colour`, sRGB
    std::optional<vec4> background;       ///< `background`, sRGB and alpha; unset: opaque black, with a figure the paper
    FigureSettings figure;                ///< `figure`, `title`, `dpi`, `print_size`, `scale_bar`
    int threads = int(opt::threads.defaultValue);  ///< `threads`; the image does not depend on it
    std::uint64_t maxMemory = 0;                   ///< `max_memory`; 0: defaultMemoryBudget()
};

/// The memory budget in bytes: spec.maxMemory, or the default share of physical memory.
std::uint64_t memoryBudget(const SliceSpec& spec);

/// The checks before anything is read: `at` and `index` together, an input that holds no field
/// (an octree file, a city model). @throws UsageError naming the settings by their keys.
void checkSliceSpec(const SliceSpec& spec);

/// How the slice is coloured (SliceView.h), and where its window or range comes from ("`window`
/// bone", "the file's display window", "the slice's range of values", ...).
struct SliceColour {
    SliceColouring colouring;
    std::string source;
};

/// A rendered slice and what was measured on the way: everything a summary, the stats and a
/// caller that draws over the slice (the studio) need. Move-only in practice (the frames).
struct SliceResult {
    /// The image to write: the figure when spec.figure.enabled, else the slice (linear RGBA).
    Frame image;
    int dpi = 0;  ///< what the image records: the figure's, else `dpi` as given (0: none)
    SliceView view;
    /// The values at the slice's pixels (before a figure frames them): what a probe reads.
    SliceValues values;
    SliceColour colour;
    std::uint64_t validPixels = 0, maskedPixels = 0;
    /// With a figure: its layout, and where the slice's pixel (0, 0) lies in the plot.
    std::optional<io::FigureLayout> layout;
    dvec2 offset{0.0};
};

/// Slices `field` (read from spec.input with spec.request) as `spec` says: the plane (default
/// axial for a patient volume, else z; axial, coronal, sagittal only for patient volumes), its
/// position (`at` in the field's world units or geographic terms, else sample `index`, else the
/// middle sample), the image size (a figure's plot less its bands for letters, ticks and scale
/// bar), the memory check against memoryBudget(spec) before sampling, the colouring (`window`
/// and a colour map are exclusive; CT presets need HU) and the figure around it. Threads:
/// spec.threads. @throws UsageError (settings that do not fit the field or each other),
/// InputError (the plane outside the grid, a preset on a field not in HU), LimitError (over the
/// budget).
SliceResult renderSlice(const ScalarField& field, const SliceSpec& spec);

/// `at` (SliceSpec::at, in the user's terms: world units, mm for patient volumes; on a
/// geographic grid metres of depth for z, degrees east for x, north for y) as the world
/// coordinate along the plane's normal, and back. A longitude in -180..180 or 0..360 alike.
double sliceWorldOfAt(const ScalarField& field, SlicePlane plane, double at);
double sliceAtOfWorld(const ScalarField& field, SlicePlane plane, double world);
/// The `at` values a plane can take on `field` (slicePositionRange in the user's terms), low
/// to high (depths: the surface first).
std::pair<double, double> sliceAtRange(const ScalarField& field, SlicePlane plane);
/// The plane's position as summaries and captions say it: "z = 12.5 mm", "500 m depth", "150°E".
std::string slicePositionText(const ScalarField& field, const SliceView& view);

/// How a slice's figure labels screen direction `d` (a signed world axis, SliceView.h): the
/// patient letter of a patient volume (L, R, P, A, S, I), else "+x", "-y", ...
std::string sliceDirectionName(const ScalarField& field, const dvec3& d);

/// The scale bar of a slice: what `slice --figure` draws under its plot and the studio's slice
/// panes in their corner, one mechanism for both. Its length is io::scaleBarLength of the view's
/// pixel size (world units per pixel: mm on patient volumes) and width, in world units;
/// `pixels` the same in the view's pixels; the label the length with its unit ("50 mm", "200
/// km" on a geographic grid). Drawn always on patient volumes, on other grids when `requested`
/// (`scale_bar`); length 0 (no bar) otherwise or when the view has no extent.
struct SliceScaleBar {
    double length = 0.0;
    double pixels = 0.0;
    std::string label;
};
SliceScaleBar sliceScaleBar(const ScalarField& field, const SliceView& view, bool requested);

/// A display window over the valid values from the `lowFraction` to the `highFraction` quantile
/// (nearest rank): the studio's automatic window for a volume without presets (MR: 1st to 99th
/// percentile). A width of at least 1e-30 when the quantiles meet. @throws EmptyResultError
/// when no value is valid.
ValueWindow quantileWindow(const ScalarField& field, double lowFraction = 0.01, double highFraction = 0.99);

/// The one-line summary that `octrace slice` logs, starting with `output` (what was written):
/// the plane, the variable and position, the sample across the plane, the image's size and
/// pixel size, the window or colour map and its source, the masked pixels.
std::string sliceSummary(const ScalarField& field, const SliceResult& r, const std::string& output);

/// The stats of a slice, in the order and with the keys of docs/user/cli.md (`octrace slice
/// --stats`), `load_ms` last.
Stats sliceStats(const ScalarField& field, const SliceResult& r, const std::string& input, double loadMs);

}  // namespace octrace::model
