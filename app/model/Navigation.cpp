#include "octrace/model/Navigation.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace octrace::model {
namespace {

dvec3 rotate(const dvec3& v, const dvec3& axis, double deg) {
    const glm::dmat4 m = glm::rotate(glm::dmat4(1.0), glm::radians(deg), glm::normalize(axis));
    return dvec3(m * glm::dvec4(v, 0.0));
}

}  // namespace

void orbit(Camera& camera, double yawDeg, double pitchDeg) {
    dvec3 right, up, back;
    camera.basis(right, up, back);
    dvec3 offset = camera.position - camera.lookAt;
    offset = rotate(offset, up, -yawDeg);
    right = rotate(right, up, -yawDeg);
    offset = rotate(offset, right, -pitchDeg);
    up = rotate(up, right, -pitchDeg);
    camera.position = camera.lookAt + offset;
    camera.up = up;
}

void pan(Camera& camera, double dx, double dy, int viewHeight) {
    dvec3 right, up, back;
    camera.basis(right, up, back);
    const double dist = glm::length(camera.position - camera.lookAt);
    const double worldPerPixel =
        (camera.orthographic() ? camera.orthoHeight : 2.0 * dist * std::tan(glm::radians(camera.fovYDegrees) * 0.5)) /
        double(std::max(1, viewHeight));
    const dvec3 shift = (-dx * right + dy * up) * worldPerPixel;
    camera.position += shift;
    camera.lookAt += shift;
}

void dolly(Camera& camera, double factor) {
    factor = std::clamp(factor, 1e-3, 1e3);
    camera.position = camera.lookAt + (camera.position - camera.lookAt) * factor;
}

Camera standardView(const Box3& bounds, int axis, int sign, int width, int height, double fovDeg) {
    Camera c = Camera::framing(bounds, width, height, fovDeg);
    const double dist = glm::length(c.position - c.lookAt);
    dvec3 dir(0.0);
    dir[axis] = sign < 0 ? -1.0 : 1.0;
    c.position = c.lookAt - dir * dist;
    c.up = axis == 2 ? dvec3(0, 1, 0) : dvec3(0, 0, 1);
    return c;
}

}  // namespace octrace::model
