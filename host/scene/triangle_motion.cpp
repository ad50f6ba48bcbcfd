// triangle_motion.cpp: moving triangles' keys in the Scene (triangle_motion.h).
#include "host/scene/triangle_motion.h"

namespace rd {

namespace {
// The keys between the first and the last: where they start in quadricMotion (three
// float4s each) and how many there are; the last key's v2.w is 1 + that start, or 0
// when there are none.
size_t middleStart(const Scene& s, size_t t) {
    return size_t(s.trianglesEnd[t].v2.w) - 1;
}
size_t middleCount(const Scene& s, size_t t) {
    return s.trianglesEnd[t].v2.w > 0.0f ? size_t(s.quadricMotion[middleStart(s, t) + 1].w)
                                         : 0;
}
void setPlace(rt_float4& to, const rt_float4& from) {
    to.x = from.x, to.y = from.y, to.z = from.z;
}
}  // namespace

void addTriangleMotion(Scene& s, const std::vector<Triangle>& keys,
                       const std::vector<float>& times) {
    // The last key by triangle index, the key times in its v0.w and v1.w; the keys
    // between in the motion buffer, v2.w 1 + where they start (cl/lib/motion.clh). (A
    // float holds the index exactly up to 2^24 float4s: past that they are left out, and
    // the triangle moves from its first key to its last.)
    const uint32_t index = uint32_t(s.triangles.size() - 1);
    if (s.trianglesEnd.size() < index) s.trianglesEnd.resize(index);
    Triangle last = keys.back();
    last.v0.w = times.front(), last.v1.w = times.back(), last.v2.w = 0.0f;
    const size_t at = s.quadricMotion.size();
    if (keys.size() > 1 && at + 3 * keys.size() < (size_t(1) << 24)) {
        last.v2.w = float(at + 1);
        for (size_t k = 0; k + 1 < keys.size(); ++k) {
            Triangle key = keys[k];
            key.v0.w = times[k + 1];
            key.v1.w = k == 0 ? float(keys.size() - 1) : 0.0f;
            for (const rt_float4& v : {key.v0, key.v1, key.v2}) s.quadricMotion.push_back(v);
        }
    }
    s.trianglesEnd.push_back(last);
    s.attrs.back().flags |= RT_QF_MOVING;
    Quadric q{};
    q.kind = RT_Q_MOVING_TRIANGLE;
    q.first_member = index;
    q.flags = RT_QF_MOVING;
    q.primvars = RT_NO_QUADRIC_PRIMVARS;
    q.point_params = RT_NO_POINT_PARAMS;
    s.quadrics.push_back(q);
    s.quadricBounds.push_back(triangleMotionBounds(s, index));
}

TriangleKeys triangleKeys(const Scene& s, size_t t) {
    TriangleKeys k;
    const Triangle& last = s.trianglesEnd[t];
    k.times.push_back(last.v0.w);
    const size_t first = middleStart(s, t), n = middleCount(s, t);
    for (size_t j = 0; j < n; ++j) {
        const rt_float4* v = &s.quadricMotion[first + 3 * j];
        k.keys.push_back({v[0], v[1], v[2]});
        k.times.push_back(v[0].w);
    }
    k.keys.push_back(last);
    k.times.push_back(last.v1.w);
    return k;
}

void setTriangleKeys(Scene& s, size_t t, const std::vector<Triangle>& keys) {
    const size_t first = middleStart(s, t), n = middleCount(s, t);
    for (size_t j = 0; j < n && j < keys.size(); ++j) {
        rt_float4* v = &s.quadricMotion[first + 3 * j];
        setPlace(v[0], keys[j].v0), setPlace(v[1], keys[j].v1), setPlace(v[2], keys[j].v2);
    }
    if (keys.size() != n + 1) return;
    Triangle& last = s.trianglesEnd[t];
    setPlace(last.v0, keys[n].v0), setPlace(last.v1, keys[n].v1), setPlace(last.v2, keys[n].v2);
}

Aabb triangleMotionBounds(const Scene& s, size_t t) {
    Aabb box;
    auto grow = [&](const Triangle& tr) {
        for (const rt_float4* v : {&tr.v0, &tr.v1, &tr.v2}) {
            const float p[3] = {v->x, v->y, v->z};
            box.grow(p);
        }
    };
    grow(s.triangles[t]);
    for (const Triangle& key : triangleKeys(s, t).keys) grow(key);
    return box;
}

}  // namespace rd
