// Tests of figure composition: the layout at a resolution, the plot copied unchanged outside
// what is drawn over it, the colour bar following its colour map, text set by FreeType.
#include "octrace/io/Figure.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;
using namespace octrace::io;

namespace {
/// A plot with a different colour in every pixel.
Frame patternPlot(int w, int h) {
    Frame f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.rgba[f.pixel(x, y)] = vec4(float(x) / float(w), float(y) / float(h), 0.3f, 1.0f);
    return f;
}
}  // namespace

TEST(Figure, LayoutPutsThePlotTheBarAndTheMarginsInsideTheFigureAtAnyDpi) {
    for (int dpi : {72, 150, 300, 600}) {
        const int w = 7 * dpi, h = 5 * dpi;  // 7 x 5 inches
        const FigureLayout l = layoutFigure(w, h, dpi, true);
        EXPECT_EQ(l.width, w);
        EXPECT_EQ(l.height, h);
        EXPECT_GT(l.plotX, 0);
        EXPECT_GT(l.plotY, int(l.titlePx));  // room for the title
        EXPECT_LT(l.plotX + l.plotW, l.barX);
        EXPECT_LT(l.barX + l.barW, w);
        EXPECT_LT(l.plotY + l.plotH, h);
        EXPECT_GT(l.plotW, w / 2);
        EXPECT_NEAR(l.labelPx, 9.0 * dpi / 72.0, 1e-9);
        const FigureLayout noBar = layoutFigure(w, h, dpi, false);
        EXPECT_EQ(noBar.barW, 0);
        EXPECT_GT(noBar.plotW, l.plotW);
    }
    EXPECT_THROW(layoutFigure(100, 80, 600, true), UsageError);
}

TEST(Figure, NiceTicksAreRoundValuesInsideTheRange) {
    EXPECT_EQ(niceTicks(0.0, 10.0, 5), (std::vector<double>{0, 2, 4, 6, 8, 10}));
    EXPECT_EQ(niceTicks(120.0, 260.0, 6), (std::vector<double>{150, 200, 250}));
    const std::vector<double> t = niceTicks(2.06, 29.2, 5);
    ASSERT_FALSE(t.empty());
    for (double v : t) {
        EXPECT_GE(v, 2.06);
        EXPECT_LE(v, 29.2);
        EXPECT_NEAR(std::fmod(v, 5.0), 0.0, 1e-9);
    }
    EXPECT_TRUE(niceTicks(1.0, 1.0, 5).empty());
}

TEST(Figure, CopiesThePlotUnchangedWhereNothingIsDrawnOverItAndTheBarFollowsItsMap) {
    if (figureFontPath().empty()) GTEST_SKIP() << "no DejaVu Sans font (fonts-dejavu-core)";
    const FigureLayout l = layoutFigure(900, 600, 150, true);
    const Frame plot = patternPlot(l.plotW, l.plotH);
    FigureSpec spec;
    spec.title = "Salinity 34.5 over the North Pacific";
    spec.subtitle = "SALT = 34.5 PPT, coloured by TEMP; 120\u00b0E\u2013100\u00b0W";
    spec.colormap = "thermal";
    spec.low = 2.0;
    spec.high = 29.0;
    spec.barLabel = "TEMP (DEG C)";
    spec.lines = {{{10, 10}, {200, 150}}, {{200, 150}, {l.plotW - 10.0, 20}}};
    spec.labels = {{{100, 80}, "140\u00b0E", 0, 1.4}, {{300, 200}, "2000 m", 2.6, 0}};
    std::vector<std::uint8_t> overlay;
    const Frame fig = composeFigure(plot, spec, l, &overlay);
    ASSERT_EQ(fig.width, 900);
    ASSERT_EQ(fig.height, 600);
    std::size_t same = 0, over = 0;
    for (int y = 0; y < l.plotH; ++y)
        for (int x = 0; x < l.plotW; ++x) {
            const std::size_t p = fig.pixel(l.plotX + x, l.plotY + y);
            if (overlay[p]) {
                ++over;
                continue;
            }
            ASSERT_EQ(fig.rgba[p], plot.rgba[plot.pixel(x, y)]) << x << "," << y;
            ++same;
        }
    // The lines and the labels cover a little of the plot, not much.
    EXPECT_GT(over, 200u);
    EXPECT_LT(over, std::size_t(l.plotW) * std::size_t(l.plotH) / 20);
    // Colour bar: every pixel the map's colour for its row, high end at the top.
    for (int r = 0; r < l.barH; ++r) {
        const vec3 want = colormap("thermal", 1.0f - (float(r) + 0.5f) / float(l.barH));
        for (int x = 0; x < l.barW; ++x) ASSERT_EQ(vec3(fig.rgba[fig.pixel(l.barX + x, l.barY + r)]), want) << r;
    }
    // Text was set: dark pixels in the title band and right of the bar (its tick labels).
    auto dark = [&](int x0, int y0, int x1, int y1) {
        std::size_t n = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) n += linearToSrgb8(fig.rgba[fig.pixel(x, y)].g) < 100;
        return n;
    };
    EXPECT_GT(dark(l.plotX, 0, l.plotX + l.plotW, l.plotY), 100u);
    EXPECT_GT(dark(l.barX + l.barW + 2, l.barY, fig.width, l.barY + l.barH), 50u);
    // Paper elsewhere: the bottom margin is white.
    EXPECT_EQ(dark(0, l.plotY + l.plotH + 2, fig.width, fig.height), 0u);
    // Without a colour map no bar is drawn.
    spec.colormap.clear();
    const Frame noBar = composeFigure(plot, spec, l, nullptr);
    EXPECT_EQ(noBar.rgba[noBar.pixel(l.barX + 1, l.barY + 1)], vec4(1.0f));
    // A plot of another size than the layout's is refused.
    EXPECT_THROW(composeFigure(patternPlot(10, 10), spec, l), UsageError);
}

