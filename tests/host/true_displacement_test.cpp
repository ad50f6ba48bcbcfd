// true_displacement_test.cpp: true displacement (host/scene/dice_displaced.h,
// host/render/true_displacement.h): the dicing's pieces meet edge to edge, within the
// ShadingRate's edge length, and a displaced surface moves its silhouette (a bump map
// does not), stays closed, and is shaded with the moved surface's normals.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "render_harness.h"
#include "scene/dice_displaced.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

const double kPi = 3.14159265358979;

// The test shaders, in a folder on the search path; returns the RIB option.
std::string shaderPath() {
    static const char* const kShaders[][2] = {
        {"push",
         "displacement push(float amount = 0.5) {\n"
         "    P += amount * normalize(N);\n    N = calculatenormal(P);\n}\n"},
        // ripples around the sphere and along it: a closed surface moved unevenly
        {"ripple",
         "displacement ripple(float amp = 0.2) {\n"
         "    point Q = transform(\"object\", P);\n"
         "    P += amp * sin(7 * xcomp(Q)) * cos(5 * ycomp(Q) + zcomp(Q)) * "
         "normalize(N);\n"
         "    N = calculatenormal(P);\n}\n"},
        // moved out, and bumped on top: its N tilted toward +x
        {"pushtilt",
         "displacement pushtilt() {\n    P += 0.1 * normalize(N);\n"
         "    N = normalize(normalize(N) + vector(0.5, 0, 0));\n}\n"},
        {"nanmove", "displacement nanmove() {\n    P += (0 / 0) * N;\n}\n"},
        // N . I toward the camera: 1 where the surface faces it
        {"facing",
         "surface facing() {\n    Ci = abs(normalize(N) . normalize(I));\n"
         "    Oi = 1;\n}\n"},
    };
    return "Option \"searchpath\" \"shader\" [\"" +
           rd::test::shaderFolder("raydrive_true_displacement", kShaders) + ":&\"]\n";
}

// Covered area of the view [-2, 2]^2 (orthographic, looking down +z at z = 5).
double coverage(const std::string& attributes, const std::string& geometry) {
    Rendered img = renderRib(shaderPath() +
                             "Format 64 64 1\nPixelSamples 4 4\n"
                             "Option \"render\" \"float pixelerror\" [1e-9]\n"
                             "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
                             "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n" +
                             attributes + geometry + "WorldEnd\n");
    return img.mean(3, 0, 0, img.width, img.height) * 16.0;
}

}  // namespace

// A unit sphere pushed out by 0.5 along its normal is a sphere of radius 1.5 (area 2.25
// pi seen head on) when truly displaced, by BMRT's attribute or PRMan's displacement
// bound; as a bump map (no attribute, or truedisplacement 0) its silhouette stays the
// unit circle's.
TEST(TrueDisplacement, SilhouetteMovesWithTheSurface) {
    const std::string sphere = "Sphere 1 -1 1 360\n";
    const std::string push = "Displacement \"push\" \"float amount\" [0.5]\n";
    EXPECT_NEAR(coverage(push, sphere), kPi, 0.1) << "bump mapped";
    EXPECT_NEAR(
        coverage("Attribute \"render\" \"int truedisplacement\" [1]\n" + push, sphere),
        2.25 * kPi, 0.1);
    EXPECT_NEAR(
        coverage("Attribute \"displacementbound\" \"float sphere\" [0.5]\n" + push,
                 sphere),
        2.25 * kPi, 0.1);
    EXPECT_NEAR(coverage("Attribute \"displacementbound\" \"float sphere\" [0.5]\n"
                         "Attribute \"render\" \"int truedisplacement\" [0]\n" +
                             push,
                         sphere),
                kPi, 0.1);
    // a polygon mesh moved toward the camera does not change its outline; one pushed
    // along a tilted normal does: a square of side 2 tilted 60 degrees about x covers
    // 2 x 1; pushed by 0.5 it slides sideways but keeps its area
    EXPECT_NEAR(coverage("Attribute \"render\" \"int truedisplacement\" [1]\n" + push +
                             "Rotate 60 1 0 0\n",
                         "Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]\n"),
                2.0, 0.1);
}

