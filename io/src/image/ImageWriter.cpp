#include "octrace/io/ImageWriter.h"

#include "octrace/io/ExrWriter.h"
#include "octrace/io/PngWriter.h"
#include "octrace/io/TiffWriter.h"
#include "octrace/util/Error.h"

#include <filesystem>

namespace octrace::io {
namespace {

std::string supportedList() {
    std::string s;
    for (const auto& e : imageExtensions()) s += (s.empty() ? "" : ", ") + e;
    return s;
}

std::string lowerAscii(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return s;
}

}  // namespace

std::vector<std::string> imageExtensions() { return {".png", ".exr", ".tif", ".tiff"}; }

void writeImage(const Frame& frame, const std::string& path, const ImageWriteOptions& options) {
    const std::string ext = std::filesystem::path(path).extension().string();
    const std::string lower = lowerAscii(ext);
    if (lower == ".png") return PngWriter::write(frame, path, options);
    if (lower == ".exr") return ExrWriter::write(frame, path, options);
    if (lower == ".tif" || lower == ".tiff") return TiffWriter::write(frame, path, options);
    if (ext.empty())
        throw UsageError("output '" + path + "' has no file extension to choose the image format (supported: " +
                         supportedList() + ")");
    throw UsageError("unsupported image extension '" + ext + "' in '" + path + "' (supported: " + supportedList() +
                     ")");
}

}  // namespace octrace::io