namespace {
/// Fails when a text of `boxes` leaves the w x h figure or two of them (not two graphics) overlap.
void expectApart(const std::vector<FigureTextBox>& boxes, int w, int h) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const FigureTextBox& a = boxes[i];
        EXPECT_TRUE(a.x0 >= 0 && a.y0 >= 0 && a.x1 <= w && a.y1 <= h) << a.text << " leaves the figure";
        for (std::size_t j = 0; j < i; ++j) {
            const FigureTextBox& b = boxes[j];
            if (a.graphic && b.graphic) continue;
            EXPECT_FALSE(a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1) << a.text << " overlaps " << b.text;
        }
    }
}
/// A figure with a long title and subtitle and a sound speed colour bar.
FigureSpec soundSpeedSpec() {
    FigureSpec spec;
    spec.title = "Levitus (1982) annual mean sound speed over the North Pacific and the Sea of Japan";
    spec.subtitle = "2000-01-01; SALT = 34.5 PPT, coloured by sound_speed, sea floor and land; 120\u00b0E\u2013100\u00b0W, "
            "0\u00b0\u201365\u00b0N, 0\u20135000 m";
    spec.colormap = "speed";
    spec.low = 1480.0;
    spec.high = 1540.0;
    spec.barLabel = "sound_speed (m/s)";
    return spec;
}
std::vector<std::string> textsOf(const std::vector<FigureTextBox>& boxes, const std::string& role) {
    std::vector<std::string> out;
    for (const auto& b : boxes)
        if (b.role == role) out.push_back(b.text);
    return out;
}
}  // namespace

TEST(FigureText, CollidingTickLabelsAreThinnedToEveryKthAndKeepAtLeastThree) {
    if (figureFontPath().empty()) GTEST_SKIP() << "no DejaVu Sans font (fonts-dejavu-core)";
    const FigureLayout l = layoutFigure(480, 360, 150, true);
    const Frame plot = patternPlot(l.plotW, l.plotH);
    FigureSpec spec;
    spec.colormap = "thermal";
    spec.low = 0.0;
    spec.high = 30.0;
    spec.barLabel = "T (C)";
    // Eleven longitude labels 12 pixels apart: each is wider than that.
    for (int i = 0; i <= 10; ++i) spec.labels.push_back({{20.0 + 12.0 * i, 100.0}, std::to_string(120 + 10 * i) + "\u00b0E", 0.0, 1.4, 0});
    // Four depth labels at one point (an edge seen end on).
    for (int i = 0; i < 4; ++i) spec.labels.push_back({{150.0, 40.0}, std::to_string(1000 * i) + " m", 2.6, 0.0, 2});
    std::vector<FigureTextBox> boxes;
    composeFigure(plot, spec, l, nullptr, &boxes);
    expectApart(boxes, l.width, l.height);
    const auto lon = textsOf(boxes, "axis 0");
    ASSERT_GE(lon.size(), 3u);
    ASSERT_LT(lon.size(), 11u);
    // Every k-th: evenly spaced values.
    const int step = std::stoi(lon[1]) - std::stoi(lon[0]);
    for (std::size_t i = 1; i < lon.size(); ++i) EXPECT_EQ(std::stoi(lon[i]) - std::stoi(lon[i - 1]), step) << lon[i];
    // The depth edge seen end on keeps none: its labels would all point at one place.
    EXPECT_EQ(textsOf(boxes, "axis 2").size(), 0u);
    // A label that would leave the figure at its edge is moved inside.
    spec.labels = {{{-10.0, 60.0}, "12345 m", -2.6, 0.0, 0}};
    composeFigure(plot, spec, l, nullptr, &boxes);
    expectApart(boxes, l.width, l.height);
    EXPECT_EQ(textsOf(boxes, "axis 0").size(), 1u);
}

