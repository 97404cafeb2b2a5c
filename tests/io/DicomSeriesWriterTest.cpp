// The DICOM series writer against the reader: the NRRD volumes of ../shared/data/medical
// written as series with chosen geometry (shuffled names, descending instance numbers, a
// rotated direction, slopes and intercepts that change per slice, a sheared stack) read back
// to the same values at the same world positions.
#include "IoTestSupport.h"

#include "octrace/io/DicomReader.h"
#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace octrace;

namespace {

void expectSameGeometry(const ScalarField& got, const ScalarField& want, double tol) {
    EXPECT_EQ(got.dims, want.dims);
    EXPECT_LT(glm::length(got.origin - want.origin), tol);
    EXPECT_LT(glm::length(got.spacing - want.spacing), tol);
    for (int a = 0; a < 3; ++a) EXPECT_LT(glm::length(got.direction[a] - want.direction[a]), 1e-12) << "axis " << a;
    // World positions of the far corner.
    EXPECT_LT(glm::length(got.worldFromGrid(got.dims.x - 1, got.dims.y - 1, got.dims.z - 1) -
                          want.worldFromGrid(want.dims.x - 1, want.dims.y - 1, want.dims.z - 1)),
              tol);
}

/// Geometry within `tol` mm and identical voxels.
void expectIdentical(const ScalarField& got, const ScalarField& want, double tol) {
    expectSameGeometry(got, want, tol);
    EXPECT_TRUE(got.values == want.values) << "voxels differ";
}

/// The chest CT's 0..255 intensities as Hounsfield units: the estimate docs/dev/medical.md
/// explains (8 HU per step, 0 at -1000 HU).
void toHounsfield(ScalarField& f) {
    for (float& v : f.values) v = 8.0f * v - 1000.0f;
    f.units = "HU";
}

}  // namespace

TEST(DicomSeriesWriter, TheChestCtWrittenShuffledAndDescendingWithPerSliceRescaleReadsBackIdentically) {
    OCTRACE_SHARED_FILE_OR_SKIP(nrrd, "medical/lidc2_chest_ct.nrrd");
    ScalarField ct = io::readField(nrrd);
    toHounsfield(ct);
    test::TempDir dir;
    io::DicomSeriesWriteOptions o;
    o.modality = "CT";
    o.description = "lidc2 chest";
    o.descending = true;
    o.shuffleSeed = 7;
    // Intercepts -1000, -1008, -1016 in turn: the stored values change, the HU do not.
    o.rescale = [](int k) { return dvec2(8.0, -1000.0 - 8.0 * (k % 3)); };
    const std::vector<std::string> names = io::DicomSeriesWriter::write(ct, dir.file("series"), o);
    ASSERT_EQ(names.size(), std::size_t(ct.dims.z));
    // The names are not in slice order.
    EXPECT_FALSE(std::is_sorted(names.begin(), names.end()));
    const ScalarField back = io::DicomReader::read(dir.file("series"));
    EXPECT_EQ(back.units, "HU");
    EXPECT_EQ(back.name, "CT");
    expectIdentical(back, ct, 1e-9);
}

