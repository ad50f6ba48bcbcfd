// blobby_test.cpp: RiBlobby polygonised (tessellate_blobby.h): a lone blob is a sphere of
// radius 0.5 under its matrix, blobs near each other blend under add and not under
// maximum, a segment blob is a capsule of half its radius, and per-blob values blend by
// the blobs' fields.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "host/scene/tessellate_blobby.h"
#include "test_util.h"

using namespace rd;

namespace {

std::vector<float> matrix(float sx, float sy, float sz, float tx, float ty, float tz) {
    return {sx, 0, 0, 0, 0, sy, 0, 0, 0, 0, sz, 0, tx, ty, tz, 1};  // RI row-vector order
}

// Every edge of a closed surface is shared by exactly two triangles.
bool closed(const SurfaceMesh& m) {
    std::map<std::pair<int, int>, int> edges;
    for (size_t k = 0; k < m.mesh.tris.size(); k += 3)
        for (int e = 0; e < 3; ++e) {
            int a = m.mesh.tris[k + size_t(e)], b = m.mesh.tris[k + size_t((e + 1) % 3)];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto& [edge, count] : edges)
        if (count != 2) return false;
    return !edges.empty();
}

}  // namespace

TEST(Blobby, LoneBlobIsASphereOfRadiusHalf) {
    SurfaceMesh m;
    std::string err, note;
    ASSERT_TRUE(
        tessellateBlobby({1001, 0}, matrix(1, 1, 1, 0, 0, 0), 128, m, &err, &note))
        << err;
    test::expectWellFormed(m);
    EXPECT_TRUE(closed(m));
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        const glm::vec3 p = m.mesh.p[i];
        EXPECT_NEAR(glm::length(p), 0.5f, 0.005f);
        EXPECT_GT(glm::dot(m.mesh.n[i], glm::normalize(p)), 0.999f);  // outward
    }
    EXPECT_NEAR(meshArea(m.mesh), M_PI, 0.02 * M_PI);
    // scaled by 2 along x: an ellipsoid with semi-axes 1, 0.5, 0.5
    SurfaceMesh e;
    ASSERT_TRUE(
        tessellateBlobby({1001, 0}, matrix(2, 1, 1, 0, 0, 0), 128, e, &err, &note));
    float most = 0;
    for (const glm::vec3& p : e.mesh.p) most = std::max(most, std::fabs(p.x));
    EXPECT_NEAR(most, 1.0f, 0.01f);
}

// Two blobs 1.2 apart: their spheres (radius 0.5) would not touch, but the fields add to
// 2 w(0.36) = 0.69 > 0.5 half way, so the sum bridges them; their maximum does not.
TEST(Blobby, AddBlendsMaximumDoesNot) {
    std::vector<float> f = matrix(1, 1, 1, -0.6f, 0, 0);
    const std::vector<float> second = matrix(1, 1, 1, 0.6f, 0, 0);
    f.insert(f.end(), second.begin(), second.end());
    auto nearMiddle = [](const SurfaceMesh& m) {
        int n = 0;
        for (const glm::vec3& p : m.mesh.p) n += std::fabs(p.x) < 0.05f;
        return n;
    };
    SurfaceMesh sum, most;
    std::string err, note;
    ASSERT_TRUE(
        tessellateBlobby({1001, 0, 1001, 16, 0, 2, 0, 1}, f, 128, sum, &err, &note));
    ASSERT_TRUE(
        tessellateBlobby({1001, 0, 1001, 16, 2, 2, 0, 1}, f, 128, most, &err, &note));
    test::expectWellFormed(sum);
    EXPECT_TRUE(closed(sum));
    EXPECT_GT(nearMiddle(sum), 0);
    EXPECT_EQ(nearMiddle(most), 0);
    EXPECT_TRUE(closed(most));
}

// A segment blob from (0,0,0) to (1,0,0) of radius 1: the points half a unit from the
// segment (a capsule).
TEST(Blobby, SegmentBlobIsACapsule) {
    std::vector<float> f = {0, 0, 0, 1, 0, 0, 1};
    const std::vector<float> m4 = matrix(1, 1, 1, 0, 0, 0);
    f.insert(f.end(), m4.begin(), m4.end());
    SurfaceMesh m;
    std::string err, note;
    ASSERT_TRUE(tessellateBlobby({1002, 0}, f, 128, m, &err, &note)) << err;
    test::expectWellFormed(m);
    for (const glm::vec3& p : m.mesh.p) {
        const float t = std::clamp(p.x, 0.0f, 1.0f);
        EXPECT_NEAR(glm::length(p - glm::vec3(t, 0, 0)), 0.5f, 0.005f);
    }
    // a constant alone bounds nothing: no surface and a note, not an endless grid
    SurfaceMesh none;
    EXPECT_TRUE(tessellateBlobby({1000, 0}, {1.0f}, 128, none, &err, &note));
    EXPECT_TRUE(none.mesh.tris.empty());
    EXPECT_FALSE(note.empty());
}

