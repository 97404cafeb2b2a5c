#pragma once
/// @file Navigation.h
/// Camera moves of the interactive views (ParaView / 3D Slicer conventions): orbit about the
/// focal point, pan in the view plane, dolly towards the focal point, standard views. The
/// studio's views and Python's Jupyter view move their cameras with these.
#include "octrace/render/Camera.h"

namespace octrace::model {

/// Orbits the camera about its look-at point: `yawDeg` about the view's up axis (positive: the
/// scene turns right), `pitchDeg` about its right axis (positive: the scene tips towards the
/// viewer). The up vector follows.
void orbit(Camera& camera, double yawDeg, double pitchDeg);
/// Moves camera and look-at point by (dx, dy) pixels of a view `viewHeight` pixels high, so
/// that the point under the cursor follows it.
void pan(Camera& camera, double dx, double dy, int viewHeight);
/// Multiplies the distance to the look-at point by `factor` (< 1 comes closer).
void dolly(Camera& camera, double factor);

/// Standard views: looking along +X, -X, +Y, -Y, +Z or -Z (axis 0..2, sign +-1) at the
/// surface's centre, from the distance that frames it; up is +Z, or +Y when looking along Z.
Camera standardView(const Box3& bounds, int axis, int sign, int width, int height, double fovDeg);

}  // namespace octrace::model
