// quadric_shapes.cpp: RI quadric parameters -> Quadric records (cl/include/quadric.h).
#include "host/scene/quadric_shapes.h"

#include <algorithm>
#include <cmath>

namespace rd {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kDeg = kPi / 180.0f;

rt_float4 f4(float x, float y = 0, float z = 0, float w = 0) { return {x, y, z, w}; }

bool finiteAll(std::initializer_list<float> xs) {
    for (float x : xs)
        if (!std::isfinite(x)) return false;
    return true;
}

// Common part of every kind: default s, t = u, v and the sweep.
QuadricShape start(uint32_t kind, float thetamaxDeg, std::initializer_list<float> params) {
    QuadricShape s;
    s.q.kind = kind;
    s.q.primvars = RT_NO_QUADRIC_PRIMVARS;
    s.q.st_s = f4(0, 1, 0, 1);
    s.q.st_t = f4(0, 0, 1, 1);
    if (!finiteAll(params) || !std::isfinite(thetamaxDeg)) {
        s.error = "non-finite parameter";
        return s;
    }
    float tm = std::clamp(thetamaxDeg, -360.0f, 360.0f) * kDeg;
    if (tm == 0.0f) s.error = "thetamax is 0: the surface is empty";
    s.q.range.w = tm;
    return s;
}

void box(QuadricShape& s, float rho, float z0, float z1) {
    s.lo = {-rho, -rho, std::min(z0, z1)};
    s.hi = {rho, rho, std::max(z0, z1)};
}

}  // namespace

QuadricShape makeSphere(float radius, float zmin, float zmax, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_SPHERE, thetamaxDeg, {radius, zmin, zmax});
    float r = std::fabs(radius);
    if (s.error.empty() && r == 0.0f) s.error = "radius is 0";
    if (!s.error.empty()) return s;
    float z0 = std::clamp(std::min(zmin, zmax), -r, r), z1 = std::clamp(std::max(zmin, zmax), -r, r);
    s.q.coef = f4(1, 1, 1, 0);
    s.q.range = f4(-r * r, z0, z1, s.q.range.w);
    s.q.shape = f4(r, std::asin(z0 / r), std::asin(z1 / r));
    if (radius < 0) s.q.flags |= RT_QF_FLIP;  // RI: a negative radius turns it inside out
    box(s, r, z0, z1);
    return s;
}

QuadricShape makeCylinder(float radius, float zmin, float zmax, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_CYLINDER, thetamaxDeg, {radius, zmin, zmax});
    float r = std::fabs(radius);
    if (s.error.empty() && (r == 0.0f || zmin == zmax)) s.error = "zero radius or height";
    if (!s.error.empty()) return s;
    s.q.coef = f4(1, 1, 0, 0);
    s.q.range = f4(-r * r, std::min(zmin, zmax), std::max(zmin, zmax), s.q.range.w);
    s.q.shape = f4(r, zmin, zmax);
    box(s, r, zmin, zmax);
    return s;
}

QuadricShape makeCone(float height, float radius, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_CONE, thetamaxDeg, {height, radius});
    float r = std::fabs(radius);
    if (s.error.empty() && (r == 0.0f || height == 0.0f)) s.error = "zero radius or height";
    if (!s.error.empty()) return s;
    // x^2 + y^2 = r^2 (1 - z/h)^2
    s.q.coef = f4(1, 1, -r * r / (height * height), 2 * r * r / height);
    s.q.range = f4(-r * r, std::min(0.0f, height), std::max(0.0f, height), s.q.range.w);
    s.q.shape = f4(height, r);
    box(s, r, 0, height);
    return s;
}

QuadricShape makeDisk(float height, float radius, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_DISK, thetamaxDeg, {height, radius});
    float r = std::fabs(radius);
    if (s.error.empty() && r == 0.0f) s.error = "radius is 0";
    if (!s.error.empty()) return s;
    s.q.range = f4(0, height, height, s.q.range.w);
    s.q.shape = f4(height, r);
    box(s, r, height, height);
    return s;
}

