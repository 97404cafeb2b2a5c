#pragma once
/// @file ImageWriter.h
/// Writing a Frame to an image file whose format follows the file's extension
/// (the `-o OUT.png` / `-o OUT.exr` contract of the CLI).
#include "octrace/io/ImageWriteOptions.h"
#include "octrace/render/Frame.h"

#include <string>
#include <vector>

namespace octrace::io {

/// Writes `frame` to `path` as PNG (".png": 8-bit sRGB, see PngWriter), OpenEXR (".exr":
/// half RGBA + float Z, see ExrWriter) or TIFF (".tif", ".tiff": 8-bit sRGB, the PNG's pixels,
/// see TiffWriter); the extension is matched case-insensitively.
/// The file is written under a temporary name in the same folder and renamed over `path`
/// only when complete, so `path` never holds a partial file.
/// @throws UsageError if the extension is missing or not supported (the message names it and
///         lists imageExtensions()) — checked before anything is written.
/// @throws OutputError naming `path` and the reason if encoding or writing fails; no
///         temporary is left behind and an existing file at `path` is untouched.
/// Thread-safe (distinct paths, or the same path: the last rename wins).
void writeImage(const Frame& frame, const std::string& path, const ImageWriteOptions& options = {});

/// The supported extensions, lower case with the leading dot: {".png", ".exr", ".tif", ".tiff"}.
std::vector<std::string> imageExtensions();

}  // namespace octrace::io
