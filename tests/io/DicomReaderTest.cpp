// DICOM series: the real files of ../shared/data/medical (skipped when absent) and the
// synthetic fixtures of tests/data/dicom (make_fixtures.py there says what each holds).
#include "../FileBytes.h"
#include "DicomPixelData.h"
#include "IoTestSupport.h"

#include "dicom/DicomFile.h"
#include "octrace/io/DicomReader.h"
#include "octrace/io/FieldReader.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/io/VolumeReader.h"
#include "octrace/util/Error.h"

#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <chrono>
#include <iterator>
#include <tuple>

using namespace octrace;

namespace {

bool anyWarningContains(const test::LogCapture& log, const std::string& text) {
    return std::any_of(log.warnings.begin(), log.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

void expectSameVoxels(const ScalarField& a, const ScalarField& b, const std::string& what) {
    EXPECT_EQ(a.dims, b.dims) << what;
    EXPECT_TRUE(a.values == b.values) << what << ": voxels differ";
    EXPECT_EQ(a.origin, b.origin) << what;
    EXPECT_EQ(a.direction, b.direction) << what;
    EXPECT_EQ(a.spacing, b.spacing) << what;
}

void expectNear(dvec3 a, dvec3 b, double tol, const std::string& what) {
    EXPECT_LT(glm::length(a - b), tol) << what << ": (" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", "
                                       << b.y << ", " << b.z << ")";
}

/// A DICOM input read as `slice` reads it (2-D fields accepted): expected to be a single image.
ScalarField readAsSlicesDo(const std::string& path) {
    io::FieldRequest req;
    req.acceptPlanar = true;
    ScalarField f = io::readField(path, req);
    EXPECT_TRUE(f.planar) << path;
    return f;
}

}  // namespace

// The four compressed variants hold the same pixels; the uncompressed "anatomical" one is
// another series (its own SeriesInstanceUID) with other pixels (gdcmconv --raw of its first
// file differs from all four) at the same positions: same geometry, different voxels.
TEST(DicomReader, TheTransferSyntaxesOfTheSagittalMrGiveIdenticalVoxelsAndGeometry) {
    OCTRACE_SHARED_FILE_OR_SKIP(rle, "medical/d2n_mr_sag_4slices_compressed_rle");
    const ScalarField ref = io::DicomReader::read(rle);
    EXPECT_EQ(ref.dims, ivec3(256, 256, 4));
    EXPECT_EQ(ref.name, "MR");
    EXPECT_EQ(ref.units, "");
    // IOP 0\1\0\0\0\-1: rows run anterior->posterior (+y), columns downwards (-z); the slice
    // normal row x column is -x, and the positions step +1 mm in x: ordered along -x, so the
    // first slice is the one at x = -100.79 and the spacing is 1 mm.
    expectNear(ref.direction[0], dvec3(0, 1, 0), 1e-12, "row direction");
    expectNear(ref.direction[1], dvec3(0, 0, -1), 1e-12, "column direction");
    expectNear(ref.direction[2], dvec3(-1, 0, 0), 1e-12, "slice normal");
    expectNear(ref.origin, dvec3(-100.79415804148, -161.07467269897, 130.05125403404), 1e-9, "origin");
    EXPECT_NEAR(ref.spacing.z, 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(ref.spacing.x, 1.0);
    for (const char* variant : {"compressed_jpegls", "compressed_j2k", "compressed_jpeg"}) {
        const std::string path = test::sharedData(std::string("medical/d2n_mr_sag_4slices_") + variant);
        ASSERT_FALSE(path.empty()) << variant;
        expectSameVoxels(io::DicomReader::read(path), ref, variant);
    }
    const std::string plain = test::sharedData("medical/d2n_mr_sag_4slices_anatomical");
    ASSERT_FALSE(plain.empty());
    const ScalarField anatomical = io::DicomReader::read(plain);
    EXPECT_EQ(anatomical.dims, ref.dims);
    EXPECT_EQ(anatomical.origin, ref.origin);
    EXPECT_EQ(anatomical.direction, ref.direction);
    EXPECT_EQ(anatomical.spacing, ref.spacing);
}

TEST(DicomReader, TheFiveMultiFrameMrEncodingsGiveIdenticalVoxels) {
    OCTRACE_SHARED_FILE_OR_SKIP(plain, "medical/emri_small.dcm");
    test::LogCapture log;
    const ScalarField ref = io::DicomReader::read(plain);
    EXPECT_EQ(ref.dims, ivec3(64, 64, 10));
    // No positions in the file: frames stacked SpacingBetweenSlices (1.2 mm) apart, with a warning.
    EXPECT_NEAR(ref.spacing.z, 1.2, 1e-12);
    EXPECT_TRUE(anyWarningContains(log, "no ImagePositionPatient")) << log.warnings.size();
    auto [lo, hi] = ref.validRange();
    EXPECT_EQ(lo, 0.0f);
    EXPECT_EQ(hi, 467.0f);
    for (const char* f : {"emri_small_RLE.dcm", "emri_small_jpeg_ls_lossless.dcm", "emri_small_big_endian.dcm",
                          "emri_small_jpeg_2k_lossless.dcm"}) {
        const std::string path = test::sharedData(std::string("medical/") + f);
        ASSERT_FALSE(path.empty()) << f;
        expectSameVoxels(io::DicomReader::read(path), ref, f);
    }
}

TEST(DicomReader, RefusesTheTruncatedJpeg2000StreamNamingTheFile) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/emri_small_jpeg_2k_lossless_too_short.dcm");
    // The file is 8 bytes short: the sequence delimitation after its last fragment. The
    // structure walk refuses it before GDCM (which would read on and fail to decode it).
    EXPECT_THROW_WITH(io::readField(path), FileError,
                      path + ": DICOM structure broken at byte 40316: encapsulated pixel data have no sequence delimitation");
}

TEST(DicomReader, ResamplesTheGantryTiltedCtOntoAnOrthogonalGridWithAWarning) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/d2n_ct_gantrytilt_4slices");
    test::LogCapture log;
    const ScalarField f = io::DicomReader::read(path);
    EXPECT_TRUE(anyWarningContains(log, "gantry tilt of 14 degrees")) << (log.warnings.empty() ? "" : log.warnings[0]);
    // IOP 1\0\0\0\0.970296\-0.241922; positions step 5 mm in z. Normal = row x column =
    // (0, 0.241922, 0.970296); the step along it is 5 * 0.970296 = 4.85148 mm, and in the
    // plane 5 * -0.241922 = -1.20961 mm along the column direction per slice: over 3 slices
    // 3.62883 mm = 8.68 rows of 0.41796875 mm, so the grid grows from 512 to 521 rows.
    expectNear(f.direction[2], dvec3(0.0, 0.2419218955997, 0.970295726276), 1e-9, "slice normal");
    EXPECT_NEAR(f.spacing.z, 5.0 * 0.970295726276, 1e-6);
    EXPECT_DOUBLE_EQ(f.spacing.x, 0.41796875);
    EXPECT_EQ(f.dims, ivec3(512, 521, 4));
    EXPECT_TRUE(f.coords[2].empty());
    // The grid starts where the last slice's shift puts it: first position + 3 * -1.20961 mm
    // along the column direction.
    const dvec3 first(-106.791015625, -256.61886606561, -61.951915066986);
    expectNear(f.origin, first + f.direction[1] * (3.0 * 5.0 * -0.2419218955997), 1e-6, "origin");
    EXPECT_EQ(f.units, "HU");
    // Stored 0..254 (BitsStored 12), RescaleIntercept -1024: Hounsfield units -1024..-770.
    auto [lo, hi] = f.validRange();
    EXPECT_EQ(lo, -1024.0f);
    EXPECT_EQ(hi, -770.0f);
    // Points outside a slice are masked: the slices are shifted against each other.
    EXPECT_LT(f.validCount(), f.sampleCount());
    EXPECT_GT(f.validCount(), 4u * 512u * 500u);
}

TEST(DicomReader, ReadsIdenticalVoxelsWhateverTheFileNamesAndTheirOrder) {
    OCTRACE_SHARED_FILE_OR_SKIP(series, "medical/d2n_mr_sag_4slices_anatomical");
    test::TempDir dir;
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(series)) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    ASSERT_EQ(files.size(), 4u);
    // Names that sort in the reverse order of the positions (and a subfolder), no extension.
    const char* names[] = {"z9", "m5", "sub/b2", "a0"};
    std::filesystem::create_directories(dir.file("sub"));
    for (std::size_t i = 0; i < files.size(); ++i) std::filesystem::copy_file(files[i], dir.file(names[i]));
    expectSameVoxels(io::DicomReader::read(dir.file("")), io::DicomReader::read(series), "shuffled copy");
}

