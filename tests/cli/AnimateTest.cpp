// octrace animate and the pipeline library's animation (model/Animation.h): the time selection,
// the plan (time axis, captions, the fixed colour range), frames as a pure function of (plan, i),
// and the MP4 that the CLI writes (counted and decoded with ffprobe / ffmpeg).
#include "../io/CfFileWriter.h"
#include "../io/ImageTestSupport.h"
#include "CliRunner.h"
#include "TimeSeries.h"

#include "octrace/io/FieldReader.h"
#include "octrace/io/TimeAxis.h"
#include "octrace/io/VideoWriter.h"
#include "octrace/model/Animation.h"
#include "octrace/model/Figure.h"
#include "octrace/model/Surface.h"
#include "octrace/model/Render.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <string>
#include <vector>

using namespace octrace::testcli;
using octrace::test::DecodedPng;
using octrace::test::decodePng;
using octrace::test::readBytes;
namespace model = octrace::model;
namespace io = octrace::io;

namespace {

io::TimeAxis monthlyAxis() {
    io::TimeAxis a;
    a.path = "monthly.nc";
    a.name = "time";
    a.size = 3;
    a.units = "days since 2000-01-01";
    a.calendar = "standard";
    a.values = {0.0, 31.0, 60.0};
    a.dates = {"2000-01-01", "2000-02-01", "2000-03-01"};
    return a;
}

model::AnimationSpec specOf(const std::string& input) {
    model::AnimationSpec s;
    s.surface.input = input;
    s.surface.request.variable = "TEMP";
    s.surface.iso = 0.8;
    s.surface.depth = 5;
    s.surface.threads = 1;
    s.render.width = 64;
    s.render.height = 48;
    return s;
}

/// Pixels that are not the white background.
std::size_t drawn(const DecodedPng& p) {
    std::size_t n = 0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) n += p.at(x, y, 0) < 250 || p.at(x, y, 1) < 250 || p.at(x, y, 2) < 250;
    return n;
}

/// A command's standard output (popen), or "" when it cannot run.
std::string capture(const std::string& command) {
    std::string out;
    if (FILE* f = popen(command.c_str(), "r")) {
        char buf[65536];
        for (std::size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
        pclose(f);
    }
    return out;
}

bool haveFfmpeg() { return std::system("ffprobe -version > /dev/null 2>&1 && ffmpeg -version > /dev/null 2>&1") == 0; }

}  // namespace

TEST(AnimationTimes, ParsesAllIndexRangesAndDateRanges) {
    EXPECT_EQ(model::parseTimeSelection("all").kind, model::TimeSelection::Kind::All);
    const auto r = model::parseTimeSelection("1:2");
    EXPECT_EQ(r.kind, model::TimeSelection::Kind::Indices);
    EXPECT_EQ(r.first, 1u);
    EXPECT_EQ(r.last, 2u);
    const auto one = model::parseTimeSelection("2");
    EXPECT_EQ(one.first, 2u);
    EXPECT_EQ(one.last, 2u);
    const auto d = model::parseTimeSelection("2000-01-15:2000-03-01T12:00");
    EXPECT_EQ(d.kind, model::TimeSelection::Kind::Dates);
    EXPECT_EQ(d.from, "2000-01-15");
    EXPECT_EQ(d.to, "2000-03-01T12:00");
    const auto t = model::parseTimeSelection("2000-01-15T06:30:2000-03-01");
    EXPECT_EQ(t.from, "2000-01-15T06:30");
    EXPECT_EQ(t.to, "2000-03-01");
    for (const char* bad : {"", "x", "1:", ":2", "2:1", "-1:2", "1:2:3", "2000-01-01:soon", "2000-03-01:2000-01-01", "1.5:2"})
        EXPECT_THROW(model::parseTimeSelection(bad), octrace::UsageError) << "'" << bad << "'";
}

