#include "octrace/render/Camera.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace octrace {

void Camera::validate() const {
    dvec3 v = lookAt - position;
    if (!(glm::length(v) > 0.0)) throw UsageError("camera position and look-at point coincide");
    if (!(glm::length(glm::cross(glm::normalize(v), up)) > 1e-9))
        throw UsageError("camera up vector is zero or parallel to the viewing direction");
    if (!(fovYDegrees > 0.0 && fovYDegrees < 180.0)) throw UsageError("field of view must be in (0, 180) degrees");
    if (orthographic() && !(orthoHeight > 0.0 && std::isfinite(orthoHeight)))
        throw UsageError("orthographic view height must be positive");
    if (width <= 0 || height <= 0) throw UsageError("image size must be positive");
    if (!(std::abs(sampleOffset.x) <= 0.5 && std::abs(sampleOffset.y) <= 0.5))
        throw UsageError("a pixel's sample offset must lie within the pixel (-0.5 to 0.5)");
}

void Camera::basis(dvec3& right, dvec3& trueUp, dvec3& back) const {
    back = glm::normalize(position - lookAt);
    right = glm::normalize(glm::cross(up, back));
    trueUp = glm::cross(back, right);
}

Ray Camera::primaryRay(int x, int y) const { return RayGenerator(*this)(x, y); }

RayGenerator::RayGenerator(const Camera& camera) : eye_(camera.position), ortho_(camera.orthographic()) {
    camera.basis(right_, up_, back_);
    halfH_ = ortho_ ? 0.5 * camera.orthoHeight : std::tan(glm::radians(camera.fovYDegrees) * 0.5);
    halfW_ = halfH_ * (double(camera.width) / double(camera.height));
    invWidth_ = 1.0 / camera.width;
    invHeight_ = 1.0 / camera.height;
    sampleX_ = 0.5 + camera.sampleOffset.x;
    sampleY_ = 0.5 + camera.sampleOffset.y;
    // A point whose ray passes through the centre of pixel x lies sampleOffset.x to the left of
    // this camera's pixel x's ray: toPixel's coordinates shift by the offset.
    pixelX0_ = 0.5 * camera.width - camera.sampleOffset.x;
    pixelY0_ = 0.5 * camera.height - camera.sampleOffset.y;
    pixelScaleX_ = 0.5 * camera.width / halfW_;
    pixelScaleY_ = 0.5 * camera.height / halfH_;
}

#if defined(__x86_64__) && defined(__GNUC__)
/// RayGenerator::row's rays four at a time in AVX2 registers: the same operations in the same
/// order (no fused multiply-add: -ffp-contract=off), so the same bits. Returns the rays made (a multiple of 4).
/// `screen` = {sampleX, invWidth, halfW}: screenX(x) = ((x + sampleX) * invWidth * 2 - 1) * halfW.
[[gnu::target("avx2")]] static int rowAvx2(const double (&screen)[3], const dvec3& eye, const dvec3& right, const dvec3& base, const dvec3& back,
                                           int x0, int n, Ray* out) {
    const __m256d one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
    const __m256d sampleX = _mm256_set1_pd(screen[0]), invWidth = _mm256_set1_pd(screen[1]), halfW = _mm256_set1_pd(screen[2]);
    int i = 0;
    for (; i + 3 < n; i += 4) {
        const int x = x0 + i;
        const __m256d px = _mm256_set_pd(double(x + 3), double(x + 2), double(x + 1), double(x));
        const __m256d sx = _mm256_mul_pd(_mm256_sub_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_add_pd(px, sampleX), invWidth), two), one), halfW);
        __m256d d[3];
        for (int a = 0; a < 3; ++a)
            d[a] = _mm256_sub_pd(_mm256_add_pd(_mm256_mul_pd(sx, _mm256_set1_pd(right[a])), _mm256_set1_pd(base[a])), _mm256_set1_pd(back[a]));
        const __m256d len2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1])), _mm256_mul_pd(d[2], d[2]));
        const __m256d inv = _mm256_div_pd(one, _mm256_sqrt_pd(len2));
        double v[3][4];
        for (int a = 0; a < 3; ++a) _mm256_storeu_pd(v[a], _mm256_mul_pd(d[a], inv));
        for (int k = 0; k < 4; ++k) out[i + k] = {eye, dvec3(v[0][k], v[1][k], v[2][k])};
    }
    return i;
}
#endif

