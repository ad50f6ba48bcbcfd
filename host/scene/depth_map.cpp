// depth_map.cpp: the camera matrices a depth map carries (depth_map.h).
#include "depth_map.h"

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

namespace rd {

DepthMapMatrices depthMapMatrices(const Scene& scene) {
    const Camera cam = scene.deviceCamera();
    // the camera of the RIB's world: the renderer keeps the world relative to the eye
    glm::dmat4 toCamera = glm::dmat4(scene.camera.worldToCamera) *
                          glm::translate(glm::dmat4(1.0), -scene.worldOrigin);
    const double hw = 0.5 * (double(cam.screen[1]) - cam.screen[0]);
    const double hh = 0.5 * (double(cam.screen[3]) - cam.screen[2]);
    const double cx = 0.5 * (double(cam.screen[1]) + cam.screen[0]);
    const double cy = 0.5 * (double(cam.screen[3]) + cam.screen[2]);
    glm::dmat4 project(0.0);  // glm is column-major: project[column][row]
    if (cam.perspective) {
        const double k = 1.0 / double(cam.tan_half_fov);
        project[0][0] = k / hw;
        project[2][0] = -cx / hw;
        project[1][1] = k / hh;
        project[2][1] = -cy / hh;
        project[2][2] = 1.0;
        project[2][3] = 1.0;  // w = z
    } else {
        project[0][0] = 1.0 / hw;
        project[3][0] = -cx / hw;
        project[1][1] = 1.0 / hh;
        project[3][1] = -cy / hh;
        project[2][2] = 1.0;
        project[3][3] = 1.0;
    }
    // glm's column-major column-vector matrix is, as it lies in memory, the row-major
    // row-vector matrix of the same map
    DepthMapMatrices out;
    glm::mat4 c(toCamera), s(project * toCamera);
    std::memcpy(out.worldToCamera.data(), &c[0][0], sizeof(float) * 16);
    std::memcpy(out.worldToScreen.data(), &s[0][0], sizeof(float) * 16);
    return out;
}

}  // namespace rd
