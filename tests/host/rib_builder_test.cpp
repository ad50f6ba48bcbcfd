// rib_builder_test.cpp: the Ri state machine: options that reach the Scene (AOV
// requests, render budgets, camera) and the errors it reports with their locations.
#include "scene/rib_builder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "../scratch_folder.h"
#include "rib/reader.h"

using namespace rd;

namespace {
struct Built {
    std::vector<Scene> scenes;
    std::string messages;
    int errors = 0;
};
Built build(const std::string& rib) {
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    RibBuilder b(diag, "t.rib");
    rib::readString(rib, "t.rib", b, diag);
    return {b.scenes(), out.str(), diag.errorCount()};
}
const char* kWorld = "WorldBegin\nWorldEnd\n";
}  // namespace

TEST(RibBuilder, AovsFromDisplayChannelAndSecondaryDisplays) {
    Built r = build(
        std::string("DisplayChannel \"float z\"\nDisplay \"+n.exr\" \"file\" \"N\"\n"
                    "Display \"+x.exr\" \"file\" \"rgba,varying color diffuse, "
                    "mask\"\nDisplay \"main.exr\" \"file\" \"rgbz\"\n"
                    "Display \"+y.exr\" \"file\" \"bogus mask\"\n"
                    "Display \"+fb\" \"framebuffer\" \"rgb\"\n") +
        kWorld);
    ASSERT_EQ(r.scenes.size(), 1u);
    const rd::Scene& s = r.scenes[0];
    // the image's: DisplayChannel's and its Display's mode (rgbz: the colour and z)
    EXPECT_EQ(s.aovs, (std::vector<std::string>{"z"}));
    EXPECT_EQ(s.display.mode, "rgb");
    ASSERT_EQ(s.aovDisplays.size(), 4u);  // files of their own
    EXPECT_EQ(s.aovDisplays[0].name, "n.exr");
    EXPECT_EQ(s.aovDisplays[0].aovs, (std::vector<std::string>{"N"}));
    EXPECT_EQ(s.aovDisplays[1].colour, "rgba");
    EXPECT_EQ(s.aovDisplays[1].aovs, (std::vector<std::string>{"diffuse", "mask"}));
    EXPECT_EQ(s.aovTypes.at("diffuse"), "color");
    EXPECT_EQ(s.aovTypes.at("z"), "float");
    EXPECT_EQ(s.aovNames(), (std::vector<std::string>{"z", "N", "diffuse", "mask"}));
    EXPECT_NE(r.messages.find("t.rib:5: warning: AOV \"mask\": type \"bogus\""),
              std::string::npos)
        << r.messages;
    // a secondary display with no window to show it in is a file, as the image's is, with
    // the same warning (before, the secondary one was written silently)
    EXPECT_NE(
        r.messages.find("t.rib:6: warning: display type \"framebuffer\" is written as "
                        "a file"),
        std::string::npos)
        << r.messages;
}

// PixelFilter: RI's default gaussian 2 2; a filter and its widths; widths out of (0, 64]
// are an error at the request, an unknown filter a warning (gaussian is used).
TEST(RibBuilder, PixelFilterAndItsErrors) {
    Built plain = build(kWorld);
    ASSERT_EQ(plain.scenes.size(), 1u);
    EXPECT_EQ(plain.scenes[0].camera.pixelFilter, "gaussian");
    EXPECT_EQ(plain.scenes[0].camera.filterWidth[0], 2.0f);
    Built r = build(std::string("PixelFilter \"catmull-rom\" 4 3\n") + kWorld);
    ASSERT_EQ(r.scenes.size(), 1u);
    EXPECT_EQ(r.scenes[0].camera.pixelFilter, "catmull-rom");
    EXPECT_EQ(r.scenes[0].camera.filterWidth[1], 3.0f);
    Built bad =
        build(std::string("PixelFilter \"gaussian\" 0 2\nPixelFilter \"box\" 2 "
                          "1e9\nPixelFilter \"airy\" 2 2\nPixelFilter \"sinc\" 40 "
                          "4\n") +
              kWorld);
    EXPECT_EQ(bad.errors, 2);
    EXPECT_NE(bad.messages.find("t.rib:1: error: PixelFilter widths"), std::string::npos)
        << bad.messages;
    EXPECT_NE(bad.messages.find("t.rib:3: warning: PixelFilter \"airy\" is not known"),
              std::string::npos)
        << bad.messages;
    EXPECT_NE(bad.messages.find("t.rib:4: warning: PixelFilter \"sinc\" changes sign"),
              std::string::npos)
        << bad.messages;
}

