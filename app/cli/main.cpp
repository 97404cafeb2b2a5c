// octrace command-line entry point: dispatches to the sub-commands and maps errors to exit
// codes (0 success, 2 command-line misuse, 1 anything found while reading or writing).
#include "Commands.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"
#include "octrace/model/OptionTable.h"
#include "octrace/util/Log.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

const char* kTopHelp =
    "octrace " OCTRACE_VERSION " - octree ray casting of scientific volumes\n"
    "\n"
    "usage: octrace COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  render INPUT -o OUT   build the isosurface octree of a field and render it to OUT (.png, .exr, .tif)\n"
    "  export INPUT -o OUT   build the isosurface octree and write it as surfels to a point cloud (.ply)\n"
    "  build INPUT -o OUT    build the octree and write it to an octree file (.oct), an INPUT of every command\n"
    "  csg A OP B -o OUT     union, intersection or difference of fields, volume octree files and solids (.oct)\n"
    "  slice INPUT -o OUT    an axial, coronal, sagittal or x/y/z slice of a field, greyed by a window or coloured (.png, .exr, .tif)\n"
    "  animate INPUT -o OUT  one surface per time step of a field, rendered as an MP4 video (.mp4)\n"
    "  info INPUT...         describe inputs: format, variables, units, value ranges, grid, bounds\n"
    "  sample NAME -o OUT    write an analytic sample field (sphere, torus, gyroid, noise, spheres) as NRRD\n"
    "  options               every setting: flag, range, default, session member, studio control\n"
    "\n"
    "INPUT is a NetCDF file (.nc, .cdf), a Zarr v2 store (its folder), a NRRD file (.nrrd, .nhdr), a DICOM\n"
    "file or folder, an octree file (.oct), or analytic:NAME[:SAMPLES].\n"
    "Run 'octrace COMMAND --help' for the options of a command; see docs/user/cli.md.\n";

}  // namespace

int main(int argc, char** argv) {
    // Ctrl-C or a kill while an output is being written must not leave its temporary behind.
    octrace::io::removeTemporariesOnSignals();
    // Core and io name parameters by key (util/Parameter.h); the CLI says its flags.
    octrace::log::setWording([](const std::string& text) { return octrace::model::sayForCli(text); });
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::fputs(kTopHelp, stderr);
        return 2;
    }
    const std::string cmd = args[0];
    std::vector<std::string> rest(args.begin() + 1, args.end());
    try {
        if (cmd == "--help" || cmd == "-h" || cmd == "help") {
            std::fputs(kTopHelp, stdout);
            return 0;
        }
        if (cmd == "--version") {
            std::puts("octrace " OCTRACE_VERSION);
            return 0;
        }
        if (cmd == "render") return octrace::cli::runRender(rest);
        if (cmd == "info") return octrace::cli::runInfo(rest);
        if (cmd == "sample") return octrace::cli::runSample(rest);
        if (cmd == "options") return octrace::cli::runOptions(rest);
        if (cmd == "export") return octrace::cli::runExport(rest);
        if (cmd == "build") return octrace::cli::runBuild(rest);
        if (cmd == "csg") return octrace::cli::runCsg(rest);
        if (cmd == "slice") return octrace::cli::runSlice(rest);
        if (cmd == "animate") return octrace::cli::runAnimate(rest);
        throw octrace::UsageError("unknown command '" + cmd + "' (commands: render, export, build, csg, slice, animate, info, sample, options)");
    } catch (const octrace::UsageError& e) {
        std::fprintf(stderr, "octrace: %s\nTry 'octrace %s --help'.\n", octrace::model::sayForCli(e.what()).c_str(),
                     (cmd == "render" || cmd == "export" || cmd == "build" || cmd == "csg" || cmd == "slice" || cmd == "animate" || cmd == "info" || cmd == "sample" || cmd == "options") ? cmd.c_str() : "");
        return 2;
    } catch (const octrace::Error& e) {
        std::fprintf(stderr, "octrace: error: %s\n", octrace::model::sayForCli(e.what()).c_str());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "octrace: error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "octrace: internal error: %s\n", e.what());
        return 1;
    }
}
