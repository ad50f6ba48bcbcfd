// shading_test.cpp: the standard RSL shaders rendered through the whole pipeline (rsl2cl
// output in the shade kernels) against closed forms: trace() through a mirror, a spot
// light's cone, shadows through shadowspot, a user shader from a searchpath folder, and
// the fallback when a shader is missing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render_harness.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"
#include "shaders/shader_set.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {
const char* kCamera = "Format 32 32 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 40\n";

// A fresh scratch folder for a test's own shaders (Option "searchpath" "shader").
std::string shaderDir(const std::string& name) {
    std::string dir = rd::test::scratchDir(name);
    std::filesystem::create_directories(dir);
    return dir;
}

// A reflector with the shader `surface` (found in `dir`) facing the camera, and behind the
// camera a wide constant plane of colour (0.2, 0.4, 1) that every reflected ray meets.
std::string reflectorOverPlane(const std::string& dir, const std::string& surface) {
    return std::string("Option \"searchpath\" \"shader\" [\"") + dir + ":&\"]\n" + kCamera +
           "WorldBegin\n"
           "AttributeBegin\nSurface \"" + surface + "\"\n"
           "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
           "AttributeEnd\n"
           "AttributeBegin\nColor [0.2 0.4 1]\nSurface \"constant\"\n"
           "Polygon \"P\" [-500 -500 -5  500 -500 -5  500 500 -5  -500 500 -5]\n"
           "AttributeEnd\nWorldEnd\n";
}
}

// A mirror facing the camera reflects a constant plane behind the camera: the pixel is
// Kr * Os * (the plane's colour) exactly (one bounce of trace()).
TEST(Shading, MirrorTracesTheReflectedRay) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\n"
                             "AttributeBegin\nSurface \"mirror\" \"Kr\" 0.8\n"
                             "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
                             "AttributeEnd\n"
                             "AttributeBegin\nColor [0.2 0.4 1]\nSurface \"constant\"\n"
                             "Polygon \"P\" [-50 -50 -5  50 -50 -5  50 50 -5  -50 50 -5]\n"
                             "AttributeEnd\nWorldEnd\n");
    const rd::Rgba& c = img.at(16, 16);
    EXPECT_NEAR(c.r, 0.8 * 0.2, 1e-4);
    EXPECT_NEAR(c.g, 0.8 * 0.4, 1e-4);
    EXPECT_NEAR(c.b, 0.8 * 1.0, 1e-4);
    EXPECT_GT(img.stats.continuationRays, 0u) << "the traced rays are counted with the spawned";
    EXPECT_NE(std::find(img.stats.features.names().begin(), img.stats.features.names().end(),
                        std::string("trace")),
              img.stats.features.names().end());
    EXPECT_FALSE(img.stats.features.sampledTrace) << "mirror rays are coherent";
    // one trace() a run: a hit spawns its continuation and that ray, no more slots
    EXPECT_NE(img.stats.program.options.find("-DRT_SPAWN_SLOTS=2 "), std::string::npos)
        << img.stats.program.options;
}

// environment("raytrace", R) (PRMan) is the ray along R from P, as trace(P, R): the
// same pixel, Kr times the plane's colour (before session 35: a map named "raytrace",
// black, in silence).
TEST(Shading, EnvironmentRaytraceIsATracedRay) {
    std::string dir = shaderDir("raydrive_environment_raytrace");
    std::ofstream(dir + "/envmirror.sl")
        << "surface envmirror(float Kr = 0.8) {\n"
           "  vector r = reflect(normalize(I), normalize(N));\n"
           "  Ci = Kr * color environment(\"raytrace\", r);\n  Oi = 1;\n}\n";
    Rendered img = renderRib(reflectorOverPlane(dir, "envmirror"));
    const rd::Rgba& c = img.at(16, 16);
    EXPECT_NEAR(c.r, 0.8 * 0.2, 1e-4);
    EXPECT_NEAR(c.g, 0.8 * 0.4, 1e-4);
    EXPECT_NEAR(c.b, 0.8 * 1.0, 1e-4);
    EXPECT_GT(img.stats.continuationRays, 0u);
}

// A shader whose trace() runs in a loop (four rays a hit, each a quarter of the plane's
// colour) gets the ABI's eight slots (RSL_MAX_TRACE), so no ray is dropped: the pixel is
// Kr * (the colour) exactly; with fewer slots than calls it would come out darker. Past
// the eight a run records, calls are counted and warned of (stats: trace_calls_ignored).
TEST(Shading, TraceInALoopGetsEverySlot) {
    std::string dir = shaderDir("raydrive_trace_loop");
    std::ofstream(dir + "/fourrays.sl")
        << "surface fourrays(float Kr = 0.8) {\n"
           "  vector r = reflect(normalize(I), normalize(N));\n"
           "  color c = 0; float i;\n"
           "  for (i = 0; i < 4; i += 1) c += 0.25 * trace(P, normalize(r + 0.05 * (i - 1.5) * vector(1, 0, 0)));\n"
           "  Oi = 1; Ci = Kr * c;\n}\n";
    Rendered img = renderRib(reflectorOverPlane(dir, "fourrays"));
    EXPECT_NE(img.stats.program.options.find("-DRT_SPAWN_SLOTS=9 "), std::string::npos)
        << img.stats.program.options;
    const rd::Rgba& c = img.at(16, 16);
    EXPECT_NEAR(c.r, 0.8 * 0.2, 1e-4);
    EXPECT_NEAR(c.g, 0.8 * 0.4, 1e-4);
    EXPECT_NEAR(c.b, 0.8 * 1.0, 1e-4);
    EXPECT_EQ(img.stats.traceCallsIgnored, 0u);
    // ten calls a run, past the eight a shaded point records: eight tenths of the colour,
    // and the two others counted (and warned of), not lost in silence
    std::ofstream(dir + "/tenrays.sl")
        << "surface tenrays(float Kr = 0.8) {\n"
           "  vector r = reflect(normalize(I), normalize(N));\n"
           "  color c = 0; float i;\n"
           "  for (i = 0; i < 10; i += 1) c += 0.1 * trace(P, r);\n"
           "  Oi = 1; Ci = Kr * c;\n}\n";
    Rendered ten = renderRib(reflectorOverPlane(dir, "tenrays"));
    EXPECT_NEAR(ten.at(16, 16).b, 0.8 * 0.8 * 1.0, 1e-4);
    EXPECT_EQ(ten.stats.traceCallsIgnored % 2, 0u);
    EXPECT_GE(ten.stats.traceCallsIgnored, 2u * 32 * 32);
}