// Per-point amounts reach the displacement shader of a diced sphere: a unit sphere whose
// four (u, v) corners each give "amount" 0.5 (the call's own 0) is pushed out to radius
// 1.5, 2.25 pi of the view (rsl_abi.h, PER-POINT PARAMETERS: pv_dslot; before, the
// call's 0: pi).
TEST(TrueDisplacement, PerPointAmountsPushTheSilhouette) {
    const std::string attributes =
        "Attribute \"displacementbound\" \"float sphere\" [0.5]\n"
        "Displacement \"push\" \"float amount\" [0]\n";
    EXPECT_NEAR(coverage(attributes, "Sphere 1 -1 1 360\n"), kPi, 0.1);
    EXPECT_NEAR(
        coverage(attributes,
                 "Sphere 1 -1 1 360 \"varying float amount\" [0.5 0.5 0.5 0.5]\n"),
        2.25 * kPi, 0.1);
}

// From inside a rippled sphere no eye ray gets out: the moved surface is closed at its
// seam and its poles (the tessellator computes their vertices twice; the dicing welds
// them), and between the pieces of differently diced triangles.
TEST(TrueDisplacement, DisplacedSphereStaysClosed) {
    for (const char* view :
         {"Rotate 90 1 0 0\n", "Rotate -90 1 0 0\n", "Rotate 90 0 1 0\n", ""}) {
        Rendered img =
            renderRib(shaderPath() +
                      "Format 48 48 1\nPixelSamples 2 2\n"
                      "Projection \"perspective\" \"fov\" 120\n" +
                      view +
                      "WorldBegin\nSurface \"constant\"\n"
                      "Attribute \"render\" \"int truedisplacement\" [1]\n"
                      "Displacement \"ripple\" \"float amp\" [0.3]\nShadingRate 4\n"
                      "Sphere 2 -2 2 360\nWorldEnd\n");
        int open = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) open += img.at(x, y).a < 1.0f;
        EXPECT_EQ(open, 0) << "view " << view;
        EXPECT_GT(img.stats.dicedTriangles, 1000u);
        EXPECT_GT(img.stats.displacedVertices, 500u);
    }
}

// The moved surface is shaded with the normals its shader leaves: a plane pushed toward
// the camera faces it (N . I = 1) as before, where a ripple tilts it the normals tilt
// too, and a shader that tilts N after moving P (a bump on a displacement) is shaded so.
TEST(TrueDisplacement, ShadedWithTheMovedSurfacesNormals) {
    auto render = [](const std::string& shader) {
        return renderRib(shaderPath() +
                         "Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                         "ScreenWindow -1 1 -1 1\nTranslate 0 0 5\nWorldBegin\n"
                         "Surface \"facing\"\n"
                         "Attribute \"render\" \"int truedisplacement\" [1]\n" +
                         shader +
                         "Polygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\nWorldEnd\n");
    };
    Rendered flat = render("Displacement \"push\" \"float amount\" [-0.5]\n");
    EXPECT_NEAR(flat.mean(0, 0, 0, 32, 32), 1.0, 1e-4);
    Rendered rippled = render("Displacement \"ripple\" \"float amp\" [0.2]\n");
    const double mean = rippled.mean(0, 0, 0, 32, 32);
    EXPECT_LT(mean, 0.97) << "the ripples' slopes turn the normals away from the camera";
    EXPECT_GT(mean, 0.5);
    // the N the shader leaves shades the moved surface: a bump on top of a displacement
    Rendered tilted = render("Displacement \"pushtilt\"\n");
    EXPECT_NEAR(tilted.mean(0, 0, 0, 32, 32), 1.0 / std::sqrt(1.25), 1e-4);
}

