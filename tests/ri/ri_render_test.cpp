// ri_render_test.cpp: renders through RiBegin(RI_NULL): the image of a scene given by Ri
// calls is the image of the same scene read from RIB, and each world block is a frame
// written where its Display says (without one, ri.exr then ri.2.exr, ...).
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../scratch_folder.h"
#include "film/exr_output.h"
#include "ocl/device.h"
#include "render/frame_output.h"
#include "render/renderer.h"
#include "ri.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

namespace {

std::string scratchDir() {
    return rd::test::scratchFolder("ri_render");
}

// A lit plastic sphere and a constant square behind it, 48x32.
void world() {
    RiWorldBegin();
    RtPoint from = {2, 3, -4};
    RtFloat intensity = 20;
    RiLightSource(RI_POINTLIGHT, RI_FROM, from, RI_INTENSITY, &intensity, RI_NULL);
    RiAttributeBegin();
    RiTranslate(0, 0, 4);
    RtFloat kd = 0.8f;
    RiSurface(RI_PLASTIC, RI_KD, &kd, RI_NULL);
    RiSphere(1, -1, 1, 360, RI_NULL);
    RiAttributeEnd();
    RiAttributeBegin();
    RiSurface(RI_CONSTANT, RI_NULL);
    RtColor green = {0.2f, 0.9f, 0.3f};
    RiColor(green);
    RtPoint square[4] = {{-10, -10, 8}, {10, -10, 8}, {10, 10, 8}, {-10, 10, 8}};
    RiPolygon(4, RI_P, square, RI_NULL);
    RiAttributeEnd();
    RiWorldEnd();
}

const char* kWorldRib = R"(WorldBegin
LightSource "pointlight" 1 "from" [2 3 -4] "intensity" [20]
AttributeBegin
Translate 0 0 4
Surface "plastic" "Kd" [0.8]
Sphere 1 -1 1 360
AttributeEnd
AttributeBegin
Surface "constant"
Color [0.2 0.9 0.3]
Polygon "P" [-10 -10 8 10 -10 8 10 10 8 -10 10 8]
AttributeEnd
WorldEnd
)";

std::vector<rd::Rgba> readImage(const std::string& path, int& w, int& h) {
    return rd::readExr(path, w, h);
}

}  // namespace

TEST(RiRender, ImageOfTheCallsIsTheImageOfTheirRib) {
    const std::string dir = scratchDir();
    const std::string viaApi = dir + "/api.exr";
    RiBegin(RI_NULL);
    RiDisplay(viaApi.c_str(), RI_FILE, RI_RGBA, RI_NULL);
    RiFormat(48, 32, 1);
    RiPixelSamples(2, 2);
    RtFloat fov = 50;
    RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
    world();
    RiEnd();
    EXPECT_EQ(RiLastError, RIE_NOERROR);
    ASSERT_TRUE(std::filesystem::exists(viaApi));

    // The same scene from RIB, rendered as the raydrive command renders it.
    const std::string viaRib = dir + "/rib.exr";
    rib::Diagnostics diag(&std::cerr);
    rd::RibBuilder builder(diag, "scene.rib");
    ASSERT_TRUE(
        rib::readString("Display \"" + viaRib +
                            "\" \"file\" \"rgba\"\nFormat 48 32 1\nPixelSamples 2 2\n"
                            "Projection \"perspective\" \"fov\" [50]\n" +
                            kWorldRib,
                        "scene.rib", builder, diag));
    ASSERT_EQ(builder.scenes().size(), 1u);
    rd::ClContext ctx(rd::selectDevice(""));
    rd::RenderSettings settings;
    settings.progress = false;
    rd::Renderer renderer(ctx, settings);
    rd::Film film;
    const rd::RenderStats st = renderer.render(builder.scenes()[0], film, diag);
    rd::writeFrameImage(viaRib, builder.scenes()[0], film, st, {}, false, "scene.rib");

    int w = 0, h = 0, w2 = 0, h2 = 0;
    const std::vector<rd::Rgba> a = readImage(viaApi, w, h),
                                b = readImage(viaRib, w2, h2);
    ASSERT_EQ(w, 48);
    ASSERT_EQ(h, 32);
    ASSERT_EQ(w2, w);
    ASSERT_EQ(h2, h);
    double differ = 0;
    for (size_t i = 0; i < a.size(); ++i)
        differ = std::max({differ, double(std::fabs(a[i].r - b[i].r)),
                           double(std::fabs(a[i].g - b[i].g)),
                           double(std::fabs(a[i].b - b[i].b)),
                           double(std::fabs(a[i].a - b[i].a))});
    EXPECT_EQ(differ, 0.0);  // the same scene, the same random numbers
    // And it is the scene: the square's constant green at a corner, the sphere lit.
    const rd::Rgba& corner = a[1 * 48 + 1];
    EXPECT_NEAR(corner.g, 0.9f, 1e-5);
    EXPECT_NEAR(corner.r, 0.2f, 1e-5);
    const rd::Rgba& centre = a[16 * 48 + 24];
    EXPECT_GT(centre.r, 0.05f);
    EXPECT_LT(std::fabs(centre.r - centre.b), 1e-4);  // white plastic, white light
}