void RayGenerator::row(int x0, int y, int n, Ray* out) const {
    if (ortho_) {
        for (int i = 0; i < n; ++i) out[i] = (*this)(x0 + i, y);
        return;
    }
    // As operator(): d = screenX * right + screenY * up - back, then d * (1 / sqrt(dot(d, d)))
    // with glm's order of operations, so the results are the same bits.
    const double sy = screenY(y);
    const dvec3 base = sy * up_;
    int i = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) i = rowAvx2({sampleX_, invWidth_, halfW_}, eye_, right_, base, back_, x0, n, out);
#endif
#if defined(__SSE2__)
    const __m128d one = _mm_set1_pd(1.0);
    for (; i + 1 < n; i += 2) {
        const __m128d sx = _mm_set_pd(screenX(x0 + i + 1), screenX(x0 + i));
        __m128d d[3];
        for (int a = 0; a < 3; ++a)
            d[a] = _mm_sub_pd(_mm_add_pd(_mm_mul_pd(sx, _mm_set1_pd(right_[a])), _mm_set1_pd(base[a])), _mm_set1_pd(back_[a]));
        const __m128d len2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(d[0], d[0]), _mm_mul_pd(d[1], d[1])), _mm_mul_pd(d[2], d[2]));
        const __m128d inv = _mm_div_pd(one, _mm_sqrt_pd(len2));
        double v[3][2];
        for (int a = 0; a < 3; ++a) _mm_storeu_pd(v[a], _mm_mul_pd(d[a], inv));
        out[i] = {eye_, dvec3(v[0][0], v[1][0], v[2][0])};
        out[i + 1] = {eye_, dvec3(v[0][1], v[1][1], v[2][1])};
    }
#endif
    for (; i < n; ++i) out[i] = (*this)(x0 + i, y);
}

