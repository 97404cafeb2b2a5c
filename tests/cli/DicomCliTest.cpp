// DICOM through the CLI: series listing and choice, rendering the real series exactly as the
// reference, and the refusal of a broken file (exit 1, one line naming it).
#include "CliRunner.h"

#include <algorithm>

using namespace octrace::testcli;

namespace {
const char* kTwoSeries = OCTRACE_TEST_DATA "/dicom/two_series";
}  // namespace

TEST(DicomCli, InfoListsEverySeriesAndSeriesChoosesOne) {
    Result r = run({"info", kTwoSeries});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("series 1: 1.2.826.0.1.3680043.9.7777.31 (MR, 'small mr', 4x4x2, 2 files)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("series 2: 1.2.826.0.1.3680043.9.7777.32 (CT, 'large ct', 6x6x3, 3 files)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("chosen: series 2"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("the largest; choose another with --series"), std::string::npos) << r.err;
    Result chosen = run({"info", kTwoSeries, "--series", "small mr"});
    ASSERT_EQ(chosen.code, 0) << chosen.err;
    EXPECT_NE(chosen.out.find("chosen: series 1"), std::string::npos) << chosen.out;
    Result unknown = run({"info", kTwoSeries, "--series", "7"});
    EXPECT_EQ(unknown.code, 1);
    EXPECT_NE(unknown.err.find("no series '7'"), std::string::npos) << unknown.err;
}

TEST(DicomCli, RendersTheMrSeriesAndTheGantryTiltedCtExactlyAsTheReference) {
    // Both hold noise (the pixels of these test series were randomised): a slab of blobs. The
    // MR is 4 mm thick in a 256 mm cube: depth 8 resolves it.
    struct Case {
        const char* input;
        const char* iso;
    };
    for (const Case& c : {Case{"medical/d2n_mr_sag_4slices_compressed_j2k", "127"}, Case{"medical/d2n_ct_gantrytilt_4slices", "-897"}}) {
        if (!haveShared(c.input)) GTEST_SKIP() << "shared data absent: " << sharedData(c.input);
        Scratch s;
        Result r = run({"render", sharedData(c.input), "--iso", c.iso, "--depth", "8", "--size", "240x180", "--threads", "2",
                        "--verify", "--stats", s.path("st.json"), "-o", s.path("out.png")});
        ASSERT_EQ(r.code, 0) << c.input << "\n" << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << c.input << "\n" << js;
        EXPECT_EQ(js.find("\"hits\": 0,"), std::string::npos) << c.input << "\n" << js;
        EXPECT_TRUE(std::filesystem::exists(s.path("out.png")));
    }
}

TEST(DicomCli, ATruncatedJpeg2000FileExitsOneNamingItAndWritesNothing) {
    const std::string f = sharedData("medical/emri_small_jpeg_2k_lossless_too_short.dcm");
    if (!haveShared("medical/emri_small_jpeg_2k_lossless_too_short.dcm")) GTEST_SKIP() << "shared data absent: " << f;
    Scratch s;
    Result r = run({"render", f, "-o", s.path("out.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(f + ": DICOM structure broken at byte 40316: encapsulated pixel data"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);
}

TEST(DicomCli, SeriesIsAUsageErrorForAnalyticInputs) {
    Result r = run({"render", "analytic:sphere:9", "--series", "1", "-o", "/tmp/never.png"});
    EXPECT_EQ(r.code, 2) << r.err;
}

// A multi-echo and a diffusion series of classic MR files (tests/data/dicom/two_echoes,
// two_bvalues: two volumes of 3 slices): `info` lists the volumes by echo or b-value, the default
// is volume 0 with a note, and `--volume N` slices each volume: the same image as the slice of a
// folder holding only that volume's files.
TEST(DicomCli, InfoListsEchoesAndBValuesAndVolumeChoosesEach) {
    struct Case {
        const char* folder;
        const char* prefix;
        const char* labels[2];
    };
    for (const Case& c : {Case{"/dicom/two_echoes", "echo", {"echo 1", "echo 2"}}, Case{"/dicom/two_bvalues", "b", {"b-value 0", "b-value 1000"}}}) {
        SCOPED_TRACE(c.folder);
        const std::string folder = std::string(OCTRACE_TEST_DATA) + c.folder;
        Result info = run({"info", folder});
        ASSERT_EQ(info.code, 0) << info.err;
        for (int v = 0; v < 2; ++v)
            EXPECT_NE(info.out.find("volume " + std::to_string(v) + ": " + c.labels[v] + ", 3 slices"), std::string::npos) << info.out;
        Scratch s;
        for (int v = 0; v < 2; ++v) {
            const std::string alone = s.path("alone" + std::to_string(v));
            std::filesystem::create_directories(alone);
            for (int k = 1; k <= 3; ++k) {
                const std::string name = c.prefix + std::to_string(v + 1) + "_s" + std::to_string(k) + ".dcm";
                std::filesystem::copy_file(folder + "/" + name, alone + "/" + name);
            }
            const std::string picked = s.path("picked" + std::to_string(v) + ".png"), reference = s.path("alone" + std::to_string(v) + ".png");
            Result r = run({"slice", folder, "--volume", std::to_string(v), "--window", "500,1000", "-o", picked});
            ASSERT_EQ(r.code, 0) << r.err;
            ASSERT_EQ(run({"slice", alone, "--window", "500,1000", "-o", reference}).code, 0);
            EXPECT_EQ(slurp(picked), slurp(reference)) << "volume " << v;
        }
        EXPECT_NE(slurp(s.path("picked0.png")), slurp(s.path("picked1.png")));  // two volumes, two images
        Result defaulted = run({"slice", folder, "-o", s.path("default.png")});
        ASSERT_EQ(defaulted.code, 0) << defaulted.err;
        EXPECT_NE(defaulted.err.find("volume 0"), std::string::npos) << defaulted.err;
    }
}

// Magnitude and phase told apart by ImageType (classic MR files) and two diffusion directions of
// one b-value (an enhanced MR file, its frames interleaved), from tests/data/dicom: `info` lists
// both volumes by what tells them apart, `--volume 1` slices the second (another image than the
// default, volume 0, which a note names).
TEST(DicomCli, InfoListsMagnitudeAndPhaseAndGradientDirectionsAsVolumes) {
    struct Case {
        const char* path;
        const char* labels[2];
    };
    for (const Case& c : {Case{"/dicom/two_image_types", {"image type ORIGINAL\\PRIMARY\\M\\ND", "image type ORIGINAL\\PRIMARY\\P\\ND"}},
                          Case{"/dicom/two_gradient_directions.dcm", {"gradient direction 0\\1\\0", "gradient direction 1\\0\\0"}}}) {
        SCOPED_TRACE(c.path);
        const std::string path = std::string(OCTRACE_TEST_DATA) + c.path;
        Result info = run({"info", path});
        ASSERT_EQ(info.code, 0) << info.err;
        EXPECT_NE(info.out.find("64x64x3, "), std::string::npos) << info.out;
        EXPECT_NE(info.out.find("volumes: 2 (choose with --volume, from 0)\nvolume 0: " + std::string(c.labels[0]) +
                                ", 3 slices\nvolume 1: " + c.labels[1] + ", 3 slices\nchosen: series 1, volume 0\n"),
                  std::string::npos) << info.out;
        Scratch s;
        Result second = run({"slice", path, "--volume", "1", "--window", "500,1000", "-o", s.path("v1.png")});
        ASSERT_EQ(second.code, 0) << second.err;
        Result defaulted = run({"slice", path, "--window", "500,1000", "-o", s.path("default.png")});
        ASSERT_EQ(defaulted.code, 0) << defaulted.err;
        EXPECT_NE(defaulted.err.find("reading volume 0"), std::string::npos) << defaulted.err;
        EXPECT_NE(slurp(s.path("v1.png")), slurp(s.path("default.png")));
    }
}

// The XA10 fMRI series (four enhanced MR files) and dcm2niix's 4-D NIfTI of it: `info` lists the
// NIfTI's volumes with their times as it lists the series' volumes with their temporal
// positions, and the slice of volume v at one position is the same PNG, byte for byte, from
// either (one window given: the NIfTI has none of its own).
TEST(DicomCli, TheFourDNiftiListsItsVolumesAndSlicesAsTheDicomSeries) {
    const std::string folder = sharedData("medical/siemens_xa10_fmri_4d"), nii = folder + "/reference_dcm2niix.nii";
    if (!std::filesystem::exists(nii)) GTEST_SKIP() << "shared data absent: " << nii;
    Result dicomInfo = run({"info", folder});
    ASSERT_EQ(dicomInfo.code, 0) << dicomInfo.err;
    EXPECT_NE(dicomInfo.out.find("64x64x6, 4 files, 4 volumes)"), std::string::npos) << dicomInfo.out;
    EXPECT_NE(dicomInfo.out.find("volume 3: temporal position 4, 6 slices\n"), std::string::npos) << dicomInfo.out;
    Result info = run({"info", nii});
    ASSERT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("volumes: 4 (choose with --volume, from 0)\n"), std::string::npos) << info.out;
    for (int v = 0; v < 4; ++v) {
        const std::string time = v % 2 ? std::to_string(v / 2) + ".5" : std::to_string(v / 2);
        EXPECT_NE(info.out.find("volume " + std::to_string(v) + ": time " + time + " s, 6 slices\n"), std::string::npos) << info.out;
    }
    EXPECT_NE(info.out.find("chosen: volume 0\n"), std::string::npos) << info.out;
    Scratch s;
    for (int v : {0, 2}) {
        const std::string fromDicom = s.path("dicom" + std::to_string(v) + ".png"), fromNifti = s.path("nifti" + std::to_string(v) + ".png");
        const std::vector<std::string> at = {"--volume", std::to_string(v), "--plane", "axial", "--at", "1.8", "--window", "600,1200", "-o"};
        std::vector<std::string> a = {"slice", folder}, b = {"slice", nii};
        a.insert(a.end(), at.begin(), at.end());
        b.insert(b.end(), at.begin(), at.end());
        a.push_back(fromDicom);
        b.push_back(fromNifti);
        Result r = run(a);
        ASSERT_EQ(r.code, 0) << r.err;
        r = run(b);
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(slurp(fromDicom), slurp(fromNifti)) << "volume " << v;
    }
    EXPECT_NE(slurp(s.path("dicom0.png")), slurp(s.path("dicom2.png")));  // two time points, two images
}