TEST(DicomReader, TakesPerFramePositionsAndRescaleFromTheFunctionalGroups) {
    const std::string path = test::testData("dicom/enhanced_ct_3frames.dcm");
    const ScalarField f = io::readField(path);
    // Frames stored at z = 4, 2, 0 with intercepts -1000, -1010, -1020 and stored values
    // 100 * frame + pixel index; ordered by position, the first slice is the third frame.
    EXPECT_EQ(f.dims, ivec3(4, 4, 3));
    EXPECT_EQ(f.origin, dvec3(-10.0, -20.0, 0.0));
    EXPECT_EQ(f.spacing, dvec3(0.25, 0.5, 2.0));  // PixelSpacing 0.5\0.25 = (rows, columns)
    EXPECT_EQ(f.values[f.index(0, 0, 0)], 200.0f - 1020.0f);
    EXPECT_EQ(f.values[f.index(3, 1, 0)], 207.0f - 1020.0f);
    EXPECT_EQ(f.values[f.index(0, 0, 1)], 100.0f - 1010.0f);
    EXPECT_EQ(f.values[f.index(3, 3, 2)], 15.0f - 1000.0f);
    EXPECT_EQ(f.units, "HU");
}

TEST(DicomReader, KeepsTheTruePositionsOfASeriesWithAMissingSliceAsARectilinearAxis) {
    const std::string path = test::testData("dicom/missing_slice");
    test::LogCapture log;
    const ScalarField f = io::readField(path);
    EXPECT_TRUE(anyWarningContains(log, "a missing slice?"));
    ASSERT_TRUE(f.isRectilinear(2));
    EXPECT_EQ(f.coords[2], (std::vector<double>{0.0, 2.0, 4.0, 8.0}));
    for (int k = 0; k < 4; ++k) EXPECT_EQ(f.values[f.index(0, 0, k)], float(f.coords[2][std::size_t(k)] * 10.0)) << k;
    EXPECT_EQ(f.units, "");  // MR: values as stored
}

TEST(DicomReader, ListsEverySeriesAndReadsTheLargestUnlessOneIsChosen) {
    const std::string path = test::testData("dicom/two_series");
    const auto list = io::DicomReader::listSeries(path);
    ASSERT_EQ(list.size(), 2u);
    EXPECT_EQ(list[0].modality, "MR");
    EXPECT_EQ(list[0].description, "small mr");
    EXPECT_EQ(list[0].slices, 2);
    EXPECT_EQ(list[1].uid, "1.2.826.0.1.3680043.9.7777.32");
    EXPECT_EQ(list[1].columns, 6);
    EXPECT_EQ(list[1].slices, 3);
    EXPECT_EQ(io::DicomReader::read(path).name, "CT");
    for (const char* choice : {"1", "small mr", "1.2.826.0.1.3680043.9.7777.31"})
        EXPECT_EQ(io::DicomReader::read(path, choice).dims, ivec3(4, 4, 2)) << choice;
    EXPECT_THROW_WITH(io::DicomReader::read(path, "3"), InputError, path + ": no series '3'");
    const std::string text = io::DicomReader::describe(path, "2");
    EXPECT_NE(text.find("series 1: 1.2.826.0.1.3680043.9.7777.31 (MR, 'small mr', 4x4x2, 2 files)"), std::string::npos) << text;
    EXPECT_NE(text.find("chosen: series 2"), std::string::npos) << text;
}

TEST(DicomReader, SeriesIsRefusedForOtherFormats) {
    io::FieldRequest r;
    r.series = "1";
    EXPECT_THROW_WITH(io::readField(test::testData("netcdf/dateline_cf.nc"), r), InputError, "`series` chooses a DICOM series");
}

