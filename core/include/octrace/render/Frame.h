#pragma once
/// @file Frame.h
/// What a renderer produces: linear RGBA, distance along the ray, and the hit voxel per pixel.
#include "octrace/util/Math.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace octrace {

/// Marks a pixel whose ray hit nothing.
inline constexpr std::uint32_t kNoHit = 0xFFFFFFFFu;

class Frame {
public:
    Frame() = default;
    Frame(int width, int height) { resize(width, height); }
    Frame(Frame&&) noexcept = default;
    Frame& operator=(Frame&&) noexcept = default;
    Frame(const Frame&) = default;
    Frame& operator=(const Frame&) = default;

    /// Sizes the frame and clears it: background-less black, depth +inf, no hits, no flags.
    void resize(int width, int height);
    /// Sizes the frame without clearing it when it already has that size (a renderer that
    /// writes every field of every pixel re-renders into the same frame without the clear).
    void reshape(int width, int height) {
        if (width != this->width || height != this->height || rgba.size() != pixel(0, height)) resize(width, height);
    }

    int width = 0;
    int height = 0;
    std::vector<vec4> rgba;            ///< linear RGB, straight alpha; row 0 at the top
    std::vector<float> depth;          ///< distance from the eye along the ray (world units); +inf = miss
    std::vector<std::uint32_t> hitId;  ///< voxel index in the octree's voxel array, kNoHit = miss
    std::vector<std::uint8_t> flags;   ///< how each pixel was made: PixelFlag bits

    enum PixelFlag : std::uint8_t {
        kTraced = 1,        ///< traced (not filled by colour coherence)
        kCommonPath = 2,    ///< started from the branch node of two neighbours
        kFallback = 4,      ///< started there but retraced from the root
        kCertified = 8,     ///< exact variant: root skipped
        kColourFilled = 16, ///< average of two neighbours, not traced (hitId = a neighbour's)
        kSplatted = 32,     ///< drawn by a direct renderer (no ray traced)
        kMissFilled = 64    ///< background between two missing neighbours, not traced (miss coherence)
    };

    std::size_t pixel(int x, int y) const { return std::size_t(y) * std::size_t(width) + std::size_t(x); }

    /// Bytes the buffers of a width x height frame take (for memory budgets).
    static std::uint64_t bytesFor(int width, int height) {
        return std::uint64_t(width) * std::uint64_t(height) *
               (sizeof(vec4) + sizeof(float) + sizeof(std::uint32_t) + sizeof(std::uint8_t));
    }
};

}  // namespace octrace
