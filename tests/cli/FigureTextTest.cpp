// The figure-text test (issue 27): every kind of figure the CLI makes (render --figure of an
// ocean field, a CT volume, a city, a molecule and analytic fields; slice --figure of a volume
// and of a 2-D map; the frames of an animation) is composed with OCTRACE_TEST_FIGURE_TEXT set,
// so that io::composeFigure appends the inked box of each text element (each rasterised on its
// own by FreeType) and the colour bar's box. The test fails when two of them overlap or one
// leaves the image, and checks what the text says where the issue found it wrong.
#include "CliRunner.h"
#include "TimeSeries.h"

#include <algorithm>
#include <cstdlib>
#include <regex>

using namespace octrace::testcli;

namespace {

struct TextBox {
    std::string role, text;
    bool graphic = false;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
struct AxisInfo {
    std::string role;
    int candidates = 0;
    double span = 0.0;  ///< of the place (box edge) drawn
    /// Each place not seen end on: the span of its labels' points and the widest label's ink
    /// along it at the smallest label size (pixels).
    std::vector<std::pair<double, double>> places;
};
struct FigureText {
    int width = 0, height = 0;
    int plot[4] = {0, 0, 0, 0};  ///< the plot's box [x0, x1) x [y0, y1) as x0, y0, x1, y1
    double labelPx = 0.0;
    std::vector<AxisInfo> axes;
    std::vector<TextBox> boxes;
    /// The texts of a role ("axis 2", "bar label", ...).
    std::vector<std::string> texts(const std::string& role) const {
        std::vector<std::string> out;
        for (const TextBox& b : boxes)
            if (b.role == role) out.push_back(b.text);
        return out;
    }
};

std::string joined(const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v) out += (out.empty() ? "" : " | ") + s;
    return out;
}

/// The figures one command composed: one JSON line each (io/src/figure/Figure.cpp, appendTextBoxes).
std::vector<FigureText> readFigureText(const std::string& path) {
    std::vector<FigureText> out;
    std::istringstream lines(slurp(path));
    const std::regex head("\"width\": ([0-9]+), \"height\": ([0-9]+), \"plot\": \\[(-?[0-9]+), (-?[0-9]+), (-?[0-9]+), "
                          "(-?[0-9]+)\\], \"labelPx\": ([0-9.eE+-]+)");
    const std::regex axis("\\{\"axis\": \"([^\"]*)\", \"edge\": [0-9]+, \"candidates\": ([0-9]+), \"span\": ([0-9.eE+-]+), "
                          "\"places\": \\[([^{}]*)\\]\\}");
    const std::regex place("\\[([0-9.eE+-]+), ([0-9.eE+-]+)\\]");
    const std::regex box(
        "\\{\"role\": \"([^\"]*)\", \"text\": \"((?:[^\"\\\\]|\\\\.)*)\", \"graphic\": (true|false), \"box\": \\[(-?[0-9]+), (-?[0-9]+), "
        "(-?[0-9]+), (-?[0-9]+)\\]\\}");
    for (std::string line; std::getline(lines, line);) {
        FigureText f;
        std::smatch m;
        if (!std::regex_search(line, m, head)) continue;
        f.width = std::stoi(m[1]), f.height = std::stoi(m[2]);
        for (int i = 0; i < 4; ++i) f.plot[i] = std::stoi(m[std::size_t(3 + i)]);
        f.labelPx = std::stod(m[7]);
        for (auto it = std::sregex_iterator(line.begin(), line.end(), axis); it != std::sregex_iterator(); ++it) {
            f.axes.push_back({(*it)[1], std::stoi((*it)[2]), std::stod((*it)[3]), {}});
            const std::string places = (*it)[4];
            for (auto p = std::sregex_iterator(places.begin(), places.end(), place); p != std::sregex_iterator(); ++p)
                f.axes.back().places.push_back({std::stod((*p)[1]), std::stod((*p)[2])});
        }
        for (auto it = std::sregex_iterator(line.begin(), line.end(), box); it != std::sregex_iterator(); ++it) {
            const std::smatch& b = *it;
            f.boxes.push_back({b[1], b[2], b[3] == "true", std::stoi(b[4]), std::stoi(b[5]), std::stoi(b[6]), std::stoi(b[7])});
        }
        out.push_back(f);
    }
    return out;
}

/// Whether `count` labels fit apart along a place of an axis: its span holds count - 1 times the
/// widest label's ink along it (at the smallest size) and the gap between texts.
bool roomFor(std::size_t count, const std::pair<double, double>& place, double labelPx) {
    const double gap = std::max(1.0, std::round(0.15 * labelPx));
    return place.first >= double(count - 1) * (place.second + gap);
}

/// Fails (naming `what`) when a text leaves the figure or two elements (not two graphics)
/// overlap, when an axis whose labels' points spread over 3 label heights or more keeps fewer
/// than 3 of them though one of its places (box edges) has room for 3 (or one seen end on keeps
/// any), when an axis with room for 3 on none of its places keeps fewer than 2 though its place
/// drawn has room for them (docs/dev/figures.md), or when a patient letter touches the plot.
void expectNoCollision(const FigureText& f, const std::string& what) {
    ASSERT_FALSE(f.boxes.empty()) << what;
    ASSERT_GT(f.labelPx, 0.0) << what;
    for (const AxisInfo& a : f.axes) {
        const std::size_t drawn = f.texts(a.role).size();
        const bool room3 = std::any_of(a.places.begin(), a.places.end(), [&](const auto& p) { return roomFor(3, p, f.labelPx); });
        const bool room2 = std::any_of(a.places.begin(), a.places.end(), [&](const auto& p) {
            return p.first == a.span && roomFor(2, p, f.labelPx);
        });
        if (a.candidates >= 2 && a.span < 0.5 * f.labelPx) {
            EXPECT_EQ(drawn, 0u) << what << ": " << a.role << " is seen end on";
        } else if (a.span >= 3.0 * f.labelPx && a.candidates >= 3 && room3) {
            EXPECT_GE(drawn, 3u) << what << ": " << a.role << " keeps " << joined(f.texts(a.role)) << " of " << a.candidates << " over "
                                 << a.span << " px";
        } else if (a.candidates >= 2 && !room3 && room2) {
            EXPECT_GE(drawn, 2u) << what << ": " << a.role << ", too short for 3 labels, keeps " << joined(f.texts(a.role)) << " of "
                                 << a.candidates << " over " << a.span << " px";
        }
    }
    for (const TextBox& b : f.boxes)
        if (b.role == "letter") {
            EXPECT_FALSE(b.x0 < f.plot[2] && f.plot[0] < b.x1 && b.y0 < f.plot[3] && f.plot[1] < b.y1)
                << what << ": the letter " << b.text << " lies over the plot";
        }
    for (std::size_t i = 0; i < f.boxes.size(); ++i) {
        const TextBox& a = f.boxes[i];
        EXPECT_TRUE(a.x0 >= 0 && a.y0 >= 0 && a.x1 <= f.width && a.y1 <= f.height)
            << what << ": '" << a.text << "' (" << a.role << ") at [" << a.x0 << "," << a.y0 << "," << a.x1 << "," << a.y1
            << ") leaves the " << f.width << "x" << f.height << " figure";
        for (std::size_t j = 0; j < i; ++j) {
            const TextBox& b = f.boxes[j];
            if (a.graphic && b.graphic) continue;
            const bool overlap = a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
            EXPECT_FALSE(overlap) << what << ": '" << a.text << "' (" << a.role << ") overlaps '" << b.text << "' (" << b.role << ")";
        }
    }
}

/// Runs `args` with the text hook on; returns the figures it composed (expects at least one).
std::vector<FigureText> figuresOf(const std::vector<std::string>& args) {
    Scratch s;
    const std::string path = s.path("text.jsonl");
    ::setenv("OCTRACE_TEST_FIGURE_TEXT", path.c_str(), 1);
    const Result r = run(args);
    ::unsetenv("OCTRACE_TEST_FIGURE_TEXT");
    EXPECT_EQ(r.code, 0) << r.err;
    std::vector<FigureText> out = readFigureText(path);
    EXPECT_FALSE(out.empty()) << "no figure text recorded";
    return out;
}

const char* kLevitus = "ocean/levitus_climatology.cdf";

}  // namespace

