// The options table (app/model) through the CLI as a user meets it: every numeric setting with
// a flag, at its minimum, its maximum and just outside both, on the real command line. A value
// inside is accepted (the run goes on to the input, which does not exist: exit 1); one outside
// is refused before any work with exit 2 and a message naming the flag. Also: core and io never
// name a CLI flag, and the CLI and the studio each say a parameter in their own words.
#include "CliRunner.h"

#include "octrace/model/OptionTable.h"
#include "octrace/model/Render.h"
#include "octrace/util/Parameter.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace octrace::testcli;
namespace model = octrace::model;

namespace {

std::string numberText(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

/// The command line that gives option `o` the value `v`: its first command, an input that does
/// not exist (or, for options that apply to sphere scenes only, a tiny sphere scene written to
/// a folder that does not exist), and the options its check depends on.
std::vector<std::string> probe(const model::Option& o, const std::string& v) {
    std::string command = o.commands;
    command = command.substr(0, command.find(' '));
    const std::string missing = "/nonexistent-octrace-input/field.nc";
    std::vector<std::string> args{command};
    if (command == "sample") {
        args.push_back("noise");  // its output folder does not exist: refused (exit 1) before the field is made
    } else if (o.key == std::string("leaf_objects") || o.key == std::string("samples") || o.key == std::string("bounces")) {
        args.insert(args.end(), {"random:3", "--size", "8x8", "--renderer", "samet"});
    } else if (o.key == std::string("terrain_depth")) {
        args.push_back("/nonexistent-octrace-input/city.json");
    } else {
        args.push_back(missing);
    }
    const std::string output = command == "build" || command == "csg" ? "x.oct"
                               : command == "sample"                  ? "x.nrrd"
                               : command == "animate"                 ? "x.mp4"
                                                                      : "x.png";
    args.insert(args.end(), {"-o", "/nonexistent-octrace-output/" + output});
    // Options whose check reads another one.
    if (o.key == std::string("level") || o.key == std::string("terrain_depth"))
        args.insert(args.end(), {"--depth", numberText(model::opt::depth.max)});
    if (o.key == std::string("ortho_height")) args.insert(args.end(), {"--projection", "ortho"});
    if (o.key == std::string("width")) args.insert(args.end(), {"--size", v + "x1"});
    else if (o.key == std::string("height")) args.insert(args.end(), {"--size", "1x" + v});
    else args.insert(args.end(), {std::string("--") + o.flag, v});
    return args;
}

std::string said(const std::vector<std::string>& args) {
    std::string s;
    for (const auto& a : args) s += a + " ";
    return s;
}

}  // namespace

TEST(OptionTable, EveryNumericSettingIsAcceptedAtItsEndsAndRefusedJustOutsideOnTheCommandLine) {
    int probed = 0;
    for (const model::Option* o : model::allOptions()) {
        if (o->kind != model::OptionKind::Integer && o->kind != model::OptionKind::Number) continue;
        const bool sized = o->key == std::string("width") || o->key == std::string("height");
        if (!*o->flag && !sized) continue;
        const std::string flag = sized ? "--size" : std::string("--") + o->flag;
        // Just inside and just outside each finite end: an integer's step is 1; a number's is
        // a millionth of the range's scale.
        const double step = o->kind == model::OptionKind::Integer ? 1.0 : 1e-6 * std::max(1.0, std::abs(o->max - o->min) < 1e300 ? std::abs(o->max - o->min) : 1.0);
        std::vector<double> inside, outside;
        if (std::isfinite(o->min)) {
            inside.push_back(o->minOpen ? o->min + step : o->min);
            outside.push_back(o->minOpen ? o->min : o->min - step);
        }
        if (std::isfinite(o->max)) {
            inside.push_back(o->maxOpen ? o->max - step : o->max);
            outside.push_back(o->maxOpen ? o->max : o->max + step);
        }
        for (double v : inside) {
            const auto args = probe(*o, numberText(v));
            const Result r = run(args);
            EXPECT_EQ(r.code, 1) << said(args) << "\n" << r.err;
            EXPECT_EQ(r.err.find(flag + ":"), std::string::npos) << said(args) << "\n" << r.err;
        }
        for (double v : outside) {
            const auto args = probe(*o, numberText(v));
            const Result r = run(args);
            EXPECT_EQ(r.code, 2) << said(args) << "\n" << r.err;
            EXPECT_NE(r.err.find("octrace: " + flag + ": "), std::string::npos) << said(args) << "\n" << r.err;
        }
        ++probed;
    }
    EXPECT_GE(probed, 20);  // the loop really ran over the table
}

TEST(OptionTable, KeysAndFlagsAreUniqueAndEveryHelpStatesItsDefault) {
    std::map<std::string, int> keys;
    for (const model::Option* o : model::allOptions()) {
        EXPECT_EQ(keys[o->key]++, 0) << o->key;
        EXPECT_TRUE(std::regex_match(std::string(o->key), std::regex("[a-z][a-z0-9_]*"))) << o->key;
        EXPECT_NE(o->helpLine().find("(default "), std::string::npos) << o->key;
        if (o->kind == model::OptionKind::Integer || o->kind == model::OptionKind::Number) {
            EXPECT_TRUE(o->defaultText[0] || o->inRange(o->defaultValue)) << o->key << ": the default is outside the range";
        }
        if (o->kind == model::OptionKind::Choice) {
            EXPECT_FALSE(o->defaultSaid().empty()) << o->key;
        }
        std::istringstream commands(o->commands);
        for (std::string c; commands >> c;) {
            for (const model::Option* p : model::allOptions()) {
                EXPECT_FALSE(p != o && *o->flag && std::string(p->flag) == o->flag && p->takenBy(c))
                    << o->key << " and " << p->key << " are both --" << o->flag << " of " << c;
            }
        }
    }
}

TEST(OptionTable, TheLibrariesDefaultsAreTheTables) {
    // Core keeps its own defaults (it does not know the table); they must be the table's, so
    // that a renderer called without a front end draws what the front ends draw by default.
    const octrace::RenderSettings core;
    const model::RenderSpec spec;
    EXPECT_EQ(double(core.coherence.colourTolerance), model::opt::colourTolerance.defaultValue);
    EXPECT_EQ(core.coherence.branchUp, int(model::opt::branchUp.defaultValue));
    EXPECT_EQ(core.coherence.miss, model::opt::missCoherence.defaultChoice() == "on");
    EXPECT_EQ(core.spheres.samples, int(model::opt::samples.defaultValue));
    EXPECT_EQ(core.spheres.bounces, int(model::opt::bounces.defaultValue));
    EXPECT_EQ(core.ambient, float(model::opt::ambient.defaultValue));
    EXPECT_EQ(spec.coherence.colourTolerance, core.coherence.colourTolerance);
    EXPECT_EQ(spec.coherence.miss, core.coherence.miss);
    EXPECT_EQ(spec.spheres.samples, core.spheres.samples);
    EXPECT_EQ(spec.renderer, model::opt::renderer.defaultText);
    EXPECT_EQ(spec.fov, model::opt::fov.defaultValue);
    EXPECT_EQ(spec.width, int(model::opt::width.defaultValue));
}

TEST(OptionTable, CoreIoAndThePipelineNameParametersNeverCliFlags) {
    // A string literal of core/, io/ or app/model (the pipeline library) that names a flag ("--depth") would show the studio's
    // and Python's users a flag they do not have: messages name `depth` instead (Parameter.h).
    const std::filesystem::path root = std::filesystem::path(OCTRACE_SAMPLES).parent_path();
    const std::regex literal(R"("(?:[^"\\\n]|\\.)*")"), flag("--[a-z]");
    int files = 0;
    for (const char* dir : {"core", "io", "app/model"}) {
        for (const auto& e : std::filesystem::recursive_directory_iterator(root / dir)) {
            const std::string ext = e.path().extension().string();
            if (ext != ".cpp" && ext != ".h" && ext != ".inc") continue;
            ++files;
            std::ifstream in(e.path());
            int n = 0;
            for (std::string line; std::getline(in, line);) {
                ++n;
                const std::size_t comment = line.find("//");
                const std::string code = line.find('"') < comment ? line : line.substr(0, comment);
                for (auto m = std::sregex_iterator(code.begin(), code.end(), literal); m != std::sregex_iterator(); ++m)
                    EXPECT_FALSE(std::regex_search(m->str(), flag)) << e.path().string() << ":" << n << ": " << m->str();
            }
        }
    }
    EXPECT_GT(files, 100);
}

TEST(OptionTable, EachFrontEndSaysAParameterInItsOwnWords) {
    // One core error text, as each front end shows it.
    const std::string text = "more than the memory budget (" + octrace::param("max_memory") + "); try a smaller " +
                             octrace::param("depth") + " or fewer `AO rays`";
    EXPECT_EQ(model::sayForCli(text), "more than the memory budget (--max-memory); try a smaller --depth or fewer `AO rays`");
    EXPECT_EQ(model::sayForStudio(text), "more than the memory budget (max memory); try a smaller 'Depth' or fewer `AO rays`");
    EXPECT_EQ(model::sayForSession(text), "more than the memory budget (max memory); try a smaller surface.depth or fewer `AO rays`");
    EXPECT_EQ(model::sayForCli("a ` alone, `unknown_key` and `branch_up`"), "a ` alone, unknown key and --branch-up");
}

TEST(OptionTable, TheCliNamesItsFlagsInCoreErrors) {
    // A core error (the octree builder's memory budget) and an io error (a NetCDF file with
    // several variables), through the real CLI: they name --max-memory and --var.
    Scratch s;
    Result r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "12", "--max-memory", "2M", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("(--max-memory"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('`'), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "4", "--size", "16x16", "--branch-up", "2", "-o", s.path("b.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("--branch-up has no effect on renderer tile (only on linear and area and their variants)"), std::string::npos)
        << r.err;
}

TEST(OptionTable, CliDocShowsTheTable) {
    // docs/user/cli.md has a heading for every option with a flag, in the section of its command,
    // and right under it the line the table generates (scripts/cli_doc.py writes them).
    const std::filesystem::path doc = std::filesystem::path(OCTRACE_SAMPLES).parent_path() / "docs" / "user" / "cli.md";
    std::vector<std::string> lines;
    {
        std::ifstream in(doc);
        ASSERT_TRUE(in) << doc;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
    }
    int checked = 0;
    for (const model::Option* o : model::allOptions()) {
        if (!*o->flag) continue;
        const std::string heading = std::string("### --") + o->flag;
        std::size_t section = lines.size(), at = lines.size();
        for (std::size_t i = 0; i < lines.size(); ++i)
            if (lines[i].rfind("## octrace " + o->docCommand(), 0) == 0) section = i;
        for (std::size_t i = section + 1; i < lines.size() && lines[i].rfind("## ", 0) != 0; ++i)
            if (lines[i].rfind(heading, 0) == 0 && (lines[i].size() == heading.size() || lines[i][heading.size()] == ' ' ||
                                                    lines[i][heading.size()] == ',')) {
                at = i;
                break;
            }
        ASSERT_LT(at, lines.size()) << "no '" << heading << "' in the section of octrace " << o->docCommand()
                                    << " of docs/user/cli.md";
        ASSERT_LT(at + 1, lines.size());
        EXPECT_EQ(lines[at + 1], o->docLine()) << heading << ": run python3 scripts/cli_doc.py";
        ++checked;
    }
    EXPECT_GE(checked, 40);
}
