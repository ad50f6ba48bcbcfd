// true_displacement.h: true displacement's second half: the displacement shaders run on
// the device at the diced vertices (cl/kernels/displace_vertices.cl) and the diced
// triangles moved to where they put them, before the BVH is built. Each diced triangle's
// normals are then the N the shader left at its vertices (else the area-weighted normals
// of the moved pieces about each vertex), and its shader is not run again as a bump map
// when it is shaded.
// Vertices whose texture lookups met absent tiles are run again once the host has
// served them, as the shade stage's points are (texture_reshade.h).
#pragma once
#include <map>
#include <string>

#include "features.h"
#include "ocl/kernel.h"
#include "rib/diagnostics.h"
#include "scene/dice_displaced.h"
#include "shaders/shader_set.h"
#include "texture/texture_set.h"

namespace rd {

struct DisplacementReport {
    size_t vertices = 0;    // displacement shader runs that stuck (one per vertex)
    size_t passes = 0;      // kernel launches (more with texture misses)
    size_t nonFinite = 0;   // vertices a shader moved to NaN or Inf: left in place
    std::map<uint32_t, size_t> nonFiniteBy;  // by Scene::displacements index
    size_t unresolved = 0;  // vertices whose tiles never fitted the cache: left in place
};

// `scene` is the diced scene (dice_displaced.h), `program` the shading program built for
// it, `eyeWidth` a camera ray's width where it starts (a pixel for an orthographic
// camera, 0 for a perspective one).
DisplacementReport displaceDicedSurfaces(const ClContext& ctx, cl_program program,
                                         Profiler& prof, Scene& scene,
                                         const DicedSurfaces& diced, const Features& f,
                                         const ShadingSetup& shading,
                                         TextureSet& textures, const DicingView& view,
                                         float eyeWidth);

// Warnings for what the dicing and the displacement could not do as asked: triangles
// left undiced, a coarser dicing to stay within the budget, vertices left in place.
void reportDicing(const DicedSurfaces& diced, const Scene& scene, rib::Diagnostics& diag);
void reportDisplacement(const DisplacementReport& r, const Scene& scene,
                        rib::Diagnostics& diag);

}  // namespace rd
