// tessellate_quadrics.cpp: RI 3.2 quadric parameterisations with analytic derivatives,
// diced by appendGrid.
#include "host/scene/tessellate_quadrics.h"

#include <algorithm>
#include <cmath>

namespace rd {
namespace {

constexpr float kDeg = float(M_PI) / 180.0f;

bool finiteAll(std::initializer_list<float> xs, std::string* err) {
    for (float x : xs)
        if (!std::isfinite(x)) {
            if (err) *err = "quadric: non-finite parameter";
            return false;
        }
    return true;
}

float thetaMaxRad(float deg) { return std::clamp(deg, -360.0f, 360.0f) * kDeg; }

// Rotation of a profile point (rho, z) with d(rho,z)/dv about z by theta = u*tm.
SurfaceSample revolve(float u, float tm, float rho, float z, float drho, float dz) {
    float c = std::cos(u * tm), s = std::sin(u * tm);
    SurfaceSample r;
    r.p = glm::vec3(rho * c, rho * s, z);
    r.dpdu = tm * glm::vec3(-rho * s, rho * c, 0.0f);
    r.dpdv = glm::vec3(drho * c, drho * s, dz);
    return r;
}

bool finish(bool ok, std::string* err) {
    if (!ok && err) *err = "quadric: mesh too large";
    return ok;
}

}  // namespace

bool tessellateCylinder(float radius, float zmin, float zmax, float thetamaxDeg, int nu,
                        int nv, SurfaceMesh& out, std::string* err) {
    if (!finiteAll({radius, zmin, zmax, thetamaxDeg}, err)) return false;
    float tm = thetaMaxRad(thetamaxDeg);
    auto eval = [=](float u, float v) {
        return revolve(u, tm, radius, zmin + v * (zmax - zmin), 0.0f, zmax - zmin);
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

bool tessellateCone(float height, float radius, float thetamaxDeg, int nu, int nv,
                    SurfaceMesh& out, std::string* err) {
    if (!finiteAll({height, radius, thetamaxDeg}, err)) return false;
    float tm = thetaMaxRad(thetamaxDeg);
    auto eval = [=](float u, float v) {
        return revolve(u, tm, radius * (1.0f - v), v * height, -radius, height);
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

bool tessellateDisk(float height, float radius, float thetamaxDeg, int nu, int nv,
                    SurfaceMesh& out, std::string* err) {
    if (!finiteAll({height, radius, thetamaxDeg}, err)) return false;
    float tm = thetaMaxRad(thetamaxDeg);
    auto eval = [=](float u, float v) {
        return revolve(u, tm, radius * (1.0f - v), height, -radius, 0.0f);
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

bool tessellateTorus(float majorrad, float minorrad, float phiminDeg, float phimaxDeg,
                     float thetamaxDeg, int nu, int nv, SurfaceMesh& out,
                     std::string* err) {
    if (!finiteAll({majorrad, minorrad, phiminDeg, phimaxDeg, thetamaxDeg}, err))
        return false;
    float tm = thetaMaxRad(thetamaxDeg);
    float p0 = phiminDeg * kDeg, dp = (phimaxDeg - phiminDeg) * kDeg;
    auto eval = [=](float u, float v) {
        float phi = p0 + v * dp;
        float c = std::cos(phi), s = std::sin(phi);
        return revolve(u, tm, majorrad + minorrad * c, minorrad * s, -minorrad * s * dp,
                       minorrad * c * dp);
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

bool tessellateParaboloid(float rmax, float zmin, float zmax, float thetamaxDeg, int nu,
                          int nv, SurfaceMesh& out, std::string* err) {
    if (!finiteAll({rmax, zmin, zmax, thetamaxDeg}, err)) return false;
    if (zmax == 0.0f) {
        if (err) *err = "Paraboloid: zmax must not be 0";
        return false;
    }
    float tm = thetaMaxRad(thetamaxDeg);
    auto eval = [=](float u, float v) {
        float z = zmin + v * (zmax - zmin);
        float q = std::max(z / zmax, 0.0f);
        float rho = rmax * std::sqrt(q);
        // d rho / dv = rmax (zmax - zmin) / (2 zmax sqrt(q)); undefined at the apex (q=0):
        // report a zero derivative there so the normal is taken just inside.
        float drho = q > 0.0f ? rmax * (zmax - zmin) / (2.0f * zmax * std::sqrt(q)) : 0.0f;
        return revolve(u, tm, rho, z, drho, q > 0.0f ? zmax - zmin : 0.0f);
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

bool tessellateHyperboloid(glm::vec3 point1, glm::vec3 point2, float thetamaxDeg, int nu,
                           int nv, SurfaceMesh& out, std::string* err) {
    if (!finiteAll({point1.x, point1.y, point1.z, point2.x, point2.y, point2.z, thetamaxDeg},
                   err))
        return false;
    float tm = thetaMaxRad(thetamaxDeg);
    glm::vec3 d = point2 - point1;
    auto eval = [=](float u, float v) {
        glm::vec3 q = point1 + v * d;
        float c = std::cos(u * tm), s = std::sin(u * tm);
        SurfaceSample r;
        r.p = glm::vec3(q.x * c - q.y * s, q.x * s + q.y * c, q.z);
        r.dpdu = tm * glm::vec3(-q.x * s - q.y * c, q.x * c - q.y * s, 0.0f);
        r.dpdv = glm::vec3(d.x * c - d.y * s, d.x * s + d.y * c, d.z);
        return r;
    };
    return finish(appendGrid(out, nu, nv, eval, 0), err);
}

}  // namespace rd