TEST(FigureText, AnOrthographicTopViewOfAnOceanSlabKeepsItsLabelsApart) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << sharedData(kLevitus);
    Scratch s;
    // Looking straight down: the depth edge is seen end on, every depth tick at one point.
    for (const std::string size : {"480x360", "800x600"}) {
        const auto figs = figuresOf({"render", sharedData(kLevitus), "--var", "TEMP", "--iso", "10", "--region", "120,260,0,65",
                                     "--depth", "6", "--projection", "ortho", "--camera-pos", "0,0,100000", "--look-at", "0,0,0",
                                     "--up", "0,1,0", "--colormap", "thermal", "--figure", "--size", size, "-o", s.path("top.png")});
        ASSERT_EQ(figs.size(), 1u);
        expectNoCollision(figs[0], "top view " + size);
        EXPECT_GE(figs[0].texts("axis 0").size(), 3u) << joined(figs[0].texts("axis 0"));
        EXPECT_GE(figs[0].texts("axis 1").size(), 3u) << joined(figs[0].texts("axis 1"));
        // The bar of a surface below the sea surface coloured by height reads depth.
        EXPECT_EQ(joined(figs[0].texts("bar label")), "depth (m)");
    }
}

TEST(FigureText, TheSoundSpeedColourBarLabelIsWholeAndTheDefaultViewFits) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << sharedData(kLevitus);
    Scratch s;
    for (const std::string size : {"480x360", "1200x900"}) {
        const auto figs = figuresOf({"render", sharedData(kLevitus), "--var", "SALT", "--iso", "34.5", "--colour-by", "sound_speed",
                                     "--region", "120,260,0,65", "--depth", "6", "--floor", "--figure", "--size", size, "-o",
                                     s.path("ss.png")});
        ASSERT_EQ(figs.size(), 1u);
        expectNoCollision(figs[0], "sound speed " + size);
        const std::string label = joined(figs[0].texts("bar label"));
        EXPECT_TRUE(label == "sound_speed (m/s)" || label == "sound_speed | (m/s)" || label == "sound_speed | (m s-1)" ||
                    label == "sound_speed (m s-1)")
            << label;
        EXPECT_GE(figs[0].texts("bar tick").size(), 3u);
    }
}

