// Colour settings in the forms users type: R,G,B in [0,1], #RRGGBB / #RGB / #RRGGBBAA, and the
// CSS colour names; the parser of the options table (app/model) and the CLI end to end.
#include "CliRunner.h"

#include "octrace/model/OptionTable.h"
#include "octrace/model/Settings.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <set>

using namespace octrace::testcli;
namespace model = octrace::model;
using octrace::UsageError;
using octrace::vec4;

namespace {

void expectColour(const vec4& c, int r, int g, int b, float a = 1.0f) {
    EXPECT_NEAR(c.r, float(r) / 255.0f, 1e-6f);
    EXPECT_NEAR(c.g, float(g) / 255.0f, 1e-6f);
    EXPECT_NEAR(c.b, float(b) / 255.0f, 1e-6f);
    EXPECT_NEAR(c.a, a, 1e-6f);
}

}  // namespace

TEST(ColourNames, HexAndNamesGiveTheCssValues) {
    const model::Option& o = model::opt::background;
    expectColour(model::parseColour(o, "steelblue", true), 70, 130, 180);
    expectColour(model::parseColour(o, "SteelBlue", true), 70, 130, 180);
    expectColour(model::parseColour(o, "#4682B4", true), 70, 130, 180);
    expectColour(model::parseColour(o, "#4682b4", true), 70, 130, 180);
    expectColour(model::parseColour(o, "#fff", true), 255, 255, 255);
    expectColour(model::parseColour(o, "#00000080", true), 0, 0, 0, 128.0f / 255.0f);
    expectColour(model::parseColour(o, "dark grey", true), 169, 169, 169);
    expectColour(model::parseColour(o, "dark_gray", true), 169, 169, 169);
    // Where X11 and CSS differ, CSS: green is 0,128,0 and grey 128.
    expectColour(model::parseColour(o, "green", true), 0, 128, 0);
    expectColour(model::parseColour(o, "grey", true), 128, 128, 128);
    const vec4 numbers = model::parseColour(o, "0.5,0.25,1", true);
    EXPECT_EQ(numbers, vec4(0.5f, 0.25f, 1.0f, 1.0f));
}

TEST(ColourNames, TheListIsSortedUniqueAndComplete) {
    const std::vector<std::string> names = model::colourNames();
    EXPECT_EQ(names.size(), 148u);  // CSS Color Module Level 4
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
    for (const std::string& n : names) EXPECT_TRUE(model::namedColour(n).has_value()) << n;
}

TEST(ColourNames, MistakesAreRefusedNamingTheOptionAndTheForms) {
    const model::Option& o = model::opt::colour;
    for (const char* bad : {"steelbleu", "#12345", "#1234567", "#12345g", "#11223344", "#", "1,2", "0.5,0.5,0.5,1"}) {
        try {
            model::parseColour(o, bad, false);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const UsageError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("colour"), std::string::npos) << m;
            EXPECT_NE(m.find("CSS colour name"), std::string::npos) << bad << ": " << m;
        }
    }
}

TEST(ColourNames, TheCliDrawsANamedColourAsItsNumbers) {
    Scratch s;
    const std::vector<std::string> base{"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48"};
    auto with = [&](const std::vector<std::string>& extra, const std::string& out) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        a.insert(a.end(), {"-o", s.path(out)});
        const Result r = run(a);
        EXPECT_EQ(r.code, 0) << r.err;
        return slurp(s.path(out));
    };
    const std::string numbers = with({"--background", "0,0,0", "--colour", "1,0.388235294,0.278431373"}, "a.png");
    const std::string named = with({"--background", "black", "--colour", "tomato"}, "b.png");
    const std::string hex = with({"--background", "#000", "--colour", "#FF6347"}, "c.png");
    EXPECT_FALSE(numbers.empty());
    EXPECT_EQ(named, numbers);
    EXPECT_EQ(hex, numbers);
    const Result bad = run({"render", "analytic:sphere", "--colour", "tomatoes", "-o", s.path("d.png")});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("--colour: unknown colour name 'tomatoes'"), std::string::npos) << bad.err;
}
