// shader_aovs.h: the AOVs shaders write (PRMan's arbitrary output variables): which of
// the AOVs a scene asks for come from shaders, their types and places in each sample's
// floats, and the code each surface shader's shade kernel runs to write them.
#pragma once
#include <string>
#include <vector>

#include "film/film.h"
#include "rib/diagnostics.h"
#include "scene/scene.h"

namespace rsl {
struct EmittedShader;
}

namespace rd {

// The AOVs RayDrive computes itself (geometric and sampling ones), not shaders.
bool isRendererAov(const std::string& name);

// Lays out the shader AOVs among `names` (renderer AOVs left out): each takes its type
// from the scene's declaration (Scene::aovTypes), else from the first of `surfaces` with
// an output variable of the name, else from the global of the name (Cs, Os, Oi, P, Ng,
// s, t, u, v); else it is a float no shader writes (warned: its channel is 0).
std::vector<ShaderAov> layoutShaderAovs(const std::vector<std::string>& names,
                                        const Scene& scene,
                                        const std::vector<const rsl::EmittedShader*>& surfaces,
                                        rib::Diagnostics& diag);

// Floats a sample of `aovs` holds.
int shaderAovFloats(const std::vector<ShaderAov>& aovs);

// Each AOV float's colour channel, comma-separated (ray_aovs.clh rd_aov_channel): k for a
// colour's channel k, -1 for a float, -2 for a coordinate of a point, vector or normal.
std::string shaderAovChannels(const std::vector<ShaderAov>& aovs);

// The macros shade_rsl.cl calls for the shader `sh` (its name in theirs):
// RD_AOV_OUTPUTS_<name>(dst, ev, g) writes every AOV from its output variables (or the
// globals g) after the base evaluation ev; RD_AOV_LIGHT_<name>(dst, le, ev) the parts of
// its output variables one light's evaluation le adds; RD_AOV_TRACE_<name>(A, te, ev) the
// AOV weights (cl/lib/ray_aovs.clh) of the ray of trace() call te's evaluation: what
// its colour and float outputs take of the radiance it brings back. An output of another
// type than the AOV's is reported (at `loc`) and left out.
std::string shaderAovMacros(const rsl::EmittedShader& sh, const std::vector<ShaderAov>& aovs,
                            rib::Diagnostics& diag,
                            const rib::SourceLoc& loc);

}  // namespace rd
