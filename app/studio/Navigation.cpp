#include "Navigation.h"

namespace octrace::studio {

void storeCamera(StudioState& state, const Camera& camera) {
    state.cameraSet = true;
    state.position = camera.position;
    state.lookAt = camera.lookAt;
    state.up = camera.up;
    state.fov = camera.fovYDegrees;
}

}  // namespace octrace::studio
