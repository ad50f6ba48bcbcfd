// instance_test.cpp: ObjectBegin/ObjectInstance without copies. An object's meshes are
// stored once (a prototype in object space under its own BVH) and each instance is one
// record placing it: the scene holds the prototype's triangles once however many
// instances there are, each instance keeps its own transform, colour and shader, and
// the image equals the same geometry written out explicitly.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const char* kCamera =
    "Format 96 96 1\nPixelSamples 3 3\nProjection \"orthographic\"\nScreenWindow -3 3 -3 3\n"
    "Translate 0 0 5\n";
const char* kSquare = "Polygon \"P\" [-0.5 -0.5 0  0.5 -0.5 0  0.5 0.5 0  -0.5 0.5 0]\n";

rd::Scene build(const std::string& rib) {
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    rd::RibBuilder b(diag, "inst.rib");
    rib::readString(rib, "inst.rib", b, diag);
    EXPECT_EQ(diag.errorCount(), 0) << err.str();
    return b.scenes().empty() ? rd::Scene() : b.scenes().back();
}

}  // namespace

// Three instances of a unit square, moved, scaled and coloured apart: the projected
// area is 1 + 2.25 + 0.25, the colours are their own, and the scene has two triangles.
TEST(Instances, EachInstanceHasItsOwnPlaceAndColour) {
    std::string world = std::string("WorldBegin\nSurface \"constant\"\nObjectBegin \"sq\"\n") +
                        kSquare + "ObjectEnd\n"
                        "AttributeBegin Translate -1.5 1.5 0 Color [1 0 0] ObjectInstance \"sq\" AttributeEnd\n"
                        "AttributeBegin Translate 1 1 0 Scale 1.5 1.5 1 Color [0 1 0] ObjectInstance \"sq\" AttributeEnd\n"
                        "AttributeBegin Translate 0 -1.5 0 Rotate 45 0 0 1 Scale 0.5 0.5 1 Color [0 0 1] "
                        "ObjectInstance \"sq\" AttributeEnd\nWorldEnd\n";
    rd::Scene s = build(kCamera + world);
    EXPECT_EQ(s.triangles.size(), 2u) << "the prototype is stored once";
    Rendered img = renderRib(kCamera + world);
    EXPECT_EQ(img.stats.instances, 3u);
    double area = img.mean(3, 0, 0, 96, 96) * 36.0;
    std::printf("NUMERICS case=instances_area tolerance=0.01 measured=%g\n",
                std::fabs(area / 3.5 - 1));
    EXPECT_NEAR(area / 3.5, 1.0, 0.01);
    auto at = [&](double x, double y) { return img.at(int((x + 3) * 16), int((3 - y) * 16)); };
    EXPECT_FLOAT_EQ(at(-1.5, 1.5).r, 1.0f);
    EXPECT_FLOAT_EQ(at(1.0, 1.0).g, 1.0f);
    EXPECT_FLOAT_EQ(at(0.0, -1.5).b, 1.0f);
    EXPECT_FLOAT_EQ(at(0.0, 0.2).a, 0.0f);
}

// Instances shade like the same geometry written out: a lit box of polygons and a sphere
// in an object, instanced twice under different transforms and shaders, against the
// same polygons given in place (sphere too); the images agree to rounding.
TEST(Instances, ImageEqualsTheGeometryWrittenOut) {
    const std::string box =
        "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 7 3] "
        "\"P\" [-0.5 -0.5 -0.5 0.5 -0.5 -0.5 -0.5 0.5 -0.5 0.5 0.5 -0.5 -0.5 -0.5 0.5 0.5 -0.5 "
        "0.5 -0.5 0.5 0.5 0.5 0.5 0.5]\n";
    const std::string light =
        "LightSource \"distantlight\" 1 \"from\" [1 2 -1] \"to\" [0 0 0]\n";
    const std::string place1 = "Translate -1.2 0.3 0 Rotate 30 1 1 0 Color [1 0.5 0.2]\n";
    const std::string place2 = "Translate 1.2 -0.4 0 Rotate 70 0 1 1 Scale 1.5 1 1 Surface \"plastic\"\n";
    std::string instanced = kCamera + ("WorldBegin\n" + light + "Surface \"matte\"\nObjectBegin \"b\"\n" +
                                       box + "ObjectEnd\nAttributeBegin\n" + place1 +
                                       "ObjectInstance \"b\"\nAttributeEnd\nAttributeBegin\n" + place2 +
                                       "ObjectInstance \"b\"\nAttributeEnd\nWorldEnd\n");
    std::string explicitly = kCamera + ("WorldBegin\n" + light + "Surface \"matte\"\nAttributeBegin\n" +
                                        place1 + box + "AttributeEnd\nAttributeBegin\n" + place2 + box +
                                        "AttributeEnd\nWorldEnd\n");
    Rendered a = renderRib(instanced), b = renderRib(explicitly);
    EXPECT_EQ(a.stats.instances, 2u);
    EXPECT_EQ(b.stats.instances, 0u);
    double diff = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        diff += std::fabs(a.pixels[i].r - b.pixels[i].r) + std::fabs(a.pixels[i].a - b.pixels[i].a);
    diff /= double(a.pixels.size());
    std::printf("NUMERICS case=instances_vs_explicit_mean_abs tolerance=0.002 measured=%g\n", diff);
    EXPECT_LT(diff, 0.002);
    EXPECT_GT(a.mean(0, 0, 0, 96, 96), 0.01);
}

