#pragma once
/// @file Camera.h
/// Pinhole camera in world units. Pixel centres at +0.5; image row 0 is at the top.
#include "octrace/util/Math.h"

namespace octrace {

struct Ray {
    dvec3 origin;     ///< world space
    dvec3 direction;  ///< world space, unit length
};

class Camera {
public:
    dvec3 position{0.0, 0.0, 1.0};
    dvec3 lookAt{0.0};
    dvec3 up{0.0, 1.0, 0.0};
    double fovYDegrees = 30.0;  ///< vertical field of view
    int width = 640;
    int height = 480;

    /// Throws UsageError when position == lookAt, up is parallel to the view direction,
    /// the field of view is outside (0,180) or the size is not positive.
    void validate() const;

    /// Primary ray through the centre of pixel (x, y); y = 0 is the top row.
    Ray primaryRay(int x, int y) const;

    /// Orthonormal camera basis: right, up, back (towards the viewer) in world space.
    void basis(dvec3& right, dvec3& trueUp, dvec3& back) const;

    /// A camera that frames the box: looking from the south-east-above direction
    /// (the viewer sees the box from +x,-y,+z), with the whole box in view.
    static Camera framing(const Box3& box, int width, int height, double fovYDegrees = 30.0);
};

/// Generates the primary rays of one camera with the per-frame terms computed once; gives
/// bitwise the same rays as Camera::primaryRay.
class RayGenerator {
public:
    explicit RayGenerator(const Camera& camera);
    Ray operator()(int x, int y) const { return {origin_, glm::normalize(direction(x, y))}; }
    /// The same direction before normalisation.
    dvec3 direction(int x, int y) const {
        const double sx = ((x + 0.5) * invWidth_ * 2.0 - 1.0) * tanAspect_;
        const double sy = (1.0 - (y + 0.5) * invHeight_ * 2.0) * tan_;
        return sx * right_ + sy * up_ - back_;
    }
    const dvec3& origin() const { return origin_; }

private:
    dvec3 origin_, right_, up_, back_;
    double tan_, tanAspect_, invWidth_, invHeight_;
};

}  // namespace octrace