// A glossy mirror (trace() in directions jittered by random()) over the same constant
// plane: every jittered ray still meets the plane, so the pixel is Kr * (its colour)
// exactly; the scene's traced rays are known to be sampled (RT_INCOHERENT_TRACE: they walk
// the nodes' hit masks), and the image is the same at both node widths.
TEST(Shading, SampledTraceWalksTheHitMasks) {
    std::string dir = shaderDir("raydrive_sampled_trace");
    std::ofstream(dir + "/glossy.sl")
        << "surface glossy(float Kr = 0.8) {\n"
           "  vector j = vector(random(), random(), random()) - 0.5;\n"
           "  vector d = normalize(reflect(normalize(I), normalize(N)) + 0.2 * j);\n"
           "  Oi = 1; Ci = Kr * trace(P, d);\n}\n";
    const std::string rib = reflectorOverPlane(dir, "glossy");
    rd::RenderSettings four, eight;
    four.bvhWidth = 4;
    eight.bvhWidth = 8;
    Rendered a = renderRib(rib, four), b = renderRib(rib, eight);
    EXPECT_TRUE(b.stats.features.sampledTrace);
    EXPECT_NEAR(b.at(16, 16).r, 0.8 * 0.2, 1e-4);
    EXPECT_NEAR(b.at(16, 16).b, 0.8 * 1.0, 1e-4);
    int differ = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i].r != b.pixels[i].r;
    EXPECT_EQ(differ, 0);
}

// occlusion() and indirectdiffuse() (session 30): one cosine-distributed ray a shading
// sample about the normal, 64 samples a pixel. A small patch at z = 5, its hemisphere
// toward +z (away from the camera): under half of a sky sphere, occlusion is 1/2 by
// symmetry; under a disk of radius 1 centred 2 units along the normal, the
// cosine-weighted fraction of the hemisphere it covers is sin^2 of its half-angle, 1 / (1
// + 4) = 0.2 (1 - occlusion 0.8), none with "maxdist" 1.5 (it is out of reach) or with
// the disk invisible to traced rays (Attribute "visibility" "int trace" [0]), and
// indirectdiffuse sees the disk's constant colour over that fraction; within a narrower
// "coneangle" the disk covers (0.2 over the cone's sin^2) of it. Image means, to 0.02
// (the samples are stratified: measured within 0.005).
TEST(Shading, OcclusionAndIndirectDiffuseAreTheirHemisphereFractions) {
    std::string dir = shaderDir("raydrive_occlusion");
    std::ofstream(dir + "/hemi.sl")
        << "surface hemi(float maxd = 0; float indirect = 0; float cone = 0;) {\n"
           "  normal Nz = normal(0, 0, 1);\n"
           "  if (indirect > 0) Ci = indirectdiffuse(P, Nz, 16);\n"
           "  else if (maxd > 0) Ci = 1 - occlusion(P, Nz, 16, \"maxdist\", maxd);\n"
           "  else if (cone > 0) Ci = 1 - occlusion(P, Nz, 16, \"coneangle\", cone);\n"
           "  else Ci = 1 - occlusion(P, Nz, 16);\n"
           "  Oi = 1;\n}\n";
    auto render = [&](const std::string& hemi, const std::string& above) {
        return renderRib(rd::test::patchUnder(dir, 8, "\"hemi\" " + hemi, above));
    };
    const std::string halfSky = "Sphere 100 -100 100 180\n";
    const std::string disk = "Translate 0 0 7\nDisk 0 1 360\n";
    Rendered half = render("", halfSky), under = render("", disk),
             reach = render("\"maxd\" 1.5", disk), light = render("\"indirect\" 1", disk),
             hidden = render("", "Attribute \"visibility\" \"int trace\" [0]\n" + disk);
    EXPECT_NEAR(half.mean(0, 0, 0, 16, 16), 0.5, 0.02);
    EXPECT_NEAR(under.mean(0, 0, 0, 16, 16), 0.8, 0.02);
    EXPECT_NEAR(reach.mean(0, 0, 0, 16, 16), 1.0, 1e-6);
    EXPECT_NEAR(hidden.mean(0, 0, 0, 16, 16), 1.0, 1e-6);  // traced rays go through it
    EXPECT_NEAR(light.mean(0, 0, 0, 16, 16), 0.2, 0.02);
    EXPECT_NEAR(light.mean(1, 0, 0, 16, 16), 0.1, 0.01);
    EXPECT_NEAR(light.mean(2, 0, 0, 16, 16), 0.05, 0.005);
    // "coneangle" (session 35; a warning before): a cone whose sin^2 is 0.4 is half
    // covered by the disk (its sin^2 0.2 over 0.4); one whose sin^2 is 0.1 wholly
    Rendered cone = render("\"cone\" " + std::to_string(std::asin(std::sqrt(0.4))), disk),
             narrow =
                 render("\"cone\" " + std::to_string(std::asin(std::sqrt(0.1))), disk);
    EXPECT_NEAR(cone.mean(0, 0, 0, 16, 16), 0.5, 0.02);
    EXPECT_NEAR(narrow.mean(0, 0, 0, 16, 16), 0.0, 1e-6);
    std::printf("NUMERICS case=occlusion_cone tolerance=0.02 measured=%.4f\n",
                cone.mean(0, 0, 0, 16, 16) - 0.5);
    std::printf("NUMERICS case=occlusion_half_sky tolerance=0.02 measured=%.4f\n",
                half.mean(0, 0, 0, 16, 16) - 0.5);
    std::printf("NUMERICS case=occlusion_disk tolerance=0.02 measured=%.4f\n",
                under.mean(0, 0, 0, 16, 16) - 0.8);
    std::printf("NUMERICS case=indirectdiffuse_disk tolerance=0.02 measured=%.4f\n",
                light.mean(0, 0, 0, 16, 16) - 0.2);
    const auto names = under.stats.features.names();
    EXPECT_NE(std::find(names.begin(), names.end(), "occlusion"), names.end());
    EXPECT_TRUE(under.stats.features.visibilityRays);
    EXPECT_TRUE(light.stats.features.sampledTrace);
}