TEST(FigureText, AnAxisWithNoRoomForThreeLabelsWithTheirUnitKeepsThreeWithoutIt) {
    if (figureFontPath().empty()) GTEST_SKIP() << "no DejaVu Sans font (fonts-dejavu-core)";
    const FigureLayout l = layoutFigure(480, 360, 150, true);
    const Frame plot = patternPlot(l.plotW, l.plotH);
    FigureSpec spec;
    // Five labels 18 pixels apart along a line: "-150 mm" is wider than 36 pixels, so no three
    // of them fit in mm; "-150" fits every other one.
    const auto axis = [&](bool bare) {
        spec.labels.clear();
        for (int i = 0; i < 5; ++i) {
            const std::string v = std::to_string(-250 + 50 * i);
            spec.labels.push_back({{60.0 + 18.0 * i, 120.0}, v + " mm", 0.0, 1.4, 1, 0, bare ? v : std::string()});
        }
        std::vector<FigureTextBox> boxes;
        composeFigure(plot, spec, l, nullptr, &boxes);
        expectApart(boxes, l.width, l.height);
        return textsOf(boxes, "axis 1");
    };
    const auto withUnit = axis(false);
    EXPECT_LT(withUnit.size(), 3u);
    for (const auto& t : withUnit) EXPECT_NE(t.find(" mm"), std::string::npos) << t;
    const auto bare = axis(true);
    ASSERT_GE(bare.size(), 3u);
    for (const auto& t : bare) EXPECT_EQ(t.find(" mm"), std::string::npos) << t;
    // Where three fit with the unit, it stays.
    spec.labels.clear();
    for (int i = 0; i < 3; ++i) {
        const std::string v = std::to_string(-250 + 50 * i);
        spec.labels.push_back({{60.0 + 120.0 * i, 120.0}, v + " mm", 0.0, 1.4, 1, 0, v});
    }
    std::vector<FigureTextBox> boxes;
    composeFigure(plot, spec, l, nullptr, &boxes);
    for (const auto& t : textsOf(boxes, "axis 1")) EXPECT_NE(t.find(" mm"), std::string::npos) << t;
    EXPECT_EQ(textsOf(boxes, "axis 1").size(), 3u);
}

TEST(FigureText, ALongBarLabelWrapsBeforeItsUnitsAndALongSubtitleWrapsInAFittedLayout) {
    if (figureFontPath().empty()) GTEST_SKIP() << "no DejaVu Sans font (fonts-dejavu-core)";
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{480, 360}, {700, 500}, {1200, 900}}) {
        FigureSpec spec = soundSpeedSpec();
        const FigureLayout l = layoutFigure(w, h, 150, true, figureRoom(spec, layoutFigure(w, h, 150, true)));
        const Frame plot = patternPlot(l.plotW, l.plotH);
        std::vector<FigureTextBox> boxes;
        composeFigure(plot, spec, l, nullptr, &boxes);
        expectApart(boxes, l.width, l.height);
        std::string bar;
        for (const auto& t : textsOf(boxes, "bar label")) bar += t + "|";
        EXPECT_TRUE(bar == "sound_speed (m/s)|" || bar == "sound_speed|(m/s)|") << w << ": " << bar;
        // The subtitle whole, on as many lines as it takes; the first starts with the date.
        const auto sub = textsOf(boxes, "subtitle");
        ASSERT_GE(sub.size(), 1u);
        EXPECT_EQ(sub[0].rfind("2000-01-01", 0), 0u) << sub[0];
        std::string whole;
        for (const auto& t : sub) whole += (whole.empty() ? "" : " ") + t;
        EXPECT_EQ(whole, spec.subtitle);
        if (w == 480) {
            EXPECT_GT(sub.size(), 1u);
        }
        // Depths positive down: the same bar reads downwards.
        spec.low = -5000.0;
        spec.high = 0.0;
        spec.barPositiveDown = true;
        spec.barLabel = "depth (m)";
        composeFigure(plot, spec, l, nullptr, &boxes);
        expectApart(boxes, l.width, l.height);
        std::vector<FigureTextBox> ticks;
        for (const auto& b : boxes)
            if (b.role == "bar tick") ticks.push_back(b);
        ASSERT_GE(ticks.size(), 3u);
        EXPECT_EQ(ticks.front().text, "0");  // at the top
        for (std::size_t i = 1; i < ticks.size(); ++i) {
            EXPECT_GT(ticks[i].y0, ticks[i - 1].y0);
            EXPECT_GT(std::stod(ticks[i].text), std::stod(ticks[i - 1].text));
        }
    }
}