TEST(DicomReader, RefusesBrokenSeriesWithOneLineNamingTheInput) {
    struct Case {
        const char* input;
        const char* message;
    };
    const Case cases[] = {
        {"invalid_no_dicom_images", "no DICOM image"},
        {"invalid_not_an_image.dcm", "a DICOM file without an image (no Rows/Columns)"},
        {"invalid_mixed_sizes", "mixed image sizes in one series"},
        {"invalid_huge_frame_count.dcm", "header declares 100000 frame(s) of 64x64 x 16 bits, which need at least 819200000 bytes, but only 8192 bytes follow the header"},
        {"invalid_zero_pixel_spacing.dcm", "PixelSpacing 0\\0.5 must be positive"},
        {"invalid_nan_position.dcm", "ImagePositionPatient 'NaN\\0\\1' of frame 2 is not 3 finite numbers"},
        // GDCM aborts the process on these seven; our structure walk (five), VR check and header checks refuse them first.
        {"invalid_length_past_end.dcm",
         "DICOM structure broken at byte 492: element (0028,1052) DS declares 8456 bytes, only 104 remain in the file"},
        {"invalid_meta_group_only.dcm", "DICOM structure broken at byte 256: the file ends after its file meta group (no data set)"},
        {"invalid_unterminated_fragments.dcm",
         "DICOM structure broken at byte 434: encapsulated pixel data have no sequence delimitation (FFFE,E0DD)"},
        {"invalid_vr_mismatch.dcm", "element (0028,0103) has VR UI, the DICOM dictionary's is US"},
        {"invalid_enhanced_without_orientation.dcm", "multi-frame image with functional groups but no ImageOrientationPatient (neither in them nor at the top level)"},
        {"invalid_tag_order.dcm", "DICOM structure broken at byte 422: element (0028,0103) comes after (FFD8,F4FD): elements below the pixel data (7FE0,0010) must come before those at or past it"},
        {"invalid_jpeg_garbage_in_header.dcm",
         "DICOM structure broken at byte 3090: a JPEG frame's header holds bytes other than a marker between its segments"},
    };
    for (const Case& c : cases) {
        const std::string path = test::testData(std::string("invalid/") + c.input);
        EXPECT_THROW_WITH(io::readField(path), FileError, path + ": ");
        EXPECT_THROW_WITH(io::readField(path), FileError, c.message);
    }
}

// fuzz_dicom's first finding as it was found: the two_series folder with one slice's
// RescaleIntercept declaring 8,456 bytes (GDCM aborted the whole process on it). The folder
// is refused, naming the folder and the broken file.
TEST(DicomReader, RefusesAFolderHoldingAFileWhoseLengthRunsPastItsEndInsteadOfAborting) {
    test::TempDir dir;
    const std::string series = test::testData("dicom/two_series");
    std::filesystem::copy(series, dir.file("two_series"), std::filesystem::copy_options::recursive);
    const std::string broken = dir.file("two_series/sub/ct0.dcm");
    std::filesystem::copy_file(test::testData("invalid/invalid_length_past_end.dcm"), broken,
                               std::filesystem::copy_options::overwrite_existing);
    const std::string folder = dir.file("two_series");
    EXPECT_THROW_WITH(io::DicomReader::read(folder), FileError,
                      folder + ": " + broken + ": DICOM structure broken at byte 492: element (0028,1052) DS declares 8456 bytes");
    EXPECT_THROW_WITH(io::DicomReader::listSeries(folder), FileError, broken + ": DICOM structure broken at byte 492");
}

// Asked for a volume (a surface), a single image is refused saying what it is and what a
// surface needs; asked by a slice (acceptPlanar), it is a 2-D field in its own plane.
TEST(DicomReader, ASingleImageIsNotAVolume) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/CT_small.dcm");
    EXPECT_THROW_WITH(io::readField(path), InputError,
                      path + ": a single 128x128 CT image (series 1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322): a surface "
                             "needs a volume, a series of slices or a multi-frame image; draw a single image with slice");
}

// The corpus' single 4x4 CT image (make_fixtures.py: stored 0..15, intercept -1024, at z = 3):
// refused as a volume, read as a 2-D field in its own plane when asked.
TEST(DicomReader, TheCorpusSingleImageIsRefusedAsAVolumeAndReadAsAMap) {
    const std::string path = test::testData("invalid/invalid_single_image.dcm");
    EXPECT_THROW_WITH(io::DicomReader::read(path), InputError,
                      path + ": a single 4x4 CT image (series 1.2.826.0.1.3680043.9.7777.90): a surface needs a volume");
    const ScalarField f = io::DicomReader::read(path, {}, 0, -1, true);
    EXPECT_TRUE(f.planar);
    EXPECT_EQ(f.dims, ivec3(4, 4, 1));
    EXPECT_EQ(f.origin, dvec3(-10.0, -20.0, 3.0));
    EXPECT_EQ(f.spacing.x, 0.5);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(f.values[std::size_t(i)], float(i - 1024)) << i;
}

// CT_small.dcm: 128 x 128 axial (ImageOrientationPatient 1\0\0\0\1\0), PixelSpacing 0.661468,
// ImagePositionPatient -158.135803\-179.035797\-75.699997, RescaleIntercept -1024, no window.
// Read as a map in its own plane: one sample along the normal, the HU of every pixel equal to
// the stored pixels (found by the Pixel Data element's bytes, not by GDCM) plus the intercept,
// and no slice spacing made up from SliceThickness or SpacingBetweenSlices (both 5 in the file).
TEST(DicomReader, ASingleCtImageIsA2DFieldInItsOwnPlaneWithItsHounsfieldUnits) {
    OCTRACE_SHARED_FILE_OR_SKIP(path, "medical/CT_small.dcm");
    const ScalarField f = readAsSlicesDo(path);
    EXPECT_TRUE(f.patientLps);
    EXPECT_EQ(f.dims, ivec3(128, 128, 1));
    EXPECT_EQ(f.units, "HU");
    EXPECT_FALSE(f.window.valid());
    EXPECT_EQ(f.direction, dmat3(1.0));
    expectNear(f.origin, dvec3(-158.135803, -179.035797, -75.699997), 1e-9, "origin");
    EXPECT_NEAR(f.spacing.x, 0.661468, 1e-12);
    EXPECT_NEAR(f.spacing.y, 0.661468, 1e-12);
    const std::vector<double> stored = test::storedPixels16(path, 128 * 128, false, true);
    ASSERT_EQ(stored.size(), f.values.size());
    int wrong = 0;
    for (std::size_t i = 0; i < stored.size(); ++i) wrong += f.values[i] != float(stored[i] - 1024.0);
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(f.values[0], float(0xaf - 1024));  // the first stored bytes: af 00
    const std::string text = io::describeInput(path);
    EXPECT_NE(text.find("spacing: 0.661468 x 0.661468 x none (one sample)"), std::string::npos) << text;
    EXPECT_NE(text.find("a single 128x128 CT image"), std::string::npos) << text;
    EXPECT_NE(text.find("no spacing between slices"), std::string::npos) << text;
}

