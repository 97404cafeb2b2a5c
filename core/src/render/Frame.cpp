#include "octrace/render/Frame.h"

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
}  // namespace octrace
