#include "IoTestSupport.h"

#include "octrace/io/NrrdReader.h"
#include "octrace/util/Error.h"

#include <numeric>

using namespace octrace;

namespace {
double sum(const ScalarField& f) { return std::accumulate(f.values.begin(), f.values.end(), 0.0); }
}  // namespace

// Expected values below were computed independently with numpy from the raw/gzip bytes.
TEST(NrrdReader, ReadsGzipChestCtWithItsSpacing) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/lidc2_chest_ct.nrrd");
    ScalarField f = io::NrrdReader::read(path);
    EXPECT_EQ(f.dims, ivec3(256, 256, 133));
    EXPECT_DOUBLE_EQ(f.spacing.x, 1.40625);
    EXPECT_DOUBLE_EQ(f.spacing.y, 1.40625);
    EXPECT_DOUBLE_EQ(f.spacing.z, 2.5);
    EXPECT_EQ(f.origin, dvec3(0.0));
    EXPECT_EQ(f.direction, dmat3(1.0));
    auto [lo, hi] = f.validRange();
    EXPECT_EQ(lo, 0.0f);
    EXPECT_EQ(hi, 255.0f);
    EXPECT_DOUBLE_EQ(sum(f), 61489178.0);
    EXPECT_EQ(f.values[f.index(128, 128, 66)], 128.0f);
    EXPECT_EQ(f.values[f.index(113, 27, 66)], 102.0f);  // rows are not flipped:
    EXPECT_EQ(f.values[f.index(113, 228, 66)], 0.0f);   // its mirror row is air
}

TEST(NrrdReader, ReadsDetachedRawSlicesInFileOrder) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/headsq_raw/quarter.nhdr");
    ScalarField f = io::NrrdReader::read(path);
    EXPECT_EQ(f.name, "quarter");
    EXPECT_EQ(f.dims, ivec3(64, 64, 93));
    EXPECT_DOUBLE_EQ(f.spacing.x, 3.2);
    EXPECT_DOUBLE_EQ(f.spacing.y, 3.2);
    EXPECT_DOUBLE_EQ(f.spacing.z, 1.5);
    auto [lo, hi] = f.validRange();
    EXPECT_EQ(lo, 0.0f);
    EXPECT_EQ(hi, 3926.0f);
    EXPECT_DOUBLE_EQ(sum(f), 193392317.0);
    // "space: 3D-left-handed" makes VTK flip rows; octrace keeps the file's order.
    EXPECT_EQ(f.values[f.index(32, 10, 46)], 270.0f);
    EXPECT_EQ(f.values[f.index(32, 50, 46)], 1009.0f);
}

TEST(NrrdReader, MissingFileIsAnInputError) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/no_such_file.nrrd")), InputError, "no such file");
}

// The invalid-input corpus (see tests/data/invalid/README.md).
TEST(NrrdReader, RefusesTruncatedRawData) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_truncated.nrrd")), FileError,
                      "data truncated: header says 16x16x16 float = 16384 bytes of data, the file has 1000");
}

TEST(NrrdReader, RefusesWrongMagicAsNotThisFormat) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_magic.nrrd")), FormatNotSupported,
                      "not a NRRD file: it starts with 'NRRX0004'");
}

TEST(NrrdReader, RefusesEmptyFile) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_empty.nrrd")), FileError,
                      "file is empty (0 bytes)");
}

TEST(NrrdReader, RefusesZeroOrNegativeSpacing) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_bad_spacing.nhdr")), FileError,
                      "spacing along axis 1 must be positive, is '0'");
}

TEST(NrrdReader, RefusesMissingDetachedDataFile) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_missing_data_file.nhdr")), FileError,
                      "no_such_data_file.raw' not found");
}

TEST(NrrdReader, RefusesTwoDimensionalImage) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_not_3d.nrrd")), FileError,
                      "expected a 3-D scalar volume, header says 'dimension: 2'");
}

TEST(NrrdReader, RefusesShortGzipStream) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_truncated_gzip.nrrd")), FileError,
                      "gzip data truncated: header says 16x16x16 uint8 = 4096 bytes, the stream inflates to 100");
}

TEST(NrrdReader, RefusesShearedSpaceDirections) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_sheared.nrrd")), FileError,
                      "space directions of axes 0 and 1 are not perpendicular (60 degrees)");
}

TEST(NrrdReader, ErrorMessagesStartWithThePath) {
    std::string path = test::testData("invalid/invalid_truncated.nrrd");
    try {
        io::NrrdReader::read(path);
        FAIL() << "no exception";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    }
}

TEST(NrrdReader, DescribeNamesFormatGeometryAndRange) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/headsq_raw/quarter.nhdr");
    std::string text = io::NrrdReader::describe(path);
    EXPECT_NE(text.find("format: NRRD (NRRD0004), int16, raw encoding, 93 detached data file(s)"), std::string::npos) << text;
    EXPECT_NE(text.find("valid range 0 .. 3926"), std::string::npos) << text;
    EXPECT_NE(text.find("spacing: 3.2 x 3.2 x 1.5"), std::string::npos) << text;
    EXPECT_NE(text.find("world bounds: (0, 0, 0) .. (201.6, 201.6, 138)"), std::string::npos) << text;
}
