// quadric_render_test.cpp: exact quadrics and CSG through the whole pipeline. Orthographic
// views of constant surfaces, whose mean alpha is the projected area: each kind against
// its closed form, CSG booleans against the closed-form areas of discs, the silhouette
// of an exact sphere against the analytic disc pixel by pixel, instances, exact against
// tessellated shading, and the errors a malformed solid gets.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

constexpr int kRes = 128;
constexpr double kHalf = 2.0;  // screen window [-2, 2]^2

// An orthographic view down +z of `world` (placed at z = 5) with a constant white surface.
Rendered orthoRender(const std::string& world, int spp = 4, const std::string& options = "") {
    std::ostringstream rib;
    rib << "Format " << kRes << " " << kRes << " 1\nPixelSamples " << spp << " " << spp
        << "\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n" << options
        << "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n" << world << "\nWorldEnd\n";
    return renderRib(rib.str());
}

double projectedArea(const Rendered& img) {
    return img.mean(3, 0, 0, img.width, img.height) * (2 * kHalf) * (2 * kHalf);
}

void expectArea(const char* name, const std::string& world, double expected, double tol) {
    Rendered img = orthoRender(world);
    double area = projectedArea(img);
    double err = std::fabs(area / expected - 1);
    std::printf("NUMERICS case=area_%s tolerance=%g measured=%g (area %.5f, expected %.5f)\n",
                name, tol, err, area, expected);
    EXPECT_LE(err, tol) << name;
}

// Turns a quadric's z axis to the screen's y axis (seen from the side).
const char* kSideways = "Rotate -90 1 0 0\n";

}  // namespace

TEST(QuadricRender, EveryKindHasItsClosedFormProjectedArea) {
    const double pi = M_PI;
    expectArea("sphere", "Sphere 1 -1 1 360", pi, 0.005);
    expectArea("half_sphere_sweep", "Sphere 1 -1 1 180", pi / 2, 0.005);
    // a band of the sphere seen from the side: 2 * int sqrt(1 - z^2) dz over [-0.5, 0.5]
    double band = 2 * (0.5 * std::sqrt(0.75) + std::asin(0.5));
    expectArea("sphere_band", std::string(kSideways) + "Sphere 1 -0.5 0.5 360", band, 0.005);
    expectArea("cylinder", std::string(kSideways) + "Cylinder 0.5 -1 1 360", 2.0, 0.005);
    expectArea("cone", std::string(kSideways) + "Translate 0 0 -0.75 Cone 1.5 0.8 360", 1.2, 0.005);
    expectArea("disk", "Disk 0 0.9 360", pi * 0.81, 0.005);
    expectArea("paraboloid", std::string(kSideways) + "Translate 0 0 -0.75 Paraboloid 0.8 0 1.5 360",
               1.6, 0.005);
    expectArea("torus", "Torus 1 0.3 0 360 360", pi * (1.69 - 0.49), 0.005);
    // hyperboloid from (0.5, 0, -1) to (0, 0.5, 1): width 2 rho(z), rho^2 = 0.25((1-v)^2 + v^2)
    double hyp = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        double v = (i + 0.5) / n;
        hyp += 2 * std::sqrt(2 * v * v - 2 * v + 1) / n;
    }
    expectArea("hyperboloid", std::string(kSideways) + "Hyperboloid 0.5 0 -1 0 0.5 1 360", hyp,
               0.005);
}

// The silhouette of an exact sphere is the analytic disc to within a pixel: every pixel
// whose centre lies more than 0.75 pixel inside is fully covered, every one more than
// 0.75 pixel outside is empty.
TEST(QuadricRender, SphereSilhouetteIsTheAnalyticDisc) {
    Rendered img = orthoRender("Sphere 1.3 -1.3 1.3 360", 4);
    const double px = 2 * kHalf / kRes;
    int wrong = 0;
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x) {
            double cx = -kHalf + (x + 0.5) * px, cy = kHalf - (y + 0.5) * px;
            double d = (std::sqrt(cx * cx + cy * cy) - 1.3) / px;  // signed, in pixels
            float a = img.at(x, y).a;
            if (d < -0.75 && a != 1.0f) ++wrong;
            if (d > 0.75 && a != 0.0f) ++wrong;
        }
    EXPECT_EQ(wrong, 0);
}

