// rng_test.cpp: the Sobol sampler's numbers on the device (cl/lib/rng.clh through
// rng_probe.cl): each replicate of a pixel's samples (the even ones, the odd ones) is a
// (0, m, 2)-net at every power of two, the two replicates are scrambled apart, and the
// bit reversal by a table (RT_NO_BITREVERSE, for Oclgrind) gives the shifts' bits.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "ocl/buffer.h"
#include "ocl/kernel.h"
#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

namespace {

struct Point2 {  // a float2 on the device
    float x, y;
};

struct Numbers {
    std::vector<Point2> points;
    std::vector<uint32_t> reversed;
};

Numbers probe(const std::string& options, uint32_t pixel, uint32_t pair, uint32_t count) {
    const ClContext& ctx = test::testContext();
    // never destroyed, as the test context (render_harness.cpp: Oclgrind crashed at exit)
    Program& program =
        *new Program(ctx, assembleClSource({"rng_probe.cl"}), "-cl-std=CL1.2 " + options);
    Profiler prof(ctx);
    Kernel k(ctx, program.get(), "rng_probe", prof);
    DeviceBuffer<Point2> points(ctx, count);
    DeviceBuffer<uint32_t> reversed(ctx, count);
    k.launch(count, cl_uint(pixel), cl_uint(pair), cl_uint(count), points, reversed);
    return {points.download(), reversed.download()};
}

// Whether the points form a (0, m, 2)-net: for every split a + b = m, each of the 2^a x
// 2^b cells of the unit square holds exactly one of the 2^m points.
bool isNet(const std::vector<Point2>& pts) {
    int m = 0;
    while ((size_t(1) << m) < pts.size()) ++m;
    if ((size_t(1) << m) != pts.size()) return false;
    for (int a = 0; a <= m; ++a) {
        const int b = m - a;
        std::vector<int> cells(size_t(1) << m, 0);
        for (const Point2& p : pts) {
            if (!(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f)) return false;
            const int cx = int(p.x * float(1 << a)), cy = int(p.y * float(1 << b));
            if (++cells[size_t(cy) * (size_t(1) << a) + size_t(cx)] > 1) return false;
        }
    }
    return true;
}

}  // namespace

TEST(Sampler, EachReplicateOfAPixelsSamplesIsANet) {
    for (uint32_t pair : {0u, 1u, 7u}) {
        const Numbers n = probe("-DRT_SAMPLER_SOBOL", 4711, pair, 64);
        for (uint32_t r = 0; r < 2; ++r)
            for (size_t count = 1; count <= 32; count *= 2) {
                std::vector<Point2> rep;
                for (size_t i = 0; i < count; ++i) rep.push_back(n.points[2 * i + r]);
                EXPECT_TRUE(isNet(rep)) << "pair " << pair << ", replicate " << r << ", "
                                        << count << " points";
            }
        // the replicates are scrambled apart: their first points differ, and their union
        // is not the one sequence's net (it would be, had they shared a scramble)
        EXPECT_NE(std::memcmp(&n.points[0], &n.points[1], sizeof(Point2)), 0);
        int sameCell = 0;
        for (size_t i = 0; i < 32; i += 2)
            sameCell += int(n.points[i].x * 4) == int(n.points[i + 1].x * 4) &&
                        int(n.points[i].y * 4) == int(n.points[i + 1].y * 4);
        EXPECT_LT(sameCell, 16);
    }
}

TEST(Sampler, BitReversalByTableIsTheShifts) {
    const Numbers shifts = probe("-DRT_SAMPLER_SOBOL", 99, 2, 256);
    const Numbers table = probe("-DRT_SAMPLER_SOBOL -DRT_NO_BITREVERSE", 99, 2, 256);
    for (size_t i = 0; i < 256; ++i) {
        const uint32_t x = uint32_t(i) * 0x9e3779b9u + 12345u;
        uint32_t want = 0;
        for (int b = 0; b < 32; ++b) want |= ((x >> b) & 1u) << (31 - b);
        EXPECT_EQ(shifts.reversed[i], want) << i;
        EXPECT_EQ(table.reversed[i], want) << i;
        EXPECT_EQ(std::memcmp(&shifts.points[i], &table.points[i], sizeof(Point2)), 0)
            << i;
    }
}