namespace {

// Every edge of the diced pieces (by their welded vertices), with how many pieces have
// it.
std::map<std::pair<uint32_t, uint32_t>, int> dicedEdges(const rd::DicedSurfaces& d) {
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t i = 0; i + 2 < d.cornerVertex.size(); i += 3)
        for (int k = 0; k < 3; ++k) {
            uint32_t a = d.cornerVertex[i + size_t(k)],
                     b = d.cornerVertex[i + size_t(k + 1) % 3];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    return edges;
}

}  // namespace

// The dicing of a square of two triangles, one of them seen much nearer: every piece's
// edges are within the limit, the pieces cover the square's area, and each inner edge
// is shared by exactly two pieces (no T-junction, so no crack), the outline's by one.
TEST(TrueDisplacement, DicedPiecesMeetEdgeToEdge) {
    rd::Scene scene = rd::test::sceneOfWorld(
        "Attribute \"render\" \"int truedisplacement\" [1]\nDisplacement \"bumpy\"\n"
        "ShadingRate 4\nPolygon \"P\" [0 0 0  8 0 0  8 8 0  0 8 0]\n");
    ASSERT_EQ(scene.triangles.size(), 2u);
    rd::DicingView view;
    view.eye = glm::vec3(0.0f, 0.0f, -1.0f);  // near the corner (0, 0)
    view.pixelSpread = 0.05f;
    const rd::DicedSurfaces d = rd::diceDisplacedSurfaces(scene, view, 1u << 20);
    EXPECT_EQ(d.diced, 2u);
    EXPECT_EQ(d.coarsening, 1.0f);
    const size_t pieces = d.cornerVertex.size() / 3;
    ASSERT_EQ(scene.triangles.size(), 2 + pieces);
    EXPECT_GT(pieces, 100u);
    double area = 0, worst = 0;
    for (size_t i = 2; i < scene.triangles.size(); ++i) {
        const rt_float4 &a = scene.triangles[i].v0, &b = scene.triangles[i].v1,
                        &c = scene.triangles[i].v2;
        const glm::vec3 pa(a.x, a.y, a.z), pb(b.x, b.y, b.z), pc(c.x, c.y, c.z);
        area += 0.5 * glm::length(glm::cross(pb - pa, pc - pa));
        for (auto [p, q] : {std::pair{pa, pb}, std::pair{pb, pc}, std::pair{pc, pa}})
            worst = std::max(worst, double(view.pixels(p, q)));
        EXPECT_TRUE(scene.attrs[i].flags & RT_QF_DISPLACED);
    }
    EXPECT_NEAR(area, 64.0, 1e-3);
    EXPECT_LE(worst, 2.0) << "edges within sqrt(ShadingRate) pixels";
    EXPECT_TRUE(scene.attrs[0].flags & RT_QF_DICED);
    int outline = 0;
    for (const auto& [edge, count] : dicedEdges(d)) {
        EXPECT_TRUE(count == 1 || count == 2) << count << " pieces on one edge";
        outline += count == 1;
    }
    EXPECT_GT(outline, 8);
    // what the camera does not see is diced four times coarser (here all but the
    // square's corner within 2 of the origin), and still meets edge to edge
    rd::Scene partly = rd::test::sceneOfWorld(
        "Attribute \"render\" \"int truedisplacement\" [1]\nDisplacement \"bumpy\"\n"
        "ShadingRate 4\nPolygon \"P\" [0 0 0  8 0 0  8 8 0  0 8 0]\n");
    rd::DicingView seen = view;
    seen.worldToCamera = glm::mat4(1.0f);
    seen.worldToCamera[3][2] = 1.0f;  // camera z = world z + 1: the square at depth 1
    seen.halfX = seen.halfY = 2.0f;
    const rd::DicedSurfaces fewer = rd::diceDisplacedSurfaces(partly, seen, 1u << 20);
    EXPECT_LT(fewer.cornerVertex.size() / 3, pieces * 3 / 4);
    for (const auto& [edge, count] : dicedEdges(fewer))
        EXPECT_TRUE(count == 1 || count == 2) << count << " pieces on one edge";
    // a budget too small for the limit: a coarser dicing that fits
    rd::Scene again = rd::test::sceneOfWorld(
        "Attribute \"render\" \"int truedisplacement\" [1]\nDisplacement \"bumpy\"\n"
        "ShadingRate 4\nPolygon \"P\" [0 0 0  8 0 0  8 8 0  0 8 0]\n");
    const rd::DicedSurfaces coarse = rd::diceDisplacedSurfaces(again, view, pieces / 4);
    EXPECT_GT(coarse.coarsening, 1.0f);
    EXPECT_LE(coarse.cornerVertex.size() / 3, pieces / 4);
    EXPECT_FALSE(coarse.truncated);
}

