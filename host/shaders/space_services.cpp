// space_services.cpp: the coordinate systems shaders name, beyond their own (see the
// header).
#include "space_services.h"

#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "emit_cl.h"
#include "shaders/message_services.h"

namespace rd {

std::string spaceService(const SpaceSlots& slots) {
    std::ostringstream s;
    // clang-format off
    s << "/* Space to current (inverse: current to space): camera and world from the scene\n"
         " * block, the rest from its table of spaces (space_services.h); the identity for\n"
         " * a name the scene does not define. */\n"
         "RslMatrix rsl_space_matrix(const RslSpaces* sp, int space, int inverse) {\n"
         "    RslMatrix m = rsl_mscalar(1.0f);\n"
         "    if (space == RSL_SPACE_CAMERA) {\n"
         "        __global const float* c = sp->scene + (inverse ? " << slots.cameraInverse
      << " : " << slots.camera << ");\n"
         "        for (int r = 0; r < 4; ++r) m.r[r] = vload4(r, c);\n"
         "        return m;\n"
         "    }\n"
         "    if (space == RSL_SPACE_WORLD) {\n"
         "        m.r[3] = vload4(0, sp->scene + " << slots.world << ");\n"
         "        if (inverse) m.r[3] = (float4)(-m.r[3].xyz, 1.0f);\n"
         "        return m;\n"
         "    }\n"
         "    int id = space == RSL_SPACE_SCREEN ? " << rsl::stringId("screen")
      << " : space == RSL_SPACE_NDC ? " << rsl::stringId("NDC")
      << " : space == RSL_SPACE_RASTER ? " << rsl::stringId("raster") << " : -space;\n"
         "    int table = as_int(sp->scene[" << slots.table << "]);\n"
         "    if (table <= 0) return m;\n"
         "    __global const float* t = sp->scene + table;\n"
         "    int count = (int)t[0];\n"
         "    for (int i = 0; i < count; ++i) {\n"
         "        __global const float* e = t + 1 + 33 * i;\n"
         "        if ((int)e[0] != id) continue;\n"
         "        for (int r = 0; r < 4; ++r) m.r[r] = vload4(r, e + 1 + (inverse ? 16 : 0));\n"
         "        break;\n"
         "    }\n"
         "    return m;\n"
         "}\n";
    // clang-format on
    return s.str();
}

std::vector<std::pair<std::string, glm::dmat4>> tableSpaces(
    const Scene& scene, const std::set<std::string>& names) {
    const Camera dc = scene.deviceCamera();
    const CameraSpec& c = scene.camera;
    // current -> camera -> screen -> NDC -> raster (glm's column vectors)
    const glm::dmat4 toCamera(c.worldToCamera);
    glm::dmat4 project(1.0);
    if (dc.perspective) {
        const double t = dc.tan_half_fov, n = c.clipNear, f = c.clipFar;
        project[0][0] = project[1][1] = 1.0 / t;
        project[2][2] = f / (f - n);
        project[3][2] = -f * n / (f - n);
        project[2][3] = 1.0;
        project[3][3] = 0.0;
    }
    const double l = dc.screen[0], r = dc.screen[1], b = dc.screen[2], tp = dc.screen[3];
    glm::dmat4 ndc(1.0);
    ndc[0][0] = 1.0 / (r - l), ndc[3][0] = -l / (r - l);
    ndc[1][1] = -1.0 / (tp - b), ndc[3][1] = tp / (tp - b);
    const glm::dmat4 raster =
        glm::scale(glm::dmat4(1.0), glm::dvec3(dc.width, dc.height, 1.0));
    const glm::dmat4 toScreen = project * toCamera, toNdc = ndc * toScreen,
                     toRaster = raster * toNdc;
    std::vector<std::pair<std::string, glm::dmat4>> out = {
        {"screen", glm::inverse(toScreen)},
        {"NDC", glm::inverse(toNdc)},
        {"raster", glm::inverse(toRaster)}};
    for (const auto& [name, toWorld] : scene.coordinateSystems)
        if (names.count(name)) out.emplace_back(name, glm::dmat4(toWorld));
    return out;
}

void appendSpaceTable(const Scene& scene, const SpaceSlots& slots,
                      const std::set<std::string>& names, std::vector<float>& params) {
    const auto spaces = tableSpaces(scene, names);
    params[slots.table] = intBits(int64_t(params.size()));
    params.push_back(float(spaces.size()));
    for (const auto& [name, toCurrent] : spaces) {
        params.push_back(float(rsl::stringId(name)));  // (24 bits: exact in a float)
        // RSL row-vector matrices are glm's column-major arrays as they are
        const glm::dmat4 fromCurrent = glm::inverse(toCurrent);
        for (const glm::dmat4* m : {&toCurrent, &fromCurrent})
            for (int i = 0; i < 16; ++i) params.push_back(float((&(*m)[0][0])[i]));
    }
}

}  // namespace rd