TEST(AnimationTimes, SelectsStepsOfTheAxisOrSaysWhyNot) {
    const io::TimeAxis axis = monthlyAxis();
    EXPECT_EQ(model::selectSteps(model::parseTimeSelection("all"), axis), (std::vector<std::size_t>{0, 1, 2}));
    EXPECT_EQ(model::selectSteps(model::parseTimeSelection("1:2"), axis), (std::vector<std::size_t>{1, 2}));
    EXPECT_EQ(model::selectSteps(model::parseTimeSelection("2000-01-15:2000-03-01"), axis), (std::vector<std::size_t>{1, 2}));
    EXPECT_EQ(model::selectSteps(model::parseTimeSelection("2000-01-01:2000-01-01"), axis), (std::vector<std::size_t>{0}));
    EXPECT_THROW(model::selectSteps(model::parseTimeSelection("1:3"), axis), octrace::InputError);
    EXPECT_THROW(model::selectSteps(model::parseTimeSelection("2001-01-01:2001-02-01"), axis), octrace::InputError);
    EXPECT_THROW(model::selectSteps(model::parseTimeSelection("2001-02-29:2001-03-01"), axis), octrace::InputError);  // not a date
    io::TimeAxis none;
    none.path = "flat.nc";
    EXPECT_THROW(model::selectSteps(model::parseTimeSelection("all"), none), octrace::InputError);
    io::TimeAxis undated = axis;
    undated.units = "months";
    undated.calendar.clear();
    undated.dates.assign(3, "");
    EXPECT_THROW(model::selectSteps(model::parseTimeSelection("2000-01-01:2000-02-01"), undated), octrace::InputError);
    EXPECT_EQ(model::selectSteps(model::parseTimeSelection("0:1"), undated).size(), 2u);
}

TEST(AnimationPlan, ReadsTheTimeAxisCaptionsTheDatesAndFixesTheColourRange) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    io::FieldRequest temp;
    temp.variable = "TEMP";
    const io::TimeAxis axis = io::readTimeAxis(nc, temp);
    EXPECT_EQ(axis.name, "time");
    ASSERT_EQ(axis.size, 3u);
    EXPECT_EQ(axis.dates, (std::vector<std::string>{"2000-01-01", "2000-02-01", "2000-03-01"}));

    model::AnimationSpec spec = specOf(nc);
    spec.orbitDegrees = 90.0;
    spec.surface.colourBy = "SAL";
    const model::AnimationPlan plan = model::planAnimation(spec);
    ASSERT_EQ(plan.frames.size(), 3u);
    EXPECT_EQ(plan.frames[1].time, "1");
    EXPECT_EQ(plan.frames[2].caption, "2000-03-01");
    EXPECT_DOUBLE_EQ(plan.frames[2].orbitDegrees, 60.0);
    EXPECT_FLOAT_EQ(plan.colourMin, 30.0f);  // the union of SAL's ranges over the three steps
    EXPECT_FLOAT_EQ(plan.colourMax, 32.0f);

    spec.surface.colourMin = 0.0f;
    spec.surface.colourMax = 100.0f;
    spec.times = "2000-02-01:2000-03-01";
    const model::AnimationPlan given = model::planAnimation(spec);
    ASSERT_EQ(given.frames.size(), 2u);
    EXPECT_EQ(given.frames[0].step, 1u);
    EXPECT_FLOAT_EQ(given.colourMax, 100.0f);
}

TEST(AnimationPlan, AFrameIsAPureFunctionOfThePlanAndItsIndex) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    model::AnimationSpec spec = specOf(nc);
    spec.orbitDegrees = 120.0;
    spec.surface.colourBy = "SAL";
    spec.figure.enabled = true;
    spec.render.width = 320;
    spec.render.height = 240;
    const model::AnimationPlan plan = model::planAnimation(spec);
    const auto first2 = model::renderAnimationFrame(plan, 2).rgba8();
    const auto first0 = model::renderAnimationFrame(plan, 0).rgba8();
    // Again, the other way round and on two threads at once, from a copy of the plan.
    const model::AnimationPlan copy = plan;
    auto again0 = std::async(std::launch::async, [&] { return model::renderAnimationFrame(copy, 0).rgba8(); });
    auto again2 = std::async(std::launch::async, [&] { return model::renderAnimationFrame(plan, 2).rgba8(); });
    EXPECT_EQ(again2.get(), first2);
    EXPECT_EQ(again0.get(), first0);
    EXPECT_NE(first0, first2);
    EXPECT_THROW(model::renderAnimationFrame(plan, 3), octrace::UsageError);
}

