// Medical volumes through the CLI: the LIDC chest CT written as a DICOM series (the project's
// writer) rendered with the skin and bone presets exactly as the reference; presets refused
// for values that are not Hounsfield units; display windows from the options and the file.
#include "ChestCt.h"
#include "CliRunner.h"

#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"

using namespace octrace::testcli;

namespace {

const char* kTwoSeries = OCTRACE_TEST_DATA "/dicom/two_series";

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }
std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

/// A small CT series of `dir`: HU = 8 * i - 1000 along x, with the options' window.
std::string smallCt(const Scratch& s, const std::string& name, const octrace::io::DicomSeriesWriteOptions& o) {
    octrace::ScalarField f;
    f.dims = octrace::ivec3(16, 12, 10);
    f.spacing = octrace::dvec3(0.7, 0.7, 2.0);
    f.values.resize(f.sampleCount());
    for (int k = 0; k < f.dims.z; ++k)
        for (int j = 0; j < f.dims.y; ++j)
            for (int i = 0; i < f.dims.x; ++i) f.values[f.index(i, j, k)] = float(100 * (i + j + k)) - 1000.0f;
    octrace::io::DicomSeriesWriter::write(f, s.path(name), o);
    return s.path(name);
}

}  // namespace

// The acceptance case of the medical issue. The sample holds 0..255 intensities; written as
// CT with RescaleSlope 8, RescaleIntercept -1000 (docs/dev/medical.md), shuffled, descending.
TEST(MedicalCli, TheChestCtAsADicomSeriesRendersTheSkinAndBonePresetsExactlyAsTheReference) {
    if (!haveShared("medical/lidc2_chest_ct.nrrd")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    octrace::io::DicomSeriesWriteOptions o;
    o.descending = true;
    o.shuffleSeed = 11;
    writeChestCtSeries(s.path("ct"), o);
    std::uint64_t voxels[2] = {0, 0};
    int n = 0;
    for (const char* preset : {"skin", "bone"}) {
        Result r = run({"render", s.path("ct"), "--iso", preset, "--depth", "8", "--size", "320x240", "--verify", "--stats",
                        s.path("st.json"), "-o", s.path(std::string(preset) + ".png")});
        ASSERT_EQ(r.code, 0) << preset << "\n" << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_TRUE(has(js, "\"mismatched_pixels\": 0,")) << preset << "\n" << js;
        EXPECT_FALSE(has(js, "\"hits\": 0,")) << preset << "\n" << js;
        EXPECT_TRUE(has(js, std::string("\"iso\": ") + (preset == std::string("skin") ? "-500" : "300"))) << js;
        EXPECT_TRUE(has(js, "\"units\": \"HU\"")) << js;
        const std::size_t at = js.find("\"boundary_voxels\": ");
        ASSERT_NE(at, std::string::npos);
        voxels[n++] = std::stoull(js.substr(at + 19));
    }
    // Two different surfaces: everything denser than -500 HU holds the bones (300 HU).
    EXPECT_GT(voxels[0], voxels[1]);
    EXPECT_GT(voxels[1], 10000u);
}

TEST(MedicalCli, PresetsAreRefusedForValuesThatAreNotHounsfieldUnits) {
    Scratch s;
    for (const char* option : {"--iso", "--window"}) {
        const char* preset = option == std::string("--iso") ? "bone" : "lung";
        Result r = run({"render", kTwoSeries, "--series", "small mr", option, preset, "-o", s.path("out.png")});
        EXPECT_EQ(r.code, 1) << r.err;
        EXPECT_TRUE(has(r.err, kTwoSeries + std::string(": ") + option + " " + preset +
                                   " is a CT preset in Hounsfield units, but the values of 'MR' are not in HU"))
            << r.err;
        Result analytic = run({"render", "analytic:sphere:9", option, preset, "-o", s.path("out.png")});
        EXPECT_EQ(analytic.code, 1) << analytic.err;
        EXPECT_TRUE(has(analytic.err, "is a CT preset in Hounsfield units")) << analytic.err;
    }
    EXPECT_EQ(countEntries(s.dir()), 0);
    // A number still works on any field; a window given as numbers too.
    Result number = run({"render", kTwoSeries, "--series", "small mr", "--iso", "5", "--window", "5,10", "--size", "64x48",
                         "-o", s.path("mr.png")});
    EXPECT_EQ(number.code, 0) << number.err;
}

TEST(MedicalCli, MalformedOrConflictingWindowsAreUsageErrors) {
    struct Case {
        std::vector<std::string> args;
        const char* message;
    };
    const Case cases[] = {
        {{"--window", "40,0"}, "--window: the width must be positive"},
        {{"--window", "liver"}, "--window: give a preset (brain, soft-tissue, lung, bone, none) or CENTRE,WIDTH, got 'liver'"},
        {{"--window", "1,2,3"}, "--window: give a preset"},
        {{"--window", "bone", "--colour", "1,0,0"}, "--window bone and --colour both colour the surface"},
        {{"--window", "40,400", "--colormap", "viridis"}, "--window 40,400 and --colormap both colour the surface"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args = {"render", "analytic:sphere:9", "-o", "/tmp/never.png"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        Result r = run(args);
        EXPECT_EQ(r.code, 2) << c.message << "\n" << r.err;
        EXPECT_TRUE(has(r.err, c.message)) << r.err;
    }
}

TEST(MedicalCli, TheWindowStoredInTheFileColoursTheSurfaceUnlessAColourIsGiven) {
    Scratch s;
    octrace::io::DicomSeriesWriteOptions o;
    o.window = {-300.0, 1200.0};
    const std::string ct = smallCt(s, "ct", o);
    o.monochrome1 = true;
    const std::string inverted = smallCt(s, "ct1", o);
    auto render = [&](const std::string& input, std::vector<std::string> extra) {
        std::vector<std::string> args = {"render", input, "--iso", "-200", "--size", "64x48", "--stats", s.path("st.json"),
                                         "-o", s.path("out.png")};
        args.insert(args.end(), extra.begin(), extra.end());
        Result r = run(args);
        EXPECT_EQ(r.code, 0) << r.err;
        return std::make_pair(r, slurp(s.path("st.json")));
    };
    auto [r, js] = render(ct, {});
    EXPECT_TRUE(has(r.err, "colouring by the file's display window, centre -300 width 1200")) << r.err;
    EXPECT_TRUE(has(js, "\"window_centre\": -300,")) << js;
    EXPECT_TRUE(has(js, "\"window_width\": 1200,")) << js;
    EXPECT_TRUE(has(js, "\"window_inverted\": false")) << js;
    EXPECT_TRUE(has(render(inverted, {}).second, "\"window_inverted\": true")) << "MONOCHROME1";
    // A preset or numbers replace it; --colour or --window none turn it off.
    EXPECT_TRUE(has(render(ct, {"--window", "lung"}).second, "\"window_centre\": -600,"));
    EXPECT_TRUE(has(render(ct, {"--window", "10,20"}).second, "\"window_source\": \"--window 10,20\""));
    EXPECT_FALSE(has(render(ct, {"--colour", "1,0,0"}).second, "window_centre"));
    EXPECT_FALSE(has(render(ct, {"--window", "none"}).second, "window_centre"));
    // octrace build colours nothing: the file's window is not applied (nor announced).
    Result built = run({"build", ct, "--iso", "-200", "-o", s.path("ct.oct")});
    EXPECT_EQ(built.code, 0) << built.err;
    EXPECT_FALSE(has(built.err, "display window")) << built.err;
}

// The real gantry-tilted CT: one warning line naming the tilt, and the geometry of the
// orthogonal grid it is resampled onto (the reader's test checks the numbers in full).
TEST(MedicalCli, TheGantryTiltedCtLoadsWithAWarningAndItsResampledGeometry) {
    const char* rel = "medical/d2n_ct_gantrytilt_4slices";
    if (!haveShared(rel)) GTEST_SKIP() << "shared data absent: " << sharedData(rel);
    Result r = run({"info", sharedData(rel)});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "warning: " + sharedData(rel) + ": slices are sheared by a gantry tilt of 14 degrees")) << r.err;
    // Once, though info reads the series twice (its description, then its depth auto).
    EXPECT_EQ(occurrences(r.err, "gantry tilt"), 1u) << r.err;
    EXPECT_TRUE(has(r.out, "dims: 512 x 521 x 4")) << r.out;
    EXPECT_TRUE(has(r.out, "spacing: 0.417969 x 0.417969 x 4.85148")) << r.out;
    EXPECT_TRUE(has(r.out, "direction (columns): (1, 0, 0) (0, 0.970296, -0.241922) (-0, 0.241922, 0.970296)")) << r.out;
    EXPECT_TRUE(has(r.out, "units 'HU'")) << r.out;
}

// A series of several volumes: info lists them, and the note that volume 0 is read comes once.
TEST(MedicalCli, InfoOnASeriesOfSeveralVolumesSaysItsNoteOnce) {
    for (const char* rel : {"medical/siemens_xa10_fmri_4d", "medical/siemens_xa10_fmri_4d/reference_dcm2niix.nii"}) {
        if (!haveShared(rel)) GTEST_SKIP() << "shared data absent: " << sharedData(rel);
        Result r = run({"info", sharedData(rel)});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_EQ(occurrences(r.err, "reading volume 0"), 1u) << rel << ": " << r.err;
        EXPECT_TRUE(has(r.out, "volume 3")) << r.out;
    }
}
