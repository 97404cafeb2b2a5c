#include "octrace/render/Camera.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>

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
    pixelX0_ = 0.5 * camera.width;
    pixelY0_ = 0.5 * camera.height;
    pixelScaleX_ = 0.5 * camera.width / halfW_;
    pixelScaleY_ = 0.5 * camera.height / halfH_;
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