TEST(FigureText, AFittedLayoutHoldsTheWholeTextAndTheLettersOutsideThePlot) {
    if (figureFontPath().empty()) GTEST_SKIP() << "no DejaVu Sans font (fonts-dejavu-core)";
    for (const auto& [w, h] : std::vector<std::pair<int, int>>{{480, 360}, {1600, 1200}}) {
        FigureSpec spec = soundSpeedSpec();
        spec.sideLetters = {"R", "S", "L", "I"};
        // Labels below the plot's bottom edge and right of its right edge, as a top view has them.
        const FigureLayout first = layoutFigure(w, h, 150, true);
        auto place = [&](const FigureLayout& l) {
            spec.labels.clear();
            for (int i = 0; i < 3; ++i)
                spec.labels.push_back({{l.plotW * (0.1 + 0.4 * i), double(l.plotH)}, std::to_string(120 + 40 * i) + "\u00b0E", 0.0, 1.4, 0});
            for (int i = 0; i < 4; ++i)
                spec.labels.push_back({{double(l.plotW), l.plotH * (0.2 + 0.2 * i)}, std::to_string(10 * i) + "\u00b0N", 2.2, 0.0, 1});
        };
        place(first);
        const FigureRoom room = figureRoom(spec, first);
        EXPECT_GT(room.bottom, 0);
        EXPECT_GT(room.right, 0);
        EXPECT_GT(room.letter, 0);
        const FigureLayout l = layoutFigure(w, h, 150, true, room);
        place(l);
        std::vector<FigureTextBox> boxes;
        composeFigure(patternPlot(l.plotW, l.plotH), spec, l, nullptr, &boxes);
        expectApart(boxes, l.width, l.height);
        // Nothing cut: the subtitle's lines make the whole of it, the bar label is whole.
        std::string sub;
        for (const auto& t : textsOf(boxes, "subtitle")) sub += (sub.empty() ? "" : " ") + t;
        EXPECT_EQ(sub, spec.subtitle);
        std::string bar;
        for (const auto& t : textsOf(boxes, "bar label")) bar += (bar.empty() ? "" : " ") + t;
        EXPECT_EQ(bar, spec.barLabel);
        EXPECT_EQ(textsOf(boxes, "axis 0").size(), 3u);
        EXPECT_EQ(textsOf(boxes, "axis 1").size(), 4u);
        // The letters outside the plot, at the middle of their sides.
        ASSERT_EQ(textsOf(boxes, "letter").size(), 4u);
        for (const auto& b : boxes) {
            if (b.role != "letter") continue;
            EXPECT_FALSE(b.x0 < l.plotX + l.plotW && l.plotX < b.x1 && b.y0 < l.plotY + l.plotH && l.plotY < b.y1) << b.text;
            const double cx = 0.5 * (b.x0 + b.x1), cy = 0.5 * (b.y0 + b.y1);
            if (b.text == "R" || b.text == "L") EXPECT_NEAR(cy, l.plotY + 0.5 * l.plotH, 0.5 * l.labelPx) << b.text;
            else EXPECT_NEAR(cx, l.plotX + 0.5 * l.plotW, 0.5 * l.labelPx) << b.text;
        }
    }
}
