#pragma once
// A MetaImage header (.mhd with a data file, .mha with local data), parsed and checked by
// octrace, and its samples, read and decoded by octrace (internal). VTK 9.1's
// vtkMetaImageReader is not used: it ignores TransformMatrix, writes past its output array for
// MET_LONG_LONG and MET_ULONG_LONG samples (2 bytes for 60 samples, valgrind), and on a corrupt or
// short zlib stream prints "Uncompress failed" and returns samples it never decoded, as it
// does for every LOCAL stream whose header has no CompressedDataSize.
#include "octrace/util/Math.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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
    bool compressed = false;      ///< CompressedData = True (zlib or gzip)
    std::uint64_t compressedSize = 0;  ///< CompressedDataSize; 0 when absent (to the end of the data file)
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
    /// The bytes of every sample, uncompressed: DimSize x ElementType.
    std::uint64_t byteCount() const { return std::uint64_t(sampleCount()) * typeSize; }
    /// "WxHxD TYPE", as messages name the volume.
    std::string shapeText() const;
    /// The file that holds the samples: `path` for LOCAL data, else `dataFile`.
    const std::string& sampleFile() const { return dataFile == "LOCAL" ? path : dataFile; }
    /// The compressed bytes, given the size of the sample file: CompressedDataSize, else the
    /// rest of the file from dataOffset.
    std::uint64_t compressedBytes(std::uintmax_t fileBytes) const {
        return compressedSize ? compressedSize : (fileBytes > dataOffset ? fileBytes - dataOffset : 0);
    }

    /// Checks that the data file exists and holds every sample: the raw bytes, or compressed
    /// bytes (at least CompressedDataSize of them) that can inflate to them, deflate expanding
    /// at most 1032:1. Throws FileError naming the shortfall.
    void checkData() const;

    /// The samples, converted to float in file order: raw bytes, or compressed ones inflated
    /// until DimSize x ElementType bytes are out (so the work is bounded by the volume whatever
    /// the stream holds), in the file's byte order. Call after checkData(). Throws FileError
    /// when the file cannot be read, or the stream is corrupt, ends before every sample or
    /// holds more than them.
    std::vector<float> readSamples() const;
};

}  // namespace octrace::io::detail
