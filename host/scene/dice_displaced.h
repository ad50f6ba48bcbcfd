// dice_displaced.h: the first half of true displacement: the triangles of truly
// displaced surfaces (RT_MATERIAL_TRUE_DISPLACEMENT) cut into micropolygons whose edges
// are about sqrt(ShadingRate) pixels long (four times that out of view), as REYES dices
// a grid. The second half
// (host/render/true_displacement.h) runs the displacement shaders on their vertices.
//
// An edge is halved when it is longer than its surface's limit, a decision that depends
// on its two ends alone, and a triangle is cut by the pattern of its halved edges (two,
// three or four pieces), again and again: neighbours cut a shared edge alike, so the
// diced surface has no T-junctions and no cracks. The diced triangles are appended to the
// scene with every per-corner value their original had (normal, s and t, Cs, Os,
// per-point shader parameters) interpolated, and s and t always given, so a surface
// shades as before; the originals are marked RT_QF_DICED and left out of the BVH.
#pragma once
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "host/scene/scene.h"

namespace rd {

// How long an edge looks from the camera.
struct DicingView {
    glm::vec3 eye{0.0f};  // device space
    bool perspective = true;
    float pixelSpread = 0.0f;  // perspective: a pixel's width at unit distance
    float pixelWidth = 1.0f;   // orthographic: a pixel's width
    float nearest = 1e-3f;     // distances are taken as at least this
    // The view, to dice what the camera does not see coarser (as Cycles does: reflections
    // and shadows of it need less): world to camera, the screen window's half extents
    // (at unit depth for a perspective camera) widened by a tenth; 0 sees everything.
    glm::mat4 worldToCamera{1.0f};
    float halfX = 0.0f, halfY = 0.0f;
    float offscreen = 4.0f;  // an edge with both ends out of view: this many times longer
    bool inView(const glm::vec3& p) const;
    // The edge's length in pixels where its nearer end is (symmetric in a and b).
    float pixels(const glm::vec3& a, const glm::vec3& b) const;
};
DicingView dicingViewOf(const Camera& deviceCamera);

struct DicedSurfaces {
    // The vertices to displace: the diced triangle and corner (0..2) that stands for
    // each. Corners of the same surface with the same place, normal and (s, t) are one
    // vertex, so the surface stays closed however the shader moves it.
    std::vector<std::array<uint32_t, 2>> vertexCorner;
    // Each diced triangle's three vertices, from firstTriangle on.
    std::vector<uint32_t> cornerVertex;
    uint32_t firstTriangle = 0;
    size_t diced = 0;    // triangles replaced
    // Each diced triangle's original (its moving keys are the original's, blended).
    std::vector<uint32_t> pieceSource;
    size_t skipped = 0;  // truly displaced triangles left as they are (in a solid:
                         // rendered undisplaced)
    size_t budget = 0;   // the most pieces asked for
    float coarsening = 1.0f;  // the edge limit's factor that kept within the budget
    bool truncated = false;   // the budget ran out all the same: surfaces left with holes
};

// The most diced triangles a render takes (about 650 MiB of scene arrays and tree).
constexpr size_t kMaxDicedTriangles = size_t(1) << 22;

// Dices every truly displaced triangle of `scene` (device space); at most about
// maxTriangles diced triangles, the limit doubled until they fit.
DicedSurfaces diceDisplacedSurfaces(Scene& scene, const DicingView& view,
                                    size_t maxTriangles);

// Whether some material of the scene is truly displaced.
bool hasTrueDisplacement(const Scene& scene);

}  // namespace rd