TEST(AnimationPlan, ColoursByHeightOverTheGridInEveryFrame) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    model::AnimationSpec spec = specOf(nc);
    spec.surface.colormap = "viridis";
    const model::AnimationPlan plan = model::planAnimation(spec);
    // Depths 0 .. 700 m: heights -700 .. 0 m above the sea surface, whatever each frame's surface spans.
    EXPECT_FLOAT_EQ(plan.colourMin, -700.0f);
    EXPECT_FLOAT_EQ(plan.colourMax, 0.0f);
    EXPECT_NE(plan.colourRangeSource.find("height over the grid: [-700, 0] m"), std::string::npos) << plan.colourRangeSource;

    // A frame is the render of its step with that range given as colour_range...
    model::SurfaceSpec step2 = plan.spec.surface;
    step2.request.time = "2";
    step2.colourMin = -700.0f;
    step2.colourMax = 0.0f;
    const model::Surface surface = model::buildSurface(step2);
    const octrace::RenderSettings rs = model::renderSettings(step2, surface, plan.spec.render);
    octrace::Frame frame;
    model::renderFrame(surface.tree, model::animationCamera(plan, 2), rs, plan.spec.render.renderer, frame);
    const model::AnimationImage framed = model::renderAnimationFrame(plan, 2);
    EXPECT_EQ(octrace::quantizeSrgb8(frame, 4), framed.rgba8());
    // ...and differs from the surface's own height range (the shrinking ball spans less than the grid).
    model::SurfaceSpec own = step2;
    own.colourMin = own.colourMax = std::numeric_limits<float>::quiet_NaN();
    const octrace::RenderSettings ownRs = model::renderSettings(own, surface, plan.spec.render);
    octrace::Frame ownFrame;
    model::renderFrame(surface.tree, model::animationCamera(plan, 2), ownRs, plan.spec.render.renderer, ownFrame);
    EXPECT_NE(octrace::quantizeSrgb8(ownFrame, 4), framed.rgba8());
}

// Without `iso`, every frame's surface is at the first step's default iso value (Otsu's
// threshold of an image volume: model::defaultIso), as render would choose it for that step:
// the XA10 fMRI's volumes have their own samples, and each frame choosing its own would move the
// surface between frames.
TEST(AnimationPlan, WithoutAnIsoEveryFrameTakesTheFirstVolumesDefault) {
    const std::string folder = sharedData("medical/siemens_xa10_fmri_4d");
    if (!std::filesystem::exists(folder)) GTEST_SKIP() << "shared data absent: " << folder;
    auto middle = [&](int volume) {
        io::FieldRequest r;
        r.volume = volume;
        return model::defaultIso(io::readField(folder, r), folder).first;
    };
    model::AnimationSpec spec;
    spec.surface.input = folder;
    spec.surface.depth = 6;
    const model::AnimationPlan plan = model::planAnimation(spec);
    ASSERT_EQ(plan.frames.size(), 4u);
    ASSERT_TRUE(plan.spec.surface.iso.has_value());
    EXPECT_DOUBLE_EQ(*plan.spec.surface.iso, middle(0));
    EXPECT_NE(middle(2), middle(0));  // the volumes' own values differ: the choice matters
    const std::string first = "every frame's surface at the iso value of the first: " + model::numberText(middle(0)) +
                              ", Otsu's threshold of the valid samples of 'MR' (range [0, 1199]";
    const bool said = std::any_of(plan.notes.begin(), plan.notes.end(), [&](const std::string& n) { return n.find(first) != std::string::npos; });
    EXPECT_TRUE(said) << ::testing::PrintToString(plan.notes);
    // A given iso stays.
    spec.surface.iso = 300.0;
    EXPECT_DOUBLE_EQ(*model::planAnimation(spec).spec.surface.iso, 300.0);

    // The CLI says it once on stderr, and no frame chooses its own.
    if (!haveFfmpeg()) GTEST_SKIP() << "ffprobe/ffmpeg absent (Debian package ffmpeg, scripts/setup.sh)";
    Scratch s;
    const Result r = run({"animate", folder, "--depth", "6", "--size", "64x48", "-o", s.path("fmri.mp4")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find(first), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--iso sets another"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("no --iso given"), std::string::npos) << r.err;
}

TEST(VideoWriter, KeepsEveryFrameWhateverTheCount) {
    if (!haveFfmpeg()) GTEST_SKIP() << "ffprobe/ffmpeg absent (Debian package ffmpeg, scripts/setup.sh)";
    Scratch s;
    for (int n = 1; n <= 9; ++n) {
        const std::string mp4 = s.path(std::string("n") + std::to_string(n) + ".mp4");
        io::VideoWriter v(mp4, 64, 48, 12);
        for (int i = 0; i < n; ++i) v.add(std::vector<std::uint8_t>(64 * 48 * 4, std::uint8_t(i * 25)));
        v.finish();
        EXPECT_EQ(capture("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 " +
                          quoteArg(mp4)),
                  std::to_string(n) + "\n")
            << n << " frames";
    }
}

// Whether this process has a library whose file name starts with `prefix` mapped.
bool libraryMapped(const std::string& prefix) {
    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);) {
        const std::size_t slash = line.rfind('/');
        if (slash != std::string::npos && line.compare(slash + 1, prefix.size(), prefix) == 0) return true;
    }
    return false;
}

