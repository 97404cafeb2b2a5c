#pragma once
/// @file Frame.h
/// What a renderer produces: linear RGBA, distance along the ray, and the hit voxel per pixel.
#include "octrace/util/Math.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace octrace {

/// Marks a pixel whose ray hit nothing.
inline constexpr std::uint32_t kNoHit = 0xFFFFFFFFu;

/// std::allocator, except that an element made without a value is default-initialized (left as
/// it is, for the trivial types of a frame's buffers) instead of zeroed: Frame::reshape sizes the
/// buffers of a frame whose every pixel the renderer then writes without first clearing them
/// serially (a 1600 x 1200 frame's 48 MB took 15-27 ms of one thread before the first frame,
/// mostly in page faults that the render's threads now take in parallel as they write).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    DefaultInitAllocator() = default;
    template <class U>
    DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// A frame's buffer of one value per pixel.
template <class T>
using PixelBuffer = std::vector<T, DefaultInitAllocator<T>>;

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
    /// Sizes the frame without clearing it: for a renderer that writes every field of every
    /// pixel (the pixels keep whatever they held, or nothing defined when the buffers grow).
    void reshape(int width, int height);

    int width = 0;
    int height = 0;
    PixelBuffer<vec4> rgba;            ///< linear RGB, straight alpha; row 0 at the top
    PixelBuffer<float> depth;          ///< distance from the eye along the ray (world units); +inf = miss
    PixelBuffer<std::uint32_t> hitId;  ///< voxel index in the octree's voxel array, kNoHit = miss
    PixelBuffer<std::uint8_t> flags;   ///< how each pixel was made: PixelFlag bits

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