TEST(QuadricRender, CsgBooleansHaveTheClosedFormAreas) {
    // two unit discs whose centres are 1 apart overlap in a lens of 2 acos(1/2) - sqrt(3)/2
    const double lens = 2 * std::acos(0.5) - std::sqrt(3.0) / 2;
    const char* a = "SolidBegin \"primitive\" AttributeBegin Translate -0.5 0 0 "
                    "Sphere 1 -1 1 360 AttributeEnd SolidEnd\n";
    const char* b = "SolidBegin \"primitive\" AttributeBegin Translate 0.5 0 0 "
                    "Sphere 1 -1 1 360 AttributeEnd SolidEnd\n";
    expectArea("csg_intersection",
               std::string("SolidBegin \"intersection\"\n") + a + b + "SolidEnd", lens, 0.01);
    expectArea("csg_union", std::string("SolidBegin \"union\"\n") + a + b + "SolidEnd",
               2 * M_PI - lens, 0.005);
    // A - B seen across the line of centres: where the view ray's chord through A is
    // longer than its chord through B, the half of the lens nearer A's centre survives
    expectArea("csg_difference", std::string("SolidBegin \"difference\"\n") + a + b + "SolidEnd",
               M_PI - lens / 2, 0.01);
    // a sphere drilled through along the view axis by a capped cylinder: an annulus
    // a polygon cube minus a sphere of radius 1.2: where x^2 + y^2 < 0.44 the sphere
    // holds the cube's whole chord, so the view is the square less a disc
    expectArea("csg_mesh_minus_sphere",
               "SolidBegin \"difference\"\nSolidBegin \"primitive\"\n"
               "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] "
               "\"P\" [-1 -1 -1 1 -1 -1 -1 1 -1 1 1 -1 -1 -1 1 1 -1 1 -1 1 1 1 1 1]\nSolidEnd\n"
               "SolidBegin \"primitive\" Sphere 1.2 -1.2 1.2 360 SolidEnd\nSolidEnd",
               4.0 - M_PI * 0.44, 0.01);
    // quadrics in solids stay exact when the others are diced
    Rendered diced = orthoRender(std::string("SolidBegin \"intersection\"\n") + a + b + "SolidEnd",
                                 4, "Option \"render\" \"int exactquadrics\" [0]\n");
    EXPECT_NEAR(projectedArea(diced) / lens, 1.0, 0.01);
    expectArea("csg_drilled",
               "SolidBegin \"difference\"\n"
               "SolidBegin \"primitive\" Sphere 1 -1 1 360 SolidEnd\n"
               "SolidBegin \"primitive\" Cylinder 0.4 -2 2 360 Disk -2 0.4 360 Disk 2 0.4 360 "
               "SolidEnd\nSolidEnd",
               M_PI * (1 - 0.16), 0.005);
}

// Instances of an object with a quadric: each placed by its own transform.
TEST(QuadricRender, ObjectInstancesOfQuadrics) {
    expectArea("instances",
               "ObjectBegin \"ball\" Sphere 0.5 -0.5 0.5 360 ObjectEnd\n"
               "AttributeBegin Translate -1 0 0 ObjectInstance \"ball\" AttributeEnd\n"
               "AttributeBegin Translate 1 0 0 Scale 2 2 2 ObjectInstance \"ball\" AttributeEnd\n",
               M_PI * (0.25 + 1.0), 0.005);
}

// Matte shading of an exact sphere against the closed form (orthographic view, distant
// light of intensity 1 along L: the mean of Kd Cs max(0, N.L) over the image), and the
// tessellated quadrics against the exact ones.
TEST(QuadricRender, ExactShadingMatchesTheClosedForm) {
    const std::string light =
        "LightSource \"distantlight\" 1 \"from\" [1 1 -1] \"to\" [0 0 0]\nSurface \"matte\"\n";
    Rendered sphere = orthoRender(light + "Sphere 0.7 -0.7 0.7 360", 4);
    const double r = 0.7, l = 1 / std::sqrt(3.0);
    double integral = 0;
    const int n = 1000;
    const double h = 2 * r / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double x = -r + (i + 0.5) * h, y = -r + (j + 0.5) * h, q = r * r - x * x - y * y;
            if (q <= 0) continue;
            double d = (x * l + y * l + std::sqrt(q) * l) / r;  // N = (x, y, -z)/r, L = (1,1,-1)/sqrt3
            if (d > 0) integral += d * h * h;
        }
    double expected = integral / ((2 * kHalf) * (2 * kHalf));
    double got = sphere.mean(0, 0, 0, kRes, kRes);
    std::printf("NUMERICS case=matte_sphere_mean tolerance=0.005 measured=%g\n",
                std::fabs(got / expected - 1));
    EXPECT_NEAR(got / expected, 1.0, 0.005);

    const std::string world = light +
        "Translate -0.9 0.6 0 Sphere 0.7 -0.7 0.7 360\n"
        "Translate 1.8 0 0 Rotate 50 1 0 0 Torus 0.6 0.2 0 360 360\n"
        "Translate -0.9 -1.4 0 Rotate -60 1 0 0 Cylinder 0.4 -0.5 0.5 360\n";
    Rendered exact = orthoRender(world, 2);
    Rendered tess = orthoRender(world, 2, "Option \"render\" \"int exactquadrics\" [0]\n");
    EXPECT_GT(exact.stats.quadrics, 0u);
    EXPECT_EQ(tess.stats.quadrics, 0u);
    // facets self-shadow near the terminator, so the tessellated image is a little darker
    double me = exact.mean(0, 0, 0, kRes, kRes), mt = tess.mean(0, 0, 0, kRes, kRes);
    std::printf("exact %.5f tessellated %.5f\n", me, mt);
    EXPECT_NEAR(mt / me, 1.0, 0.02);
}