TEST(DicomSeriesWriter, TheHeadMrWithARotatedDirectionAndAnOffsetOriginReadsBackIdentically) {
    OCTRACE_SHARED_FILE_OR_SKIP(nhdr, "medical/headsq_raw/quarter.nhdr");
    ScalarField head = io::readField(nhdr);
    // A rotation of 30 degrees about z then 20 about x, right-handed, and an origin off zero.
    const double a = glm::radians(30.0), b = glm::radians(20.0);
    const dmat3 rz(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
    const dmat3 rx(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
    head.direction = rx * rz;
    head.origin = dvec3(-101.25, 37.5, -12.125);
    test::TempDir dir;
    io::DicomSeriesWriteOptions o;
    o.modality = "MR";
    o.shuffleSeed = 3;
    io::DicomSeriesWriter::write(head, dir.file("mr"), o);
    const ScalarField back = io::DicomReader::read(dir.file("mr"));
    EXPECT_EQ(back.units, "");
    // Positions and cosines go through 16-character decimal strings (DICOM's DS).
    expectIdentical(back, head, 1e-9);
}

TEST(DicomSeriesWriter, AShearedStackIsReadAsAGantryTiltAndResampledExactlyAtWholeRows) {
    OCTRACE_SHARED_FILE_OR_SKIP(nrrd, "medical/lidc2_chest_ct.nrrd");
    ScalarField head = io::readField(nrrd);
    test::TempDir dir;
    io::DicomSeriesWriteOptions o;
    o.modality = "MR";  // values as stored
    o.shearRows = 1.0;  // one row (1.40625 mm) further along the columns per slice (2.5 mm): 29 degrees
    io::DicomSeriesWriter::write(head, dir.file("tilt"), o);
    test::LogCapture log;
    const ScalarField back = io::DicomReader::read(dir.file("tilt"));
    const std::string tilt = "gantry tilt of " + std::to_string(glm::degrees(std::atan(1.40625 / 2.5))).substr(0, 5);
    EXPECT_TRUE(std::any_of(log.warnings.begin(), log.warnings.end(),
                            [&](const std::string& w) { return w.find(tilt) != std::string::npos; }))
        << tilt << " vs " << (log.warnings.empty() ? "no warning" : log.warnings[0]);
    const ivec3 d = head.dims;
    ASSERT_EQ(back.dims, ivec3(d.x, d.y + d.z - 1, d.z));
    EXPECT_LT(glm::length(back.origin - head.origin), 1e-9);
    EXPECT_NEAR(back.spacing.z, head.spacing.z, 1e-12);
    // Slice k's row j lies k rows further on: sample (i, j + k, k) of the grid.
    std::size_t wrong = 0, masked = 0;
    for (int k = 0; k < d.z; ++k)
        for (int j = 0; j < back.dims.y; ++j)
            for (int i = 0; i < d.x; ++i) {
                const std::size_t at = back.index(i, j, k);
                const int src = j - k;
                if (src < 0 || src >= d.y) masked += back.isValid(at);
                else wrong += !back.isValid(at) || back.values[at] != head.values[head.index(i, src, k)];
            }
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(masked, 0u) << "samples outside their slice must be masked";
}

TEST(DicomSeriesWriter, TheStoredWindowAndMonochrome1ReachTheField) {
    ScalarField f;
    f.dims = ivec3(4, 3, 3);
    f.spacing = dvec3(0.5, 0.75, 2.0);
    f.values.resize(f.sampleCount());
    for (std::size_t i = 0; i < f.values.size(); ++i) f.values[i] = float(i) - 10.0f;
    test::TempDir dir;
    io::DicomSeriesWriteOptions o;
    o.window = {40.0, 400.0};
    o.monochrome1 = true;
    io::DicomSeriesWriter::write(f, dir.file("s"), o);
    const ScalarField back = io::DicomReader::read(dir.file("s"));
    EXPECT_EQ(back.window.centre, 40.0);
    EXPECT_EQ(back.window.width, 400.0);
    EXPECT_TRUE(back.invertedGrey);
    EXPECT_TRUE(back.values == f.values);
    // Without them: no window, not inverted.
    io::DicomSeriesWriter::write(f, dir.file("plain"), {});
    const ScalarField plain = io::DicomReader::read(dir.file("plain"));
    EXPECT_FALSE(plain.window.valid());
    EXPECT_FALSE(plain.invertedGrey);
}

TEST(DicomSeriesWriter, RefusesValuesThatAreNotInt16OnceRescaledAndMaskedSamples) {
    ScalarField f;
    f.dims = ivec3(2, 2, 2);
    f.values = {0, 1, 2, 3, 4, 5, 6, 7.5f};
    test::TempDir dir;
    EXPECT_THROW_WITH(io::DicomSeriesWriter::write(f, dir.file("a")), OutputError, "is not an int16 once rescaled");
    f.values[7] = 40000.0f;
    EXPECT_THROW_WITH(io::DicomSeriesWriter::write(f, dir.file("b")), OutputError, "is not an int16 once rescaled");
    f.values[7] = 7.0f;
    f.valid.assign(8, 1);
    f.valid[3] = 0;
    EXPECT_THROW_WITH(io::DicomSeriesWriter::write(f, dir.file("c")), OutputError, "masked samples");
}

// A colour image is refused by its PhotometricInterpretation, naming it, even with one sample
// per pixel (a palette): the file is the writer's with the value replaced in place.
TEST(DicomReader, RefusesColourImagesByTheirPhotometricInterpretation) {
    ScalarField f;
    f.dims = ivec3(2, 2, 2);
    f.values = {0, 1, 2, 3, 4, 5, 6, 7};
    test::TempDir dir;
    const std::vector<std::string> names = io::DicomSeriesWriter::write(f, dir.file("s"), {});
    const std::string file = dir.file("s/" + names[0]);
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        bytes = s.str();
    }
    const std::size_t at = bytes.find("MONOCHROME2 ");
    ASSERT_NE(at, std::string::npos);
    bytes.replace(at, 12, "RGB         ");
    std::ofstream(file, std::ios::binary) << bytes;
    EXPECT_THROW_WITH(io::DicomReader::read(file), FileError,
                      file + ": PhotometricInterpretation RGB: colour images are not supported");
}