TEST(RiRender, EachWorldBlockIsAFrame) {
    const std::string dir = scratchDir() + "/frames";
    std::filesystem::create_directories(dir);
    const auto cwd = std::filesystem::current_path();
    std::filesystem::current_path(dir);
    RiBegin(RI_NULL);
    RiFormat(16, 16, 1);
    RiFrameBegin(1);
    world();
    RiFrameEnd();
    RiFrameBegin(2);
    world();
    RiFrameEnd();
    RiEnd();
    std::filesystem::current_path(cwd);
    EXPECT_TRUE(std::filesystem::exists(dir + "/ri.exr"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/ri.2.exr"));
    EXPECT_EQ(RiLastError, RIE_NOERROR);
}

// RiProcedural with RiProcDynamicLoad (session 33; it was a warning, skipped): the test
// object (tests/cli/dynamic_spheres.cpp) makes a sphere and, two levels down, two more
// one unit apart along x through its own DynamicLoad procedurals; the image shows three
// spheres where they are and nothing between.
TEST(RiRender, DynamicLoadProceduralsRenderTheirCalls) {
    const std::string dir = scratchDir() + "/dynamic_load";
    std::filesystem::create_directories(dir);
    const std::string out = dir + "/dl.exr";
    RiBegin(RI_NULL);
    RiDisplay(out.c_str(), RI_FILE, RI_RGBA, RI_NULL);
    RiFormat(48, 16, 1);
    RiProjection(RI_ORTHOGRAPHIC, RI_NULL);
    RiScreenWindow(-1, 5, -1, 1);
    RiTranslate(0, 0, 5);
    RiWorldBegin();
    RiSurface("constant", RI_NULL);
    const std::string data = std::string(RD_DYNAMIC_SPHERES) + " 2";
    RtString* args = static_cast<RtString*>(std::malloc(2 * sizeof(RtString)));
    args[0] = const_cast<char*>(RD_DYNAMIC_SPHERES);
    args[1] = const_cast<char*>(data.c_str());
    RtBound bound = {-1, 10, -1, 1, -1, 1};
    RiProcedural(args, bound, RiProcDynamicLoad, RiProcFree);
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(RiLastError, RIE_NOERROR);
    int w = 0, h = 0;
    const std::vector<rd::Rgba> img = readImage(out, w, h);
    ASSERT_EQ(w, 48);
    // sphere centres at x = 0, 1, 2 (pixels 8, 16, 24 of 8 a unit); between them (0.2
    // units of gap, blurred by the 2 x 2 gaussian) partly covered; beyond, nothing
    for (int x : {8, 16, 24}) EXPECT_GT(img[size_t(8 * w + x)].a, 0.99f) << x;
    for (int x : {12, 20}) EXPECT_LT(img[size_t(8 * w + x)].a, 0.6f) << x;
    for (int x : {32, 40}) EXPECT_LT(img[size_t(8 * w + x)].a, 0.01f) << x;
}

// RiTransformPoints (session 32; it did not exist): points between the current transform,
// world, camera, a named system, screen, NDC and raster. The camera 5 units back, 90
// degrees, a 200 x 100 frame (screen window -2..2 x -1..1): the object origin translated
// to (1, 2, 3) is (1, 2, 8) in camera space, (1/8, 2/8) on the screen, NDC ((2 + 1/8) /
// 4, (1 - 2/8) / 2), raster 200 and 100 times those; back from raster it is the origin
// again. An unknown space, or a call outside a world, gives RI_NULL; a RIB file target
// too.
TEST(RiRender, TransformPointsBetweenSpaces) {
    const std::string dir = scratchDir() + "/transform_points";
    std::filesystem::create_directories(dir);
    RiBegin(RI_NULL);
    RiFormat(200, 100, 1);
    RtFloat fov = 90;
    RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
    const std::string out = dir + "/empty.exr";
    RiDisplay(out.c_str(), RI_FILE, RI_RGBA, RI_NULL);
    RtPoint p[1] = {{0, 0, 0}};
    EXPECT_EQ(RiTransformPoints("world", "camera", 1, p), nullptr);  // (no world yet)
    RiTranslate(0, 0, 5);
    RiWorldBegin();
    RiTranslate(1, 2, 3);
    RiCoordinateSystem("mine");
    auto moved = [&](const char* from, const char* to, RtPoint q) {
        RtPoint pts[1] = {{q[0], q[1], q[2]}};
        RtPoint* r = RiTransformPoints(from, to, 1, pts);
        EXPECT_EQ(r, r ? pts : nullptr);
        return r ? std::array<float, 3>{pts[0][0], pts[0][1], pts[0][2]}
                 : std::array<float, 3>{NAN, NAN, NAN};
    };
    RtPoint origin = {0, 0, 0};
    auto expectNear = [](std::array<float, 3> a, std::array<float, 3> b,
                         const char* what) {
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-5f) << what << " " << k;
    };
    expectNear(moved("current", "world", origin), {1, 2, 3}, "current");
    expectNear(moved("current", "camera", origin), {1, 2, 8}, "camera");
    expectNear(moved("current", "screen", origin), {0.125f, 0.25f, 8}, "screen");
    expectNear(moved("current", "NDC", origin), {2.125f / 4, 0.75f / 2, 8}, "NDC");
    expectNear(moved("current", "raster", origin), {200 * 2.125f / 4, 100 * 0.75f / 2, 8},
               "raster");
    RtPoint raster = {200 * 2.125f / 4, 100 * 0.75f / 2, 8};
    expectNear(moved("raster", "mine", raster), {0, 0, 0}, "raster to mine");
    RiTranslate(1, 0, 0);
    expectNear(moved("mine", "object", origin), {-1, 0, 0}, "mine to object");
    EXPECT_EQ(RiTransformPoints("world", "nosuch", 1, p), nullptr);
    RiWorldEnd();
    RiEnd();
    EXPECT_EQ(RiLastError, RIE_NOERROR);

    RiBegin((dir + "/calls.rib").c_str());  // (a RIB file keeps no state)
    RiWorldBegin();
    EXPECT_EQ(RiTransformPoints("current", "world", 1, p), nullptr);
    RiWorldEnd();
    RiEnd();
}