// occlusion()'s `samples`, a literal: that many rays from one shading sample (up to the
// eight an evaluation records), spread over the hemisphere. Under the disk above, one
// sample a pixel: 1 - occlusion is 0 or 1 a pixel with one ray (spread 0.4 about 0.8),
// far less spread with eight; both means 0.8.
TEST(Shading, OcclusionSamplesAreRaysOfOneShadingSample) {
    std::string dir = shaderDir("raydrive_occlusion_samples");
    for (int n : {1, 8})
        std::ofstream(dir + "/occl" + std::to_string(n) + ".sl")
            << "surface occl" << n << "() {\n  Ci = 1 - occlusion(P, normal(0, 0, 1), "
            << n << ");\n  Oi = 1;\n}\n";
    auto render = [&](int n) {
        return renderRib(rd::test::patchUnder(dir, 1, "\"occl" + std::to_string(n) + "\"",
                                              "Translate 0 0 7\nDisk 0 1 360\n"));
    };
    auto spread = [](const Rendered& img, double mean) {
        double q = 0;
        for (const rd::Rgba& p : img.pixels) q += (p.r - mean) * (p.r - mean);
        return std::sqrt(q / double(img.pixels.size()));
    };
    Rendered one = render(1), eight = render(8);
    const double m1 = one.mean(0, 0, 0, 16, 16), m8 = eight.mean(0, 0, 0, 16, 16);
    std::printf(
        "NUMERICS case=occlusion_samples_spread one=%.3f eight=%.3f means %.4f %.4f\n",
        spread(one, 0.8), spread(eight, 0.8), m1, m8);
    EXPECT_NEAR(m1, 0.8, 0.08);
    EXPECT_NEAR(m8, 0.8, 0.03);
    EXPECT_GT(spread(one, 0.8), 0.3);
    EXPECT_LT(spread(eight, 0.8), 0.5 * spread(one, 0.8));
}

// transmission(P0, P1) in a surface shader (session 30; it returned 1 before): a ray from
// P0 to P1. A patch at z = 5 asks toward P + (0, 0, 3); a square over its left half at
// z = 6.5 blocks those rays (0), the right half sees through (1); the same square at
// z = 9, beyond P1, blocks nothing. In a light shader it stays 1 (the light's shadow ray
// asks the same).
TEST(Shading, TransmissionInASurfaceIsAVisibilityRay) {
    std::string dir = shaderDir("raydrive_transmission");
    std::ofstream(dir + "/seethrough.sl")
        << "surface seethrough() {\n"
           "  Ci = transmission(P, P + vector(0, 0, 3));\n  Oi = 1;\n}\n";
    auto render = [&](const char* z) {
        return renderRib(
            "Option \"searchpath\" \"shader\" [\"" + dir +
            ":&\"]\nFormat 16 16 1\nPixelSamples 2 2\nProjection "
            "\"orthographic\"\nWorldBegin\nAttributeBegin\nSurface "
            "\"constant\"\nPolygon \"P\" [-2 -2 " +
            std::string(z) + "  0 -2 " + z + "  0 2 " + z + "  -2 2 " + z +
            "]\nAttributeEnd\nSurface "
            "\"seethrough\"\nPolygon \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5]\n"
            "WorldEnd\n");
    };
    Rendered near = render("6.5"), far = render("9");
    EXPECT_NEAR(near.mean(0, 0, 0, 8, 16), 0.0,
                1e-6);  // (the left half, behind the square)
    EXPECT_NEAR(near.mean(0, 8, 0, 16, 16), 1.0, 1e-6);
    EXPECT_NEAR(far.mean(0, 0, 0, 16, 16), 1.0, 1e-6);
    EXPECT_TRUE(near.stats.features.visibilityRays);
}