TEST(FigureText, TheSubtitleGivesTheTimeStepOfTheInput) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    const auto figs = figuresOf({"render", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "5", "--time", "1", "--figure", "--size",
                                 "640x480", "-o", s.path("t.png")});
    ASSERT_EQ(figs.size(), 1u);
    expectNoCollision(figs[0], "time step");
    const std::string sub = joined(figs[0].texts("subtitle"));
    EXPECT_EQ(sub.rfind("2000-02-01", 0), 0u) << sub;
    // No --time: the first step, said as such.
    const auto first = figuresOf({"render", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "5", "--figure", "--size", "640x480", "-o",
                                  s.path("t0.png")});
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(joined(first[0].texts("subtitle")).rfind("2000-01-01", 0), 0u) << joined(first[0].texts("subtitle"));
    // A date: the step nearest to it (the reader's ScalarField::timeLabel, whatever its note says).
    const auto dated = figuresOf({"render", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "5", "--time", "2000-02-25", "--figure",
                                  "--size", "640x480", "-o", s.path("td.png")});
    ASSERT_EQ(dated.size(), 1u);
    EXPECT_EQ(joined(dated[0].texts("subtitle")).rfind("2000-03-01", 0), 0u) << joined(dated[0].texts("subtitle"));
    const auto slice = figuresOf({"slice", nc, "--var", "TEMP", "--time", "2", "--plane", "z", "--at", "300", "--figure", "-o",
                                  s.path("ts.png")});
    ASSERT_EQ(slice.size(), 1u);
    EXPECT_EQ(joined(slice[0].texts("subtitle")).rfind("2000-03-01", 0), 0u) << joined(slice[0].texts("subtitle"));
}

TEST(FigureText, AnimationFramesCarryTheirDateAndKeepTheirTextApart) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    const auto figs = figuresOf({"animate", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "5", "--time", "all", "--size", "401x301",
                                 "--figure", "--title", "shrinking", "--frames", s.path("frames"), "-o", s.path("a.mp4")});
    ASSERT_EQ(figs.size(), 3u);
    // Frames are composed in parallel: their lines come in any order.
    std::vector<std::string> subtitles;
    for (std::size_t i = 0; i < figs.size(); ++i) {
        expectNoCollision(figs[i], "frame " + std::to_string(i));
        subtitles.push_back(joined(figs[i].texts("subtitle")));
    }
    std::sort(subtitles.begin(), subtitles.end());
    const char* dates[] = {"2000-01-01", "2000-02-01", "2000-03-01"};
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(subtitles[i].rfind(dates[i], 0), 0u) << subtitles[i];
}

