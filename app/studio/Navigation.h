#pragma once
// The studio's camera moves: the pipeline library's (octrace/model/Navigation.h), and keeping
// the camera in StudioState, so that a session records exactly what is shown.
#include "StudioState.h"

#include "octrace/model/Navigation.h"

namespace octrace::studio {

using model::dolly;
using model::orbit;
using model::pan;
using model::standardView;

/// Stores `camera`'s position, look-at point and up vector and field of view in `state`.
void storeCamera(StudioState& state, const Camera& camera);

}  // namespace octrace::studio