// spotlight: inside the cone a matte plane gets intensity * cos^beam / d^2 * N.L; outside
// the cone (coneangle 10 degrees, plane corners) nothing.
TEST(Shading, SpotlightConeAndFalloff) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\nLightSource \"spotlight\" 1 \"from\" [0 0 0] "
                             "\"to\" [0 0 1] \"intensity\" 25 \"coneangle\" [0.1745]\n"
                             "Surface \"matte\"\n"
                             "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
                             "WorldEnd\n");
    EXPECT_NEAR(img.mean(0, 15, 15, 17, 17), 25.0 / 25.0, 0.02);  // on axis: Cl = 1, N.L = 1
    EXPECT_EQ(img.at(1, 1).r, 0.0f);
}

// A light edited between renders (its intensity, cone angle and place) is data, not
// code: the program is the same (its cache key), so the edit costs no build and no
// kernel compile (SPD teapot: 0.23 s against 2.85 s when values were compiled in). The
// new values take effect: on the axis half the light at half the intensity, a corner
// lit by the wider cone (the cone's cosine prepared once per instance), and a surface
// reading lightsource("intensity") sees each render's value.
TEST(Shading, EditedLightsKeepTheProgram) {
    std::string dir = shaderDir("raydrive_shaders");
    std::ofstream(dir + "/ls_intensity.sl")
        << "surface ls_intensity() {\n    float k = 0;\n"
           "    illuminance(P) { lightsource(\"intensity\", k); }\n    Ci = k; Oi = 1;\n}\n";
    auto scene = [&](const char* from, const char* intensity, const char* cone,
                     const char* surface) {
        return renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                         std::string(kCamera) + "WorldBegin\nLightSource \"spotlight\" 1 "
                         "\"from\" [" + from + "] \"to\" [0 0 1] \"intensity\" " + intensity +
                         " \"coneangle\" [" + cone + "]\nSurface \"" + surface + "\"\n"
                         "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\nWorldEnd\n");
    };
    const Rendered narrow = scene("0 0 0", "25", "0.1745", "matte");
    const Rendered wide = scene("0 0 0.001", "12.5", "1.2", "matte");
    EXPECT_EQ(narrow.stats.program.cacheKey, wide.stats.program.cacheKey);
    EXPECT_NEAR(narrow.mean(0, 15, 15, 17, 17), 1.0, 0.02);
    EXPECT_NEAR(wide.mean(0, 15, 15, 17, 17), 0.5, 0.01);
    EXPECT_EQ(narrow.at(1, 1).r, 0.0f);
    EXPECT_GT(wide.at(1, 1).r, 0.01f);
    EXPECT_EQ(wide.stats.kernels.count("rd_prepare_uniforms"), 1u);
    const Rendered read25 = scene("0 0 0", "25", "0.1745", "ls_intensity");
    const Rendered read12 = scene("0 0 0", "12.5", "0.1745", "ls_intensity");
    EXPECT_EQ(read25.stats.program.cacheKey, read12.stats.program.cacheKey);
    EXPECT_EQ(read25.at(16, 16).r, 25.0f);
    EXPECT_EQ(read12.at(16, 16).r, 12.5f);
}

// A camera moved, and an image size changed, between renders is data too (the scene
// block at the front of the parameter buffer): the same program, while what a shader
// reads of them follows. An orthographic camera over a plane at z = 5 (Clipping 1 10):
// world x of the point (transform "world") + 1, depth(P) + 1/2 = (5 - 1) / 9 + 1/2 (the
// film keeps no negative value), option("Format")'s x resolution; the camera moved by
// 0.25 in x sees world x 0.25 lower at each pixel (its sample at the same place in it).
TEST(Shading, MovedCameraKeepsTheProgram) {
    std::string dir = shaderDir("raydrive_shaders");
    std::ofstream(dir + "/cam_reads.sl")
        << "surface cam_reads() {\n    point Pw = transform(\"world\", P);\n"
           "    float f[3] = {0, 0, 0};\n    option(\"Format\", f);\n"
           "    Ci = color(xcomp(Pw) + 1, depth(P) + 0.5, f[0] / 100);\n    Oi = 1;\n}\n";
    auto scene = [&](const char* move, int size) {
        const std::string res = std::to_string(size);
        return renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                         "Format " + res + " " + res + " 1\nPixelSamples 1 1\n"
                         "Projection \"orthographic\"\nClipping 1 10\nTranslate " + move +
                         " 0 0\nWorldBegin\nSurface \"cam_reads\"\n"
                         "Polygon \"P\" [-9 -9 5  9 -9 5  9 9 5  -9 9 5]\nWorldEnd\n");
    };
    const Rendered at0 = scene("0", 16), moved = scene("0.25", 16), larger = scene("0", 32);
    EXPECT_EQ(at0.stats.program.cacheKey, moved.stats.program.cacheKey);
    EXPECT_EQ(at0.stats.program.cacheKey, larger.stats.program.cacheKey);
    for (int x : {2, 8, 13}) {
        EXPECT_NEAR(moved.at(x, 8).r, at0.at(x, 8).r - 0.25f, 1e-5) << x;
        EXPECT_NEAR(at0.at(x, 8).g, 0.5f + 4.0f / 9.0f, 1e-5) << x;
    }
    EXPECT_NEAR(at0.at(8, 8).b, 0.16f, 1e-6);
    EXPECT_NEAR(larger.at(16, 16).b, 0.32f, 1e-6);
}