// A diced sphere is closed: every edge of its welded pieces is in exactly two pieces.
// The tessellator computes the seam's vertices twice (cos 0, cos 2 pi) and each pole once
// per column; without the weld those edges would each be in one piece, and the
// displaced surface would open there.
TEST(TrueDisplacement, DicedSphereIsClosed) {
    rd::Scene scene = rd::test::sceneOfWorld(
        "Attribute \"render\" \"int truedisplacement\" [1]\nDisplacement \"bumpy\"\n"
        "Translate 0 0 5\nRotate 30 1 1 0\nSphere 1 -1 1 360\n");
    rd::DicingView view;
    view.pixelSpread = 0.01f;
    const rd::DicedSurfaces d = rd::diceDisplacedSurfaces(scene, view, 1u << 22);
    EXPECT_GT(d.cornerVertex.size() / 3, 1000u);
    size_t open = 0;
    for (const auto& [edge, count] : dicedEdges(d)) open += count != 2;
    EXPECT_EQ(open, 0u);
}

// A moving surface is diced and displaced on its first key, and each vertex's offset is
// carried to the later keys by the motion: a rippled cube (object-space ripples) turned
// about the view axis from 0 to 90 degrees, seen at the shutter's end (Shutter 1 1), has
// the outline of the cube placed at 90 degrees, pixel for pixel (orthographic, so the
// dicing does not depend on the turn): also through three keys (0, 30, 90) and from a
// 45-degree first key, and moved along x with keys at times -1 and 1. Bump mapped (as
// moving surfaces were before) the outline differs. Open for the whole motion
// (Shutter 0 1) a sphere pushed out by 0.5 along x covers its radius-1.5 disc at every
// instant: 2.25 pi, where bump mapped it is pi.
TEST(TrueDisplacement, MovingSurfacesAreDisplacedAtEveryKey) {
    const std::string cube =
        "Rotate 35 1 0 0\nRotate 25 0 1 0\n"
        "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 "
        "7 "
        "3] \"P\" [-0.8 -0.8 -0.8  0.8 -0.8 -0.8  -0.8 0.8 -0.8  0.8 0.8 -0.8  -0.8 -0.8 "
        "0.8  0.8 -0.8 0.8  -0.8 0.8 0.8  0.8 0.8 0.8]\n";
    auto render = [&](const std::string& shutter, const std::string& placement,
                      int truly) {
        return renderRib(
            shaderPath() + "Format 64 64 1\nPixelSamples 4 4\nShutter " + shutter +
            "\nProjection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
            "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n"
            "Attribute \"render\" \"int truedisplacement\" [" +
            std::to_string(truly) + "]\nDisplacement \"ripple\" \"float amp\" [0.25]\n" +
            placement + cube + "WorldEnd\n");
    };
    auto alphaDiff = [](const Rendered& a, const Rendered& b) {
        double worst = 0;
        for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
            worst = std::max(worst, double(std::fabs(a.pixels[i].a - b.pixels[i].a)));
        return worst;
    };
    const Rendered turned = render("0 1", "Rotate 90 0 0 1\n", 1);
    struct Case {
        const char* name;
        std::string placement;
    } cases[] = {
        {"two keys", "MotionBegin [0 1]\nRotate 0 0 0 1\nRotate 90 0 0 1\nMotionEnd\n"},
        {"three keys",
         "MotionBegin [0 0.5 1]\nRotate 0 0 0 1\nRotate 30 0 0 1\nRotate 90 0 0 1\n"
         "MotionEnd\n"},
        {"from 45", "MotionBegin [0 1]\nRotate 45 0 0 1\nRotate 90 0 0 1\nMotionEnd\n"},
    };
    for (const Case& c : cases) {
        const Rendered moving = render("1 1", c.placement, 1);
        EXPECT_LT(alphaDiff(turned, moving), 1e-6) << c.name;
        EXPECT_GT(moving.stats.dicedTriangles, 1000u) << c.name;
    }
    EXPECT_LT(alphaDiff(render("0 1", "Translate 0.5 0 0\n", 1),
                        render("1 1",
                               "MotionBegin [-1 1]\nTranslate 0 0 0\nTranslate 0.5 0 0\n"
                               "MotionEnd\n",
                               1)),
              1e-6);
    EXPECT_GT(alphaDiff(turned, render("1 1", cases[0].placement, 0)), 0.5)
        << "bump mapped";
    // motion blur over the whole motion
    const std::string sweep =
        "MotionBegin [0 1]\nTranslate -0.4 0 0\nTranslate 0.4 0 0\nMotionEnd\n";
    auto blurred = [&](int truly) {
        Rendered r = renderRib(
            shaderPath() +
            "Format 64 64 1\nPixelSamples 6 6\nShutter 0 1\n"
            "Projection \"orthographic\"\nScreenWindow -2.5 2.5 -2.5 2.5\n"
            "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\n"
            "Attribute \"render\" \"int truedisplacement\" [" +
            std::to_string(truly) + "]\nDisplacement \"push\" \"float amount\" [0.5]\n" +
            sweep + "Sphere 1 -1 1 360\nWorldEnd\n");
        return r.mean(3, 0, 0, r.width, r.height) * 25.0;
    };
    EXPECT_NEAR(blurred(1), 2.25 * kPi, 0.15);
    EXPECT_NEAR(blurred(0), kPi, 0.15);
}

