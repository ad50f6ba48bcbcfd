// quadric_blocks.cpp: an object block's plain quadrics side by side, after the leaf blocks.
#include "quadric_blocks.h"

#include <cmath>
#include <cstring>

namespace rd {

bool isPlainQuadric(const Quadric& q) {
    // (rt_quadric_uv_test's test of a full sweep, in the same precision: a hyperboloid's
    // angle is measured from its generating line, which the four-wide test does not do)
    const bool full = std::fabs(double(q.range.w)) >= 6.283185307179586 * double(1 - 1e-6f);
    const bool shape = q.kind == RT_Q_SPHERE || q.kind == RT_Q_CYLINDER ||
                       q.kind == RT_Q_CONE || q.kind == RT_Q_PARABOLOID || q.kind == RT_Q_DISK ||
                       (q.kind == RT_Q_HYPERBOLOID && q.shape.w == 0.0f && full);
    return shape && !(q.flags & RT_QF_MOVING);
}

size_t appendQuadricBlocks(std::vector<Triangle4>& blocks, const std::vector<Quadric>& objects) {
    static_assert(sizeof(QuadricBlock) == 2 * sizeof(Triangle4), "two slots a record");
    const size_t leafBlocks = blocks.size();
    size_t made = 0;
    for (size_t i = 0; i < leafBlocks; ++i) {
        const uint32_t first = blocks[i].prim[0];
        if (first == RT_EMPTY_LANE || !(first & RT_OBJECT_BIT)) continue;
        // every lane a quadric (the others, one at a time beside the plain ones), one plain
        int quadrics = 0, plain = 0, live = 0;
        for (uint32_t prim : blocks[i].prim) {
            if (prim == RT_EMPTY_LANE) continue;
            ++live;
            if (!(prim & RT_OBJECT_BIT)) continue;
            const Quadric& q = objects.at(prim & RT_OBJECT_MASK);
            quadrics += q.kind <= RT_Q_TORUS;
            plain += isPlainQuadric(q);
        }
        if (quadrics < live || plain == 0) continue;
        QuadricBlock qb{};
        for (int lane = 0; lane < 4; ++lane) {
            const uint32_t prim = blocks[i].prim[lane];
            if (prim == RT_EMPTY_LANE) continue;
            const Quadric& q = objects[prim & RT_OBJECT_MASK];
            if (!isPlainQuadric(q)) {  // intersected on its own: marked by a NaN sweep
                (&qb.sweep.x)[lane] = NAN;
                continue;
            }
            const float* c = &q.center.x;
            for (int a = 0; a < 3; ++a) (&qb.center[a].x)[lane] = c[a];
            for (int r = 0; r < 3; ++r)
                for (int a = 0; a < 3; ++a) (&qb.to_object[3 * r + a].x)[lane] = (&q.to_object[r].x)[a];
            for (int a = 0; a < 4; ++a) (&qb.coef[a].x)[lane] = (&q.coef.x)[a];
            for (int a = 0; a < 3; ++a) (&qb.range[a].x)[lane] = (&q.range.x)[a];
            (&qb.sweep.x)[lane] = q.range.w;
            if (q.kind == RT_Q_DISK) {  // no quadratic (no roots), and the plane for z's clip
                for (int a = 0; a < 4; ++a) (&qb.coef[a].x)[lane] = 0.0f;
                (&qb.range[0].x)[lane] = 0.0f;
                (&qb.range[1].x)[lane] = q.shape.x;
                (&qb.range[2].x)[lane] = std::fabs(q.shape.y);
            }
        }
        const int32_t offset = int32_t(blocks.size() - i);
        std::memcpy(&blocks[i].v2x.x, &offset, sizeof offset);
        blocks.resize(blocks.size() + 2);
        std::memcpy(&blocks[blocks.size() - 2], &qb, sizeof qb);
        ++made;
    }
    return made;
}

}  // namespace rd