// One spotlight of intensity 25 and forty at the same place, alternately 1.5 and 0.5 of
// 25/40, light the plane alike: every instance goes through its shader's one inlined
// call site (feature specialised_lights), told apart by the offsets of its data (its
// block, its place, its prepared cone); one reading another's block breaks the sum. So
// must
// seventy of 25/70: more than kLightCoefLimit, so the surface runs once per light (no
// light coefficients) and lights past the cache are run where they are read.
TEST(Shading, OneLightAndManyAgree) {
    auto spots = [](int n) {
        std::string rib = std::string(kCamera) + "WorldBegin\n";
        for (int i = 0; i < n; ++i)
            rib += "LightSource \"spotlight\" " + std::to_string(i + 1) +
                   " \"from\" [0 0 0] \"to\" [0.1 0 1] \"intensity\" " +
                   std::to_string((n == 1 ? 1.0 : i % 2 ? 0.5 : 1.5) * 25.0 / n) +
                   " \"coneangle\" [0.3]\n";
        return rib + "Surface \"matte\"\n"
                     "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\nWorldEnd\n";
    };
    Rendered one = renderRib(spots(1)), many = renderRib(spots(40)), most = renderRib(spots(70));
    static_assert(rd::kLightCoefLimit < 70, "seventy lights are shaded once per light");
    EXPECT_TRUE(one.stats.features.specialisedLights);
    EXPECT_TRUE(many.stats.features.specialisedLights);
    EXPECT_TRUE(many.stats.features.lightCoefficients);
    EXPECT_FALSE(most.stats.features.lightCoefficients);
    double lit = 0;
    for (int y = 0; y < one.height; ++y)
        for (int x = 0; x < one.width; ++x) {
            const float a = one.at(x, y).r, b = many.at(x, y).r, c = most.at(x, y).r;
            ASSERT_NEAR(a, b, 1e-5 + 1e-5 * a) << "pixel " << x << ", " << y;
            ASSERT_NEAR(a, c, 1e-5 + 1e-5 * a) << "pixel " << x << ", " << y;
            lit += a > 0.1;
        }
    EXPECT_GT(lit, 20) << "inside the cone";
    EXPECT_LT(lit, one.width * one.height - 20) << "and outside it";
}

// Three coloured lights (point, spot, distant) on plastic: with light coefficients (the
// base evaluation gives each light's part) and through a shader that computes the same
// into an array (evaluated once more per light, as coefficients are not carried through
// arrays), every pixel agrees to rounding. It fails when a light's coefficient is taken
// from another light or lost.
TEST(Shading, LightCoefficientsAgreeWithPerLightEvaluation) {
    std::string dir = shaderDir("raydrive_coef_shaders");
    std::ofstream(dir + "/plasticarr.sl")
        << "surface plasticarr(float Ks = .5, Kd = .5, Ka = 1, roughness = .1;\n"
           "                   color specularcolor = 1;) {\n"
           "    normal Nf = faceforward(normalize(N), I);\n"
           "    vector V = -normalize(I);\n"
           "    color lit[2];\n"
           "    lit[0] = Kd * diffuse(Nf);\n"
           "    lit[1] = specularcolor * Ks * specular(Nf, V, roughness);\n"
           "    Oi = Os;\n"
           "    Ci = Os * (Cs * (Ka * ambient() + lit[0]) + lit[1]);\n"
           "}\n";
    auto scene = [&](const std::string& surface) {
        return "Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" + std::string(kCamera) +
               "WorldBegin\n"
               "LightSource \"ambientlight\" 1 \"intensity\" 0.1\n"
               "LightSource \"pointlight\" 2 \"from\" [1 1 3] \"intensity\" 4 "
               "\"lightcolor\" [1 0.5 0.25]\n"
               "LightSource \"spotlight\" 3 \"from\" [-1 0 0] \"to\" [0 0 5] \"intensity\" 30 "
               "\"coneangle\" 0.3 \"lightcolor\" [0.2 1 0.4]\n"
               "LightSource \"distantlight\" 4 \"from\" [0 2 0] \"to\" [0 0 5] "
               "\"intensity\" 0.5 \"lightcolor\" [0.3 0.3 1]\n"
               "Surface \"" + surface + "\" \"roughness\" 0.2\nColor [0.9 0.6 0.3]\n"
               "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
               "Translate 0.3 -0.2 3.5\nSphere 0.6 -0.6 0.6 360\nWorldEnd\n";
    };
    Rendered coef = renderRib(scene("plastic")), per = renderRib(scene("plasticarr"));
    EXPECT_TRUE(coef.stats.features.lightCoefficients);
    EXPECT_FALSE(per.stats.features.lightCoefficients);
    double lit = 0;
    for (int y = 0; y < coef.height; ++y)
        for (int x = 0; x < coef.width; ++x) {
            const auto a = coef.at(x, y), b = per.at(x, y);
            ASSERT_NEAR(a.r, b.r, 2e-5 + 1e-5 * b.r) << "pixel " << x << ", " << y;
            ASSERT_NEAR(a.g, b.g, 2e-5 + 1e-5 * b.g) << "pixel " << x << ", " << y;
            ASSERT_NEAR(a.b, b.b, 2e-5 + 1e-5 * b.b) << "pixel " << x << ", " << y;
            lit += b.r > 0.2 && b.g > 0.2;
        }
    EXPECT_GT(lit, 50) << "the lights must light the frame for the test to mean anything";
}