// A thousand instances of a 2048-triangle object: the scene stores 2048 triangles, the
// render sees all thousand.
TEST(Instances, AThousandInstancesStoreTheObjectOnce) {
    std::ostringstream rib;
    rib << kCamera << "WorldBegin\nSurface \"constant\"\nObjectBegin \"grid\"\n";
    // a 32 x 32 grid of quads over [-0.05, 0.05]^2: 2048 triangles
    rib << "PointsPolygons [";
    for (int i = 0; i < 1024; ++i) rib << "4 ";
    rib << "] [";
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i) {
            int a = j * 33 + i;
            rib << a << " " << a + 1 << " " << a + 34 << " " << a + 33 << " ";
        }
    rib << "] \"P\" [";
    for (int j = 0; j <= 32; ++j)
        for (int i = 0; i <= 32; ++i) rib << (i / 320.0 - 0.05) << " " << (j / 320.0 - 0.05) << " 0 ";
    rib << "]\nObjectEnd\n";
    for (int j = 0; j < 25; ++j)
        for (int i = 0; i < 40; ++i)
            rib << "AttributeBegin Translate " << (-2.9 + 0.145 * i) << " " << (-2.9 + 0.2 * j)
                << " 0 ObjectInstance \"grid\" AttributeEnd\n";
    rib << "WorldEnd\n";
    rd::Scene s = build(rib.str());
    EXPECT_EQ(s.triangles.size(), 2048u);
    EXPECT_EQ(s.prototypes.size(), 1u);
    Rendered img = renderRib(rib.str());
    EXPECT_EQ(img.stats.instances, 1000u);
    double area = img.mean(3, 0, 0, 96, 96) * 36.0;  // 1000 squares of 0.01
    EXPECT_NEAR(area / 10.0, 1.0, 0.03);
}

// ObjectBegin and SolidBegin blocks save and restore the attributes (RI 3.2: every
// begin-end pair but TransformBegin and MotionBegin): a Translate inside an object
// places the object's sphere for its instances, and one inside a solid its sphere, but
// neither moves the square given after the block. Before, both leaked: the square sat
// at (1.5, 1.5) and the origin was empty.
TEST(Instances, ObjectAndSolidBlocksKeepTheirTransformToThemselves) {
    const std::string world =
        std::string("WorldBegin\nSurface \"constant\"\nObjectBegin \"o\"\nTranslate 1.5 0 0\n"
                    "Sphere 0.5 -0.5 0.5 360\nObjectEnd\nObjectInstance \"o\"\n"
                    "SolidBegin \"primitive\"\nTranslate 0 1.5 0\nSphere 0.5 -0.5 0.5 360\n"
                    "SolidEnd\n") +
        kSquare + "WorldEnd\n";
    Rendered img = renderRib(kCamera + world);
    auto alpha = [&](double x, double y) {
        return img.at(int((x + 3) * 16), int((3 - y) * 16)).a;
    };
    EXPECT_FLOAT_EQ(alpha(0, 0), 1.0f) << "the square, at the origin";
    EXPECT_FLOAT_EQ(alpha(1.5, 0), 1.0f) << "the object's sphere";
    EXPECT_FLOAT_EQ(alpha(0, 1.5), 1.0f) << "the solid's sphere";
    EXPECT_FLOAT_EQ(alpha(-1.5, 0), 0.0f);
    EXPECT_FLOAT_EQ(alpha(2.5, 0), 0.0f);
}
