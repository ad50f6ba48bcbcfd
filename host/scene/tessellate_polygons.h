// tessellate_polygons.h: RI 3.2 GeneralPolygon and PointsGeneralPolygons (planar,
// possibly concave polygons with holes): each polygon is projected onto the plane of
// its outer loop's Newell normal and triangulated by ear clipping with hole bridging
// (a port of the mapbox/earcut algorithm: bridges to the leftmost hole vertex, filters
// duplicate and collinear points, cures local self-intersections and splits as last
// resorts). Triangles are wound counter-clockwise about the outer loop's Newell normal
// (the right-hand rule on the vertex order as given); the caller flips per Orientation.
// Output is faceted (mesh.n empty; polygons have no (u,v), st = (0,0)), vertices are
// the input points (shared between the polygons of PointsGeneralPolygons), faceIndex =
// the polygon index. Degenerate polygons (all collinear, fewer than 3 distinct points)
// produce no triangles and are not errors.
#pragma once
#include <string>
#include <vector>

#include "host/scene/tessellate_types.h"

namespace rd {

constexpr int kMaxPolygonVertices = 1 << 18;  // per polygon (ear clipping is O(n^2))

// Triangulates one polygon: loops[0] the outer boundary, the rest holes, each a list of
// indices into `pts`. Appends index triples to `tris`. False only for bad input (index
// out of range, too many vertices).
bool triangulatePolygon(const std::vector<glm::vec3>& pts,
                        const std::vector<std::vector<int>>& loops, std::vector<int>& tris,
                        std::string* err = nullptr);

// GeneralPolygon nloops nverts "P": loop l has nverts[l] consecutive points of P.
bool tessellateGeneralPolygon(const std::vector<int>& nverts, const std::vector<glm::vec3>& P,
                              SurfaceMesh& out, std::string* err = nullptr);

// PointsGeneralPolygons npolys nloops nverts vertices "P".
bool tessellatePointsGeneralPolygons(const std::vector<int>& nloops,
                                     const std::vector<int>& nverts,
                                     const std::vector<int>& vertices,
                                     const std::vector<glm::vec3>& P, SurfaceMesh& out,
                                     std::string* err = nullptr);

}  // namespace rd
