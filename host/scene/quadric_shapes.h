// quadric_shapes.h: RenderMan quadric requests (RI 3.2 section 5.3) turned into the exact
// Quadric records the device intersects (cl/include/quadric.h): implicit coefficients,
// clip ranges and parameterisation constants in object space, then placed in the world
// by an object-to-world matrix. Also each shape's object-space bounds and its boundary
// circles (for the closedness check of CSG primitive solids).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cl/include/quadric.h"
#include "host/bvh/aabb.h"

namespace rd {

// A quadric in its own space with its object-space bounding box. `error` is set (and
// the quadric unusable) for non-finite or degenerate parameters.
struct QuadricShape {
    Quadric q{};
    glm::vec3 lo{0.0f}, hi{0.0f};
    std::string error;
};

QuadricShape makeSphere(float radius, float zmin, float zmax, float thetamaxDeg);
QuadricShape makeCylinder(float radius, float zmin, float zmax, float thetamaxDeg);
QuadricShape makeCone(float height, float radius, float thetamaxDeg);
QuadricShape makeDisk(float height, float radius, float thetamaxDeg);
QuadricShape makeParaboloid(float rmax, float zmin, float zmax, float thetamaxDeg);
QuadricShape makeHyperboloid(glm::vec3 point1, glm::vec3 point2, float thetamaxDeg);
QuadricShape makeTorus(float majorRadius, float minorRadius, float phiminDeg, float phimaxDeg,
                       float thetamaxDeg);

// Sets the quadric's centre and matrices for `objectToWorld`; false when the matrix is
// singular or not finite.
bool placeQuadric(Quadric& q, const glm::mat4& objectToWorld);

// The object-to-world matrix a placed quadric was given.
glm::mat4 quadricPlacement(const Quadric& q);

// World-space box of a placed quadric whose object-space box is [lo, hi] (for a quadric,
// the box of the cylinder about its axis that holds it; for an instance, the corners of
// its prototype's box).
Aabb quadricWorldBounds(const Quadric& q, glm::vec3 lo, glm::vec3 hi);

// Object-space position on a placed quadric's surface at (u, v) (host mirror of the
// device evaluation, used by checks and tests).
glm::vec3 quadricObjectPoint(const Quadric& q, float u, float v);
glm::vec3 quadricToWorld(const Quadric& q, glm::vec3 objectPoint);
glm::vec3 quadricToObject(const Quadric& q, glm::vec3 worldPoint);

// A circle where the surface ends: z = height, radius rho about the object's z axis.
struct BoundaryCircle {
    float z, rho;
};
// The surface's boundary circles, or nullopt when its boundary is not a set of full
// circles (a partial sweep in theta has straight edges too).
std::optional<std::vector<BoundaryCircle>> quadricBoundary(const Quadric& q);

// Ri request name of a quadric kind ("Sphere", ...).
const char* quadricKindName(uint32_t kind);

}  // namespace rd