// shadowspot with shadowname "raytrace": a spot at (0, 3, 2) aimed at the plane's centre
// (0, 0, 5); a sphere of radius 0.3 half way, (0, 1.5, 3.5), shadows the centre (shadow
// radius about 0.6 on the plane), which the eye sees unobstructed (the sphere is above
// the frame). Next to the shadow the plane is lit: Cl = 25 / 18, N.L = cos 45.
TEST(Shading, ShadowspotCastsRayTracedShadows) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\nLightSource \"shadowspot\" 1 \"from\" [0 3 2] "
                             "\"to\" [0 0 5] \"intensity\" 25 \"shadowname\" [\"raytrace\"]\n"
                             "Surface \"matte\"\n"
                             "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
                             "AttributeBegin\nTranslate 0 1.5 3.5\nSphere 0.3 -0.3 0.3 360\n"
                             "AttributeEnd\nWorldEnd\n");
    EXPECT_LT(img.mean(0, 15, 15, 17, 17), 0.01) << "shadow centre";
    EXPECT_GT(img.at(26, 16).r, 0.5) << "lit beside the shadow";
    EXPECT_GT(img.stats.shadowRays, 0u);
}

// A user shader found through Option "searchpath" "shader", with a parameter override.
TEST(Shading, UserShaderOnTheSearchPath) {
    std::string dir = shaderDir("raydrive_shaders");
    std::ofstream(dir + "/tint.sl") << "surface tint(color tint = 1; float gain = 1;) {\n"
                                       "    Oi = Os;\n    Ci = Os * tint * gain;\n}\n";
    Rendered img = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                             std::string(kCamera) +
                             "WorldBegin\nSurface \"tint\" \"color tint\" [0.5 0.25 1] "
                             "\"gain\" 2\n"
                             "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
                             "WorldEnd\n");
    EXPECT_NEAR(img.at(16, 16).r, 1.0, 1e-5);
    EXPECT_NEAR(img.at(16, 16).g, 0.5, 1e-5);
    EXPECT_NEAR(img.at(16, 16).b, 2.0, 1e-5);
}

// A shader that is not found is reported and the surface renders with defaultsurface.
TEST(Shading, MissingShaderFallsBackToDefaultsurface) {
    Rendered img = renderRib(std::string(kCamera) +
                             "WorldBegin\nSurface \"no_such_shader\"\n"
                             "Polygon \"P\" [-50 -50 5  50 -50 5  50 50 5  -50 50 5]\n"
                             "WorldEnd\n");
    // defaultsurface: Ka + Kd * (I.N)^2 = 0.2 + 0.8 on the axis
    EXPECT_NEAR(img.at(16, 16).r, 1.0, 0.01);
}

// Per-vertex primitive variables reach the shader interpolated: "Cs" on a polygon
// (constant shades with Cs), and "st" read by a shader as s and t.
TEST(Shading, VertexPrimitiveVariables) {
    // Orthographic over [-1, 1]^2; a square with Cs red at x = -1 and blue at x = 1.
    const std::string cam = "Format 16 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\n";
    Rendered cs = renderRib(cam + "WorldBegin\nSurface \"constant\"\n"
                            "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                            "\"Cs\" [1 0 0  0 0 1  0 0 1  1 0 0]\nWorldEnd\n");
    // pixel column 4 of 16 has centre x = -0.4375: red 0.72, blue 0.28 (mean over it)
    EXPECT_NEAR(cs.mean(0, 4, 0, 5, 16), (1 - (-0.4375)) / 2, 0.02);
    EXPECT_NEAR(cs.mean(2, 4, 0, 5, 16), (1 + (-0.4375)) / 2, 0.02);

    std::string dir = shaderDir("raydrive_st");
    std::ofstream(dir + "/showst.sl") << "surface showst() {\n    Oi = 1;\n"
                                         "    Ci = color(s, t, 0);\n}\n";
    Rendered st = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" + cam +
                            "WorldBegin\nSurface \"showst\"\n"
                            "Polygon \"P\" [-1 -1 1  1 -1 1  1 1 1  -1 1 1] "
                            "\"st\" [0 0  2 0  2 4  0 4]\nWorldEnd\n");
    // s = x + 1 across [0, 2]; t = 2 (y + 1) with y up: row 4 has centre y = 0.4375.
    EXPECT_NEAR(st.mean(0, 12, 0, 13, 16), 0.5625 + 1, 0.03);
    EXPECT_NEAR(st.mean(1, 0, 4, 16, 5), 2 * (0.4375 + 1), 0.05);
}

// Atmosphere "fog" (the standard volume shader) on constant white surfaces at distances
// 1 and 3 from an orthographic eye: Ci = mix(Ci, background, 1 - exp(-d / distance)).
TEST(Shading, FogAtmosphereFollowsItsClosedForm) {
    Rendered img = renderRib("Format 64 16 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                             "ScreenWindow -4 4 -1 1\nWorldBegin\nSurface \"constant\"\n"
                             "Atmosphere \"fog\" \"distance\" 2 \"background\" [0 0 1]\n"
                             "Polygon \"P\" [-4 -1 1  0 -1 1  0 1 1  -4 1 1]\n"
                             "Polygon \"P\" [0 -1 3  4 -1 3  4 1 3  0 1 3]\nWorldEnd\n");
    for (auto [x0, d] : {std::pair<int, double>{4, 1.0}, {36, 3.0}}) {
        double fog = 1 - std::exp(-d / 2);
        EXPECT_NEAR(img.mean(0, x0, 4, x0 + 24, 12), 1 - fog, 1e-4) << "distance " << d;
        EXPECT_NEAR(img.mean(2, x0, 4, x0 + 24, 12), 1.0, 1e-4) << "distance " << d;
        EXPECT_NEAR(img.mean(3, x0, 4, x0 + 24, 12), 1.0, 1e-6) << "distance " << d;
    }
    EXPECT_TRUE(std::find(img.stats.features.names().begin(), img.stats.features.names().end(),
                          "atmosphere") != img.stats.features.names().end());
}

