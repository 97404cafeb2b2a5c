// octrace animate: one surface per time step of a field, rendered from a fixed (or orbiting)
// camera in one colour range, written as an MP4 video (and, with --frames, as PNGs). The
// pipeline is the library's (model/Animation.h): the plan once, then each frame by itself.
#include "Commands.h"
#include "FigureOptions.h"
#include "Options.h"
#include "SurfaceOptions.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/io/VideoWriter.h"
#include "octrace/model/Animation.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Parallel.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace octrace::cli {
namespace {

struct AnimateArgs : SurfaceArgs {
    model::RenderSpec render;
    FigureArgs figure;
    std::string output, framesDir, times = model::opt::times.defaultText;
    double orbit = model::opt::orbit.defaultValue;
    int fps = int(model::opt::fps.defaultValue);
};

constexpr int kWidth = 960, kHeight = 720;  // a video's default size: smaller than a still's

OptionParser makeParser(AnimateArgs& a) {
    OptionParser p("animate", "octrace animate INPUT -o OUT.mp4 [--time all|I:J|DATE:DATE] [options]");
    p.add({"o", "FILE", "output video, .mp4 (H.264) (required)", [&](const std::string& v) { a.output = v; }});
    p.add(tableOption(model::opt::times, [&](const std::string& v) {
        model::parseTimeSelection(v);
        a.times = v;
    }));
    p.add(tableOption(model::opt::fps, [&](const std::string& v) { a.fps = tableInt(model::opt::fps, v); }));
    p.add(tableOption(model::opt::orbit, [&](const std::string& v) { a.orbit = tableNumber(model::opt::orbit, v); }));
    p.add(tableOption(model::opt::frames, [&](const std::string& v) {
        if (v.empty()) throw UsageError("--frames: empty (give a folder)");
        a.framesDir = v;
    }));
    addSurfaceOptions(p, a);
    addFormOptions(p, a);
    addLightingOption(p, a);
    addBakeOptions(p, a);
    addColourOptions(p, a);
    addLayerOptions(p, a);
    addGeographicOptions(p, a.request, false);
    // The view, as render takes it (a fixed camera unless --orbit).
    model::RenderSpec& r = a.render;
    r.width = kWidth;
    r.height = kHeight;
    const model::SettingTargets into{.surface = &a, .render = &r, .figure = &a.figure};
    p.add(settingOption(model::opt::renderer, into, "one of " + joinNames(rendererNames())));
    p.add({"size", "WxH", "frame size in pixels, each side " + model::opt::width.rangeText() + " (default " + std::to_string(kWidth) +
           "x" + std::to_string(kHeight) + "; odd sides are padded to even in the video)",
           [into](const std::string& v) { model::applySetting(model::opt::size, v, into); }});
    for (const model::Option* o : {&model::opt::cameraPos, &model::opt::lookAt, &model::opt::up, &model::opt::fov,
                                   &model::opt::background, &model::opt::light, &model::opt::samples})
        p.add(settingOption(*o, into));
    addThreadsOption(p, a, "the video");
    addFigureOptions(p, a.figure, "a colour bar with units, the variable, the region, labelled ticks on the bounding box, and each "
                                  "frame's date at the start of the subtitle");
    addMessageOptions(p, a);
    return p;
}

/// "\roctrace: animate [#####.....] 5/10 frames" on a terminal; nothing otherwise.
class ProgressBar {
public:
    ProgressBar(bool quiet, std::size_t total) : on_(!quiet && isatty(2)), total_(total) {}
    void show(const char* what, std::size_t done) const {
        if (!on_) return;
        constexpr std::size_t kCells = 30;
        const std::size_t full = total_ ? done * kCells / total_ : kCells;
        std::string bar(full, '#');
        bar.resize(kCells, '.');
        std::fprintf(stderr, "\roctrace: %s [%s] %zu/%zu", what, bar.c_str(), done, total_);
        if (done >= total_) std::fputs("\n", stderr);
        std::fflush(stderr);
    }

private:
    bool on_;
    std::size_t total_;
};

}  // namespace

