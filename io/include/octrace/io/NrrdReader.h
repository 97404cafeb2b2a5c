#pragma once
/// @file NrrdReader.h
/// Reads NRRD volumes (.nrrd with attached data, .nhdr with detached data files or slices;
/// raw, gzip or ascii encoding; any scalar type) into a ScalarField.
#include "octrace/build/ScalarField.h"

#include <cstdint>
#include <string>

namespace octrace::io {

class NrrdReader {
public:
    /// Reads a 3-D scalar NRRD volume. Samples become float; NaN and inf samples are marked
    /// invalid. Geometry follows the NRRD header: `space origin` (or `axis mins`) is the
    /// origin, the columns of `space directions` give ScalarField::direction (normalised)
    /// and spacing (their lengths); `spacings` alone gives an axis-aligned grid. `name` is the
    /// header's `content` (else the file name without extension), `units` the key/value
    /// pair `units:=...` when present.
    /// @throws InputError if the file is missing, FormatNotSupported if it is not NRRD,
    ///         FileError if it is broken (truncated data, missing data file, bad spacing,
    ///         sheared directions, not 3-D, unsupported encoding or type).
    ///         LimitError if decoding the samples would need more than `memoryBudget` bytes
    ///         (0 = no limit), before they are allocated.
    /// Thread-safe (no shared state).
    static ScalarField read(const std::string& path, std::uint64_t memoryBudget = 0);

    /// Multi-line human-readable summary (format, type, encoding, dims, geometry, value range)
    /// for `octrace info`. Reads the data to find the value range. Throws as read().
    static std::string describe(const std::string& path, std::uint64_t memoryBudget = 0);
};

}  // namespace octrace::io