// Primitive variables over (u, v): varying Cs at the four corners, bilinear; constant Os.
TEST(QuadricRender, PrimitiveVariablesInterpolateOverUV) {
    // a disk's v runs from the rim (0) to the centre (1): red at the rim, blue at the centre
    Rendered img = orthoRender("Disk 0 1.5 360 \"Cs\" [1 0 0  1 0 0  0 0 1  0 0 1] "
                               "\"st\" [0 0 1 0 0 1 1 1]\n"
                               "Translate 0 0 -1 Disk 0 0.5 360 \"Os\" [0.25 0.25 0.25]\n");
    const double px = 2 * kHalf / kRes;
    auto pixelAt = [&](double x, double y) {
        return img.at(int((x + kHalf) / px), int((kHalf - y) / px));
    };
    rd::Rgba mid = pixelAt(1.05 + px / 2, px / 2);  // radius ~1.05: v = 0.3, behind nothing
    EXPECT_NEAR(mid.r, 0.7f, 0.03f);
    EXPECT_NEAR(mid.b, 0.3f, 0.03f);
    // the small disk in front covers the centre with opacity 0.25 over the blue
    rd::Rgba centre = pixelAt(px / 2, px / 2);
    EXPECT_NEAR(centre.r, 0.25f, 0.02f);
    EXPECT_NEAR(centre.b, 0.25f + 0.75f * 1.0f, 0.02f);
    EXPECT_GT(img.stats.quadrics, 1u);
}

namespace {
std::string buildErrors(const std::string& world) {
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "solid.rib");
    rib::readString("WorldBegin " + world + "\nWorldEnd\n", "solid.rib", b, diag);
    return err.str();
}
}  // namespace

// A primitive solid must be closed; an open one is an error naming the surface and line.
TEST(QuadricRender, OpenPrimitiveSolidsAreErrors) {
    std::string e = buildErrors("SolidBegin \"difference\"\nSolidBegin \"primitive\"\n"
                                "Sphere 1 -1 1 360\nSolidEnd\nSolidBegin \"primitive\"\n"
                                "Cylinder 0.4 -2 2 360\nSolidEnd\nSolidEnd");
    EXPECT_NE(e.find("solid.rib:5"), std::string::npos) << e;  // its SolidBegin
    EXPECT_NE(e.find("not closed"), std::string::npos) << e;
    EXPECT_NE(e.find("Cylinder at solid.rib:6"), std::string::npos) << e;
    e = buildErrors("SolidBegin \"primitive\"\nSphere 1 -1 1 270\nSolidEnd");
    EXPECT_NE(e.find("sweeps less than 360"), std::string::npos) << e;
    // closed: the capped cylinder, and a polygon box
    EXPECT_EQ(buildErrors("SolidBegin \"primitive\"\nCylinder 0.4 -2 2 360\nDisk -2 0.4 360\n"
                          "Disk 2 0.4 360\nSolidEnd"),
              "");
    EXPECT_EQ(buildErrors(
                  "SolidBegin \"primitive\"\nPointsPolygons [4 4 4 4 4 4] "
                  "[0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] "
                  "\"P\" [0 0 0 1 0 0 0 1 0 1 1 0 0 0 1 1 0 1 0 1 1 1 1 1]\nSolidEnd"),
              "");
    e = buildErrors("Sphere 1 0 0 360");
    EXPECT_EQ(e, "") << "a zero-height band is empty but not malformed";
    e = buildErrors("Paraboloid 1 -1 1 360");
    EXPECT_NE(e.find("solid.rib:1"), std::string::npos) << e;
}
