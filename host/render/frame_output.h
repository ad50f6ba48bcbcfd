// frame_output.h: a rendered world block to its image file: the name its Display gives
// (numbered when frames share one), the EXR with alpha unless the mode is "rgb", a depth
// map's Z and camera matrices, the AOVs asked for, and metadata saying how the image was
// made. The raydrive command and the Ri API (host/ri/) write frames alike.
#pragma once
#include <string>
#include <vector>

#include "film/film.h"
#include "renderer.h"
#include "scene/scene.h"

namespace rd {

// The file of frame `frame` of `frames`: `override` (-o), else the Display's name, else
// the scene file's stem with ".exr".
std::string frameOutputName(const Scene& scene, const std::string& override, size_t frame,
                            size_t frames);

// Writes `film` as rendered with `st` to `out` with the AOVs named (the scene's own and
// `aovs`). Throws std::exception when the file cannot be written.
void writeFrameImage(const std::string& out, const Scene& scene, const Film& film,
                     const RenderStats& st, const std::vector<std::string>& aovs,
                     bool halfFloat, const std::string& scenePath);

}  // namespace rd