int runAnimate(const std::vector<std::string>& args) {
    AnimateArgs a;
    const OptionParser parser = makeParser(a);
    if (!parseCommandLine(parser, args, a, a.output, "an output video: -o OUT.mp4")) return 0;
    if (model::lowerExtension(a.output) != ".mp4") throw UsageError("-o " + a.output + ": animate writes an MP4 video (.mp4)");
    checkFigureOptions(a.figure, "frame.png");  // each frame is a PNG-like image; the video holds them
    if (a.quiet) log::setLevel(log::Level::Error);
    if (a.verbose) log::setLevel(log::Level::Debug);
    io::checkOutputFolder(a.output);
    if (!a.framesDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(a.framesDir, ec);
        if (ec || !std::filesystem::is_directory(a.framesDir))
            throw OutputError(a.framesDir + ": cannot make the folder for --frames" + (ec ? ": " + ec.message() : std::string()));
    }

    model::AnimationSpec spec;
    spec.surface = a;
    spec.render = a.render;
    spec.figure = a.figure;
    spec.times = a.times;
    spec.orbitDegrees = a.orbit;
    spec.fps = a.fps;
    model::AnimationHooks planning;
    if (!a.quiet && isatty(2))
        planning.progress = [](double f) {
            std::fprintf(stderr, "\roctrace: planning %3d%%", int(f * 100.0 + 0.5));
            if (f >= 1.0) std::fputs("\n", stderr);
        };
    model::AnimationPlan plan = model::planAnimation(spec, planning);
    for (const auto& n : plan.notes) log::info(n);
    const std::size_t n = plan.frames.size();

    // Frames in parallel, a batch at a time, each with its share of the memory budget; the video
    // takes them in order. Each frame is a pure function of the plan: the batch size changes no pixel.
    const int threads = a.threads == 0 ? hardwareThreads() : a.threads;
    const std::size_t batch = std::clamp<std::size_t>(std::size_t(threads), 1, n);
    plan.spec.surface.maxMemory = std::max<std::uint64_t>(1, memoryBudget(a) / batch);
    plan.spec.surface.threads = std::max(1, threads / int(batch));
    io::VideoWriter video(a.output, plan.width, plan.height, a.fps);
    io::ImageWriteOptions png;
    png.dpi = plan.figureLayout ? plan.figureLayout->dpi : a.figure.dpi;
    const ProgressBar bar(a.quiet, n);
    bar.show("animate", 0);
    for (std::size_t start = 0; start < n; start += batch) {
        const std::size_t count = std::min(batch, n - start);
        std::vector<model::AnimationImage> images(count);
        parallelFor(count, int(count), [&](std::size_t k) { images[k] = model::renderAnimationFrame(plan, start + k); });
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t i = start + k;
            if (images[k].stats.hits == 0) log::warning("frame " + std::to_string(i) + " (" + plan.frames[i].caption + "): the surface is not in view");
            video.add(images[k].rgba8());
            if (!a.framesDir.empty()) {
                char name[32];
                std::snprintf(name, sizeof name, "frame_%04zu.png", i);
                io::writeImage(images[k].image, (std::filesystem::path(a.framesDir) / name).string(), png);
            }
            bar.show("animate", i + 1);
        }
    }
    video.finish();
    std::ostringstream s;
    s << a.output << ": " << n << " frames " << plan.width << "x" << plan.height << " at " << a.fps << " fps (" << video.codec()
      << "), steps " << plan.frames.front().caption << " .. " << plan.frames.back().caption << " of '" << plan.timeAxis << "'";
    if (a.orbit != 0.0) s << ", orbiting " << a.orbit << " degrees";
    log::info(s.str());
    return 0;
}

}  // namespace octrace::cli
