#pragma once
// The fields of a MetaImage header (.mhd with a data file, .mha with local data) that octrace
// uses, parsed and checked before VTK reads the samples (internal). VTK 9.1's
// vtkMetaImageReader ignores TransformMatrix, so geometry comes from here.
#include "octrace/util/Math.h"

#include <cstddef>
#include <cstdint>
#include <string>

namespace octrace::io::detail {

struct MetaImageHeader {
    std::string path;             ///< the file holding the header
    ivec3 dims{0};                ///< DimSize
    dvec3 spacing{1.0};           ///< ElementSpacing (else ElementSize, else 1)
    dvec3 origin{0.0};            ///< Offset (or its synonyms Position, Origin)
    dmat3 direction{1.0};         ///< columns: TransformMatrix (or Rotation, Orientation) read 3 values per axis
    bool hasDirection = false;
    std::string elementType;      ///< e.g. "MET_SHORT"
    std::size_t typeSize = 0;
    bool compressed = false;      ///< CompressedData = True (zlib)
    bool bigEndian = false;       ///< BinaryDataByteOrderMSB / ElementByteOrderMSB
    std::string dataFile;         ///< "LOCAL" or the data file, absolute
    std::uint64_t dataOffset = 0; ///< where the samples start in the data file
    std::string anatomicalOrientation;  ///< as given (informational), may be empty

    /// Parses `text`, the beginning of `path` (at least the whole header, which ends with the
    /// ElementDataFile line). Throws FormatNotSupported when it is not a MetaImage header,
    /// FileError "PATH: ..." when it is malformed or asks for something octrace does not read
    /// (not 3-D, several channels, a file list, an unknown element type, HeaderSize -1).
    static MetaImageHeader parseText(const std::string& path, const std::string& text);
    /// Reads the beginning of `path` and parses it.
    static MetaImageHeader parse(const std::string& path);

    std::size_t sampleCount() const { return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z); }

    /// Checks that the data file exists and, for uncompressed data, holds every sample.
    /// Throws FileError naming the shortfall.
    void checkData() const;
};

}  // namespace octrace::io::detail
