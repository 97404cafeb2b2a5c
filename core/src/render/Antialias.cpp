// Antialiasing of every voxel renderer: the frame drawn once per sample point of a regular grid
// inside each pixel (Camera::sampleOffset), the colours averaged. See renderAntialiased in
// Renderer.h.
#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <cmath>
#include <string>

namespace octrace {

int samplesPerSide(int samples) {
    const int s = int(std::lround(std::sqrt(double(samples))));
    if (samples < 1 || s * s != samples || s > 16)
        throw UsageError("`samples` must be a square number of rays per pixel (1, 4, 9, 16, ... 256), got " + std::to_string(samples));
    return s;
}

RenderStats renderAntialiased(const Renderer& renderer, const Octree& octree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame) {
    const int s = samplesPerSide(settings.spheres.samples);
    if (s == 1) return renderer.render(octree, camera, settings, frame);
    camera.validate();
    Timer timer;
    const std::size_t n = std::size_t(camera.width) * std::size_t(camera.height);
    std::vector<vec4> sum(n, vec4(0.0f));  // premultiplied colour, alpha
    Frame sample;
    RenderStats total;
    for (int b = 0; b < s; ++b)
        for (int a = 0; a < s; ++a) {
            Camera c = camera;
            c.sampleOffset = dvec2((a + 0.5) / s - 0.5, (b + 0.5) / s - 0.5);
            Frame& target = (a == 0 && b == 0) ? frame : sample;
            const RenderStats st = renderer.render(octree, c, settings, target);
            if (a == 0 && b == 0) {
                total = st;
            } else {
                total.add(st);
            }
            parallelFor(std::size_t(camera.height), settings.threads, [&](std::size_t y) {
                const std::size_t row = y * std::size_t(camera.width);
                for (std::size_t i = row; i < row + std::size_t(camera.width); ++i) {
                    const vec4 p = target.rgba[i];
                    sum[i] += vec4(vec3(p) * p.a, p.a);
                }
            });
        }
    const float inv = 1.0f / float(s * s);
    parallelFor(std::size_t(camera.height), settings.threads, [&](std::size_t y) {
        const std::size_t row = y * std::size_t(camera.width);
        for (std::size_t i = row; i < row + std::size_t(camera.width); ++i) {
            const vec4 m = sum[i];
            frame.rgba[i] = m.a > 0.0f ? vec4(vec3(m) / m.a, m.a * inv) : vec4(0.0f);
        }
    });
    total.pixels = n;
    total.renderMs = timer.ms();
    return total;
}

}  // namespace octrace