Camera Camera::framing(const Box3& box, int width, int height, double fovYDegrees) {
    Camera c;
    c.width = width;
    c.height = height;
    c.fovYDegrees = fovYDegrees;
    c.lookAt = box.centre();
    c.up = dvec3(0, 0, 1);
    const dvec3 dir = glm::normalize(dvec3(0.55, -1.0, 0.75));  // from south-east, above
    c.position = c.lookAt + dir;
    dvec3 right, up, back;
    c.basis(right, up, back);
    const double tanV = std::tan(glm::radians(fovYDegrees) * 0.5);
    const double tanH = tanV * double(width) / double(height);
    // Smallest distance at which every corner of the box is inside the view, plus a margin.
    double dist = 0.0;
    for (int k = 0; k < 8; ++k) {
        dvec3 p((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        dvec3 o = p - c.lookAt;
        double z = glm::dot(o, back);
        dist = std::max(dist, z + std::abs(glm::dot(o, right)) / tanH);
        dist = std::max(dist, z + std::abs(glm::dot(o, up)) / tanV);
    }
    if (!(dist > 0.0)) dist = 1.0;
    c.position = c.lookAt + back * (dist * 1.08);
    return c;
}

Camera Camera::fit(const Box3& box, int width, int height, double fovYDegrees, dvec3 towardsViewer, dvec3 up, double fill) {
    Camera c;
    c.width = width;
    c.height = height;
    c.fovYDegrees = fovYDegrees;
    c.up = up;
    const dvec3 centre = box.centre();
    c.lookAt = centre;
    c.position = centre + glm::normalize(towardsViewer);
    dvec3 right, trueUp, back;
    c.basis(right, trueUp, back);
    const double tanV = std::tan(glm::radians(fovYDegrees) * 0.5) * fill;
    const double tanH = tanV * double(width) / double(height);
    // Corners in camera axes about the centre: x along right, y along up, z towards the viewer.
    // At eye = centre + a right + b up + d back a corner is in view when |x - a| <= tanH (d - z)
    // and |y - b| <= tanV (d - z). The least d for each image axis is the mean of the two
    // largest of z + x / tan and z - x / tan; the larger of the two axes wins.
    double xs[8], ys[8], zs[8];
    for (int k = 0; k < 8; ++k) {
        const dvec3 p((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        const dvec3 o = p - centre;
        xs[k] = glm::dot(o, right);
        ys[k] = glm::dot(o, trueUp);
        zs[k] = glm::dot(o, back);
    }
    const auto leastDistance = [&](const double* s, double t) {
        double plus = -std::numeric_limits<double>::infinity(), minus = plus;
        for (int k = 0; k < 8; ++k) {
            plus = std::max(plus, zs[k] + s[k] / t);
            minus = std::max(minus, zs[k] - s[k] / t);
        }
        return 0.5 * (plus + minus);
    };
    double d = std::max(leastDistance(xs, tanH), leastDistance(ys, tanV));
    if (!(d > 0.0) || !std::isfinite(d)) d = 1.0;
    // At that distance the sideways offsets allowed along an axis form an interval (a point for
    // the limiting axis). Within it, the offset whose projection reaches as far to one side as
    // to the other: the sum of the two extreme projections falls as the offset grows, so
    // bisection finds it.
    const auto centredOffset = [&](const double* s, double t) {
        double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
        for (int k = 0; k < 8; ++k) {
            lo = std::max(lo, s[k] - t * (d - zs[k]));
            hi = std::min(hi, s[k] + t * (d - zs[k]));
        }
        if (!(lo <= hi)) return 0.0;
        const auto lopsided = [&](double a) {
            double most = -std::numeric_limits<double>::infinity(), least = -most;
            for (int k = 0; k < 8; ++k) {
                const double p = (s[k] - a) / std::max(d - zs[k], 1e-300);
                most = std::max(most, p);
                least = std::min(least, p);
            }
            return most + least;
        };
        for (int i = 0; i < 100 && hi - lo > 1e-12 * std::max(1.0, std::abs(lo) + std::abs(hi)); ++i) {
            const double mid = 0.5 * (lo + hi);
            (lopsided(mid) > 0.0 ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    };
    const double a = centredOffset(xs, tanH), b = centredOffset(ys, tanV);
    c.lookAt = centre + a * right + b * trueUp;
    c.position = c.lookAt + d * back;
    return c;
}

double Camera::pixelFootprint() const {
    if (orthographic()) return orthoHeight / double(height);
    return 2.0 * glm::length(lookAt - position) * std::tan(glm::radians(fovYDegrees) * 0.5) / double(height);
}

void Camera::frameOrthographic(const Box3& box) {
    projection = Projection::Orthographic;
    dvec3 right, trueUp, back;
    basis(right, trueUp, back);
    const double aspect = double(width) / double(height);
    double half = 0.0, front = 0.0;
    for (int k = 0; k < 8; ++k) {
        dvec3 p((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        dvec3 o = p - lookAt;
        half = std::max({half, std::abs(glm::dot(o, trueUp)), std::abs(glm::dot(o, right)) / aspect});
        front = std::max(front, glm::dot(p - position, back));
    }
    orthoHeight = half > 0.0 ? 2.0 * half * 1.08 : 1.0;
    // Every corner in front of the view plane, with a margin.
    if (front >= 0.0) position += back * (front + 0.05 * orthoHeight);
}

}  // namespace octrace
