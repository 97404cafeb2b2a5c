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