// MR_small.dcm keeps its stored window (600/1600) and its values as stored; the multi-frame
// emri_small.dcm (10 frames) stays a volume; JPEG-lossy.dcm, one NM frame without position or
// orientation, is a single image placed at the origin with a warning.
TEST(DicomReader, SingleImagesKeepTheirWindowAndMultiFrameImagesStayVolumes) {
    OCTRACE_SHARED_FILE_OR_SKIP(mr, "medical/MR_small.dcm");
    const ScalarField f = readAsSlicesDo(mr);
    EXPECT_EQ(f.dims, ivec3(64, 64, 1));
    EXPECT_EQ(f.units, "");
    EXPECT_EQ(f.window.centre, 600.0);
    EXPECT_EQ(f.window.width, 1600.0);
    const std::vector<double> stored = test::storedPixels16(mr, 64 * 64, false, true);
    ASSERT_EQ(stored.size(), f.values.size());
    EXPECT_TRUE(std::equal(stored.begin(), stored.end(), f.values.begin(), [](double a, float b) { return float(a) == b; }));
    const std::string big = test::sharedData("medical/MR_small_bigendian.dcm");
    ASSERT_FALSE(big.empty());
    expectSameVoxels(readAsSlicesDo(big), f, "big endian");

    const std::string emri = test::sharedData("medical/emri_small.dcm");
    ASSERT_FALSE(emri.empty());
    io::FieldRequest req;
    req.acceptPlanar = true;
    const ScalarField volume = io::readField(emri, req);
    EXPECT_FALSE(volume.planar);
    EXPECT_EQ(volume.dims, ivec3(64, 64, 10));

    const std::string nm = test::sharedData("medical/JPEG-lossy.dcm");
    ASSERT_FALSE(nm.empty());
    test::LogCapture log;
    const ScalarField one = readAsSlicesDo(nm);
    EXPECT_EQ(one.dims, ivec3(256, 1024, 1));
    EXPECT_EQ(one.origin, dvec3(0.0));
    EXPECT_TRUE(anyWarningContains(log, "no ImagePositionPatient: the image is placed at the origin"));
    EXPECT_THROW_WITH(io::readField(nm), InputError, "a single 256x1024 NM image");
}

// The single-image MR in little and big endian: the same image: identical decoded values,
// size and geometry.
TEST(DicomReader, TheLittleAndBigEndianSingleMrImagesDecodeIdentically) {
    OCTRACE_SHARED_FILE_OR_SKIP(little, "medical/MR_small.dcm");
    const std::string big = test::sharedData("medical/MR_small_bigendian.dcm");
    ASSERT_FALSE(big.empty());
    std::string whyNot;
    const auto a = io::detail::readDicomHeader(little, whyNot), b = io::detail::readDicomHeader(big, whyNot);
    ASSERT_TRUE(a && b) << whyNot;
    EXPECT_EQ(a->columns, b->columns);
    EXPECT_EQ(a->rows, b->rows);
    ASSERT_EQ(a->frames.size(), 1u);
    ASSERT_EQ(b->frames.size(), 1u);
    EXPECT_EQ(a->frames[0].position, b->frames[0].position);
    EXPECT_EQ(a->frames[0].rowDir, b->frames[0].rowDir);
    EXPECT_EQ(a->frames[0].pixelSpacing, b->frames[0].pixelSpacing);
    const std::vector<float> va = io::detail::decodeDicomFrames(*a), vb = io::detail::decodeDicomFrames(*b);
    EXPECT_EQ(va.size(), std::size_t(64 * 64));
    EXPECT_TRUE(va == vb) << "decoded values differ";
    EXPECT_NE(*std::max_element(va.begin(), va.end()), *std::min_element(va.begin(), va.end()));
}

namespace {

// dcm2niix's NIfTI of the XA10 series, read by the test itself (not by octrace's NIfTI
// reader): dims, the sform (RAS, rows), and the int16 samples, x fastest.
struct RawNifti {
    int dim[8] = {};
    double srow[3][4] = {};
    std::vector<std::int16_t> samples;
};

RawNifti readRawNifti(const std::string& path) {
    const auto bytes = testutil::fileBytes<std::vector<char>>(path);
    RawNifti n;
    EXPECT_GE(bytes.size(), 352u);
    std::int16_t d[8], datatype;
    std::memcpy(d, bytes.data() + 40, sizeof d);
    std::memcpy(&datatype, bytes.data() + 70, 2);
    EXPECT_EQ(datatype, 4) << "int16 expected";
    float offset, srow[12];
    std::memcpy(&offset, bytes.data() + 108, 4);
    std::memcpy(srow, bytes.data() + 280, sizeof srow);
    for (int i = 0; i < 8; ++i) n.dim[i] = d[i];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) n.srow[r][c] = srow[4 * r + c];
    const std::size_t count = std::size_t(n.dim[1]) * std::size_t(n.dim[2]) * std::size_t(n.dim[3]) * std::size_t(n.dim[4]);
    n.samples.resize(count);
    EXPECT_GE(bytes.size(), std::size_t(offset) + 2 * count);
    std::memcpy(n.samples.data(), bytes.data() + std::size_t(offset), 2 * count);
    return n;
}

/// The NIfTI voxel (x, y, z, within 0.001 of integers) at the patient position `lps` (DICOM's
/// LPS turned into RAS, through the inverse of the sform), checked to lie inside the image;
/// `worst` gets the largest distance off the grid, in voxels.
ivec3 niftiVoxel(const RawNifti& ref, dvec3 lps, double& worst) {
    dmat3 m;
    dvec3 offset;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[c][r] = ref.srow[r][c];
        offset[r] = ref.srow[r][3];
    }
    const dvec3 voxel = glm::inverse(m) * (dvec3(-lps.x, -lps.y, lps.z) - offset);
    const dvec3 rounded = glm::round(voxel);
    worst = std::max(worst, glm::length(voxel - rounded));
    const ivec3 v(rounded);
    EXPECT_TRUE(v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < ref.dim[1] && v.y < ref.dim[2] && v.z < ref.dim[3])
        << "(" << lps.x << ", " << lps.y << ", " << lps.z << ") lies outside the NIfTI";
    return glm::clamp(v, ivec3(0), ivec3(ref.dim[1] - 1, ref.dim[2] - 1, ref.dim[3] - 1));
}

/// The stored integer of time point `t` of the NIfTI at its voxel `v`.
float niftiSample(const RawNifti& ref, int t, ivec3 v) {
    const std::size_t nx = std::size_t(ref.dim[1]), ny = std::size_t(ref.dim[2]), nz = std::size_t(ref.dim[3]);
    return float(ref.samples[((std::size_t(t) * nz + std::size_t(v.z)) * ny + std::size_t(v.y)) * nx + std::size_t(v.x)]);
}

