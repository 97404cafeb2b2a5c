#pragma once
/// @file ImageWriteOptions.h
/// What the image writers can be asked for beyond the Frame itself.

namespace octrace::io {

struct ImageWriteOptions {
    /// PNG: always write an alpha channel. Without it, the PNG gets one only when some pixel
    /// has alpha < 1 (so opaque renders stay RGB). EXR files always carry A.
    bool alpha = false;
    /// PNG and TIFF: the print resolution in dots per inch, recorded in a PNG's pHYs chunk and
    /// in a TIFF's XResolution / YResolution (ResolutionUnit inch) (0: none).
    int dpi = 0;
};

}  // namespace octrace::io
