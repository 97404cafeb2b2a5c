#pragma once
/// @file Camera.h
/// Pinhole (perspective) or orthographic camera in world units. Pixel centres at +0.5; image
/// row 0 is at the top.
///
/// Orthographic: every ray has the viewing direction; its origin is on the plane through
/// `position` perpendicular to it, offset by the pixel's place in a window `orthoHeight` world
/// units high (width by the aspect ratio). Nothing behind that plane is drawn.
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
    double fovYDegrees = 30.0;  ///< vertical field of view (perspective)
    enum class Projection { Perspective, Orthographic };
    Projection projection = Projection::Perspective;
    double orthoHeight = 1.0;   ///< world height of the view window (orthographic)
    int width = 640;
    int height = 480;
    /// Where each pixel's ray passes through the pixel, in pixels from its centre (x right, y
    /// down), each in [-0.5, 0.5]; the samples of antialiasing (renderAntialiased, Renderer.h).
    /// Every renderer reads it through RayGenerator; 0 gives the pixel-centre rays bit for bit.
    dvec2 sampleOffset{0.0, 0.0};

    /// Throws UsageError when position == lookAt, up is parallel to the view direction,
    /// the field of view is outside (0,180), the orthographic height is not positive, the
    /// size is not positive or the sample offset leaves the pixel.
    void validate() const;

    /// Primary ray through the centre of pixel (x, y); y = 0 is the top row.
    Ray primaryRay(int x, int y) const;

    /// Orthonormal camera basis: right, up, back (towards the viewer) in world space.
    void basis(dvec3& right, dvec3& trueUp, dvec3& back) const;

    /// A camera that frames the box: looking from the south-east-above direction
    /// (the viewer sees the box from +x,-y,+z), with the whole box in view.
    static Camera framing(const Box3& box, int width, int height, double fovYDegrees = 30.0);
    /// The south-east-above direction of framing(), towards the viewer.
    static dvec3 obliqueDirection() { return glm::normalize(dvec3(0.55, -1.0, 0.75)); }
    /// A camera looking along -`towardsViewer` with `up` that frames the box tightly: the
    /// nearest position at which the 8 corners' projection fits in `fill` of the image's width
    /// and height, the camera moved sideways (look-at point off the box's centre when the
    /// perspective makes the projection lopsided) so that the projection is centred and touches
    /// the limiting pair of sides. `up` must not be parallel to `towardsViewer` (else the camera
    /// fails validate()).
    static Camera fit(const Box3& box, int width, int height, double fovYDegrees, dvec3 towardsViewer, dvec3 up,
                      double fill = 0.92);
    /// Makes this camera orthographic with the window height that shows the whole box from the
    /// current position and direction, and moves the position back along the viewing
    /// direction so that the box lies in front of the ray origins.
    void frameOrthographic(const Box3& box);
    bool orthographic() const { return projection == Projection::Orthographic; }
    /// World size of one pixel at the look-at point: the height of the view window there (the
    /// orthographic window) over the image height.
    double pixelFootprint() const;
};

/// Generates the primary rays of one camera with the per-frame terms computed once; gives
/// bitwise the same rays as Camera::primaryRay.
class RayGenerator {
public:
    explicit RayGenerator(const Camera& camera);
    Ray operator()(int x, int y) const { return {origin(x, y), glm::normalize(direction(x, y))}; }
    /// The rays of pixels (x0, y) .. (x0 + n - 1, y) into out[0 .. n-1]: bit for bit those of
    /// operator(), four at a time with AVX2 (else two; a tracer that keeps a whole tile of rays
    /// spends much of its time in their square roots and divisions).
    void row(int x0, int y, int n, Ray* out) const;
    /// The same direction before normalisation.
    dvec3 direction(int x, int y) const {
        if (ortho_) return -back_;
        return screenX(x) * right_ + screenY(y) * up_ - back_;
    }
    /// Origin of the ray of pixel (x, y): the eye (perspective) or a point of the view plane.
    dvec3 origin(int x, int y) const {
        if (!ortho_) return eye_;
        return eye_ + screenX(x) * right_ + screenY(y) * up_;
    }
    bool orthographic() const { return ortho_; }
    const dvec3& eye() const { return eye_; }
    const dvec3& right() const { return right_; }
    const dvec3& up() const { return up_; }
    const dvec3& back() const { return back_; }
    /// Pixel coordinates (continuous, pixel centres at +0.5) of a point given in camera
    /// coordinates (along right, up, back from the eye); perspective needs back < 0.
    void toPixel(double cx, double cy, double cz, double& px, double& py) const {
        if (!ortho_) {
            const double w = -1.0 / cz;
            cx *= w;
            cy *= w;
        }
        px = pixelX0_ + cx * pixelScaleX_;
        py = pixelY0_ - cy * pixelScaleY_;
    }
    /// toPixel's terms, for code that projects many points at once: px = x0 + cx * sx and
    /// py = y0 - cy * sy, cx and cy first multiplied by -1 / cz in perspective.
    void pixelTerms(double& x0, double& y0, double& sx, double& sy) const {
        x0 = pixelX0_;
        y0 = pixelY0_;
        sx = pixelScaleX_;
        sy = pixelScaleY_;
    }

private:
    // Offsets of the pixel centre on the view plane at unit distance (perspective) or in
    // world units (orthographic), along right and up.
    double screenX(int x) const { return ((x + sampleX_) * invWidth_ * 2.0 - 1.0) * halfW_; }
    double screenY(int y) const { return (1.0 - (y + sampleY_) * invHeight_ * 2.0) * halfH_; }
    dvec3 eye_, right_, up_, back_;
    double halfH_, halfW_, invWidth_, invHeight_;
    double sampleX_, sampleY_;  // where in a pixel its ray passes: 0.5 + Camera::sampleOffset
    double pixelX0_, pixelY0_, pixelScaleX_, pixelScaleY_;  // toPixel: image centre, pixels per unit
    bool ortho_;
};

}  // namespace octrace
