// Fuzz target: MetaImage files, from the header text (MetaImageHeader: DimSize, spacing,
// offset, TransformMatrix, element types, byte order, compression, data file) through the data
// checks to the decoding and inflating of the samples (VolumeReader::read). The input is the bytes of a file; it is read
// once as 'input.mha' (samples after the header, or a detached file the header names) and once
// as 'input.mhd'. The private folder also holds 'data.raw' (4 KiB), so headers naming a
// detached data file reach the decoding.
#include "FuzzSupport.h"
#include "octrace/io/VolumeReader.h"
#include "octrace/util/Error.h"

namespace {

const octrace::fuzz::ScratchDir& scratch() {
    static const octrace::fuzz::ScratchDir dir;
    return dir;
}

void readAs(const char* name, const std::uint8_t* data, std::size_t size) {
    const std::string path = scratch().write(name, data, size);
    try {
        octrace::ScalarField f =
            octrace::io::VolumeReader::read(path, octrace::io::VolumeReader::Format::MetaImage, octrace::fuzz::kMemoryBudget);
        (void)f;
    } catch (const octrace::Error&) {
        // A clean refusal: what we want for broken input.
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    scratch().writePattern("data.raw", 4096);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    readAs("input.mha", data, size);
    readAs("input.mhd", data, size);
    return 0;
}
