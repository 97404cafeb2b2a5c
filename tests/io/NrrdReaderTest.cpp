#include "IoTestSupport.h"

#include "octrace/io/NrrdReader.h"
#include "octrace/util/Error.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <vector>

using namespace octrace;

namespace {
double sum(const ScalarField& f) { return std::accumulate(f.values.begin(), f.values.end(), 0.0); }

// Reading tests/data/invalid/FILE throws FileError with `message` in it.
void expectCorpusRefusal(const std::string& file, const std::string& message) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/" + file)), FileError, message);
}
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

// Found by fuzz_nrrd (docs/dev/fuzzing.md): vtkNrrdReader ends the header at a NUL byte and
// then never returned; the header parser refuses it first, in any line.
TEST(NrrdReader, RefusesANulByteInTheHeaderInsteadOfHanging) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_nul_in_header.nrrd")), FileError,
                      "header line 6 holds a NUL byte: a NRRD header is text");
    test::TempDir dir;
    const std::string path = dir.file("nul_in_magic_line.nrrd");
    const std::string bytes("NRRD0004\0\0\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n01234567", 72);
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    EXPECT_THROW_WITH(io::NrrdReader::read(path), FileError, "header line 1 holds a NUL byte");
}

// Found by fuzz_nrrd: two files of two slices each; vtkNrrdReader reads one slice per file
// and indexed its list of two file names with slices 2 and 3 (SEGV).
TEST(NrrdReader, RefusesSplitDataWithFewerFilesThanSlices) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_fewer_files_than_slices.nhdr")), FileError,
                      "header lists 2 data files for 4 slices along the last axis (split data must hold one slice "
                      "per file)");
}

