#pragma once
// Private to the image writers: the checks every writer makes before encoding a Frame.
#include "octrace/io/AtomicFile.h"
#include "octrace/render/Frame.h"
#include "octrace/util/Error.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// @throws OutputError("<format>: ...") if the frame has no pixels, or a buffer the format
///         needs does not hold width·height values.
inline void checkFrameForWriting(const Frame& frame, const char* format, bool needsDepth) {
    const std::string size = std::to_string(frame.width) + "x" + std::to_string(frame.height);
    if (frame.width <= 0 || frame.height <= 0)
        throw OutputError(std::string(format) + ": the frame is empty (" + size + " pixels)");
    const std::size_t n = std::size_t(frame.width) * std::size_t(frame.height);
    if (frame.rgba.size() != n)
        throw OutputError(std::string(format) + ": the frame holds " + std::to_string(frame.rgba.size()) +
                          " colour values for " + size + " pixels");
    if (needsDepth && frame.depth.size() != n)
        throw OutputError(std::string(format) + ": the frame holds " + std::to_string(frame.depth.size()) +
                          " depth values for " + size + " pixels");
}

/// Encodes in memory with `encode()` (throwing OutputError), then writes the bytes to `path`
/// atomically; an encoding failure is reported with the path and leaves no file.
template <class Encode>
void encodeAndWrite(const std::string& path, Encode encode) {
    std::vector<std::uint8_t> bytes;
    try {
        bytes = encode();
    } catch (const OutputError& e) {
        throw OutputError("cannot write '" + path + "': " + e.what());
    }
    writeFileAtomically(path, bytes);
}

}  // namespace octrace::io::detail
