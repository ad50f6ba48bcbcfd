// depth_map.h: what a depth map (Display mode "z", driver "zfile" or "shadow") carries
// besides its depths: the camera's "worldToCamera" and "worldToScreen" matrices in the
// RIB's world (row-vector convention, row-major, as OpenEXR and OpenImageIO keep them),
// which MakeShadow keeps and shadow() reads back (cl/lib/texture_lookup.clh). Screen
// space spans the screen window as [-1, 1]; for a perspective camera its w is the
// camera-space z, so x/w, y/w are the screen position.
#pragma once
#include <array>

#include "scene.h"

namespace rd {

struct DepthMapMatrices {
    std::array<float, 16> worldToCamera, worldToScreen;
};

DepthMapMatrices depthMapMatrices(const Scene& scene);

}  // namespace rd
