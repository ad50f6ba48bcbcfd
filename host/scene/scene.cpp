// scene.cpp: deriving the device camera (screen window, fov scale, camera-to-world) from
// the RenderMan camera options.
#include "scene.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace rd {

Camera Scene::deviceCamera() const {
    Camera d{};
    const CameraSpec& c = camera;
    float frame = c.frameAspect > 0 ? c.frameAspect
                                    : float(c.width) * c.pixelAspect / float(c.height);
    if (c.screenWindowSet) {
        for (int i = 0; i < 4; ++i) d.screen[i] = c.screen[i];
    } else if (frame >= 1.0f) {
        d.screen[0] = -frame, d.screen[1] = frame, d.screen[2] = -1, d.screen[3] = 1;
    } else {
        d.screen[0] = -1, d.screen[1] = 1, d.screen[2] = -1 / frame, d.screen[3] = 1 / frame;
    }
    d.perspective = c.perspective ? 1u : 0u;
    d.tan_half_fov = std::tan(glm::radians(c.fovDeg) * 0.5f);
    d.clip_near = c.clipNear;
    d.clip_far = c.clipFar;
    d.width = c.width;
    d.height = c.height;
    d.spp_x = static_cast<int32_t>(c.pixelSamples[0]);
    d.spp_y = static_cast<int32_t>(c.pixelSamples[1]);
    glm::mat4 camToWorld = glm::inverse(c.worldToCamera);
    for (int r = 0; r < 3; ++r)
        d.camera_to_world[r] = {camToWorld[0][r], camToWorld[1][r], camToWorld[2][r],
                                camToWorld[3][r]};
    return d;
}

}  // namespace rd