TEST(VideoWriter, FfmpegIsLoadedOnlyWhenAVideoIsWritten) {
    if (!std::ifstream("/proc/self/maps")) GTEST_SKIP() << "no /proc/self/maps";
    if (!haveFfmpeg()) GTEST_SKIP() << "ffprobe/ffmpeg absent (Debian package ffmpeg, scripts/setup.sh)";
    // In a fresh process (the test binary started again for this statement alone): another test
    // of this process may have written a video already.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            int code = 0;
            if (libraryMapped("libavcodec.so") || libraryMapped("libavformat.so")) code |= 1;  // linked: loaded at start
            {
                Scratch s;
                const std::string mp4 = s.path("one.mp4");
                io::VideoWriter v(mp4, 16, 16, 12);
                if (!libraryMapped("libavcodec.so") || !libraryMapped("libswscale.so")) code |= 2;
                v.add(std::vector<std::uint8_t>(16 * 16 * 4, 200));
                v.finish();
                const std::string frames = capture(
                    "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 " + quoteArg(mp4));
                if (frames != "1\n") code |= 4;
            }
            std::_Exit(code);
        },
        testing::ExitedWithCode(0), "")
        << "exit code 1: FFmpeg is linked (every octrace process loads its 88 libraries at start); 2: not opened by the "
           "writer; 4: the video does not hold its one frame";
}

TEST(AnimateCli, WritesOneVideoFramePerStepInOrderWithTheDateInTheCaption) {
    if (!haveFfmpeg()) GTEST_SKIP() << "ffprobe/ffmpeg absent (Debian package ffmpeg, scripts/setup.sh)";
    Scratch s;
    const std::string nc = s.path("monthly.nc"), mp4 = s.path("out.mp4"), dir = s.path("frames");
    writeTimeSeries(nc);
    if (const char* keep = std::getenv("OCTRACE_KEEP_ANIMATION")) std::filesystem::copy_file(nc, keep, std::filesystem::copy_options::overwrite_existing);
    const Result r = run({"animate", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "5", "--time", "all", "--size", "401x301",
                          "--figure", "--title", "shrinking", "--frames", dir, "-o", mp4});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("3 frames"), std::string::npos) << r.err;
    EXPECT_EQ(capture("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,codec_name,width,height "
                      "-of csv=p=0 " + quoteArg(mp4)),
              "h264,402,302,3\n");  // odd sides padded to even

    // The PNG frames: the ball shrinks step after step; the subtitle (above the plot) differs by its date.
    std::vector<DecodedPng> frames;
    for (int i = 0; i < 3; ++i) frames.push_back(decodePng(readBytes(dir + "/frame_000" + std::to_string(i) + ".png")));
    ASSERT_EQ(frames[0].width, 401);
    EXPECT_GT(drawn(frames[0]), drawn(frames[1]) + 200);
    EXPECT_GT(drawn(frames[1]), drawn(frames[2]) + 200);
    auto topRows = [](const DecodedPng& p) {
        return std::vector<std::uint8_t>(p.pixels.begin(), p.pixels.begin() + std::ptrdiff_t(60 * p.width * p.channels));
    };
    EXPECT_NE(topRows(frames[0]), topRows(frames[1]));

    // The video's frames, decoded, in the same order: fewer drawn pixels each step.
    const std::string raw = capture("ffmpeg -v error -i " + quoteArg(mp4) + " -f rawvideo -pix_fmt rgb24 -");
    const std::size_t frameBytes = 402u * 302u * 3u;
    ASSERT_EQ(raw.size(), 3 * frameBytes);
    std::vector<std::size_t> dark(3, 0);
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t p = 0; p < frameBytes; p += 3)
            dark[i] += std::uint8_t(raw[i * frameBytes + p]) < 235 || std::uint8_t(raw[i * frameBytes + p + 2]) < 235;
    EXPECT_GT(dark[0], dark[1]);
    EXPECT_GT(dark[1], dark[2]);
}