// Found by fuzz_nrrd: vtkNrrdReader went round its header loop forever when the last line of a
// detached header had no newline (a plain and valid way to save one).
TEST(NrrdReader, ReadsADetachedHeaderWhoseLastLineHasNoNewline) {
    test::TempDir dir;
    std::vector<unsigned char> bytes(16 * 8 * 2);
    std::iota(bytes.begin(), bytes.end(), 0);
    std::ofstream(dir.file("data.raw"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    std::ofstream(dir.file("no_final_newline.nhdr"))
        << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 8 2\nencoding: raw\ndata file: data.raw";
    ScalarField f = io::NrrdReader::read(dir.file("no_final_newline.nhdr"));
    EXPECT_EQ(f.dims, ivec3(16, 8, 2));
    EXPECT_EQ(sum(f), 255.0 * 256.0 / 2.0);
    std::ofstream(dir.file("list.nhdr")) << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16 8 2\nencoding: raw\n"
                                            "data file: LIST\ndata.raw\ndata.raw";
    EXPECT_EQ(io::NrrdReader::read(dir.file("list.nhdr")).dims, ivec3(16, 8, 2));
}

// Absurd headers are refused before VTK allocates what they announce.
TEST(NrrdReader, RefusesAGzipVolumeLargerThanItsStreamCanInflateToBeforeAllocatingIt) {
    EXPECT_THROW_WITH(io::NrrdReader::read(test::testData("invalid/invalid_oversized_gzip.nrrd")), FileError,
                      "gzip data truncated: header says 2048x2048x1024 double = 34359738368 bytes, the file's 29 bytes "
                      "of gzip data inflate to at most 29928 (deflate expands at most 1032:1)");
}

TEST(NrrdReader, RefusesDataFilePatternsThatCouldOverflowOrPadForever) {
    test::TempDir dir;
    auto header = [&](const std::string& pattern) {
        const std::string path = dir.file("pattern.nhdr");
        std::ofstream(path) << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 2\nencoding: raw\ndata file: "
                            << pattern << "\n";
        return path;
    };
    EXPECT_THROW_WITH(io::NrrdReader::read(header("s%999999999d 1 2 1")), FileError,
                      "must hold exactly one integer conversion like %03d (width at most 16)");
    EXPECT_THROW_WITH(io::NrrdReader::read(header("s%d 2147483646 2147483647 1")), FileError,
                      "data file pattern range 2147483646 2147483647 1 is invalid");
    EXPECT_THROW_WITH(io::NrrdReader::read(header("s%d -2000000000 2000000000 4000")), FileError, "is invalid");
    EXPECT_THROW_WITH(io::NrrdReader::read(header("s%d 1 2 x")), FileError, "is invalid");
    EXPECT_THROW_WITH(io::NrrdReader::read(header("s%03d 1 2 1")), FileError, "s001' not found");
}

// The absurd headers of tests/data/invalid: refused from the header alone. None of these
// files holds data for what it announces, so a reader that allocated first would be caught
// by the sanitizer build (allocator out of memory) or take gigabytes here.
TEST(NrrdReader, RefusesDimensionsOfABillionOrSampleCountsBeyondTwoToTheThirtyTwo) {
    expectCorpusRefusal("invalid_huge_sizes.nrrd",
                        "size of axis 0 is 1000000000, more than the 16777216 (2^24) octrace reads along one axis");
    expectCorpusRefusal("invalid_too_many_samples.nrrd", "sizes 4000 x 4000 x 4000 exceed the supported 2^32 samples");
    expectCorpusRefusal("invalid_size_overflow.nrrd",
                        "size of axis 0 is 18446744073709551617, more than the 16777216 (2^24)");
}

TEST(NrrdReader, RefusesNegativeInfiniteOrZeroSpacingAndANaNOrigin) {
    expectCorpusRefusal("invalid_negative_spacing.nrrd", "spacing along axis 2 must be positive, is '-2'");
    expectCorpusRefusal("invalid_infinite_spacing.nrrd", "spacing along axis 1 must be positive, is 'inf'");
    expectCorpusRefusal("invalid_zero_space_direction.nrrd",
                        "space direction of axis 1 has zero length (spacing must be positive)");
    expectCorpusRefusal("invalid_nan_origin.nrrd", "'space origin': 'nan' is not a finite number");
}

// Finite spacings can still make a grid no double-precision camera can frame: 7 x 1e308
// overflows, 7 x 1e-310 is denormal (the render used to fail with "camera position and
// look-at point coincide", exit 2, as if the command line were wrong).
TEST(NrrdReader, RefusesAGridWhoseWorldExtentOverflowsOrIsDenormal) {
    expectCorpusRefusal("invalid_infinite_extent.nrrd",
                        "world bounds 0..inf x 0..7 x 0..7 go beyond the supported +-1e+30 (origin or spacing absurd)");
    expectCorpusRefusal("invalid_tiny_extent.nrrd", "world extent 7e-310 is too small to place the grid");
}

// A 1024^3 float volume whose 4 GiB of data are there (a sparse file): over a 1 GiB budget it
// is refused before VTK decodes it.
TEST(NrrdReader, RefusesSamplesBeyondTheMemoryBudgetBeforeDecodingThem) {
    test::TempDir dir;
    const std::string path = dir.file("big.nrrd");
    const std::string header = "NRRD0004\ntype: float\ndimension: 3\nsizes: 1024 1024 1024\nendian: little\nencoding: raw\n\n";
    std::ofstream(path, std::ios::binary) << header;
    std::filesystem::resize_file(path, header.size() + (std::uintmax_t(4) << 30));
    EXPECT_THROW_WITH(io::NrrdReader::read(path, std::uint64_t(1) << 30), LimitError,
                      path + ": reading 1024x1024x1024 float samples needs about 9 GiB, more than the memory budget of "
                             "1 GiB (`max_memory`)");
    EXPECT_THROW_WITH(io::NrrdReader::describe(path, std::uint64_t(1) << 30), LimitError, "needs about 9 GiB");
    // Within the budget it is read as usual.
    const std::string small = dir.file("small.nrrd");
    std::ofstream(small, std::ios::binary) << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n"
                                           << std::string(64, '\x07');
    EXPECT_EQ(io::NrrdReader::read(small, 64 * 6).dims, ivec3(4));
    EXPECT_THROW_WITH(io::NrrdReader::read(small, 64 * 5 - 1), LimitError, "4x4x4 uint8 samples needs about 320 bytes");
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