// Interior: a clear ball (every hit traces straight on) over a white plane, absorbing
// inside by exp(-sigma length(I)): seen head on, each pixel's ray crosses a chord of
// 2 sqrt(1 - r^2) and brings back exp(-sigma chord) of the plane's white; the front
// face (hit from outside) takes no absorption. Without Interior the ball is clear (1);
// Exterior and Deformation are warnings (not carried out), not silently dropped.
TEST(Shading, InteriorVolumeAbsorbsAlongTheChord) {
    const std::string dir = shaderDir("raydrive_interior");
    std::ofstream(dir + "/clear.sl")
        << "surface clear() {\n    Ci = trace(P, normalize(I));\n"
           "    Oi = 1;\n}\n";
    std::ofstream(dir + "/absorb.sl") << "volume absorb(float sigma = 1) {\n"
                                         "    Ci *= exp(-sigma * length(I));\n}\n";
    auto render = [&](const std::string& inside) {
        return renderRib(
            "Option \"searchpath\" \"shader\" [\"" + dir +
            ":&\"]\n"
            "Format 64 64 1\nPixelSamples 4 4\nOption \"render\" \"float pixelerror\" "
            "[1e-9]\n"
            "Projection \"orthographic\"\n"
            "ScreenWindow -1.6 1.6 -1.6 1.6\nWorldBegin\n"
            "Attribute \"trace\" \"int maxspeculardepth\" [4]\n"
            "AttributeBegin\nSurface \"constant\"\n"
            "Polygon \"P\" [-5 -5 10  5 -5 10  5 5 10  -5 5 10]\nAttributeEnd\n"
            "AttributeBegin\nTranslate 0 0 5\nSurface \"clear\"\n" +
            inside + "Sphere 1 -1 1 360\nAttributeEnd\nWorldEnd\n");
    };
    const Rendered clear = render("");
    const Rendered absorbing = render("Interior \"absorb\" \"sigma\" 0.7\n");
    double worst = 0, clearWorst = 0;
    int inside = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const double px = (x + 0.5) / 64 * 3.2 - 1.6, py = (y + 0.5) / 64 * 3.2 - 1.6;
            const double r2 = px * px + py * py;
            // (toward the rim the chord changes fast across a pixel, whose mean is taken)
            if (r2 > 0.6) continue;
            ++inside;
            const double expect = std::exp(-0.7 * 2 * std::sqrt(1 - r2));
            worst = std::max(worst, std::fabs(absorbing.at(x, y).g - expect));
            clearWorst = std::max(clearWorst, std::fabs(clear.at(x, y).g - 1.0));
        }
    EXPECT_GT(inside, 700);
    EXPECT_LT(worst, 2.5e-3) << "exp(-sigma chord) (pixel means of a curved function)";
    EXPECT_LT(clearWorst, 1e-5);
    std::printf("NUMERICS case=interior_absorption tolerance=2.5e-3 measured=%.3g\n",
                worst);
    const auto& names = absorbing.stats.features.names();
    EXPECT_TRUE(std::find(names.begin(), names.end(), "interior") != names.end());
    std::ostringstream messages;
    rib::Diagnostics diag(&messages);
    rd::RibBuilder builder(diag, "test.rib");
    rib::readString("WorldBegin\nDeformation \"twist\"\nWorldEnd\n", "test.rib", builder,
                    diag);
    EXPECT_NE(messages.str().find("test.rib:2: warning: Deformation \"twist\""),
              std::string::npos);
}

// Exterior: a mirror at 45 degrees (z = x) turns the orthographic eye rays (+z) toward
// +x, onto a white plane at x = 3; with `Exterior "absorb"` on the mirror the reflected
// segment, 3 - x long from the mirror point at x, brings back exp(-sigma (3 - x)). The
// eye rays (from no surface) take no absorption.
TEST(Shading, ExteriorVolumeAbsorbsAlongTheReflectedRay) {
    const std::string dir = shaderDir("raydrive_exterior");
    std::ofstream(dir + "/mirrorx.sl") << "surface mirrorx() {\n    Ci = trace(P, "
                                          "reflect(normalize(I), normalize(N)));\n"
                                          "    Oi = 1;\n}\n";
    std::ofstream(dir + "/absorb.sl") << "volume absorb(float sigma = 1) {\n"
                                         "    Ci *= exp(-sigma * length(I));\n}\n";
    auto render = [&](const std::string& outside) {
        return renderRib(
            "Option \"searchpath\" \"shader\" [\"" + dir +
            ":&\"]\n"
            "Format 32 32 1\nPixelSamples 4 4\n"
            "Option \"render\" \"float pixelerror\" [1e-9]\n"
            "Projection \"orthographic\"\nScreenWindow -2 2 -2 2\n"
            "Translate 0 0 5\nWorldBegin\n"
            "AttributeBegin\nSurface \"constant\"\n"
            "Polygon \"P\" [3 -9 -9  3 9 -9  3 9 9  3 -9 9]\nAttributeEnd\n"
            "AttributeBegin\nSurface \"mirrorx\"\n" +
            outside +
            "Polygon \"P\" [-1.5 -2 -1.5  1.5 -2 1.5  1.5 2 1.5  -1.5 2 -1.5]\n"
            "AttributeEnd\nWorldEnd\n");
    };
    const Rendered plain = render("");
    const Rendered absorbing = render("Exterior \"absorb\" \"sigma\" 0.5\n");
    double worst = 0, plainWorst = 0;
    for (int x = 4; x < 28; ++x) {  // over the mirror, x in [-1.5, 1.5] is pixels 4..27
        const double wx = (x + 0.5) / 32 * 4 - 2;
        const double expect = std::exp(-0.5 * (3 - wx));
        for (int y = 8; y < 24; ++y) {
            worst = std::max(worst, std::fabs(absorbing.at(x, y).g - expect));
            plainWorst = std::max(plainWorst, std::fabs(plain.at(x, y).g - 1.0));
        }
    }
    EXPECT_LT(worst, 4e-3) << "exp(-sigma (3 - x)) (a pixel's mean over its width)";
    EXPECT_LT(plainWorst, 1e-5);
    std::printf("NUMERICS case=exterior_absorption tolerance=4e-3 measured=%.3g\n",
                worst);
    const auto& names = absorbing.stats.features.names();
    EXPECT_TRUE(std::find(names.begin(), names.end(), "exterior") != names.end());
}