// A truly displaced instance is diced and displaced where it stands, in its own object
// space (the ripple reads P there): two instances of a cube, one turned, give the image
// of the cube written out twice at the same places, alpha for alpha; bump mapped, their
// outline is the undisplaced cube's. (Before, instances were bump mapped with a warning.)
TEST(TrueDisplacement, InstancesAreDisplacedEachInItsOwnSpace) {
    const std::string cube =
        "PointsPolygons [4 4 4 4 4 4] [0 1 3 2  4 6 7 5  0 4 5 1  2 3 7 6  0 2 6 4  1 5 "
        "7 3] \"P\" [-0.8 -0.8 -0.8  0.8 -0.8 -0.8  -0.8 0.8 -0.8  0.8 0.8 -0.8  -0.8 "
        "-0.8 0.8  0.8 -0.8 0.8  -0.8 0.8 0.8  0.8 0.8 0.8]\n";
    const char* const places[] = {
        "Translate -1.6 0 0\nRotate 35 1 0 0\nRotate 25 0 1 0\n",
        "Translate 1.6 0 0\nRotate 80 0 0 1\nRotate 35 1 0 0\n"};
    auto render = [&](bool instanced, int truly) {
        std::string world = "Attribute \"render\" \"int truedisplacement\" [" +
                            std::to_string(truly) +
                            "]\nDisplacement \"ripple\" \"float amp\" [0.25]\n";
        for (const char* place : places)
            world += std::string("AttributeBegin\n") + place +
                     (instanced ? "ObjectInstance \"cube\"\n" : cube) + "AttributeEnd\n";
        return renderRib(
            shaderPath() +
            "Format 112 64 1\nPixelSamples 4 4\n"
            "Projection \"orthographic\"\nScreenWindow -3.5 3.5 -2 2\n"
            "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\nShadingRate 4\n"
            "ObjectBegin \"cube\"\n" +
            cube + "ObjectEnd\n" + world + "WorldEnd\n");
    };
    auto alphaDiff = [](const Rendered& a, const Rendered& b) {
        double worst = 0;
        for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
            worst = std::max(worst, double(std::fabs(a.pixels[i].a - b.pixels[i].a)));
        return worst;
    };
    const Rendered written = render(false, 1), instanced = render(true, 1);
    EXPECT_LT(alphaDiff(written, instanced), 1e-6);
    EXPECT_GT(instanced.stats.dicedTriangles, 1000u);
    EXPECT_EQ(instanced.stats.dicedTriangles, written.stats.dicedTriangles);
    EXPECT_GT(alphaDiff(instanced, render(true, 0)), 0.5) << "bump mapped";
}