/// Every voxel of `f` lies on a voxel of the NIfTI (within 0.001 voxel) and holds the stored
/// integer of its time point `t` there.
void expectNiftiTimePoint(const ScalarField& f, const RawNifti& ref, int t, const std::string& what) {
    double worst = 0.0;
    std::size_t wrong = 0;
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i)
                if (f.values[f.index(i, j, k)] != niftiSample(ref, t, niftiVoxel(ref, f.worldFromGrid(i, j, k), worst)))
                    ++wrong;
    EXPECT_EQ(wrong, 0u) << what << ": voxels that differ from time point " << t << " of the NIfTI";
    EXPECT_LT(worst, 1e-3) << what << ": voxels off the NIfTI's grid (in NIfTI voxels)";
}

}  // namespace

// The Siemens XA10 resting-state fMRI (four enhanced MR files, one time point each, 6 frames
// at the same positions in each) is four volumes told apart by TemporalPositionIndex. Each
// equals dcm2niix's 4-D NIfTI of the series: every voxel's world position (DICOM LPS, turned
// into RAS) lies on a NIfTI voxel through the inverse of its sform, and the stored integers
// there are equal, voxel for voxel. octrace's own 4-D NIfTI reader gives the same volume at
// the same LPS positions.
TEST(DicomReader, TheXa10FmriSeriesIsFourVolumesEqualToDcm2niixsReference) {
    OCTRACE_SHARED_FILE_OR_SKIP(folder, "medical/siemens_xa10_fmri_4d");
    const std::string nii = folder + "/reference_dcm2niix.nii";
    const RawNifti ref = readRawNifti(nii);
    ASSERT_EQ(ref.dim[0], 4);
    ASSERT_EQ(ref.dim[4], 4);
    const std::vector<std::string> labels = io::DicomReader::listVolumes(folder);
    ASSERT_EQ(labels.size(), 4u);
    for (int t = 0; t < 4; ++t) EXPECT_EQ(labels[std::size_t(t)], "temporal position " + std::to_string(t + 1));

    const int nx = ref.dim[1], ny = ref.dim[2], nz = ref.dim[3];
    for (int t = 0; t < 4; ++t) {
        const ScalarField f = io::DicomReader::read(folder, {}, 0, t);
        ASSERT_EQ(f.dims, ivec3(nx, ny, nz)) << "volume " << t;
        expectNiftiTimePoint(f, ref, t, "volume " + std::to_string(t));
        const ScalarField fromNifti = io::VolumeReader::read(nii, io::VolumeReader::Format::Nifti, 0, t);
        ASSERT_EQ(fromNifti.dims, ivec3(nx, ny, nz));
        dmat3 niftiAxes = fromNifti.direction;
        for (int a = 0; a < 3; ++a) niftiAxes[a] *= fromNifti.spacing[a];
        const dmat3 niftiGrid = glm::inverse(niftiAxes);  // LPS offset from the origin -> grid index
        std::size_t checked = 0;
        double worst = 0.0, worstNifti = 0.0;
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) {
                    const dvec3 lps = f.worldFromGrid(i, j, k);
                    const float stored = niftiSample(ref, t, niftiVoxel(ref, lps, worst));
                    // octrace's NIfTI reader (which may store the slices reversed: VTK does with a
                    // reflection): the same value at the same LPS position.
                    const dvec3 g = niftiGrid * (lps - fromNifti.origin);
                    const ivec3 w(glm::round(g));
                    worstNifti = std::max(worstNifti, glm::length(g - dvec3(w)));
                    ASSERT_TRUE(w.x >= 0 && w.y >= 0 && w.z >= 0 && w.x < nx && w.y < ny && w.z < nz);
                    EXPECT_EQ(fromNifti.values[fromNifti.index(w.x, w.y, w.z)], stored);
                    ++checked;
                }
        EXPECT_EQ(checked, std::size_t(nx) * ny * nz);
        EXPECT_LT(worstNifti, 1e-3) << "volume " << t << ": DICOM voxels off octrace's NIfTI grid (in its voxels)";
    }
    // The default is volume 0, and a volume beyond the last is refused naming the count.
    expectSameVoxels(io::DicomReader::read(folder), io::DicomReader::read(folder, {}, 0, 0), "default volume");
    EXPECT_THROW_WITH(io::DicomReader::read(folder, {}, 0, 4), InputError, "no volume 4: series");
    EXPECT_THROW_WITH(io::DicomReader::read(folder, {}, 0, 4), InputError, "holds 4 volumes, 0..3 (0: temporal position 1");
    EXPECT_THROW_WITH(io::VolumeReader::read(nii, io::VolumeReader::Format::Nifti, 0, 4), InputError,
                      "no volume 4: the NIfTI image holds 4 volumes (dim[4]), 0..3");
    // info lists the volumes with what tells them apart.
    const std::string text = io::DicomReader::describe(folder, {}, 0, 2);
    // The series line counts the slices of one volume (4 x 6 frames: 64x64x6), then the volumes.
    EXPECT_NE(text.find("(MR, 'REST1 w SMS PF7-8', 64x64x6, 4 files, 4 volumes)"), std::string::npos) << text;
    const std::vector<io::DicomSeriesInfo> series = io::DicomReader::listSeries(folder);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].slices, 6);
    EXPECT_EQ(series[0].volumes, 4);
    EXPECT_NE(text.find("volume 3: temporal position 4, 6 slices"), std::string::npos) << text;
    EXPECT_NE(text.find("chosen: series 1, volume 2"), std::string::npos) << text;
    // An animation's steps are the volumes.
    const io::TimeAxis axis = io::readTimeAxis(folder);
    EXPECT_TRUE(axis.volumes);
    EXPECT_EQ(axis.size, 4u);
    const io::TimeAxis niftiAxis = io::readTimeAxis(nii);
    EXPECT_TRUE(niftiAxis.volumes);
    EXPECT_EQ(niftiAxis.size, 4u);
    // The NIfTI's volumes are labelled by their time: pixdim[4] 0.5 in seconds (xyzt_units 10),
    // dcm2niix's RepetitionTime; info lists them as it lists the DICOM series' volumes.
    const std::vector<std::string> times = {"time 0 s", "time 0.5 s", "time 1 s", "time 1.5 s"};
    EXPECT_EQ(niftiAxis.labels, times);
    EXPECT_EQ(io::VolumeReader::volumeLabels(nii, io::VolumeReader::Format::Nifti), times);
    const std::string niftiText = io::VolumeReader::describe(nii, io::VolumeReader::Format::Nifti, 0, 2);
    EXPECT_NE(niftiText.find("volumes: 4 (choose with `volume`, from 0)\nvolume 0: time 0 s, 6 slices\n"), std::string::npos)
        << niftiText;
    EXPECT_NE(niftiText.find("volume 3: time 1.5 s, 6 slices\nchosen: volume 2\n"), std::string::npos) << niftiText;
    EXPECT_NE(niftiText.find("note: volume 2 of 4 (NIfTI dim[4]): time 1 s"), std::string::npos) << niftiText;
}

