#pragma once
// Camera moves of the studio's views (ParaView / 3D Slicer conventions): orbit about the
// focal point, pan in the view plane, dolly towards the focal point, standard views.
// Plain functions on StudioState's camera, so that a session records exactly what is shown.
#include "StudioState.h"

namespace octrace::studio {

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

/// Stores `camera`'s position, look-at point and up vector and field of view in `state`.
void storeCamera(StudioState& state, const Camera& camera);

}  // namespace octrace::studio
