// Fuzz target: NRRD files, from the header text (NrrdHeader: fields, sizes, spacings, space
// directions, data file names and patterns) through the data checks to VTK's decoding
// (NrrdReader::read). The input is the bytes of a .nrrd file. It is written to a private
// folder that also holds small detached data files, so that headers naming 'data file: data.raw'
// or 'data file: slice.%d.raw 1 4 1' reach the decoding too.
#include "FuzzSupport.h"
#include "octrace/io/NrrdReader.h"
#include "octrace/util/Error.h"

namespace {

const octrace::fuzz::ScratchDir& scratch() {
    static const octrace::fuzz::ScratchDir dir;
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    scratch().writePattern("data.raw", 4096);
    for (int s = 1; s <= 4; ++s) scratch().writePattern("slice." + std::to_string(s) + ".raw", 1024);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = scratch().write("input.nrrd", data, size);
    try {
        octrace::ScalarField f = octrace::io::NrrdReader::read(path, octrace::fuzz::kMemoryBudget);
        (void)f;
    } catch (const octrace::Error&) {
        // A clean refusal: what we want for broken input.
    }
    return 0;
}