// Real slices (the XA10 series as dcm2niix wrote it) as classic MR files of two time points
// (TemporalPositionIdentifier): volumes that do not hold the same slices are refused, naming
// the volume (tests/data/dicom/make_volume_corpus.py writes them).
TEST(DicomReader, VolumesWithoutTheSameSlicesAreRefusedNamingTheVolume) {
    const std::string counts = test::testData("invalid/invalid_volume_slice_counts");
    EXPECT_THROW_WITH(io::DicomReader::read(counts), FileError,
                      counts + ": volume 1 (temporal position 2) has 4 slices, volume 0 (temporal position 1) has 6 slices");
    EXPECT_THROW_WITH(io::DicomReader::listVolumes(counts), FileError, "volume 1 (temporal position 2) has 4 slices");
    const std::string missing = test::testData("invalid/invalid_volume_missing_slice");
    EXPECT_THROW_WITH(io::DicomReader::read(missing, {}, 0, 0), FileError,
                      missing + ": volume 1 (temporal position 2) is missing a slice: it has none at");
    EXPECT_THROW_WITH(io::DicomReader::read(missing), FileError, "(slice 4 of the series' 6 positions)");
    // Without the second time point's files the first is one ordinary volume.
    test::TempDir dir;
    for (int k = 1; k <= 6; ++k)
        std::filesystem::copy_file(missing + "/t1_s" + std::to_string(k) + ".dcm", dir.file("s" + std::to_string(k) + ".dcm"));
    const ScalarField one = io::DicomReader::read(dir.file(""));
    EXPECT_EQ(one.dims, ivec3(64, 64, 6));
    EXPECT_EQ(io::DicomReader::listVolumes(dir.file("")).size(), 1u);
}

// Classic MR files whose volumes are told apart by EchoNumbers (a multi-echo series) or by
// DiffusionBValue (a diffusion series), without a temporal position: two volumes of 3 slices
// (tests/data/dicom/make_volume_corpus.py writes them from the XA10 slices of two time points).
// listVolumes and info name what tells them apart, and each volume read is that echo's or
// b-value's slices alone: the same voxels as a folder holding only its files.
TEST(DicomReader, EchoesAndBValuesAreVolumesNamedByWhatTellsThemApart) {
    struct Case {
        const char* folder;
        const char* prefix;  // the files of volume v: PREFIX<v+1>_s<k>.dcm
        std::vector<std::string> labels;
    };
    for (const Case& c : {Case{"dicom/two_echoes", "echo", {"echo 1", "echo 2"}},
                          Case{"dicom/two_bvalues", "b", {"b-value 0", "b-value 1000"}}}) {
        SCOPED_TRACE(c.folder);
        const std::string folder = test::testData(c.folder);
        EXPECT_EQ(io::DicomReader::listVolumes(folder), c.labels);
        const std::string text = io::DicomReader::describe(folder, {}, 0, 1);
        EXPECT_NE(text.find("2 volumes)"), std::string::npos) << text;
        EXPECT_NE(text.find("volume 0: " + c.labels[0] + ", 3 slices"), std::string::npos) << text;
        EXPECT_NE(text.find("volume 1: " + c.labels[1] + ", 3 slices"), std::string::npos) << text;
        EXPECT_NE(text.find("chosen: series 1, volume 1"), std::string::npos) << text;
        const ScalarField v0 = io::DicomReader::read(folder, {}, 0, 0), v1 = io::DicomReader::read(folder, {}, 0, 1);
        EXPECT_EQ(v0.dims, ivec3(64, 64, 3));
        EXPECT_FALSE(v0.values == v1.values);  // two time points' samples: not the same volume twice
        for (int v = 0; v < 2; ++v) {
            test::TempDir alone;
            for (int k = 1; k <= 3; ++k) {
                const std::string name = c.prefix + std::to_string(v + 1) + "_s" + std::to_string(k) + ".dcm";
                std::filesystem::copy_file(folder + "/" + name, alone.file(name));
            }
            expectSameVoxels(io::DicomReader::read(alone.file("")), v ? v1 : v0, c.labels[std::size_t(v)].c_str());
        }
        EXPECT_THROW_WITH(io::DicomReader::read(folder, {}, 0, 2), InputError, "holds 2 volumes, 0..1 (0: " + c.labels[0]);
    }
}

namespace {

// Read hooks that record every progress value and say "cancel" once `cancelAfter` values
// were reported (never when negative).
struct RecordingHooks {
    std::vector<double> reported;
    int cancelAfter = -1;

    io::ReadHooks hooks() {
        return {[this](double f) { reported.push_back(f); },
                [this] { return cancelAfter >= 0 && int(reported.size()) >= cancelAfter; }};
    }
};

// The first `n` of `bytes` written to `path`, plain or gzipped.
void writePrefix(const std::string& path, const std::string& bytes, std::size_t n, bool gzip) {
    if (!gzip) {
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), std::streamsize(n));
        return;
    }
    gzFile g = gzopen(path.c_str(), "wb");
    ASSERT_NE(g, nullptr);
    ASSERT_EQ(gzwrite(g, bytes.data(), unsigned(n)), int(n));
    gzclose(g);
}

void expectRisingToOne(const std::vector<double>& reported, const std::string& what) {
    ASSERT_FALSE(reported.empty()) << what;
    EXPECT_GE(reported.front(), 0.0) << what;
    for (std::size_t i = 1; i < reported.size(); ++i) EXPECT_LE(reported[i - 1], reported[i]) << what << " at " << i;
    EXPECT_EQ(reported.back(), 1.0) << what;
}

}  // namespace