TEST(AnimateCli, RefusesWhatItCannotAnimateClearly) {
    Scratch s;
    const std::string nc = s.path("monthly.nc");
    writeTimeSeries(nc);
    Result r = run({"animate", "analytic:sphere", "-o", s.path("a.mp4")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("has no time axis"), std::string::npos) << r.err;
    r = run({"animate", nc, "--var", "TEMP", "--time", "1:5", "-o", s.path("b.mp4")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("has 3 steps, indices 0..2; --time 1:5 goes beyond them"), std::string::npos) << r.err;
    r = run({"animate", nc, "--var", "TEMP", "--time", "3:1", "-o", s.path("c.mp4")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--time: the range 3:1 ends before it starts"), std::string::npos) << r.err;
    r = run({"animate", nc, "--var", "TEMP", "-o", s.path("d.avi")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("animate writes an MP4 video (.mp4)"), std::string::npos) << r.err;
    r = run({"animate", nc, "--var", "TEMP", "-o", "/nonexistent-octrace-output/e.mp4"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("/nonexistent-octrace-output/e.mp4"), std::string::npos) << r.err;
    // A folder that cannot be written: refused after the work, and nothing is left in it.
    const std::string locked = s.path("locked");
    std::filesystem::create_directories(locked);
    std::filesystem::permissions(locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    if (::access(locked.c_str(), W_OK) != 0) {  // root writes anyway
        r = run({"animate", nc, "--var", "TEMP", "--iso", "0.8", "--depth", "4", "--size", "32x24", "-o", locked + "/f.mp4"});
        EXPECT_EQ(r.code, 1);
        EXPECT_NE(r.err.find(locked + "/f.mp4"), std::string::npos) << r.err;
        EXPECT_TRUE(std::filesystem::is_empty(locked));
    }
    std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
}

// The four time points of the XA10 fMRI series (four enhanced MR files): one frame per volume,
// in order, each captioned with its volume and temporal position, from one camera and one
// window (the file's), counted with ffprobe.
TEST(AnimateCli, WritesOneVideoFramePerVolumeOfADicomSeriesWithItsLabelInTheCaption) {
    if (!haveFfmpeg()) GTEST_SKIP() << "ffprobe/ffmpeg absent (Debian package ffmpeg, scripts/setup.sh)";
    const std::string folder = sharedData("medical/siemens_xa10_fmri_4d");
    if (!std::filesystem::exists(folder)) GTEST_SKIP() << "shared data absent: " << folder;
    Scratch s;
    const std::string mp4 = s.path("fmri.mp4"), dir = s.path("frames");
    const Result r = run({"animate", folder, "--iso", "300", "--depth", "6", "--size", "320x240", "--figure", "--frames", dir,
                          "-o", mp4});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("4 frames"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("steps volume 0: temporal position 1 .. volume 3: temporal position 4 of 'volume'"), std::string::npos) << r.err;
    EXPECT_EQ(capture("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 " +
                      quoteArg(mp4)),
              "4\n");
    // Each frame's subtitle (above the plot) says its own volume.
    std::vector<DecodedPng> frames;
    for (int i = 0; i < 4; ++i) frames.push_back(decodePng(readBytes(dir + "/frame_000" + std::to_string(i) + ".png")));
    auto topRows = [](const DecodedPng& p) {
        return std::vector<std::uint8_t>(p.pixels.begin(), p.pixels.begin() + std::ptrdiff_t(70 * p.width * p.channels));
    };
    for (int i = 1; i < 4; ++i) EXPECT_NE(topRows(frames[0]), topRows(frames[std::size_t(i)])) << "frame " << i;
    for (const DecodedPng& f : frames) EXPECT_GT(drawn(f), 1000u);
    // Volumes have no dates; one volume is not an animation's to choose.
    Result bad = run({"animate", folder, "--time", "2000-01-01:2000-02-01", "-o", s.path("b.mp4")});
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("its 4 volumes have no dates"), std::string::npos) << bad.err;
    bad = run({"animate", folder, "--time", "2:7", "-o", s.path("c.mp4")});
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("has 4 steps, indices 0..3"), std::string::npos) << bad.err;
}