// A blob under a singular matrix (or with non-finite numbers) reaches nothing: the others
// are polygonised as without it.
// A sum or maximum of blobs is sampled on its grid blob by blob, over each blob's box
// and on the host's cores; any other program point by point. Wrapped in an identity (op
// 7) the same blobs take the second way: the meshes must be the same, bit for bit, with
// 60 ellipsoids and segments of several sizes overlapping at random (boxes of a few
// grid points to many, partly off the grid's slabs).
TEST(Blobby, BlobByBlobSamplingIsThePointwiseField) {
    std::vector<int> code;
    std::vector<float> f;
    uint32_t state = 12345u;
    auto uniform = [&](float lo, float hi) {
        state = state * 1664525u + 1013904223u;
        return lo + (hi - lo) * float(state >> 8) / float(1u << 24);
    };
    const int blobs = 60;
    for (int b = 0; b < blobs; ++b) {
        const float s = uniform(0.2f, 1.5f);
        std::vector<float> m = matrix(s * uniform(0.5f, 2.0f), s, s * uniform(0.5f, 2.0f),
                                      uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
        if (b % 5 == 0) {  // a segment: its ends and radius, then its matrix
            code.insert(code.end(), {1002, int(f.size())});
            f.insert(f.end(), {0, 0, 0, uniform(0.2f, 1.0f), 0, 0, uniform(0.5f, 1.0f)});
        } else {
            code.insert(code.end(), {1001, int(f.size())});
        }
        f.insert(f.end(), m.begin(), m.end());
    }
    for (int op : {0, 2}) {  // sum, maximum
        std::vector<int> flat = code;
        flat.insert(flat.end(), {op, blobs});
        for (int b = 0; b < blobs; ++b) flat.push_back(b);
        std::vector<int> wrapped = flat;
        wrapped.insert(wrapped.end(), {7, blobs});
        SurfaceMesh byBlob, byPoint;
        std::string err, note;
        ASSERT_TRUE(tessellateBlobby(flat, f, 96, byBlob, &err, &note)) << err;
        ASSERT_TRUE(tessellateBlobby(wrapped, f, 96, byPoint, &err, &note)) << err;
        EXPECT_GT(byBlob.mesh.tris.size(), 30000u) << "op " << op;
        EXPECT_TRUE(byBlob.mesh.p == byPoint.mesh.p) << "op " << op;
        EXPECT_TRUE(byBlob.mesh.n == byPoint.mesh.n) << "op " << op;
        EXPECT_TRUE(byBlob.mesh.tris == byPoint.mesh.tris) << "op " << op;
        test::expectWellFormed(byBlob);
    }
}

TEST(Blobby, DegenerateBlobsAreLeftOut) {
    std::vector<float> f = matrix(1, 1, 1, 0, 0, 0);
    const std::vector<float> flat = matrix(0, 0, 0, 0.2f, 0, 0);
    std::vector<float> bad = matrix(1, 1, 1, 0, 0, 0);
    bad[0] = NAN;
    f.insert(f.end(), flat.begin(), flat.end());
    f.insert(f.end(), bad.begin(), bad.end());
    SurfaceMesh m;
    std::string err, note;
    ASSERT_TRUE(tessellateBlobby({1001, 0, 1001, 16, 1001, 32, 0, 3, 0, 1, 2}, f, 128, m,
                                 &err, &note))
        << err;
    ASSERT_FALSE(m.mesh.p.empty());
    for (const glm::vec3& p : m.mesh.p) EXPECT_NEAR(glm::length(p), 0.5f, 0.005f);
    // per-blob values come from the one blob that reaches anything (leaf 0) alone
    SurfaceMesh w;
    BlobbyLeafWeights weights;
    ASSERT_TRUE(tessellateBlobby({1001, 0, 1001, 16, 1001, 32, 0, 3, 0, 1, 2}, f, 128, w,
                                 &err, &note, &weights));
    ASSERT_EQ(weights.start.size(), w.mesh.p.size() + 1);
    for (size_t i = 0; i < w.mesh.p.size(); ++i) {
        ASSERT_EQ(weights.start[i + 1] - weights.start[i], 1u);
        EXPECT_EQ(weights.leaf[weights.start[i]], 0);
        EXPECT_EQ(weights.weight[weights.start[i]], 1.0f);
    }
}

// Per-blob values (BlobbyLeafWeights): two unit blobs at x = -0.6 and 0.6 added, behind a
// constant leaf (leaf 0: counted, never weighted). At each vertex the weights are the
// blobs' own fields over their sum (Wyvill's falloff of the squared distance; within
// 1e-6), they sum to 1, and a vertex the second blob does not reach (x < -0.4) takes the
// first's value alone.
TEST(Blobby, LeafWeightsAreTheBlobsFieldsShares) {
    std::vector<float> f = {0.0f};
    for (float x : {-0.6f, 0.6f}) {
        const std::vector<float> m = matrix(1, 1, 1, x, 0, 0);
        f.insert(f.end(), m.begin(), m.end());
    }
    SurfaceMesh m;
    BlobbyLeafWeights w;
    std::string err, note;
    ASSERT_TRUE(tessellateBlobby({1000, 0, 1001, 1, 1001, 17, 0, 3, 0, 1, 2}, f, 128, m,
                                 &err, &note, &w))
        << err;
    ASSERT_EQ(w.start.size(), m.mesh.p.size() + 1);
    auto falloff = [](double r2) {
        return r2 >= 1 ? 0.0 : 1 + r2 * (-22.0 / 9 + r2 * (17.0 / 9 - r2 * 4.0 / 9));
    };
    int alone = 0, shared = 0;
    for (size_t i = 0; i < m.mesh.p.size(); ++i) {
        const glm::dvec3 p(m.mesh.p[i]);
        const double f1 =
            falloff(glm::dot(p - glm::dvec3(-0.6, 0, 0), p - glm::dvec3(-0.6, 0, 0)));
        const double f2 =
            falloff(glm::dot(p - glm::dvec3(0.6, 0, 0), p - glm::dvec3(0.6, 0, 0)));
        double share[3] = {0, 0, 0}, sum = 0;
        for (size_t k = w.start[i]; k < w.start[i + 1]; ++k) {
            ASSERT_GE(w.leaf[k], 1);  // the constant is never weighted
            ASSERT_LE(w.leaf[k], 2);
            share[w.leaf[k]] += w.weight[k];
            sum += w.weight[k];
        }
        EXPECT_NEAR(sum, 1.0, 1e-6);
        EXPECT_NEAR(share[1], f1 / (f1 + f2), 1e-6) << p.x;
        EXPECT_NEAR(share[2], f2 / (f1 + f2), 1e-6) << p.x;
        if (p.x < -0.4) alone += share[1] == 1.0;
        if (std::fabs(p.x) < 0.05) shared += std::fabs(share[1] - 0.5) < 0.1;
    }
    EXPECT_GT(alone, 100);
    EXPECT_GT(shared, 10);
    // twenty blobs in one place (a surface of radius about 0.95): each vertex blends the
    // eight strongest, a bound on the lists, with weights summing to 1
    std::vector<int> code;
    std::vector<float> same;
    for (int i = 0; i < 20; ++i) {
        code.insert(code.end(), {1001, 16 * i});
        const std::vector<float> unit = matrix(1, 1, 1, 0, 0, 0);
        same.insert(same.end(), unit.begin(), unit.end());
    }
    code.insert(code.end(), {0, 20});
    for (int i = 0; i < 20; ++i) code.push_back(i);
    SurfaceMesh dense;
    ASSERT_TRUE(tessellateBlobby(code, same, 64, dense, &err, &note, &w)) << err;
    ASSERT_FALSE(dense.mesh.p.empty());
    ASSERT_EQ(w.start.size(), dense.mesh.p.size() + 1);
    for (size_t i = 0; i < dense.mesh.p.size(); ++i) {
        ASSERT_EQ(w.start[i + 1] - w.start[i], 8u);
        double sum = 0;
        for (size_t k = w.start[i]; k < w.start[i + 1]; ++k) sum += w.weight[k];
        EXPECT_NEAR(sum, 1.0, 1e-6);
    }
}
