// scene.cpp: deriving the device camera (screen window, fov scale, camera-to-world, pixel
// filter) from the RenderMan camera options, and the AOVs a scene asks for.
#include "scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "pixel_filter.h"

namespace rd {

std::vector<std::string> Scene::aovNames() const {
    std::vector<std::string> names = aovs;
    for (const AovDisplay& d : aovDisplays)
        for (const std::string& a : d.aovs)
            if (std::find(names.begin(), names.end(), a) == names.end()) names.push_back(a);
    return names;
}

Camera Scene::deviceCamera() const {
    Camera d{};
    const CameraSpec& c = camera;
    d.shutter[0] = c.shutter[0];
    d.shutter[1] = c.shutter[1];
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
    // (the builder checked the filter: a box of the widths if the table cannot be made)
    setCameraFilter(d, c.pixelFilter, c.filterWidth[0], c.filterWidth[1]);
    if (c.perspective && c.fstop > 0 && std::isfinite(c.fstop) && c.focalLength > 0 &&
        c.focalDistance > 0) {
        d.lens_radius = c.focalLength / (2.0f * c.fstop);
        d.focal_distance = c.focalDistance;
    }
    glm::mat4 camToWorld = glm::inverse(c.worldToCamera);
    glm::mat4 camToWorldEnd = glm::inverse(c.moving ? c.worldToCameraEnd : c.worldToCamera);
    for (int r = 0; r < 3; ++r) {
        d.camera_to_world[r] = {camToWorld[0][r], camToWorld[1][r], camToWorld[2][r],
                                camToWorld[3][r]};
        d.camera_to_world_end[r] = {camToWorldEnd[0][r], camToWorldEnd[1][r],
                                    camToWorldEnd[2][r], camToWorldEnd[3][r]};
    }
    d.moving = c.moving ? 1u : 0u;
    d.motion_times[0] = c.motionTimes[0];
    d.motion_times[1] = c.motionTimes[1];
    for (const auto& [t, key] : c.worldToCameraBetween) {
        if (!c.moving || d.between == RT_CAMERA_MAX_BETWEEN) break;
        const glm::mat4 m = glm::inverse(key);
        for (int r = 0; r < 3; ++r)
            d.camera_to_world_between[d.between][r] = {m[0][r], m[1][r], m[2][r],
                                                       m[3][r]};
        d.between_times[d.between++] = t;
    }
    return d;
}

void CameraSpec::cropPixels(int& x0, int& x1, int& y0, int& y1) const {
    // RI: the pixels whose centres fall inside the window (at least one pixel).
    auto edge = [](float f, int res) {
        return std::clamp(int(std::ceil(f * float(res) - 0.5f)), 0, res);
    };
    x0 = edge(crop[0], width);
    x1 = std::max(x0 + 1, edge(crop[1], width));
    y0 = edge(crop[2], height);
    y1 = std::max(y0 + 1, edge(crop[3], height));
    x1 = std::min(x1, width);
    y1 = std::min(y1, height);
    x0 = std::min(x0, x1 - 1);
    y0 = std::min(y0, y1 - 1);
}

}  // namespace rd