// Reading a series reports per header scanned and per file decoded (only the files of the
// volume read), rising to 1, and stops with CancelledError when asked between files; without
// a cancel it gives the same voxels as a read without hooks.
TEST(DicomReader, ReportsProgressPerFileAndStopsBetweenFilesWhenCancelled) {
    OCTRACE_SHARED_FILE_OR_SKIP(folder, "medical/siemens_xa10_fmri_4d");
    RecordingHooks all;
    const ScalarField f = io::DicomReader::read(folder, {}, 0, 2, false, all.hooks());
    expectRisingToOne(all.reported, "XA10 volume 2");
    // Four headers scanned, the one file of volume 2 decoded, then 1.
    EXPECT_EQ(all.reported.size(), 4u + 1u + 1u);
    expectSameVoxels(f, io::DicomReader::read(folder, {}, 0, 2), "with hooks");
    for (int k : {0, 2, 4}) {
        RecordingHooks stop;
        stop.cancelAfter = k;
        EXPECT_THROW_WITH(io::DicomReader::read(folder, {}, 0, 2, false, stop.hooks()), CancelledError, folder + ": read cancelled");
        EXPECT_EQ(int(stop.reported.size()), k) << "cancelled after " << k << " reports";
    }
    // Listing the series (the studio's Series box) scans the headers with the same hooks.
    RecordingHooks listing;
    EXPECT_EQ(io::listInputChoices(folder, listing.hooks()).series.size(), 1u);
    EXPECT_EQ(listing.reported.size(), 4u);
    listing.cancelAfter = 1;
    EXPECT_THROW(io::listInputChoices(folder, listing.hooks()), CancelledError);
    // Through readField, as the model reads: the request carries the hooks.
    OCTRACE_SHARED_FILE_OR_SKIP(sagittal, "medical/d2n_mr_sag_4slices_anatomical");
    RecordingHooks viaRequest;
    io::FieldRequest req;
    req.hooks = viaRequest.hooks();
    io::readField(sagittal, req);
    expectRisingToOne(viaRequest.reported, "sagittal MR through readField");
    viaRequest.reported.clear();
    viaRequest.cancelAfter = 3;
    EXPECT_THROW(io::readField(sagittal, req), CancelledError);
}

// The headers of the last input scanned are kept while its files stay as they were (the studio
// lists a folder's series, reads one and lists its volumes): a second scan reads none of them,
// and a file added, changed or removed scans again.
TEST(DicomReader, AFolderScannedAgainUnchangedIsNotReadAgain) {
    test::TempDir dir;
    const std::string folder = dir.file("series");
    std::filesystem::copy(test::testData("dicom/two_series"), folder, std::filesystem::copy_options::recursive);
    std::vector<std::string> said;
    // Every message, Debug included, until the test ends (or an assertion returns early).
    struct Listen {
        log::Level level = log::level();
        explicit Listen(std::vector<std::string>& to) {
            log::setLevel(log::Level::Debug);
            log::setSink([&to](log::Level, const std::string& text) { to.push_back(text); });
        }
        ~Listen() {
            log::setSink({});
            log::setLevel(level);
        }
    } listen(said);
    const auto kept = [&] {
        return std::count_if(said.begin(), said.end(), [&](const std::string& t) { return t.find("the headers of the last scan") != std::string::npos; });
    };
    const auto first = io::DicomReader::listSeries(folder);
    const auto before = kept();
    EXPECT_EQ(io::DicomReader::listSeries(folder).size(), first.size());
    EXPECT_EQ(io::DicomReader::read(folder).name, "CT");
    EXPECT_EQ(kept(), before + 2);
    // One file rewritten with another series description (same size: the time tells).
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(folder))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    const std::string from = first.front().description;
    ASSERT_FALSE(from.empty());
    // The first file holding it.
    std::string bytes;
    std::size_t at = std::string::npos;
    std::filesystem::path changed;
    for (const auto& f : files) {
        std::ifstream in(f, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
        at = bytes.find(from);
        if (at != std::string::npos) {
            changed = f;
            break;
        }
    }
    ASSERT_NE(at, std::string::npos);
    std::string renamed = from;
    renamed[0] = renamed[0] == 'x' ? 'y' : 'x';
    bytes.replace(at, from.size(), renamed);
    const auto stamp = std::filesystem::last_write_time(changed) + std::chrono::seconds(2);
    {
        std::ofstream out(changed, std::ios::binary | std::ios::trunc);
        out << bytes;
    }
    std::filesystem::last_write_time(changed, stamp);  // later than before, whatever the clock's resolution
    const auto again = io::DicomReader::listSeries(folder);
    EXPECT_EQ(kept(), before + 2);
    bool seen = false;
    for (const auto& s : again) seen |= s.description.find(renamed) != std::string::npos;
    EXPECT_TRUE(seen) << "the rewritten file's series description";
    // A file removed: scanned again too.
    std::filesystem::remove(changed == files.back() ? files.front() : files.back());
    (void)io::DicomReader::listSeries(folder);
    EXPECT_EQ(kept(), before + 2);
}

