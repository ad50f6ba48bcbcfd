// aabb.h: the axis-aligned bounding box the host BVH builder works with. Kept apart from
// BvhNode (cl/include/bvh.h) so that the builder's arithmetic does not leak into the
// layout shared with the OpenCL kernels.
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace rd {

struct Aabb {
    // Default-constructed boxes are empty (lo > hi) so that growing them yields exactly
    // the grown-in box. FLT_MAX rather than infinity keeps the values finite for
    // kernels built with -cl-fast-relaxed-math.
    float lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX};
    float hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};

    Aabb() = default;
    Aabb(float x0, float y0, float z0, float x1, float y1, float z1)
        : lo{x0, y0, z0}, hi{x1, y1, z1} {}

    static Aabb empty() { return Aabb(); }

    void grow(const Aabb& b) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], b.lo[a]);
            hi[a] = std::max(hi[a], b.hi[a]);
        }
    }
    void grow(const float p[3]) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], p[a]);
            hi[a] = std::max(hi[a], p[a]);
        }
    }

    bool isEmpty() const { return lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]; }

    // A box the builder may use: every bound finite and lo <= hi on every axis. NaN fails
    // both comparisons, so it is rejected here too.
    bool isValid() const {
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || !(lo[a] <= hi[a]))
                return false;
        return true;
    }

    // Surface area in double: boxes near FLT_MAX would overflow a float product and turn
    // every SAH cost into inf/inf = NaN. Empty boxes have area 0, not a negative one.
    double area() const {
        if (isEmpty()) return 0.0;
        double dx = double(hi[0]) - lo[0], dy = double(hi[1]) - lo[1];
        double dz = double(hi[2]) - lo[2];
        return 2.0 * (dx * dy + dy * dz + dz * dx);
    }

    // Halving before adding keeps the centroid finite for boxes spanning +-FLT_MAX.
    float centroid(int axis) const { return 0.5f * lo[axis] + 0.5f * hi[axis]; }
    void centroid(float out[3]) const {
        for (int a = 0; a < 3; ++a) out[a] = centroid(a);
    }

    bool contains(const Aabb& b) const {
        for (int a = 0; a < 3; ++a)
            if (b.lo[a] < lo[a] || b.hi[a] > hi[a]) return false;
        return true;
    }
};

}  // namespace rd
