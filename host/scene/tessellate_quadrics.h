// tessellate_quadrics.h: dicing of the RI 3.2 section 5.3 quadrics other than the sphere
// (Cylinder, Cone, Disk, Torus, Paraboloid, Hyperboloid) into SurfaceMeshes, with the
// spec's parameterisations: u in [0,1] sweeps theta = u*thetamax (degrees, clamped to
// [-360,360]), v in [0,1] as given per primitive below. st = (u,v), faceIndex = 0.
// Normals are normalize(dP/du x dP/dv) literally (RI 3.2 section 5; tessellate_types.h):
// outward ("away from the z axis") for positive parameters; a negative thetamax reverses
// dP/du and so turns the surface inside out. A negative radius is taken as written: the
// points are mirrored through the axis and the normal is whatever the cross product
// gives (still away from the axis for Cylinder/Cone/Disk, as their dP/du flips with the
// radius; the sphere of tessellate.h, quadratic in the radius, turns inward).
// Paraboloid uses z = zmin + v (zmax - zmin) (the 3.2 text's "v (zmax - zmin)" is a
// typo every implementation corrects).
// nu, nv are the segment counts over the whole u and v ranges (clamped to [1, 4096]);
// the caller picks them from screen size (e.g. circleSegments scaled by |thetamax|/360).
// All functions return false with a message for unusable input (non-finite numbers).
#pragma once
#include <string>

#include "host/scene/tessellate_types.h"

namespace rd {

// x = r cos t, y = r sin t, z = zmin + v (zmax - zmin)
bool tessellateCylinder(float radius, float zmin, float zmax, float thetamaxDeg, int nu,
                        int nv, SurfaceMesh& out, std::string* err = nullptr);
// x = radius (1-v) cos t, y = radius (1-v) sin t, z = v height
bool tessellateCone(float height, float radius, float thetamaxDeg, int nu, int nv,
                    SurfaceMesh& out, std::string* err = nullptr);
// x = radius (1-v) cos t, y = radius (1-v) sin t, z = height
bool tessellateDisk(float height, float radius, float thetamaxDeg, int nu, int nv,
                    SurfaceMesh& out, std::string* err = nullptr);
// phi = phimin + v (phimax - phimin) (degrees); r = minorrad cos phi;
// x = (majorrad + r) cos t, y = (majorrad + r) sin t, z = minorrad sin phi
bool tessellateTorus(float majorrad, float minorrad, float phiminDeg, float phimaxDeg,
                     float thetamaxDeg, int nu, int nv, SurfaceMesh& out,
                     std::string* err = nullptr);
// z = zmin + v (zmax - zmin); r = rmax sqrt(z / zmax); x = r cos t, y = r sin t
bool tessellateParaboloid(float rmax, float zmin, float zmax, float thetamaxDeg, int nu,
                          int nv, SurfaceMesh& out, std::string* err = nullptr);
// the line point1 + v (point2 - point1) swept by rotation about z through t
bool tessellateHyperboloid(glm::vec3 point1, glm::vec3 point2, float thetamaxDeg, int nu,
                           int nv, SurfaceMesh& out, std::string* err = nullptr);

}  // namespace rd