// A 4-D NIfTI image is read one volume at a time: per slice of the volume asked for (progress
// rising to 1, cancellation between slices), and a file cut after volume 0 still gives volume 0
// while volume 3 is refused naming it (the other volumes are not decoded), plain or gzipped.
TEST(DicomReader, TheFourDNiftiDecodesOnlyTheVolumeAskedForSliceBySlice) {
    OCTRACE_SHARED_FILE_OR_SKIP(folder, "medical/siemens_xa10_fmri_4d");
    const std::string nii = folder + "/reference_dcm2niix.nii";
    using io::VolumeReader;
    const ScalarField whole0 = VolumeReader::read(nii, VolumeReader::Format::Nifti, 0, 0);
    const ScalarField whole3 = VolumeReader::read(nii, VolumeReader::Format::Nifti, 0, 3);
    EXPECT_FALSE(whole0.values == whole3.values);

    RecordingHooks slices;
    expectSameVoxels(VolumeReader::read(nii, VolumeReader::Format::Nifti, 0, 3, slices.hooks()), whole3, "with hooks");
    expectRisingToOne(slices.reported, "NIfTI volume 3");
    EXPECT_EQ(slices.reported.size(), std::size_t(whole3.dims.z) + 1u);  // one per slice, then 1
    RecordingHooks stop;
    stop.cancelAfter = 2;
    EXPECT_THROW_WITH(VolumeReader::read(nii, VolumeReader::Format::Nifti, 0, 3, stop.hooks()), CancelledError, "read cancelled");
    EXPECT_EQ(stop.reported.size(), 2u);

    // Cut inside volume 1: volume 0 (64x64x6 int16 from the header's vox_offset) is whole.
    const std::string bytes = testutil::fileBytes(nii);
    float voxOffset = 0.0f;
    std::memcpy(&voxOffset, bytes.data() + 108, 4);
    const std::size_t volumeBytes = std::size_t(whole0.sampleCount()) * 2;
    test::TempDir dir;
    const std::string cut = dir.file("cut.nii");
    const std::size_t cutAt = std::size_t(voxOffset) + volumeBytes + volumeBytes / 3;
    writePrefix(cut, bytes, cutAt, false);
    expectSameVoxels(VolumeReader::read(cut, VolumeReader::Format::Nifti, 0, 0), whole0, "cut file, volume 0");
    EXPECT_THROW_WITH(VolumeReader::read(cut, VolumeReader::Format::Nifti, 0, 3), FileError,
                      cut + ": NIfTI data truncated: volume 3 of 4: 64x64x6 x 16 bits");
    // Gzipped and cut in the same place of the decompressed data: volume 0 is inflated and
    // read, volume 3 runs into the end of the stream.
    const std::string gz = dir.file("cut.nii.gz");
    writePrefix(gz, bytes, cutAt, true);
    std::filesystem::resize_file(gz, std::filesystem::file_size(gz) - 8);  // no gzip trailer either
    expectSameVoxels(VolumeReader::read(gz, VolumeReader::Format::Nifti, 0, 0), whole0, "cut .nii.gz, volume 0");
    EXPECT_THROW_WITH(VolumeReader::read(gz, VolumeReader::Format::Nifti, 0, 3), FileError,
                      gz + ": NIfTI data truncated: volume 3 of 4");
    // The whole file gzipped reads every volume as the plain file does.
    const std::string full = dir.file("full.nii.gz");
    writePrefix(full, bytes, bytes.size(), true);
    expectSameVoxels(VolumeReader::read(full, VolumeReader::Format::Nifti, 0, 3), whole3, ".nii.gz, volume 3");
    // The same file big-endian (every header field and sample byte-swapped): the same voxels.
    std::string big = bytes;
    const auto swapAt = [&](std::size_t at, std::size_t size, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) std::reverse(big.begin() + std::ptrdiff_t(at + i * size), big.begin() + std::ptrdiff_t(at + (i + 1) * size));
    };
    // NIfTI-1 fields by (offset, size, count): sizeof_hdr, extents, session_error, dim,
    // intent_p1..3, intent_code .. slice_start, pixdim, vox_offset .. scl_inter, slice_end,
    // cal_max .. toffset, glmax and glmin, qform_code and sform_code, quatern_b .. srow_z.
    for (auto [at, size, count] : {std::tuple<std::size_t, std::size_t, std::size_t>{0, 4, 1}, {32, 4, 1}, {36, 2, 1}, {40, 2, 8},
                                   {56, 4, 3}, {68, 2, 4}, {76, 4, 8}, {108, 4, 3}, {120, 2, 1}, {124, 4, 4}, {140, 4, 2},
                                   {252, 2, 2}, {256, 4, 18}})
        swapAt(at, size, count);
    swapAt(std::size_t(voxOffset), 2, (bytes.size() - std::size_t(voxOffset)) / 2);
    writePrefix(dir.file("big.nii"), big, big.size(), false);
    expectSameVoxels(VolumeReader::read(dir.file("big.nii"), VolumeReader::Format::Nifti, 0, 3), whole3, "big-endian, volume 3");
    expectSameVoxels(VolumeReader::read(full, VolumeReader::Format::Nifti, 0, 1), VolumeReader::read(nii, VolumeReader::Format::Nifti, 0, 1),
                     ".nii.gz, volume 1");
}

// The other attributes that tell the volumes of a series apart, each alone in a series of two
// volumes of 3 slices written from time points 1 and 2 of the XA10 fMRI's NIfTI
// (tests/data/dicom/make_volume_corpus.py): classic MR files told apart by ImageType (M and P),
// ComplexImageComponent, TriggerTime, or by nothing but AcquisitionTime (time point 2 acquired
// first, its files last in name order); enhanced MR files (the two volumes' frames interleaved)
// by StackID, by DimensionIndexValues alone (InversionTimes, which octrace does not read), or by
// DiffusionGradientOrientation at one b-value. Each is two volumes labelled by what tells them
// apart, in that order; volume v holds the samples of the time point it was written from at
// their positions; the default is volume 0, with a note naming it.
TEST(DicomReader, EveryVolumeAttributeSplitsASeriesIntoVolumesNamedByIt) {
    struct Case {
        const char* path;
        std::vector<std::string> labels;
        int timePoint[2];  // of the NIfTI, that volume 0 and 1 were written from
    };
    const Case cases[] = {
        {"dicom/two_image_types", {"image type ORIGINAL\\PRIMARY\\M\\ND", "image type ORIGINAL\\PRIMARY\\P\\ND"}, {0, 1}},
        {"dicom/two_complex_components", {"complex component MAGNITUDE", "complex component PHASE"}, {0, 1}},
        {"dicom/two_trigger_times", {"trigger time 0.0", "trigger time 400.0"}, {0, 1}},
        {"dicom/two_acquisitions", {"repeat 1 (acquired 120001.000)", "repeat 2 (acquired 120003.000)"}, {1, 0}},
        {"dicom/two_stacks.dcm", {"stack 1", "stack 2"}, {0, 1}},
        {"dicom/two_dimension_indices.dcm", {"dimension index 1 (InversionTimes)", "dimension index 2 (InversionTimes)"}, {0, 1}},
        {"dicom/two_gradient_directions.dcm", {"gradient direction 0\\1\\0", "gradient direction 1\\0\\0"}, {0, 1}},
    };
    const std::string nii = test::sharedData("medical/siemens_xa10_fmri_4d/reference_dcm2niix.nii");
    const RawNifti ref = nii.empty() ? RawNifti{} : readRawNifti(nii);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.path);
        const std::string path = test::testData(c.path);
        EXPECT_EQ(io::DicomReader::listVolumes(path), c.labels);
        const std::string text = io::DicomReader::describe(path, {}, 0, 1);
        EXPECT_NE(text.find("64x64x3, "), std::string::npos) << text;
        EXPECT_NE(text.find(", 2 volumes)"), std::string::npos) << text;
        EXPECT_NE(text.find("volume 0: " + c.labels[0] + ", 3 slices\nvolume 1: " + c.labels[1] + ", 3 slices\n"),
                  std::string::npos) << text;
        EXPECT_NE(text.find("chosen: series 1, volume 1"), std::string::npos) << text;
        const ScalarField v0 = io::DicomReader::read(path, {}, 0, 0), v1 = io::DicomReader::read(path, {}, 0, 1);
        ASSERT_EQ(v0.dims, ivec3(64, 64, 3));
        ASSERT_EQ(v1.dims, ivec3(64, 64, 3));
        EXPECT_FALSE(v0.values == v1.values);
        const ScalarField defaulted = io::DicomReader::read(path);
        expectSameVoxels(defaulted, v0, "default volume");
        EXPECT_NE(std::find(defaulted.notes.begin(), defaulted.notes.end(), "volume 0 of 2: " + c.labels[0]), defaulted.notes.end());
        if (nii.empty()) continue;
        expectNiftiTimePoint(v0, ref, c.timePoint[0], "volume 0");
        expectNiftiTimePoint(v1, ref, c.timePoint[1], "volume 1");
    }
    if (nii.empty()) GTEST_SKIP() << "shared data absent: the volumes' samples were not compared with the NIfTI";
}
