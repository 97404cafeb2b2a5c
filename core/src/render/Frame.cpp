#include "octrace/render/Frame.h"

#include <algorithm>

namespace octrace {
void Frame::resize(int w, int h) {
    std::size_t n = std::size_t(w) * std::size_t(h);
    rgba.assign(n, vec4(0.0f));
    depth.assign(n, std::numeric_limits<float>::infinity());
    hitId.assign(n, kNoHit);
    flags.assign(n, 0);
    width = w;
    height = h;
}

void Frame::reshape(int w, int h) {
    const std::size_t n = std::size_t(std::max(w, 0)) * std::size_t(std::max(h, 0));
    if (w == width && h == height && rgba.size() == n && depth.size() == n && hitId.size() == n && flags.size() == n) return;
    // Emptied first, so that growing copies nothing; the new elements are left as they are. The
    // size is set last: a frame whose buffers could not all grow (bad_alloc) keeps its old size.
    const auto size = [n](auto& buffer) {
        buffer.clear();
        buffer.resize(n);
    };
    size(rgba);
    size(depth);
    size(hitId);
    size(flags);
    width = w;
    height = h;
}
}  // namespace octrace
