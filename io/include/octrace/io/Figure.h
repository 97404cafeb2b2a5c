#pragma once
/// @file Figure.h
/// Publication figures: a rendered image (the plot) framed by a title, a colour bar with its
/// variable and units, and labelled ticks on the data's bounding box, at a print resolution.
/// Text is set with FreeType in DejaVu Sans (Debian fonts-dejavu-core).
#include "octrace/render/Frame.h"
#include "octrace/util/Math.h"

#include <array>
#include <string>
#include <vector>

namespace octrace::io {

/// The room a figure's text needs around its plot, from FreeType's metrics of that text
/// (figureRoom): how far tick labels reach beyond each side of the plot, the lines the title,
/// subtitle and colour bar label take, the colour bar's panel and the patient's letters.
struct FigureRoom {
    int left = 0, top = 0, right = 0, bottom = 0;  ///< tick labels beyond each side of the plot, pixels
    int letter = 0;            ///< a patient letter's size (0: none) beyond the tick labels on each side
    int panel = 0;             ///< the colour bar panel's width right of the plot's margin (0: estimated)
    int titleLines = 1, subtitleLines = 1, barLabelLines = 2;
    bool operator==(const FigureRoom&) const = default;
};

/// Where the parts of a figure lie, in pixels of the figure (row 0 at the top).
struct FigureLayout {
    int width = 0, height = 0;                ///< the whole figure
    int plotX = 0, plotY = 0, plotW = 0, plotH = 0;  ///< the rendered image
    int barX = 0, barY = 0, barW = 0, barH = 0;      ///< the colour bar (barW = 0: none); top = high end
    int dpi = 150;
    double labelPx = 0.0, titlePx = 0.0;      ///< font sizes in pixels (9 pt and 11 pt at dpi)
    FigureRoom room;                          ///< what the margins were made for
};

/// The layout of a figure of width x height pixels at `dpi` (fonts scale with it), with or
/// without a colour bar, whose margins hold `room` (the default: one line of title and
/// subtitle, two of bar label, a panel for short bar ticks, no tick labels beyond the plot). @throws UsageError
/// when the figure is too small for its text (the plot would be under 16 pixels either way).
FigureLayout layoutFigure(int width, int height, int dpi, bool colourBar, const FigureRoom& room = {});

/// A label at a point of the plot (pixels of the plot, continuous), e.g. a longitude tick on
/// the bounding box; `dx`, `dy` move the text's centre away from the point, in label heights.
struct FigureLabel {
    dvec2 at;
    std::string text;
    double dx = 0.0, dy = 0.0;
    /// The axis the label belongs to (ticks of one axis): labels of an axis that would collide
    /// are thinned together, keeping every k-th.
    int axis = 0;
    /// Which of the axis's places the label belongs to: 0 the preferred one (a box edge), 1, 2,
    /// ... alternatives (the three parallel box edges), tried in order when the preferred one
    /// cannot keep 3 of its labels clear of the rest (composeFigure); only one place per axis
    /// is drawn, with its tick marks.
    int edge = 0;
    /// The text without its unit ("-120" for "-120 mm"), or empty: an axis that cannot keep 3
    /// of its labels with their unit on any of its places sets them without it, where the
    /// subtitle names the unit (composeFigure).
    std::string bare;
};

/// Rough width of a label in label heights (DejaVu Sans: about 0.6 of the height a character),
/// to move its centre off a point before the text is measured.
double labelWidthEstimate(const std::string& text);

/// What a figure shows besides the plot.
struct FigureSpec {
    std::string title;        ///< first line at the top (may be empty)
    std::string subtitle;     ///< second line: variable, iso value, region
    /// Colour bar: map name (Shading.h), value range and its label ("TEMP (DEG C)"); no colour
    /// bar when colormap is empty.
    std::string colormap;
    /// Instead of a colour map, a display window's grey ramp (low .. high = C - W/2 .. C + W/2,
    /// black .. white as display values, white .. black when invertedGrey: MONOCHROME1).
    bool greyRamp = false, invertedGrey = false;
    double low = 0.0, high = 1.0;
    std::string barLabel;
    /// The bar's ticks read -value (a depth, positive down, for a bar over heights low..high):
    /// the colours stay where they are (high at the top), the numbers grow downwards.
    bool barPositiveDown = false;
    /// Lines over the plot (the bounding box's edges, plot pixels) and labelled ticks on them.
    std::vector<std::pair<dvec2, dvec2>> lines;
    std::vector<FigureLabel> labels;
    /// Coastlines over the plot (plot pixels), already clipped to where they belong; drawn
    /// thinner than the box and under it.
    std::vector<std::vector<dvec2>> coastlines;
    /// Scale bar in the plot's lower left corner: `scaleBarPx` plot pixels long (0: none),
    /// labelled `scaleBarLabel` (e.g. "500 km") above it.
    double scaleBarPx = 0.0;
    std::string scaleBarLabel;
    /// The patient's letters (R/L, A/P, S/I) for the sides of the plot: left, top, right,
    /// bottom; drawn outside the plot at the middle of each side, beyond its tick labels.
    std::array<std::string, 4> sideLetters;
};

/// The room `spec`'s text needs around the plot of `layout` (whose plot `spec`'s labels were
/// placed on), measured with FreeType: the lines its title, subtitle and bar label wrap into
/// across the figure, how far the tick labels reach beyond the plot (at most 8 label heights a
/// side), the bar panel its ticks and label need, and the letters. A layout made for this room
/// (layoutFigure) holds the text without cutting it; model::fitFigureLayout iterates the two
/// until the room stops growing.
FigureRoom figureRoom(const FigureSpec& spec, const FigureLayout& layout);

/// A round scale-bar length (1, 2 or 5 times a power of ten, in world units) of at most a
/// fifth of a plot `plotWidth` pixels wide where one pixel spans `worldPerPixel` world units;
/// 0 when there is none (no finite positive scale).
double scaleBarLength(double worldPerPixel, int plotWidth);

/// One element of a composed figure as laid out (pixels of the figure, [x0, x1) x [y0, y1)):
/// a text's inked pixels (its glyphs as FreeType rasterises them), or a graphic that text must
/// not cover (the colour bar). What composeFigure's `text` reports, for tests and debugging.
struct FigureTextBox {
    std::string role;  ///< "title", "subtitle", "bar label", "bar tick", "scale bar", "axis N", "colour bar"
    std::string text;  ///< as drawn (after thinning, wrapping or abbreviation); empty for a graphic
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool graphic = false;
};

/// The figure as a Frame (linear RGBA, opaque white paper) of layout's size; the plot's pixels
/// are copied unchanged into its area except where a line or label is drawn over them, which
/// `overlay` (when not null) marks with 1 (figure pixels, row-major). Colour bar pixels are
/// the map's colour for their row (high end at the top). @throws UsageError when plot's size
/// is not layout's plot size, OutputError when the font cannot be read.
///
/// Text is laid out from FreeType's metrics before it is drawn, so that no two texts overlap
/// and none leaves the figure: the title and subtitle wrap into the lines the layout's room
/// gives them (at whole "; " or ", " parts, else at spaces; an ellipsis ends the last line only
/// when the room is short); the colour bar's label goes above the bar, split before its units
/// when the room says two lines; the patient's letters go outside the plot at the middle of each
/// side, beyond the tick labels; tick labels of an axis that would collide keep every k-th, at
/// least 3 (at a smaller size, down to 70%, when 3 do not fit at 9 pt); an edge seen end on
/// keeps none. `text` (when not null) receives every text's inked box and the colour bar's.
/// With the environment variable OCTRACE_TEST_FIGURE_TEXT set to a path, each figure also
/// appends them to that file as one JSON line (the figure-text test), with the plot's box, the
/// label size and each axis's candidate count and span.
Frame composeFigure(const Frame& plot, const FigureSpec& spec, const FigureLayout& layout,
                    std::vector<std::uint8_t>* overlay = nullptr, std::vector<FigureTextBox>* text = nullptr);

/// Up to about `count` round values (1, 2 or 5 times a power of ten) in [lo, hi].
std::vector<double> niceTicks(double lo, double hi, int count);

/// The font file figures are set in (DejaVu Sans), as found on this system; empty if none.
std::string figureFontPath();

}  // namespace octrace::io