QuadricShape makeParaboloid(float rmax, float zmin, float zmax, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_PARABOLOID, thetamaxDeg, {rmax, zmin, zmax});
    float r = std::fabs(rmax);
    if (s.error.empty() && (r == 0.0f || zmax == 0.0f || zmin == zmax))
        s.error = "zero rmax, zmax or height";
    if (s.error.empty() && (zmin / zmax < 0.0f)) s.error = "zmin and zmax on opposite sides of 0";
    if (!s.error.empty()) return s;
    // x^2 + y^2 = rmax^2 z / zmax
    s.q.coef = f4(1, 1, 0, -r * r / zmax);
    s.q.range = f4(0, std::min(zmin, zmax), std::max(zmin, zmax), s.q.range.w);
    s.q.shape = f4(r, zmin, zmax);
    float rho = r * std::sqrt(std::max(std::fabs(zmin), std::fabs(zmax)) / std::fabs(zmax));
    box(s, rho, zmin, zmax);
    return s;
}

QuadricShape makeHyperboloid(glm::vec3 p1, glm::vec3 p2, float thetamaxDeg) {
    QuadricShape s = start(RT_Q_HYPERBOLOID, thetamaxDeg, {p1.x, p1.y, p1.z, p2.x, p2.y, p2.z});
    if (s.error.empty() && p1 == p2) s.error = "point1 equals point2";
    if (!s.error.empty()) return s;
    glm::vec2 a(p1), d = glm::vec2(p2) - glm::vec2(p1);
    float rho = std::max(glm::length(a), glm::length(glm::vec2(p2)));
    s.q.shape = f4(p1.x, p1.y, p1.z);
    s.q.shape2 = f4(p2.x, p2.y, p2.z);
    float dz = p2.z - p1.z;
    if (std::fabs(dz) <= 1e-6f * std::max(glm::length(p2 - p1), 1e-30f)) {
        // planar: a ring between the segment's nearest and farthest points from the axis
        float v = glm::dot(d, d) > 0 ? std::clamp(-glm::dot(a, d) / glm::dot(d, d), 0.0f, 1.0f) : 0;
        s.q.shape.w = 1;
        s.q.shape2.w = glm::length(a + v * d);
        s.q.range = f4(0, p1.z, rho, s.q.range.w);
        box(s, rho, p1.z, p1.z);
        return s;
    }
    // rho^2 = a0 + a1 v + a2 v^2 with v = (z - z1) / dz, as a quadratic in z
    double a0 = glm::dot(a, a), a1 = 2.0 * glm::dot(a, d), a2 = glm::dot(d, d);
    double al = a2 / (double(dz) * dz), be = -2 * al * p1.z + a1 / dz,
           ga = al * p1.z * p1.z - a1 * p1.z / dz + a0;
    s.q.coef = f4(1, 1, float(-al), float(-be));
    s.q.range = f4(float(-ga), std::min(p1.z, p2.z), std::max(p1.z, p2.z), s.q.range.w);
    box(s, rho, p1.z, p2.z);
    return s;
}

QuadricShape makeTorus(float majorRadius, float minorRadius, float phiminDeg, float phimaxDeg,
                       float thetamaxDeg) {
    QuadricShape s = start(RT_Q_TORUS, thetamaxDeg,
                           {majorRadius, minorRadius, phiminDeg, phimaxDeg});
    if (s.error.empty() && (minorRadius == 0.0f || phiminDeg == phimaxDeg))
        s.error = "zero minor radius or phi range";
    if (!s.error.empty()) return s;
    float phi0 = std::clamp(phiminDeg, -720.0f, 720.0f) * kDeg,
          phi1 = std::clamp(phimaxDeg, -720.0f, 720.0f) * kDeg;
    if (std::fabs(phi1 - phi0) > 2 * kPi) phi1 = phi0 + std::copysign(2 * kPi, phi1 - phi0);
    float R = majorRadius, r = std::fabs(minorRadius);
    s.q.shape = f4(R, r, phi0, phi1);
    s.q.range = f4(0, -r, r, s.q.range.w);
    box(s, std::fabs(R) + r, -r, r);
    return s;
}