// A frame's options are its own (RI: FrameBegin saves them, FrameEnd restores them): its
// secondary displays and Format do not reach the next frame.
TEST(RibBuilder, FramesKeepTheirOwnOptions) {
    Built r = build(
        "Format 8 8 1\nFrameBegin 1\nFormat 16 16 1\n"
        "Display \"+a.1.exr\" \"file\" \"albedo\"\n" +
        std::string(kWorld) +
        "FrameEnd\nFrameBegin 2\nDisplay \"+a.2.exr\" \"file\" \"albedo\"\n" + kWorld +
        "FrameEnd\n");
    ASSERT_EQ(r.scenes.size(), 2u);
    EXPECT_EQ(r.scenes[0].camera.width, 16);
    EXPECT_EQ(r.scenes[1].camera.width, 8);
    ASSERT_EQ(r.scenes[1].aovDisplays.size(), 1u);
    EXPECT_EQ(r.scenes[1].aovDisplays[0].name, "a.2.exr");
}

TEST(RibBuilder, RenderOptionsAndTheirErrors) {
    Built r = build(std::string("Option \"render\" \"float time\" [2.5] \"float error\" [0.02] "
                                "\"int firstpassblock\" [4]\n") + kWorld);
    ASSERT_EQ(r.scenes.size(), 1u);
    EXPECT_FLOAT_EQ(r.scenes[0].render.time, 2.5f);
    EXPECT_FLOAT_EQ(r.scenes[0].render.error, 0.02f);
    EXPECT_EQ(r.scenes[0].render.firstPassBlock, 4);
    Built bad = build(std::string("Option \"render\" \"float time\" [-1]\n") + kWorld);
    EXPECT_EQ(bad.errors, 1);
    EXPECT_NE(bad.messages.find("t.rib:1: error: Option \"render\""), std::string::npos);
    EXPECT_TRUE(r.scenes[0].render.sobol);  // the default
    Built independent = build(
        std::string("Option \"render\" \"string sampler\" \"independent\"\n") + kWorld);
    ASSERT_EQ(independent.scenes.size(), 1u);
    EXPECT_FALSE(independent.scenes[0].render.sobol);
    Built sobol = build(std::string("Option \"render\" \"string sampler\" \"sobol\"\n") + kWorld);
    ASSERT_EQ(sobol.scenes.size(), 1u);
    EXPECT_TRUE(sobol.scenes[0].render.sobol);
    Built unknown = build(std::string("Option \"render\" \"string sampler\" \"halton\"\n") + kWorld);
    EXPECT_EQ(unknown.errors, 1);
    EXPECT_NE(unknown.messages.find("t.rib:1: error: Option \"render\" \"sampler\" \"halton\": "
                                    "known samplers are \"independent\" and \"sobol\""),
              std::string::npos)
        << unknown.messages;
}

TEST(RibBuilder, CameraOptions) {
    Built r = build(std::string("Format 200 100 1\nCropWindow 0.5 1 0 0.5\n"
                                "Projection \"perspective\" \"fov\" 45\n"
                                "DepthOfField 4 0.5 10\n") + kWorld);
    ASSERT_EQ(r.scenes.size(), 1u);
    const CameraSpec& c = r.scenes[0].camera;
    int x0, x1, y0, y1;
    c.cropPixels(x0, x1, y0, y1);
    EXPECT_EQ(x0, 100);
    EXPECT_EQ(x1, 200);
    EXPECT_EQ(y0, 0);
    EXPECT_EQ(y1, 50);
    Camera d = r.scenes[0].deviceCamera();
    EXPECT_FLOAT_EQ(d.lens_radius, 0.5f / 8.0f);
    EXPECT_FLOAT_EQ(d.focal_distance, 10.0f);
    EXPECT_FLOAT_EQ(d.screen[0], -2.0f);  // frame aspect 2: screen window [-2, 2] x [-1, 1]
    Built bad = build(std::string("CropWindow 0.5 0.2 0 1\n") + kWorld);
    EXPECT_EQ(bad.errors, 1);
}