// Uniform work hoisted into the per-instance prepare kernel gives what the same shader
// computes at every point (its twin declares the variables varying, so nothing is
// hoisted), and each instance keeps its own prepared values.
TEST(Shading, HoistedUniformWorkEqualsPerPointWork) {
    std::string dir = shaderDir("raydrive_shaders");
    for (const char* storage : {"uniform", "varying"})
        std::ofstream(dir + "/prep_" + storage + ".sl")
            << "surface prep_" << storage << "(float Kd = 0.5; float rough = 0.25;\n"
            << "                 color tint = color(1, 0.5, 0.25);) {\n"
            << "    " << storage << " float k = pow(Kd, 2) + sqrt(rough);\n"
            << "    " << storage << " color c = tint * k;\n"
            << "    " << storage << " matrix m = rotate(matrix 1, radians(90), vector(0, 0, 1));\n"
            << "    Ci = c * (2 + xcomp(transform(m, point(1, 0, 0))) + ycomp(transform(m, point(1, 0, 0))));\n"
            << "    Oi = 1;\n}\n";
    auto scene = [&](const std::string& name) {
        return renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                         std::string(kCamera) + "WorldBegin\nAttributeBegin\nSurface \"" + name +
                         "\" \"Kd\" 0.8\n"
                         "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5]\nAttributeEnd\n"
                         "Surface \"" + name + "\" \"rough\" 0.5\n"
                         "Polygon \"P\" [0 -50 5  50 -50 5  50 50 5  0 50 5]\nWorldEnd\n");
    };
    Rendered hoisted = scene("prep_uniform"), perPoint = scene("prep_varying");
    const double left = 0.64 + std::sqrt(0.25), right = 0.25 + std::sqrt(0.5);  // k
    EXPECT_NEAR(hoisted.at(4, 16).g, 0.5 * left * 3.0, 1e-5);
    EXPECT_NEAR(hoisted.at(28, 16).g, 0.5 * right * 3.0, 1e-5);
    for (int x : {4, 28})
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ((&hoisted.at(x, 16).r)[c], (&perPoint.at(x, 16).r)[c]) << x << " " << c;
    EXPECT_EQ(hoisted.stats.kernels.count("rd_prepare_uniforms"), 1u);
    EXPECT_EQ(perPoint.stats.kernels.count("rd_prepare_uniforms"), 0u);
}

// A primitive variable named like a shader parameter gives it its value on that
// primitive (constant ones, and uniform ones of a single face, as the instance's value;
// varying ones per point: point_params_test.cpp); varying strings warn.
TEST(Shading, ConstantPrimitiveVariablesOverrideShaderParameters) {
    std::string dir = shaderDir("raydrive_shaders");
    std::ofstream(dir + "/gained.sl") << "surface gained(float gain = 1; color tint = 1;) {\n"
                                         "    Oi = 1;\n    Ci = tint * gain;\n}\n";
    ::testing::internal::CaptureStderr();
    Rendered img = renderRib("Option \"searchpath\" \"shader\" [\"" + dir + ":&\"]\n" +
                             std::string(kCamera) + "WorldBegin\nSurface \"gained\"\n"
                             "Polygon \"P\" [-50 -50 5  0 -50 5  0 50 5  -50 50 5] "
                             "\"constant float gain\" [3] \"uniform color tint\" [1 0.5 0.25]\n"
                             "Polygon \"P\" [0 -50 5  50 -50 5  50 50 5  0 50 5] "
                             "\"varying float gain\" [5 5 5 5] "
                             "\"varying string label\" [\"a\" \"b\" \"c\" \"d\"]\nWorldEnd\n");
    std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_NEAR(img.at(4, 16).r, 3.0, 1e-5);
    EXPECT_NEAR(img.at(4, 16).g, 1.5, 1e-5);
    EXPECT_NEAR(img.at(28, 16).r, 5.0, 1e-5) << "the other polygon's own gain, per point";
    EXPECT_NEAR(img.at(28, 16).g, 5.0, 1e-5) << "and the default tint";
    EXPECT_NE(err.find("primitive variable \"label\" (varying string)"), std::string::npos) << err;
}
