#pragma once
// The fields of a NRRD header that octrace uses, parsed from the header text (internal).
// VTK 9.1's vtkNrrdReader decodes the samples but ignores `space directions` (it keeps only
// their lengths) and flips rows for left-handed spaces, so geometry comes from here.
#include "octrace/util/Math.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace octrace::io::detail {

struct NrrdHeader {
    std::string path;            ///< the file holding the header (.nrrd or .nhdr)
    std::string magic;           ///< e.g. "NRRD0004"
    int dimension = 0;
    std::string type;            ///< normalised: int8 uint8 int16 uint16 int32 uint32 int64 uint64 float double
    std::size_t typeSize = 0;
    std::string encoding;        ///< normalised: raw, gzip or ascii
    std::string endian;          ///< little, big, or empty when not given
    ivec3 sizes{0};
    bool hasSpacings = false;
    dvec3 spacings{1.0};
    bool hasDirections = false;
    dmat3 directions{1.0};       ///< columns: world step of one sample along each axis (not normalised)
    bool hasOrigin = false;
    dvec3 origin{0.0};
    std::string space;           ///< `space` field (e.g. "left-posterior-superior"), may be empty
    std::string content;         ///< `content` field, may be empty
    std::map<std::string, std::string> keyValues;  ///< `key:=value` pairs
    std::vector<std::string> dataFiles;            ///< detached data files, absolute; empty: attached
    std::size_t headerBytes = 0; ///< offset of attached data in `path`

    /// Parses and checks the header of `path`.
    /// Throws FormatNotSupported (no NRRD magic) or FileError (malformed or unsupported header).
    static NrrdHeader parse(const std::string& path);

    std::size_t sampleCount() const { return std::size_t(sizes.x) * std::size_t(sizes.y) * std::size_t(sizes.z); }

    /// Checks that the data the header announces is there: detached files exist, raw data is
    /// long enough, ascii data has enough numbers. Throws FileError naming the shortfall.
    void checkData() const;
};

}  // namespace octrace::io::detail