// What shadow rays see of a surface (RT_MATERIAL_SHADOW_MASK), by PRMan's "string
// transmission", "int transmission" and "shade" "transmissionhitmode", and BMRT's "render"
// "casts_shadows": each polygon's material's mode, the last word holding.
TEST(RibBuilder, ShadowModesByEveryName) {
    const char* poly = "Polygon \"P\" [0 0 0  1 0 0  1 1 0]\n";
    const std::pair<const char*, uint32_t> cases[] = {
        {"", 0u},
        {"Attribute \"visibility\" \"string transmission\" [\"shader\"]", RT_MATERIAL_SHADER_SHADOW},
        {"Attribute \"visibility\" \"string transmission\" [\"opaque\"]", RT_MATERIAL_OPAQUE_SHADOW},
        {"Attribute \"visibility\" \"string transmission\" [\"transparent\"]",
         RT_MATERIAL_NO_TRANSMISSION},
        {"Attribute \"visibility\" \"int transmission\" [0]", RT_MATERIAL_NO_TRANSMISSION},
        {"Attribute \"shade\" \"string transmissionhitmode\" [\"shader\"]", RT_MATERIAL_SHADER_SHADOW},
        {"Attribute \"shade\" \"string transmissionhitmode\" [\"shader\"]\n"
         "Attribute \"visibility\" \"int transmission\" [0]\n"
         "Attribute \"visibility\" \"int transmission\" [1]",
         RT_MATERIAL_SHADER_SHADOW},
        {"Attribute \"visibility\" \"string transmission\" [\"shader\"]\n"
         "Attribute \"shade\" \"string transmissionhitmode\" [\"primitive\"]",
         0u},
        {"Attribute \"visibility\" \"string transmission\" [\"opaque\"]\n"
         "Attribute \"shade\" \"string transmissionhitmode\" [\"shader\"]",
         RT_MATERIAL_OPAQUE_SHADOW},
        {"Attribute \"render\" \"string casts_shadows\" [\"shade\"]", RT_MATERIAL_SHADER_SHADOW},
        {"Attribute \"render\" \"string casts_shadows\" [\"none\"]", RT_MATERIAL_NO_TRANSMISSION},
        {"Attribute \"render\" \"string casts_shadows\" [\"opaque\"]", RT_MATERIAL_OPAQUE_SHADOW},
        {"Attribute \"render\" \"string casts_shadows\" [\"shade\"]\n"
         "Attribute \"render\" \"string casts_shadows\" [\"Os\"]",
         0u},
    };
    for (const auto& [attributes, mode] : cases) {
        SCOPED_TRACE(attributes);
        Built b = build(std::string("WorldBegin\n") + attributes + "\n" + poly + "WorldEnd\n");
        EXPECT_EQ(b.errors, 0);
        EXPECT_EQ(b.messages.find("warning"), std::string::npos) << b.messages;
        ASSERT_EQ(b.scenes.size(), 1u);
        ASSERT_FALSE(b.scenes[0].triangles.empty());
        const uint32_t m = b.scenes[0].attrs[0].material;
        EXPECT_EQ(b.scenes[0].materials[m].flags & RT_MATERIAL_SHADOW_MASK, mode);
    }
    Built bad = build(
        "WorldBegin\nAttribute \"shade\" \"string transmissionhitmode\" [\"bogus\"]\n"
        "Attribute \"render\" \"string casts_shadows\" [\"maybe\"]\nWorldEnd\n");
    EXPECT_NE(bad.messages.find("t.rib:2: warning: Attribute \"shade\" \"transmissionhitmode\" "
                                "\"bogus\""),
              std::string::npos)
        << bad.messages;
    EXPECT_NE(bad.messages.find("t.rib:3: warning: Attribute \"render\" \"casts_shadows\""),
              std::string::npos);
}

