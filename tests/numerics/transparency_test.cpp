// transparency_test.cpp: case 1, transparency chains: 100 stacked constant layers of
// opacity o over an opaque back plane give the analytic transmittance (1 - o)^100.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

// `layers` red constant squares of opacity o (z = 5 .. 5.99), then a blue opaque square at
// z = 10. Red = 1 - (1 - o)^layers, blue = (1 - o)^layers, alpha = 1.
std::string stack(double o, int layers, const std::string& options = "") {
    std::string rib = options + camera(8, 20, 1) + "WorldBegin\nSurface \"constant\"\n";
    char buf[96];
    std::snprintf(buf, sizeof buf, "AttributeBegin\nColor [1 0 0]\nOpacity [%.9g %.9g %.9g]\n",
                  o, o, o);
    rib += buf;
    for (int i = 0; i < layers; ++i) rib += squareAtZ(5.0 + 0.01 * i);
    rib += "AttributeEnd\nColor [0 0 1]\n" + squareAtZ(10.0) + "WorldEnd\n";
    return rib;
}

// Largest error of red, blue and alpha against the analytic values over the image.
double stackError(const rd::test::Rendered& img, double red, double blue) {
    double err = 0;
    for (const rd::Rgba& p : img.pixels)
        err = std::fmax(err, std::fmax(std::fabs(p.r - red),
                                       std::fmax(std::fabs(p.b - blue), std::fabs(p.a - 1.0))));
    return err;
}

}  // namespace

// Tolerance 1e-5 absolute: 100 float additions into the sample (about 1e-7 each) and the
// 1e-6 weight below which a continuation is not traced further.
TEST(Numerics, TransparencyChainOf100Layers) {
    for (double o : {0.01, 0.1, 0.5, 0.9, 0.99}) {
        Diagnosed d = renderWithDiagnostics(stack(o, 100));
        const double t = std::pow(1.0 - o, 100.0);
        const double err = stackError(d.image, 1.0 - t, t);
        char name[64];
        std::snprintf(name, sizeof name, "transparency_chain_100_o%g", o);
        EXPECT_TRUE(report(name, 1e-5, err)) << "opacity " << o << " transmittance " << t;
        EXPECT_EQ(d.image.stats.transparentDepthCut, 0u);
        EXPECT_EQ(countOf(d.messages, "maxtransparentdepth"), 0) << d.messages;
    }
}

// A scene that asks for fewer layers than it has is cut there, exactly (11 of the layers:
// the eye hit and 10 continuations), and the cut is counted and reported once, not
// silent; the work is bounded (10 continuation rays per eye ray).
TEST(Numerics, TransparentDepthComesFromTheScene) {
    Diagnosed d = renderWithDiagnostics(
        stack(0.01, 100, "Option \"trace\" \"int maxtransparentdepth\" [10]\n"));
    // red and alpha 1 - 0.99^11, blue 0: the rest of the stack is never reached
    const double red = 1.0 - std::pow(0.99, 11.0);
    double err = 0;
    for (const rd::Rgba& p : d.image.pixels)
        err = std::fmax(err, std::fmax(std::fabs(p.r - red),
                                       std::fmax(std::fabs(p.b), std::fabs(p.a - red))));
    EXPECT_TRUE(report("transparency_depth_cut_at_10", 1e-5, err));
    EXPECT_EQ(d.image.stats.features.maxTransparentDepth, 10);
    EXPECT_EQ(d.image.stats.transparentDepthCut, d.image.stats.eyeRays);
    EXPECT_EQ(d.image.stats.continuationRays, 10 * d.image.stats.eyeRays);
    EXPECT_EQ(countOf(d.messages, "maxtransparentdepth"), 1) << d.messages;
}