TEST(FigureText, ACtFigureHasMillimetreTicksAndThePatientsLetters) {
    if (!haveShared("medical/lidc2_chest_ct.nrrd")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    for (const std::string size : {"480x360", "1000x800"}) {
        const auto figs = figuresOf({"render", sharedData("medical/lidc2_chest_ct.nrrd"), "--iso", "100", "--depth", "7", "--figure",
                                     "--size", size, "-o", s.path("ct.png")});
        ASSERT_EQ(figs.size(), 1u);
        expectNoCollision(figs[0], "CT " + size);
        // The patient's letters outside the plot (expectNoCollision), each at the middle of a side.
        const FigureText& f = figs[0];
        std::string letters;
        for (const TextBox& b : f.boxes) {
            if (b.role != "letter") continue;
            letters += b.text;
            EXPECT_NE(std::string("RLAPSI").find(b.text), std::string::npos) << b.text;
            const double cx = 0.5 * (b.x0 + b.x1), cy = 0.5 * (b.y0 + b.y1);
            const double midX = 0.5 * (f.plot[0] + f.plot[2]), midY = 0.5 * (f.plot[1] + f.plot[3]);
            const bool side = std::abs(cx - midX) < 0.5 * f.labelPx || std::abs(cy - midY) < 0.5 * f.labelPx;
            EXPECT_TRUE(side) << b.text << " at " << cx << "," << cy << ", not at the middle of a side of the plot " << f.plot[0] << ","
                              << f.plot[1] << "," << f.plot[2] << "," << f.plot[3];
        }
        EXPECT_GE(letters.size(), 2u) << letters;
        // Ticks in mm; an axis with no room for 3 of them with the unit (the A-P axis at
        // 480x360, receding) gives all its values without it, the subtitle naming the unit.
        std::size_t inMm = 0;
        for (const char* axis : {"axis 0", "axis 1", "axis 2"}) {
            const auto ticks = figs[0].texts(axis);
            EXPECT_GE(ticks.size(), 3u) << axis << ": " << joined(ticks);
            const auto mm = std::count_if(ticks.begin(), ticks.end(), [](const std::string& t) { return t.find(" mm") != std::string::npos; });
            EXPECT_TRUE(mm == 0 || std::size_t(mm) == ticks.size()) << axis << ": " << joined(ticks);
            inMm += std::size_t(mm) == ticks.size();
        }
        EXPECT_EQ(inMm, size == "1000x800" ? 3u : 2u) << size;
        EXPECT_NE(joined(f.texts("subtitle")).find("patient LPS, mm"), std::string::npos) << joined(f.texts("subtitle"));
    }
    // A DICOM CT series: the iso value in HU, the letters of an anterior-ish view.
    if (haveShared("medical/d2n_ct_gantrytilt_4slices")) {
        // Depth 9, not auto's 10: a quarter of the voxels, the same figure text.
        const auto dicom = figuresOf({"render", sharedData("medical/d2n_ct_gantrytilt_4slices"), "--iso", "-900", "--depth", "9",
                                      "--figure", "--size", "640x480", "-o", s.path("hu.png")});
        ASSERT_EQ(dicom.size(), 1u);
        expectNoCollision(dicom[0], "DICOM CT");
        // Its 4 slices make a flat box seen from the front: the A-P edges (axis 1) recede
        // almost end on, and none of the four has room for 3 labels in mm ("-150 mm"); the axis
        // keeps 3 without the unit (the subtitle names it), the others 3 or more in mm.
        for (const AxisInfo& a : dicom[0].axes) {
            const auto drawn = dicom[0].texts(a.role);
            EXPECT_GE(drawn.size(), 3u) << a.role << ": " << joined(drawn);
            for (const auto& t : drawn) {
                if (a.role == "axis 1") {
                    EXPECT_EQ(t.find(" mm"), std::string::npos) << t;
                    EXPECT_NO_THROW((void)std::stod(t)) << t;
                } else {
                    EXPECT_NE(t.find(" mm"), std::string::npos) << a.role << ": " << t;
                }
            }
        }
        EXPECT_NE(joined(dicom[0].texts("subtitle")).find("patient LPS, mm"), std::string::npos) << joined(dicom[0].texts("subtitle"));
        EXPECT_EQ(joined(dicom[0].texts("subtitle")).rfind("CT = -900 HU", 0), 0u) << joined(dicom[0].texts("subtitle"));
        EXPECT_EQ(joined(dicom[0].texts("letter")), "R | S | L | I");
    }
    // A slice of the volume: its letters and scale bar apart.
    const auto slice = figuresOf({"slice", sharedData("medical/lidc2_chest_ct.nrrd"), "--plane", "axial", "--figure", "--size",
                                  "480x360", "-o", s.path("ax.png")});
    ASSERT_EQ(slice.size(), 1u);
    expectNoCollision(slice[0], "CT slice");
}

TEST(FigureText, CityMoleculeAndAnalyticFiguresKeepTheirTextApart) {
    Scratch s;
    std::vector<std::vector<std::string>> cases = {
        {"render", std::string(OCTRACE_TEST_DATA) + "/city/cube.city.json", "--depth", "6"},
        {"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--colormap", "viridis"},
        {"render", "analytic:sphere", "--iso", "0", "--depth", "6"},
        {"render", "random:200", "--depth", "7"},
    };
    if (haveShared("molecule/4HHB.pdb")) cases.push_back({"render", sharedData("molecule/4HHB.pdb"), "--depth", "7"});
    if (haveShared("city/delft.json")) cases.push_back({"render", sharedData("city/delft.json"), "--depth", "7", "--scale-bar"});
    for (auto args : cases) {
        for (const std::string size : {"320x240", "800x600"}) {
            std::vector<std::string> a = args;
            for (const char* x : {"--figure", "--size"}) a.push_back(x);
            a.push_back(size);
            a.push_back("-o");
            a.push_back(s.path("f.png"));
            const auto figs = figuresOf(a);
            ASSERT_EQ(figs.size(), 1u) << args[1];
            expectNoCollision(figs[0], args[1] + " " + size);
            // Ticks a reader reads at a glance: no exponents (a city's projected metres count
            // from the box's corner instead).
            for (const TextBox& b : figs[0].boxes)
                if (b.role.rfind("axis", 0) == 0) {
                    EXPECT_EQ(b.text.find("e+"), std::string::npos) << args[1] << ": " << b.text;
                }
        }
    }
}

TEST(FigureText, SliceFiguresOfAVolumeAndOfAMapKeepTheirTextApart) {
    if (!haveShared(kLevitus) || !haveShared("ocean/etopo20.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::vector<std::vector<std::string>> cases = {
        {"slice", sharedData(kLevitus), "--var", "TEMP", "--plane", "z", "--at", "0"},
        {"slice", sharedData(kLevitus), "--var", "sound_speed", "--plane", "x", "--at", "180", "--region", "120,260,-60,65"},
        {"slice", sharedData("ocean/etopo20.cdf")},
    };
    for (const auto& args : cases)
        for (const std::string size : {"480x360", "1200x1000"}) {
            std::vector<std::string> a = args;
            for (const std::string& x : {std::string("--figure"), std::string("--size"), size, std::string("-o"), s.path("s.png")})
                a.push_back(x);
            const auto figs = figuresOf(a);
            ASSERT_EQ(figs.size(), 1u);
            expectNoCollision(figs[0], args[1] + " " + args.back() + " " + size);
        }
}

TEST(FigureText, TheSeaFloorDoesNotWidenTheIsosurfacesColourRange) {
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << sharedData(kLevitus);
    Scratch s;
    std::vector<std::string> args = {"render", sharedData(kLevitus), "--var", "TEMP", "--iso", "10", "--region", "120,260,0,65",
                                     "--depth", "6", "--colormap", "thermal", "--figure", "--size", "800x600", "-o", s.path("f.png")};
    const auto plain = figuresOf(args);
    args.push_back("--floor");
    const auto floor = figuresOf(args);
    ASSERT_EQ(plain.size(), 1u);
    ASSERT_EQ(floor.size(), 1u);
    expectNoCollision(floor[0], "with --floor");
    // The 10 degree isotherm lies in the upper ~700 m; the floor reaches 5000 m.
    const auto ticks = plain[0].texts("bar tick");
    ASSERT_GE(ticks.size(), 3u);
    EXPECT_LT(std::stod(ticks.back()), 1500.0) << joined(ticks);
    EXPECT_EQ(joined(floor[0].texts("bar tick")), joined(ticks));
}
