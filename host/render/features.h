// features.h: what a scene needs (DESIGN.md section 5). analyse() reads the Scene once;
// buildOptions() is the one place -D options for the kernels come from, so a scene gets
// no code, ray fields or buffers for features it does not use.
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"

namespace rd {

struct Features {
    bool smoothNormals = false; // per-vertex normals to interpolate
    bool transparency = false;  // some Os < 1: continuation rays
    bool shadowRays = false;    // some light other than ambient
    bool aovs = false;          // geometric AOVs (z, N) asked for
    bool depthOfField = false;  // a thin-lens camera
    uint32_t lightCount = 0;
    int maxTransparentDepth = 16;

    std::vector<std::string> names() const;
};

Features analyse(const Scene& scene);
std::string buildOptions(const Features& f);

}  // namespace rd
