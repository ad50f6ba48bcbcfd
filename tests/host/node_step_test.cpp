// node_step_test.cpp: the wide node step's helpers on the device (cl/lib/node_test.clh
// through node_probe.cl), four-, eight- and sixteen-wide: the lane mask (movmskps on x86, one
// multiply elsewhere: both built here) is exact for every compare pattern, the lowest lane and the distance order are right,
// and the box test (compare-and-select min/max, far planes padded through the inverse)
// keeps a ray that lies in a box's face plane, where 0 * inf is NaN, and never passes an
// unused slot.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <map>
#include <string>
#include <vector>

#include "cl/include/bvh.h"
#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

namespace {

// How the lane masks are gathered (math.clh): the device's own form (PoCL here: AVX-512's
// mask registers on a CPU that has them), movmskps (an AVX CPU), or the multiply that
// non-x86 devices use.
enum class MaskForm { Native, Movmsk, Portable };

const Program& probeProgram(int width, MaskForm form = MaskForm::Native) {
    const ClContext& ctx = test::testContext();
    // never destroyed, as the test context (render_harness.cpp: Oclgrind crashed at exit)
    static std::map<std::pair<int, MaskForm>, Program*>& built =
        *new std::map<std::pair<int, MaskForm>, Program*>;
    Program*& p = built[{width, form}];
    if (!p) {
        std::string options = "-cl-std=CL1.2";
        if (width == 8) options += " -DRT_BVH8";
        if (width == 16) options += " -DRT_BVH16";
        if (form == MaskForm::Movmsk) options += " -DRT_MOVMSK_MASKS";
        if (form == MaskForm::Portable) options += " -DRT_PORTABLE_MASKS";
        p = new Program(ctx, assembleClSource({"node_probe.cl"}), options);
    }
    return *p;
}

void expectLaneMasks(int width, MaskForm form) {
    const ClContext& ctx = test::testContext();
    Profiler prof(ctx);
    Kernel k(ctx, probeProgram(width, form).get(), "lane_mask_probe", prof);
    const size_t n = size_t(1) << width;
    DeviceBuffer<uint32_t> mask(ctx, n);
    DeviceBuffer<int32_t> lowest(ctx, n), order(ctx, n * width);
    k.launch(n, cl_uint(n), mask, lowest, order);
    std::vector<uint32_t> m = mask.download();
    std::vector<int32_t> lo = lowest.download(), ord = order.download();
    for (uint32_t i = 0; i < n; ++i) {
        ASSERT_EQ(m[i], i) << "pattern " << i << ", " << width << " lanes";
        int expectLowest = -1;
        for (int b = 0; b < width; ++b)
            if (i >> b & 1u) {
                expectLowest = b;
                break;
            }
        EXPECT_EQ(lo[i], expectLowest) << "pattern " << i;
        // the set lanes by ascending distance (5 k mod W, all distinct)
        std::vector<int> want;
        for (int b = 0; b < width; ++b)
            if (i >> b & 1u) want.push_back(b);
        std::sort(want.begin(), want.end(),
                  [&](int a, int b) { return (5 * a) % width < (5 * b) % width; });
        for (int j = 0; j < width; ++j)
            EXPECT_EQ(ord[i * width + j], j < int(want.size()) ? want[j] : -1)
                << "pattern " << i << ", place " << j;
    }
}

// One node whose slot 0 is the unit box [0, 1]^3 and whose other slots are unused
// (inverted boxes, count -1), against rays given as (origin, tmin) and (direction, tmax).
template <class Node>
std::vector<uint32_t> boxMasks(int width, const std::vector<rt_float4>& org,
                               const std::vector<rt_float4>& dir) {
    const ClContext& ctx = test::testContext();
    Node node{};
    for (int k = 0; k < width; ++k) {
        bool used = k == 0;
        float lo = used ? 0.0f : FLT_MAX, hi = used ? 1.0f : -FLT_MAX;
        float* planes = reinterpret_cast<float*>(&node);
        for (int a = 0; a < 3; ++a) {
            planes[a * width + k] = lo;
            planes[(3 + a) * width + k] = hi;
        }
        node.child[k] = 0;
        node.count[k] = used ? 1 : -1;
    }
    Profiler prof(ctx);
    Kernel k(ctx, probeProgram(width).get(), "node_boxes_probe", prof);
    DeviceBuffer<Node> nb(ctx, std::vector<Node>{node});
    DeviceBuffer<rt_float4> ob(ctx, org), db(ctx, dir);
    DeviceBuffer<uint32_t> mask(ctx, org.size());
    k.launch(org.size(), cl_uint(org.size()), nb, ob, db, mask);
    return mask.download();
}

void expectBoxTest(int width) {
    const float inf = 1e30f;
    // in the face plane x = 0 (direction x +0: 0 * inf), in x = 1 going -0 in x, along an
    // edge, through the inside, parallel but outside, and behind tmax
    std::vector<rt_float4> org{{0.0f, 0.5f, 0.5f, 0.0f},  {1.0f, 0.5f, -1.0f, 0.0f},
                               {0.0f, 0.0f, -1.0f, 0.0f}, {0.5f, 0.5f, -1.0f, 0.0f},
                               {-0.5f, 0.5f, -1.0f, 0.0f}, {1.5f, 0.5f, 0.5f, 0.0f},
                               {0.5f, 0.5f, -1.0f, 0.0f}};
    std::vector<rt_float4> dir{{0.0f, 0.0f, 1.0f, inf},  {-0.0f, 0.0f, 1.0f, inf},
                               {0.0f, 0.0f, 1.0f, inf},  {0.0f, 0.0f, 1.0f, inf},
                               {0.0f, 0.0f, 1.0f, inf},  {0.0f, 0.0f, 1.0f, inf},
                               {0.0f, 0.0f, 1.0f, 0.5f}};
    std::vector<uint32_t> want{1, 1, 1, 1, 0, 0, 0};
    std::vector<uint32_t> got = width == 16  ? boxMasks<Bvh16Node>(16, org, dir)
                                : width == 8 ? boxMasks<Bvh8Node>(8, org, dir)
                                             : boxMasks<Bvh4Node>(4, org, dir);
    for (size_t i = 0; i < want.size(); ++i)
        EXPECT_EQ(got[i], want[i]) << "ray " << i << ", " << width << " lanes";
}

}  // namespace

TEST(NodeStep, LaneMaskIsExactForEveryPattern) {
    for (MaskForm form : {MaskForm::Native, MaskForm::Movmsk, MaskForm::Portable}) {
        expectLaneMasks(4, form);
        expectLaneMasks(8, form);
        expectLaneMasks(16, form);
    }
}

TEST(NodeStep, BoxTestKeepsRaysInAFacePlaneAndSkipsUnusedSlots) {
    expectBoxTest(4);
    expectBoxTest(8);
    expectBoxTest(16);
}
