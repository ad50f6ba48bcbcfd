// energy_test.cpp: case 7, energy: under uniform white light (many distant lights spread
// evenly over the sphere of directions, scaled so a white Lambertian surface reflects
// exactly 1), no standard surface shader reflects more than it receives: Ci <= 1 at every
// point of a white sphere, every view angle, within the light set's discretisation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <array>
#include <vector>

#include "numerics_util.h"

using namespace rd::numerics;

namespace {

constexpr int kLights = 64;

// Fibonacci-sphere directions, evenly spread.
std::vector<std::array<double, 3>> directions() {
    std::vector<std::array<double, 3>> d;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kLights; ++i) {
        double z = 1.0 - (i + 0.5) * 2.0 / kLights, r = std::sqrt(1.0 - z * z);
        d.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    return d;
}

// Largest discrete irradiance sum_l (4 / n) max(0, N.L) over many normals: what a white
// matte surface shows at most (1 in the limit of infinitely many lights).
double lambertBound() {
    auto dirs = directions();
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        double z = 1.0 - (i + 0.5) * 2.0 / 20000, r = std::sqrt(1.0 - z * z);
        double a = M_PI * (3.0 - std::sqrt(5.0)) * i, n[3] = {r * std::cos(a), r * std::sin(a), z};
        double s = 0;
        for (auto& l : dirs) s += 4.0 / kLights * std::fmax(0.0, n[0] * l[0] + n[1] * l[1] + n[2] * l[2]);
        worst = std::fmax(worst, s);
    }
    return worst;
}

const char* kShaders[] = {"matte", "plastic", "paintedplastic", "metal",
                          "shinymetal", "mirror", "glass"};
constexpr int kShaderCount = 7;

// Sphere k (radius 0.6) at column k % 4, row k / 4 of a grid in front of the eye.
void centre(int k, double& x, double& y) {
    x = -2.1 + 1.4 * (k % 4);
    y = k < 4 ? 0.8 : -0.8;
}

}  // namespace

// Tolerance: 1 + the discretisation of the light set (its largest Lambert sum, about
// 1.01 for 64 lights) + 1e-4. Pixels fully on a sphere are checked (all view angles
// from head-on to grazing at the silhouette).
TEST(Numerics, StandardShadersReflectNoMoreThanTheyReceive) {
    std::string rib = camera(40, 60, 1) + "WorldBegin\n";
    char buf[160];
    for (auto& d : directions()) {
        std::snprintf(buf, sizeof buf,
                      "LightSource \"distantlight\" 1 \"intensity\" %.9g \"from\" [%.9g %.9g %.9g] "
                      "\"to\" [0 0 0]\n", 4.0 / kLights, d[0], d[1], d[2]);
        rib += buf;
    }
    rib += "Color [1 1 1]\n";
    for (int k = 0; k < kShaderCount; ++k) {
        double x, y;
        centre(k, x, y);
        std::snprintf(buf, sizeof buf,
                      "AttributeBegin\nSurface \"%s\"\nTranslate %g %g 5\nSphere 0.6 -0.6 0.6 360\n"
                      "AttributeEnd\n", kShaders[k], x, y);
        rib += buf;
    }
    rib += "WorldEnd\n";
    Diagnosed d = renderWithDiagnostics(rib);
    ASSERT_EQ(countOf(d.messages, "error"), 0) << d.messages;
    const rd::test::Rendered& img = d.image;
    const double bound = lambertBound();
    std::printf("largest discrete Lambert sum of %d lights: %.5f\n", kLights, bound);
    std::vector<double> most(kShaderCount, 0.0);
    std::vector<int> pixels(kShaderCount, 0);
    const double t = std::tan(30.0 * M_PI / 180.0);
    for (int py = 0; py < img.height; ++py)
        for (int px = 0; px < img.width; ++px) {
            const rd::Rgba& p = img.at(px, py);
            if (p.a < 1.0f) continue;
            // which sphere: the nearest projected centre
            double sx = ((px + 0.5) / img.width * 2 - 1) * t * 5, sy = (1 - (py + 0.5) / img.height * 2) * t * 5;
            int best = 0;
            double bestD = 1e9;
            for (int k = 0; k < kShaderCount; ++k) {
                double x, y;
                centre(k, x, y);
                double dd = (sx - x) * (sx - x) + (sy - y) * (sy - y);
                if (dd < bestD) bestD = dd, best = k;
            }
            most[best] = std::fmax(most[best], std::fmax(p.r, std::fmax(p.g, p.b)));
            ++pixels[best];
        }
    for (int k = 0; k < kShaderCount; ++k) {
        EXPECT_GT(pixels[k], 20) << kShaders[k];
        EXPECT_TRUE(report(std::string("energy_") + kShaders[k] + "_max_Ci_minus_1",
                           bound - 1.0 + 1e-4, most[k] - 1.0))
            << kShaders[k] << " reflects " << most[k];
    }
    // matte reaches the Lambert bound's neighbourhood: the lights do light the spheres
    EXPECT_GT(most[0], 0.95);
}