// An instanced quadric is made again where a truly displaced instance stands, and diced:
// a unit sphere pushed out by 0.5 covers a disc of radius 1.5 (as in
// SilhouetteMovesWithTheSurface), also inside a transform of the object's own; bump
// mapped, the unit disc. (Before, it stayed an exact sphere, with a warning that spoke of
// solids.)
TEST(TrueDisplacement, InstancedQuadricsAreDicedWhereTheInstanceStands) {
    const std::string object =
        "ObjectBegin \"ball\"\nAttributeBegin\nScale 0.5 0.5 0.5\nSphere 2 -2 2 360\n"
        "AttributeEnd\nObjectEnd\n";
    const std::string push = "Displacement \"push\" \"float amount\" [0.5]\n";
    EXPECT_NEAR(
        coverage(object + "Attribute \"render\" \"int truedisplacement\" [1]\n" + push,
                 "ObjectInstance \"ball\"\n"),
        2.25 * kPi, 0.1);
    EXPECT_NEAR(coverage(object + push, "ObjectInstance \"ball\"\n"), kPi, 0.1)
        << "bump mapped";
}

// A displacement that moves its vertices to NaN is reported at its own request's line,
// the vertices left in place; a negative displacement bound is a warning; a coarser
// dicing than asked (a plane to the horizon at a tiny ShadingRate) is a warning and stays
// within the budget.
TEST(TrueDisplacement, BadValuesAreReported) {
    const std::string dir = rd::test::scratchDir("raydrive_true_displacement_bad");
    const std::string messages = rd::test::renderRibToFiles(
        shaderPath() +
        "Option \"limits\" \"int dicedtriangles\" [100000]\n"
        "Format 32 32 1\nProjection \"perspective\" \"fov\" 90\n"
        "Display \"" +
        dir +
        "/bad.exr\" \"file\" \"rgba\"\nWorldBegin\n"
        "Attribute \"displacementbound\" \"float sphere\" [-1]\n"
        "AttributeBegin\nAttribute \"render\" \"int truedisplacement\" [1]\n"
        "ShadingRate 0.000001\nDisplacement \"push\" \"float amount\" [0.1]\n"
        "Translate 0 -1 0\nRotate 90 1 0 0\n"
        "Polygon \"P\" [-1e5 -1e5 0  1e5 -1e5 0  1e5 1e5 0  -1e5 1e5 0]\nAttributeEnd\n"
        "Attribute \"render\" \"int truedisplacement\" [1]\n"
        "Displacement \"nanmove\"\nTranslate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_NE(messages.find("test.rib:7: warning: Attribute \"displacementbound\""),
              std::string::npos)
        << messages;
    EXPECT_NE(messages.find("coarser than ShadingRate asks, to stay within 100000"),
              std::string::npos)
        << messages;
    EXPECT_NE(messages.find("test.rib:17: warning: displacement moved"),
              std::string::npos)
        << messages;
    EXPECT_TRUE(std::filesystem::exists(dir + "/bad.exr"));
}