bool placeQuadric(Quadric& q, const glm::mat4& m) {
    glm::mat3 l(m);
    float det = glm::determinant(l);
    if (!std::isfinite(det) || det == 0.0f) return false;
    glm::mat3 inv = glm::inverse(l);
    for (int r = 0; r < 3; ++r) {
        // glm is column-major: element (row r, column c) is l[c][r]
        q.to_world[r] = f4(l[0][r], l[1][r], l[2][r]);
        q.to_object[r] = f4(inv[0][r], inv[1][r], inv[2][r]);
    }
    q.center = f4(m[3][0], m[3][1], m[3][2]);
    return std::isfinite(q.center.x) && std::isfinite(q.center.y) && std::isfinite(q.center.z);
}

glm::mat4 quadricPlacement(const Quadric& q) {
    glm::mat4 m(1.0f);
    for (int r = 0; r < 3; ++r) {
        m[0][r] = q.to_world[r].x;
        m[1][r] = q.to_world[r].y;
        m[2][r] = q.to_world[r].z;
    }
    m[3] = glm::vec4(q.center.x, q.center.y, q.center.z, 1.0f);
    return m;
}

glm::vec3 quadricToWorld(const Quadric& q, glm::vec3 p) {
    glm::vec3 w;
    for (int r = 0; r < 3; ++r)
        w[r] = q.to_world[r].x * p.x + q.to_world[r].y * p.y + q.to_world[r].z * p.z;
    return w + glm::vec3(q.center.x, q.center.y, q.center.z);
}

glm::vec3 quadricToObject(const Quadric& q, glm::vec3 p) {
    p -= glm::vec3(q.center.x, q.center.y, q.center.z);
    glm::vec3 o;
    for (int r = 0; r < 3; ++r)
        o[r] = q.to_object[r].x * p.x + q.to_object[r].y * p.y + q.to_object[r].z * p.z;
    return o;
}

Aabb quadricWorldBounds(const Quadric& q, glm::vec3 lo, glm::vec3 hi) {
    Aabb b;
    // Every quadric's object box is [-rho, rho]^2 x [z0, z1] about its axis with rho its
    // largest radius: the surface lies in the cylinder of radius rho over [z0, z1], whose
    // world box is its end circles' (a circle of radius rho at height z spans
    // c + T z +- rho |(Tx, Ty)| along a world axis whose row of the map is T). A rotated
    // shape's box is up to sqrt(2) narrower per axis than its object box's corners; a
    // sphere's is also clipped to its ellipsoid's, up to sqrt(3) narrower. A cone narrows
    // to its apex.
    // (an instance's box is its prototype's, no surface of revolution: its corners)
    const bool aboutZ = q.kind <= RT_Q_TORUS && lo.x == -hi.x && lo.y == -hi.y && hi.x == hi.y;
    for (int c = 0; c < 8 && !aboutZ; ++c) {  // any other box: its corners
        glm::vec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        glm::vec3 w = quadricToWorld(q, p);
        const float f[3] = {w.x, w.y, w.z};
        b.grow(f);
    }
    for (int a = 0; a < 3 && aboutZ; ++a) {
        const double tx = q.to_world[a].x, ty = q.to_world[a].y, tz = q.to_world[a].z;
        const double c = (&q.center.x)[a];
        const double rho = double(hi.x) * std::sqrt(tx * tx + ty * ty);
        double z0 = c + tz * lo.z, z1 = c + tz * hi.z, r0 = rho, r1 = rho;
        if (q.kind == RT_Q_CONE) {  // base circle at z = 0, apex at z = height
            z0 = c, z1 = c + tz * q.shape.x, r1 = 0;
        }
        double blo = std::min(z0 - r0, z1 - r1), bhi = std::max(z0 + r0, z1 + r1);
        if (q.kind == RT_Q_SPHERE) {
            const double e = std::fabs(double(q.shape.x)) * std::sqrt(tx * tx + ty * ty + tz * tz);
            blo = std::max(blo, c - e), bhi = std::min(bhi, c + e);
        }
        b.lo[a] = float(blo), b.hi[a] = float(bhi);
    }
    // pad by a few ulps of the extent so rounding in the map never clips the surface
    for (int a = 0; a < 3; ++a) {
        float pad = 1e-6f * (std::fabs(b.lo[a]) + std::fabs(b.hi[a]) + (b.hi[a] - b.lo[a]));
        b.lo[a] -= pad;
        b.hi[a] += pad;
    }
    return b;
}

