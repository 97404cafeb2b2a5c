#include "octrace/render/Frame.h"

#include <algorithm>

namespace octrace {
void Frame::resize(int w, int h) {
    width = w;
    height = h;
    std::size_t n = std::size_t(w) * std::size_t(h);
    rgba.assign(n, vec4(0.0f));
    depth.assign(n, std::numeric_limits<float>::infinity());
    hitId.assign(n, kNoHit);
    flags.assign(n, 0);
}

void Frame::reshape(int w, int h) {
    const std::size_t n = std::size_t(std::max(w, 0)) * std::size_t(std::max(h, 0));
    if (w == width && h == height && rgba.size() == n) return;
    width = w;
    height = h;
    // Emptied first, so that growing copies nothing; the new elements are left as they are.
    const auto size = [n](auto& buffer) {
        buffer.clear();
        buffer.resize(n);
    };
    size(rgba);
    size(depth);
    size(hitId);
    size(flags);
}
}  // namespace octrace
