// space_services.h: the service behind the coordinate systems a shader names that are
// neither its own ("shader", "object") nor "current" (rsl_abi.h, SPACES): "world" and
// "camera" from the scene block, and a table of the projective "screen", "NDC" and
// "raster" and the scene's named coordinate systems (CoordinateSystem, Camera), each
// with its exact inverse, laid out only when some shader reads one of them.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rd {

// Where rsl_space_matrix finds its data in the scene block (RslGlobals::scene_params):
// the camera-to-current matrix and its inverse (16 floats each), the world row (4), and
// the table's start (an int's bits, message_services.h intBits; 0: no table).
struct SpaceSlots {
    size_t camera = 0, cameraInverse = 0, world = 0, table = 0;
};

// rsl_space_matrix(sp, space, inverse), OpenCL C.
std::string spaceService(const SpaceSlots& slots);

// Appends the table to `params` and writes its start into the scene block: its count,
// then per space its name's string id, space-to-current and current-to-space (16 floats
// each, RSL row-vector matrices). Screen space is camera space projected onto z = 1
// through the screen window's scale, its z PRMan's depth (0 at the near clipping plane,
// 1 at the far one) in perspective and the camera's z in an orthographic view; NDC maps
// the screen window to [0, 1] (y down), raster to the Format's pixels.
// `names`: the named systems shaders may ask for (their literals, the string values
// their calls and defaults give); the scene's others are left out, so that the table and
// its search stay as small as the shaders make them.
void appendSpaceTable(const Scene& scene, const SpaceSlots& slots,
                      const std::set<std::string>& names, std::vector<float>& params);

// The spaces' matrices to current, by name (tests read the table's contents here).
std::vector<std::pair<std::string, glm::dmat4>> tableSpaces(
    const Scene& scene, const std::set<std::string>& names);

}  // namespace rd
