// Fuzz target: DICOM series assembly, from GDCM's parsing of each file's header (DicomFile:
// sizes, frame counts, functional groups, positions, orientations, spacings, rescale) through
// the grouping by series, the ordering along the slice normal, spacing and gantry-tilt checks
// (DicomSeries) to the decoding of the pixel data and the resampling of a sheared stack
// (DicomReader::read). The input is up to 4 files joined by the line "OCTRACE-NEXT-FILE"
// (see fuzz_dicom.dict); they are written to a private folder, which is read as a series.
#include "FuzzSupport.h"
#include "octrace/io/DicomReader.h"
#include "octrace/util/Error.h"

#include <filesystem>
#include <string_view>

namespace {

const octrace::fuzz::ScratchDir& scratch() {
    static const octrace::fuzz::ScratchDir dir;
    return dir;
}

constexpr std::string_view kSeparator = "\nOCTRACE-NEXT-FILE\n";
constexpr int kMaxFiles = 4;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    std::filesystem::create_directories(scratch().path("series"));
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    std::size_t start = 0;
    for (int n = 0; n < kMaxFiles; ++n) {
        const std::string name = "series/f" + std::to_string(n) + ".dcm";
        if (start > bytes.size()) {
            std::filesystem::remove(scratch().path(name));
            continue;
        }
        std::size_t end = n + 1 < kMaxFiles ? bytes.find(kSeparator, start) : std::string_view::npos;
        if (end == std::string_view::npos) end = bytes.size();
        scratch().write(name, bytes.data() + start, end - start);
        start = end == bytes.size() ? bytes.size() + 1 : end + kSeparator.size();
    }
    try {
        // 2-D fields accepted, so that a single image is decoded too, as slice reads it.
        octrace::ScalarField f = octrace::io::DicomReader::read(scratch().path("series"), {}, 0, -1, true);
        (void)f;
    } catch (const octrace::Error&) {
        // A clean refusal: what we want for broken input.
    }
    return 0;
}