glm::vec3 quadricObjectPoint(const Quadric& q, float u, float v) {
    const rt_float4 &sh = q.shape, &sh2 = q.shape2;
    float th = u * q.range.w, c = std::cos(th), s = std::sin(th);
    float rho = 0, z = 0;
    switch (q.kind) {
    case RT_Q_SPHERE: {
        float phi = sh.y + v * (sh.z - sh.y);
        rho = sh.x * std::cos(phi), z = sh.x * std::sin(phi);
        break;
    }
    case RT_Q_CYLINDER: rho = sh.x, z = sh.y + v * (sh.z - sh.y); break;
    case RT_Q_CONE: rho = sh.y * (1 - v), z = v * sh.x; break;
    case RT_Q_DISK: rho = sh.y * (1 - v), z = sh.x; break;
    case RT_Q_PARABOLOID:
        z = sh.y + v * (sh.z - sh.y), rho = sh.x * std::sqrt(std::max(z / sh.z, 0.0f));
        break;
    case RT_Q_TORUS: {
        float phi = sh.z + v * (sh.w - sh.z);
        rho = sh.x + sh.y * std::cos(phi), z = sh.y * std::sin(phi);
        break;
    }
    case RT_Q_HYPERBOLOID: {
        glm::vec3 a(sh.x, sh.y, sh.z), b(sh2.x, sh2.y, sh2.z);
        glm::vec3 l = a + v * (b - a);
        return {l.x * c - l.y * s, l.x * s + l.y * c, l.z};
    }
    }
    return {rho * c, rho * s, z};
}

std::optional<std::vector<BoundaryCircle>> quadricBoundary(const Quadric& q) {
    if (std::fabs(q.range.w) < 2 * kPi * (1 - 1e-6f)) return std::nullopt;
    std::vector<BoundaryCircle> out;
    auto edge = [&](float v) {
        glm::vec3 p = quadricObjectPoint(q, 0.0f, v);
        out.push_back({p.z, glm::length(glm::vec2(p))});
    };
    const rt_float4& sh = q.shape;
    switch (q.kind) {
    case RT_Q_TORUS:
        if (std::fabs(sh.w - sh.z) < 2 * kPi * (1 - 1e-6f)) edge(0), edge(1);
        break;
    case RT_Q_SPHERE:
        if (sh.y > -kPi / 2 + 1e-6f) edge(0);
        if (sh.z < kPi / 2 - 1e-6f) edge(1);
        break;
    case RT_Q_CONE:
    case RT_Q_DISK: edge(0); break;  // v = 1 is the apex / centre, a point
    default: edge(0), edge(1); break;
    }
    // circles of (nearly) zero radius are points: they leave no hole
    float size = std::max({std::fabs(sh.x), std::fabs(sh.y), std::fabs(sh.z), 1e-30f});
    out.erase(std::remove_if(out.begin(), out.end(),
                             [&](const BoundaryCircle& b) { return b.rho <= 1e-5f * size; }),
              out.end());
    return out;
}

const char* quadricKindName(uint32_t kind) {
    static const char* names[] = {"Sphere",     "Cylinder",    "Cone",  "Disk",
                                  "Paraboloid", "Hyperboloid", "Torus", "SolidBegin"};
    return kind < 8 ? names[kind] : "quadric";
}

}  // namespace rd