// GeometricRepresentation (RI 3.2; BMRT's and the RenderMan Repository's scenes give
// "primitive"): read, and a warning at its line for a wire frame or points, which are
// rendered as surfaces. Before, it was an unknown request (an error).
TEST(RibBuilder, GeometricRepresentationIsReadAndOnlyPrimitiveRendered) {
    Built b = build("WorldBegin\nGeometricRepresentation \"primitive\"\n"
                    "GeometricRepresentation \"lines\"\nSphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_EQ(b.errors, 0) << b.messages;
    EXPECT_EQ(b.messages.find("t.rib:2:"), std::string::npos) << b.messages;
    EXPECT_NE(b.messages.find("t.rib:3: warning: GeometricRepresentation \"lines\": surfaces are "
                              "rendered as \"primitive\""),
              std::string::npos)
        << b.messages;
    ASSERT_EQ(b.scenes.size(), 1u);
}

// A shader that reads "object" space gets an instance per object space its primitives
// have (Shading.ObjectSpaceIsEachPrimitivesOwn), each a parameter block of its own: at
// most kMaxObjectSpaces of them, past which the call's space stands in, with a warning
// at the Surface's line. One instance per placement below, 65536 + 10 spheres placed
// apart; one instance for all when the shader does not read "object" space.
TEST(RibBuilder, ObjectSpacesAreBounded) {
    const std::string dir = rd::test::scratchFolder("raydrive_object_spaces");
    std::ofstream(dir + "/objx.sl")
        << "surface objx() { Ci = xcomp(transform(\"object\", P)); }\n";
    std::ofstream(dir + "/plainx.sl") << "surface plainx() { Ci = xcomp(P); }\n";
    for (const char* shader : {"objx", "plainx"}) {
        std::string rib = "Option \"searchpath\" \"shader\" [\"" + dir +
                          ":&\"]\nWorldBegin\nSurface \"" + shader + "\"\n";
        for (size_t i = 0; i < RibBuilder::kMaxObjectSpaces + 10; ++i)
            rib += "Translate 1 0 0\nSphere 1 -1 1 360\n";
        Built b = build(rib + "WorldEnd\n");
        ASSERT_EQ(b.scenes.size(), 1u);
        const bool reads = std::string(shader) == "objx";
        EXPECT_EQ(b.scenes[0].surfaceRefs.size(),
                  reads ? RibBuilder::kMaxObjectSpaces + 1 : 1u)
            << shader;
        EXPECT_EQ(b.messages.find("t.rib:3: warning: more than 65536 object spaces") !=
                      std::string::npos,
                  reads)
            << b.messages.substr(0, 500);
    }
}

// Geometry names an implementation's own primitive: "teapot" is drawn (teapot_test.cpp);
// another name is skipped with a warning at its line, as PRMan does, and the render goes
// on.
TEST(RibBuilder, UnknownGeometryTypeIsAWarningAtItsLine) {
    Built b = build("WorldBegin\nGeometry \"bunny\"\nGeometry \"teapot\"\nWorldEnd\n");
    EXPECT_EQ(b.errors, 0) << b.messages;
    EXPECT_NE(
        b.messages.find("t.rib:2: warning: Geometry \"bunny\": unknown type (RayDrive "
                        "draws \"teapot\"), skipped"),
        std::string::npos)
        << b.messages;
    EXPECT_EQ(b.messages.find("t.rib:3:"), std::string::npos) << b.messages;
    ASSERT_EQ(b.scenes.size(), 1u);
    EXPECT_GT(b.scenes[0].triangles.size(), 32u * 8u);  // the teapot's 32 patches, diced
}
