// Fuzz target: the CLI's option parsing (app/cli: OptionParser and the value parsers of
// numbers, integers, vectors, colours, sizes, regions, renderer and colormap names) through
// the real commands. The input is a command line, arguments separated by NUL bytes, the
// first one the command (render, export, info, sample). "--help" goes first, so that a command line
// that parses prints the help and returns instead of reading or writing files; every option
// after it is still parsed and checked.
#include "Commands.h"
#include "FuzzSupport.h"
#include "octrace/util/Error.h"

#include <cstdio>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    if (!std::freopen("/dev/null", "w", stdout)) return 1;  // the help texts
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> args(1);
    for (std::size_t i = 0; i < size; ++i) {
        if (data[i] == 0) args.emplace_back();
        else args.back() += char(data[i]);
    }
    const std::string command = args[0];
    args[0] = "--help";
    try {
        if (command == "render") octrace::cli::runRender(args);
        else if (command == "export") octrace::cli::runExport(args);
        else if (command == "info") octrace::cli::runInfo(args);
        else if (command == "sample") octrace::cli::runSample(args);
        else if (command == "slice") octrace::cli::runSlice(args);
    } catch (const octrace::UsageError&) {
        // The only error a command line alone may cause.
    }
    return 0;
}
