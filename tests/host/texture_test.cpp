// texture_test.cpp: textures (issue 9) through the whole pipeline: texture making,
// filtered lookups against a supersampled reference at a grazing angle, a tile cache
// far smaller than the texture giving the resident image exactly, lat-long environment
// and shadow maps against their closed forms, textureinfo(), bump mapping, and missing
// or corrupt files reported with the file and the shader while the render goes on.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <OpenImageIO/imagebuf.h>

#include <zlib.h>

#include "film/exr_output.h"
#include "render_harness.h"
#include "rib/reader.h"
#include "scene/depth_map.h"
#include "scene/rib_builder.h"
#include "texture/texture_maker.h"

using rd::test::Rendered;
using rd::test::renderRib;
namespace OIIO = OIIO_NAMESPACE;

namespace {

std::string dir() {
    static std::string d = [] {
        std::string p = rd::test::scratchDir("raydrive_textures");
        std::filesystem::create_directories(p);
        std::ofstream(p + "/texcheck.sl")
            << "surface texcheck(string map = \"\"; float rep = 1; float width = 1;) {\n"
               "    Ci = color texture(map, s * rep, t * rep, \"width\", width);\n"
               "    Oi = 1;\n}\n";
        std::ofstream(p + "/texop.sl")
            << "surface texop(string map = \"\";) {\n"
               "    Oi = float texture(map, s, t);\n    Ci = 0;\n}\n";
        std::ofstream(p + "/envlook.sl")
            << "surface envlook(string map = \"\"; vector dir = (0, 0, -1);) {\n"
               "    Ci = color environment(map, dir);\n    Oi = 1;\n}\n";
        std::ofstream(p + "/shadowlook.sl")
            << "surface shadowlook(string map = \"\";) {\n"
               "    Ci = 1 - shadow(map, P, \"bias\", 0.1);\n    Oi = 1;\n}\n";
        std::ofstream(p + "/texinfo.sl")
            << "surface texinfo(string map = \"\";) {\n"
               "    float res[2] = {0, 0}; float ch = 0;\n"
               "    float ok = textureinfo(map, \"resolution\", res) + textureinfo(map, \"channels\", ch);\n"
               "    Ci = color(res[0], res[1], ch * ok / 2);\n    Oi = 1;\n}\n";
        return p;
    }();
    return d;
}

// An n x n image of `squares` x `squares` black and white squares (one channel), or an
// RGB one whose colour follows the texel (for equality tests).
std::string picture(const std::string& name, int n, int squares, bool rgb,
                    bool stripes = false) {
    OIIO::ImageSpec spec(n, n, rgb ? 3 : 1, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf img(spec);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float c = float(((x * squares / n) + (stripes ? 0 : y * squares / n)) % 2);
            float px[3] = {c, rgb ? float(x) / n : c, rgb ? float(y) / n : c};
            img.setpixel(x, y, px, rgb ? 3 : 1);
        }
    std::string path = dir() + "/" + name;
    EXPECT_TRUE(img.write(path)) << img.geterror();
    return path;
}

std::string texture(const std::string& name, int n, int squares, bool rgb,
                    const std::string& wrap = "periodic", bool stripes = false) {
    std::string tex = dir() + "/" + name + ".tex";
    rd::MakeTextureOptions o;
    o.swrap = o.twrap = wrap;
    rd::makeTexture(picture(name + ".exr", n, squares, rgb, stripes), tex, o);
    return tex;
}

std::string searchPath() { return "Option \"searchpath\" \"shader\" [\"" + dir() + ":&\"]\n"; }

// A floor from the eye's feet to 400 units away, seen at a grazing angle; its texture
// repeats `rep` times.
Rendered floorScene(const std::string& tex, int samples, float width, int size = 48,
                    int rep = 64) {
    return renderRib(searchPath() + "Format " + std::to_string(size) + " " +
                     std::to_string(size) + " 1\nPixelSamples " +
                     std::to_string(samples) + " " + std::to_string(samples) +
                     "\nProjection \"perspective\" \"fov\" 40\nWorldBegin\n"
                     "Surface \"texcheck\" \"map\" \"" +
                     tex + "\" \"rep\" " + std::to_string(rep) + " \"width\" " +
                     std::to_string(width) +
                     "\nPolygon \"P\" [-50 -1 2  50 -1 2  50 -1 400  -50 -1 400]"
                     " \"st\" [0 0  1 0  1 1  0 1]\nWorldEnd\n");
}

double rmsBelowHorizon(const Rendered& a, const Rendered& b, int rows0, int rows1) {
    double sum = 0;
    int n = 0;
    for (int y = rows0; y < rows1; ++y)
        for (int x = 0; x < a.width; ++x) {
            double d = a.at(x, y).r - b.at(x, y).r;
            sum += d * d;
            ++n;
        }
    return std::sqrt(sum / n);
}

}  // namespace

// A checkerboard floor at a grazing angle: one sample a pixel with the filter (trilinear
// over the footprint) against 16 x 16 point samples a pixel (the pixel's box average),
// compared with one point sample a pixel (aliased). Rows 25..32 are the distant floor,
// where the checks are far smaller than a pixel.
TEST(Textures, GrazingCheckerboardIsFilteredNotAliased) {
    std::string tex = texture("checker", 256, 32, false);
    Rendered reference = floorScene(tex, 16, 0.0f);
    Rendered filtered = floorScene(tex, 1, 1.0f);
    Rendered pointSampled = floorScene(tex, 1, 0.0f);
    const double eFiltered = rmsBelowHorizon(filtered, reference, 25, 33);
    const double eAliased = rmsBelowHorizon(pointSampled, reference, 25, 33);
    std::printf("NUMERICS case=grazing_checker_filtered_rms tolerance=0.12 measured=%.3g\n", eFiltered);
    std::printf("NUMERICS case=grazing_checker_point_sampled_rms (for comparison) measured=%.3g\n", eAliased);
    EXPECT_LT(eFiltered, 0.12);
    EXPECT_LT(eFiltered, 0.5 * eAliased) << "filtering must remove most of the aliasing";
    EXPECT_TRUE(filtered.stats.features.textures);
}

// Stripes across the floor (s only; 8 texels wide, the texture repeated 16 times: each
// stripe 0.2 units wide) seen at a grazing angle, where a pixel's footprint is 5-10
// times longer in t (depth) than in s. Rows 31..39, where the stripes are 1.3-3 pixels
// wide: 4 x 4 filtered samples a pixel against 16 x 16 point samples (the box average),
// RMS. Filtering at the mip level of the footprint's long side (trilinear alone, before
// session 30) blurred the stripes across (RMS 0.081; 0.053 now); probes along the long
// side at the level of the short one keep them.
TEST(Textures, AnisotropicFootprintKeepsDetailAcrossIt) {
    std::string tex = texture("stripes", 256, 32, false, "periodic", /*stripes=*/true);
    Rendered reference = floorScene(tex, 16, 0.0f, 48, 16);
    Rendered filtered = floorScene(tex, 4, 1.0f, 48, 16);
    const double e = rmsBelowHorizon(filtered, reference, 31, 40);
    std::printf(
        "NUMERICS case=grazing_stripes_anisotropic_rms tolerance=0.065 measured=%.3g\n",
        e);
    EXPECT_LT(e, 0.065);
}

// A texture of 341 tiles through a cache of 64: tiles stream in as lookups miss, the
// points that missed are shaded again, and the image is exactly the resident one.
TEST(Textures, CacheOverflowEqualsResident) {
    std::string tex = texture("colours", 512, 16, true);
    auto scene = searchPath() +
                 "Format 96 96 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 50\n"
                 "WorldBegin\nSurface \"texcheck\" \"map\" \"" + tex + "\" \"rep\" 2\n"
                 "Polygon \"P\" [-3 -1 2  3 -1 2  3 1 8  -3 1 8] \"st\" [0 0  1 0  1 1  0 1]\n"
                 "WorldEnd\n";
    Rendered resident = renderRib(scene);
    rd::RenderSettings small;
    small.textureCacheTiles = 64;
    Rendered streamed = renderRib(scene, small);
    EXPECT_TRUE(resident.stats.textures.resident);
    EXPECT_FALSE(streamed.stats.textures.resident);
    EXPECT_EQ(streamed.stats.textures.cacheTiles, 64u);
    EXPECT_GT(streamed.stats.textures.totalTiles, 300u);
    EXPECT_GT(streamed.stats.textures.retryPasses, 0u);
    EXPECT_EQ(streamed.stats.textures.unresolved, 0u);
    EXPECT_LT(streamed.stats.textures.hitRate(), 1.0);
    size_t differ = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x)
            for (int c = 0; c < 4; ++c)
                differ += (&resident.at(x, y).r)[c] != (&streamed.at(x, y).r)[c];
    EXPECT_EQ(differ, 0u);
}

// Shadows through a surface whose shader takes its opacity from a texture (transmission
// "shader": a leaf's alpha map). A square of 2 x 2 black and white texels the camera does
// not see, over a floor lit straight on: under its white (opaque) quarters the floor is 0,
// under the black ones 1. With a cache of 4 tiles the shadow rays' lookups miss, are shaded
// again once their tiles are there, and give the same image.
TEST(Textures, ShadowsThroughATexturesOpacity) {
    std::string tex = texture("opacity", 256, 2, false, "clamp");
    auto scene = searchPath() +
                 "Format 32 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
                 "ScreenWindow -1 1 -1 1\nTranslate 0 0 5\nWorldBegin\n"
                 "LightSource \"distantlight\" 1 \"from\" [0 0 0] \"to\" [0 0 1]\n"
                 "Surface \"matte\"\nPolygon \"P\" [-9 -9 0  9 -9 0  9 9 0  -9 9 0]\n"
                 "Attribute \"visibility\" \"int camera\" [0]\n"
                 "Attribute \"visibility\" \"string transmission\" [\"shader\"]\n"
                 "Surface \"texop\" \"map\" \"" + tex + "\"\n"
                 "Polygon \"P\" [-2 -2 -1  2 -2 -1  2 2 -1  -2 2 -1] \"st\" [0 0  1 0  1 1  0 1]\n"
                 "WorldEnd\n";
    Rendered resident = renderRib(scene);
    rd::RenderSettings small;
    small.textureCacheTiles = 4;
    Rendered streamed = renderRib(scene, small);
    EXPECT_TRUE(resident.stats.features.shaderShadows);
    EXPECT_GT(streamed.stats.textures.retryPasses, 0u);
    EXPECT_EQ(streamed.stats.textures.unresolved, 0u);
    // (the square spans the frame twice over: each quarter of the frame is one texel)
    const double quarter[2][2] = {{resident.mean(0, 2, 2, 14, 14), resident.mean(0, 18, 2, 30, 14)},
                                  {resident.mean(0, 2, 18, 14, 30), resident.mean(0, 18, 18, 30, 30)}};
    EXPECT_NEAR(quarter[0][0] + quarter[0][1], 1.0, 1e-5);  // one white, one black
    EXPECT_NEAR(quarter[0][0] * quarter[0][1], 0.0, 1e-5);
    EXPECT_NEAR(quarter[0][0], quarter[1][1], 1e-5);  // a checker
    EXPECT_NEAR(quarter[0][1], quarter[1][0], 1e-5);
    size_t differ = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) differ += resident.at(x, y).r != streamed.at(x, y).r;
    EXPECT_EQ(differ, 0u);
}

// Texels are RGB: under ColorSamples they come into the scene's channels through RGBn.
// With red and blue swapped the image is the RGB one exactly; with one luminance channel
// (shown grey) every pixel is the RGB image's luminance (the lookups are linear).
TEST(Textures, TexelsEnterTheScenesColourChannels) {
    std::string tex = texture("colours", 512, 16, true);
    auto scene = [&](const std::string& colorSamples) {
        // (a pixel error of 1e-9: every pixel takes all its samples, whatever its channels show)
        return renderRib(searchPath() + colorSamples + "Option \"render\" \"float pixelerror\" [1e-9]\n"
                         "Format 32 32 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" 50\n"
                         "WorldBegin\nSurface \"texcheck\" \"map\" \"" + tex + "\" \"rep\" 2\n"
                         "Polygon \"P\" [-3 -1 2  3 -1 2  3 1 8  -3 1 8] \"st\" [0 0  1 0  1 1  0 1]\n"
                         "WorldEnd\n");
    };
    Rendered rgb = scene("");
    Rendered swapped = scene("ColorSamples [0 0 1 0 1 0 1 0 0] [0 0 1 0 1 0 1 0 0]\n");
    Rendered grey = scene("ColorSamples [1 1 1] [0.299 0.587 0.114]\n");
    double spread = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const rd::Rgba &a = rgb.at(x, y), &b = swapped.at(x, y), &c = grey.at(x, y);
            ASSERT_EQ(a.r, b.r);
            ASSERT_EQ(a.g, b.g);
            ASSERT_EQ(a.b, b.b);
            const float lum = 0.299f * a.r + 0.587f * a.g + 0.114f * a.b;
            ASSERT_NEAR(c.r, lum, 1e-5f) << x << ", " << y;
            ASSERT_EQ(c.r, c.g);
            ASSERT_EQ(c.r, c.b);
            spread += std::fabs(a.r - a.b);
        }
    EXPECT_GT(spread, 1.0);  // the texture is coloured: the swap is no identity
}

// Missing and corrupt files: a warning names the map, the shader that asked and why; the
// lookups give the default (0) and the render goes on.
TEST(Textures, MissingAndCorruptFilesAreReportedAndRenderTheDefault) {
    std::ofstream(dir() + "/corrupt.tex") << "this is not an image";
    for (const std::string& name : {std::string("no_such_map.tex"), dir() + "/corrupt.tex"}) {
        ::testing::internal::CaptureStderr();
        Rendered img = renderRib(searchPath() +
                                 "Format 8 8 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                                 "WorldBegin\nSurface \"texcheck\" \"map\" \"" + name + "\"\n"
                                 "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
        std::string err = ::testing::internal::GetCapturedStderr();
        EXPECT_NE(err.find("shader \"texcheck\" asked for texture \"" + name + "\""), std::string::npos) << err;
        EXPECT_NE(err.find(name.find("corrupt") != std::string::npos ? "cannot read" : "file not found"),
                  std::string::npos) << err;
        EXPECT_EQ(img.at(4, 4).r, 0.0f);
        EXPECT_EQ(img.at(4, 4).a, 1.0f) << "the surface still renders";
    }
}

// A picture whose header claims more pixels than a texture may have is refused before
// it is read (a 436-byte PNG claiming 60000 x 60000 had its read ask for 43 GB, which a
// machine with that much memory would have given), with one line that says why.
TEST(Textures, PictureTooLargeIsRefusedBeforeItIsRead) {
    auto chunk = [](const std::string& type, const std::string& data) {
        auto be32 = [](uint32_t v) {
            return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
        };
        const std::string td = type + data;
        return be32(uint32_t(data.size())) + td +
               be32(uint32_t(crc32(0, reinterpret_cast<const Bytef*>(td.data()), uInt(td.size()))));
    };
    std::string ihdr = {0, 0, char(0xea), 0x60, 0, 0, char(0xea), 0x60, 8, 2, 0, 0, 0};
    const std::string row(1 + 60000 * 3, '\0');
    std::string z(compressBound(uLong(row.size())), '\0');
    uLongf zn = uLongf(z.size());
    compress(reinterpret_cast<Bytef*>(&z[0]), &zn, reinterpret_cast<const Bytef*>(row.data()),
             uLong(row.size()));
    z.resize(zn);
    const std::string path = dir() + "/huge.png";
    std::ofstream(path, std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8)
                                          << chunk("IHDR", ihdr) << chunk("IDAT", z)
                                          << chunk("IEND", "");
    try {
        rd::makeTexture(path, dir() + "/huge.tex", rd::MakeTextureOptions{});
        FAIL() << "a 60000 x 60000 picture was made into a texture";
    } catch (const std::exception& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("is 60000 x 60000 pixels: a texture may have at most 2^28"),
                  std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

// Lat-long environment: +y up at t = 0, s = 0.5 looking along -z, s growing toward +x.
// The map's red is s and green t (of its texel centres), so a direction reads back where
// it looks: (1, 0, 0) at s = 0.75, t = 0.5; (0, 0, -1) at s = 0.5.
TEST(Textures, LatLongEnvironmentDirections) {
    const int w = 64, h = 32;
    OIIO::ImageBuf img(OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float px[3] = {(x + 0.5f) / w, (y + 0.5f) / h, 0.0f};
            img.setpixel(x, y, px, 3);
        }
    ASSERT_TRUE(img.write(dir() + "/sky.exr"));
    rd::makeLatLongEnvironment(dir() + "/sky.exr", dir() + "/sky.env", {});
    struct Case {
        const char* dir;
        float s, t;
    };
    for (const Case c : {Case{"1 0 0", 0.75f, 0.5f}, Case{"0 0 -1", 0.5f, 0.5f},
                         Case{"-1 0 0", 0.25f, 0.5f}, Case{"0 1 -1", 0.5f, 0.25f}}) {
        Rendered r = renderRib(searchPath() +
                               "Format 4 4 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                               "WorldBegin\nSurface \"envlook\" \"map\" \"" + dir() +
                               "/sky.env\" \"vector dir\" [" + c.dir + "]\n"
                               "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
        EXPECT_NEAR(r.at(2, 2).r, c.s, 1.0 / w) << c.dir;
        EXPECT_NEAR(r.at(2, 2).g, c.t, 1.0 / h) << c.dir;
    }
}

// A shadow map made from a depth image with its light's matrices: a light at the origin
// looking down +z orthographically over [-4, 4]^2, the depth 5 (the wall) except a square
// at depth 2 over x, y in [-1, 1] (an occluder). The wall at z = 5 is unshadowed (1)
// except behind the square (0).
TEST(Textures, ShadowMapShadowsBehindItsOccluder) {
    const int n = 64;
    OIIO::ImageSpec spec(n, n, 1, OIIO::TypeDesc::FLOAT);
    float toCamera[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    float toScreen[16] = {0.25f, 0, 0, 0, 0, 0.25f, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    spec.attribute("worldtocamera", OIIO::TypeMatrix, toCamera);
    spec.attribute("worldtoscreen", OIIO::TypeMatrix, toScreen);
    OIIO::ImageBuf depth(spec);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            float wx = -4 + 8 * (x + 0.5f) / n, wy = 4 - 8 * (y + 0.5f) / n;
            float z = std::fabs(wx) < 1 && std::fabs(wy) < 1 ? 2.0f : 5.0f;
            depth.setpixel(x, y, &z, 1);
        }
    ASSERT_TRUE(depth.write(dir() + "/depth.exr"));
    // through the RIB request, beside the scene (relative names are the RIB's folder's)
    Rendered r = renderRib(searchPath() + "MakeShadow \"" + dir() + "/depth.exr\" \"" + dir() +
                           "/light.shd\"\nFormat 16 16 1\nPixelSamples 1 1\n"
                           "Projection \"orthographic\"\nScreenWindow -4 4 -4 4\nWorldBegin\n"
                           "Surface \"shadowlook\" \"map\" \"" + dir() + "/light.shd\"\n"
                           "Polygon \"P\" [-8 -8 5  8 -8 5  8 8 5  -8 8 5]\nWorldEnd\n");
    EXPECT_NEAR(r.at(8, 8).r, 0.0, 1e-6) << "behind the occluder";
    EXPECT_NEAR(r.at(1, 1).r, 1.0, 1e-6) << "in the open";
    EXPECT_NEAR(r.at(14, 8).r, 1.0, 1e-6) << "in the open";
}

// textureinfo() knows a texture's resolution and channels.
TEST(Textures, TextureinfoResolutionAndChannels) {
    std::string tex = texture("info", 128, 4, true);
    Rendered r = renderRib(searchPath() +
                           "Format 4 4 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                           "WorldBegin\nSurface \"texinfo\" \"map\" \"" + tex + "\"\n"
                           "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
    EXPECT_EQ(r.at(2, 2).r, 128.0f);
    EXPECT_EQ(r.at(2, 2).g, 128.0f);
    EXPECT_EQ(r.at(2, 2).b, 3.0f);
}

// The standard bumpy displacement with a map: the bumps change the shading, and a map
// that is everywhere the same (so its slope is 0) does not.
TEST(Textures, BumpyDisplacesByItsMap) {
    std::string tex = texture("bumps", 64, 8, false);
    auto lit = [&](const std::string& disp) {
        return renderRib(searchPath() +
                         "Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                         "WorldBegin\nLightSource \"distantlight\" 1 \"from\" [1 1 -1] "
                         "\"to\" [0 0 0]\nSurface \"matte\"\n" + disp +
                         "\nPatch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 5]\nWorldEnd\n");
    };
    Rendered flat = lit(""), bumped = lit("Displacement \"bumpy\" \"texturename\" \"" + tex +
                                          "\" \"Km\" 0.05");
    int changed = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) changed += std::fabs(bumped.at(x, y).r - flat.at(x, y).r) > 0.01;
    EXPECT_GT(changed, 50) << "the checks' edges tilt the normal";
    EXPECT_LT(changed, 32 * 32) << "inside the checks the map is flat";
}

// bumpy as a true displacement: a 2 x 2 patch head on, its white checks raised by Km
// toward the camera or away (the patch's normal decides), the black ones left; the
// camera-space depth a pixel sees is then 5 - or + Km there, so its mean distance from 5
// is Km times the map's mean, 0.5 (the filtered lookups keep the mean; the pieces slope
// across each check's edge). As a bump map P stays on the patch: 0. With a tile cache far
// smaller than the map, the vertices whose lookups missed run again: the same image.
TEST(Textures, TrueDisplacementByAMap) {
    std::string tex = texture("heights", 256, 8, false);
    std::ofstream(dir() + "/depthlook.sl")
        << "surface depthlook() {\n    Ci = abs(zcomp(transform(\"camera\", P)) - 5);\n"
           "    Oi = 1;\n}\n";
    auto scene = [&](const std::string& attr) {
        return searchPath() +
               "Format 32 32 1\nPixelSamples 2 2\nProjection \"orthographic\"\n"
               "ScreenWindow -0.8 0.8 -0.8 0.8\nWorldBegin\nSurface \"depthlook\"\n" +
               attr + "Displacement \"bumpy\" \"texturename\" \"" + tex +
               "\" \"Km\" 0.2\n"
               "Patch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 5]\nWorldEnd\n";
    };
    const std::string truly = "Attribute \"render\" \"int truedisplacement\" [1]\n";
    Rendered bumped = renderRib(scene(""));
    EXPECT_NEAR(bumped.mean(0, 0, 0, 32, 32), 0.0, 1e-5);
    Rendered resident = renderRib(scene(truly));
    EXPECT_NEAR(resident.mean(0, 0, 0, 32, 32), 0.2 * 0.5, 0.01);
    EXPECT_GT(resident.stats.displacedVertices, 1000u);
    rd::RenderSettings small;
    small.textureCacheTiles = 8;
    Rendered streamed = renderRib(scene(truly), small);
    EXPECT_FALSE(streamed.stats.textures.resident);
    EXPECT_GT(streamed.stats.textures.totalTiles, 60u);
    EXPECT_EQ(streamed.stats.textures.unresolved, 0u);
    size_t differ = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) differ += resident.at(x, y).r != streamed.at(x, y).r;
    EXPECT_EQ(differ, 0u);
}

// A true displacement whose every vertex looks up more tiles than the texture cache can
// hold at once (80 scattered level-0 lookups, a cache of 64 tiles): its passes cannot
// finish, so after the last one the vertices are given up, left where they were, and
// said so at the Displacement's line; the render goes on (the surface undisplaced).
TEST(Textures, DisplacementOutgrowingTheCacheIsLeftInPlace) {
    std::string tex = texture("scatter", 1024, 64, false);
    std::ofstream(dir() + "/depthlook.sl")
        << "surface depthlook() {\n    Ci = abs(zcomp(transform(\"camera\", P)) - 5);\n"
           "    Oi = 1;\n}\n";
    std::ofstream(dir() + "/scatterbump.sl")
        << "displacement scatterbump(string map = \"\") {\n    float h = 0, i;\n"
           "    for (i = 0; i < 80; i += 1)\n"
           "        h += texture(map, mod(s + i * 0.0123, 1), mod(t + i * 0.0371, 1), "
           "\"width\", 0);\n"
           "    P += normalize(N) * 0.004 * (1 + h);\n    N = calculatenormal(P);\n}\n";
    const std::string rib =
        searchPath() +
        "Format 16 16 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
        "ScreenWindow -0.8 0.8 -0.8 0.8\nWorldBegin\nSurface \"depthlook\"\n"
        "Attribute \"render\" \"int truedisplacement\" [1]\n"
        "Attribute \"displacementbound\" \"float sphere\" [0.5]\n"
        "Displacement \"scatterbump\" \"map\" \"" +
        tex +
        "\"\n"
        "Patch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 5]\nWorldEnd\n";
    // every tile resident: each vertex moves at least 0.004 toward the eye or away
    Rendered resident = renderRib(rib);
    EXPECT_GT(resident.stats.displacedVertices, 100u);
    EXPECT_GT(resident.mean(0, 0, 0, 16, 16), 0.003);
    rd::RenderSettings small;
    small.textureCacheTiles = 64;
    ::testing::internal::CaptureStderr();
    Rendered streamed = renderRib(rib, small);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_FALSE(streamed.stats.textures.resident);
    EXPECT_EQ(streamed.stats.displacedVertices, 0u);
    EXPECT_NE(err.find("warning: displacement: the texture cache could not hold what "),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("vertices look up; they are left in place"), std::string::npos)
        << err;
    EXPECT_NEAR(streamed.mean(0, 0, 0, 16, 16), 0.0, 1e-4)
        << "the surface stays at z = 5";
}

// MakeBump makes a height map that bump() reads as MakeTexture's: the same image (before,
// MakeBump was ignored, the map never made, and bump() left N alone with a warning).
TEST(Textures, MakeBumpMakesAHeightMapForBump) {
    const std::string pic = picture("bumpsrc.exr", 64, 4, false);
    std::ofstream(dir() + "/bumplook.sl")
        << "surface bumplook(string map = \"\") {\n"
           "    normal n = normalize(bump(map, normalize(N), dPdu, dPdv));\n"
           "    Ci = abs(n . normalize(I));\n    Oi = 1;\n}\n";
    const std::string made = dir() + "/bumpmade.tex";
    std::filesystem::remove(made);
    auto scene = [&](const std::string& before, const std::string& map) {
        return searchPath() + before +
               "Format 32 32 1\nPixelSamples 1 1\nProjection "
               "\"orthographic\"\nWorldBegin\n"
               "Surface \"bumplook\" \"map\" \"" +
               map +
               "\"\nPatch \"bilinear\" \"P\" [-1 1 5  1 1 5  -1 -1 5  1 -1 "
               "5]\nWorldEnd\n";
    };
    Rendered viaBump = renderRib(scene("MakeBump \"" + pic + "\" \"" + made +
                                           "\" \"periodic\" \"periodic\" \"box\" 1 1\n",
                                       made));
    ASSERT_TRUE(std::filesystem::exists(made));
    rd::MakeTextureOptions o;
    o.swrap = o.twrap = "periodic";
    o.filter = "box";
    const std::string direct = dir() + "/bumpdirect.tex";
    rd::makeTexture(pic, direct, o);
    Rendered viaTexture = renderRib(scene("", direct));
    int tilted = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            EXPECT_EQ(viaBump.at(x, y).r, viaTexture.at(x, y).r);
            tilted += viaBump.at(x, y).r < 0.999f;
        }
    EXPECT_GT(tilted, 20) << "the map's edges tilt the normal";
}

// MakeCubeFaceEnvironment: six constant faces (+x red, -x green, +y blue, -y yellow,
// +z white, -z grey) resampled into a lat-long map; each axis reads its face's colour.
TEST(Textures, CubeFacesBecomeALatLongMap) {
    const float colours[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}};
    std::array<std::string, 6> faces;
    for (int f = 0; f < 6; ++f) {
        OIIO::ImageBuf img(OIIO::ImageSpec(16, 16, 3, OIIO::TypeDesc::FLOAT));
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) img.setpixel(x, y, colours[f], 3);
        faces[size_t(f)] = dir() + "/face" + std::to_string(f) + ".exr";
        ASSERT_TRUE(img.write(faces[size_t(f)]));
    }
    rd::makeCubeFaceEnvironment(faces, dir() + "/cube.env", 90.0f, {});
    const char* dirs[6] = {"1 0 0", "-1 0 0", "0 1 0", "0 -1 0", "0 0 1", "0 0 -1"};
    for (int f = 0; f < 6; ++f) {
        Rendered r = renderRib(searchPath() +
                               "Format 4 4 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                               "WorldBegin\nSurface \"envlook\" \"map\" \"" + dir() +
                               "/cube.env\" \"vector dir\" [" + dirs[f] + "]\n"
                               "Polygon \"P\" [-2 -2 5  2 -2 5  2 2 5  -2 2 5]\nWorldEnd\n");
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR((&r.at(2, 2).r)[c], colours[f][c], 1e-3) << dirs[f] << " channel " << c;
    }
}

// A scene whose shaders look nothing up gets no texture code or buffers.
TEST(Textures, ScenesWithoutTexturesGetNone) {
    Rendered r = renderRib("Format 4 4 1\nPixelSamples 1 1\nWorldBegin\nSurface \"matte\"\n"
                           "Sphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_FALSE(r.stats.features.textures);
    EXPECT_EQ(r.stats.program.options.find("RT_HAS_TEXTURES"), std::string::npos);
    EXPECT_EQ(r.stats.textures.textures, 0u);
}

// The whole shadow-map path: RayDrive renders a depth map from a perspective light at
// the origin (Display mode "z": Z and the camera's matrices, as raydrive writes it),
// MakeShadow makes it a shadow map, and a wall at z = 6 seen orthographically is dark
// exactly behind an occluder at z = 3 (half size 0.5: its shadow's half size is 1).
TEST(Textures, ShadowMapFromARenderedDepthMap) {
    const std::string occluder = "Polygon \"P\" [-0.5 -0.5 3  0.5 -0.5 3  0.5 0.5 3  -0.5 0.5 3]\n";
    const std::string wall = "Polygon \"P\" [-8 -8 6  8 -8 6  8 8 6  -8 8 6]\n";
    rd::RenderSettings depthSettings;
    depthSettings.geometricAovs = true;
    Rendered depth = renderRib("Format 128 128 1\nPixelSamples 1 1\nProjection \"perspective\" "
                               "\"fov\" 60\nDisplay \"light.z\" \"zfile\" \"z\"\nWorldBegin\n" +
                                   occluder + wall + "WorldEnd\n",
                               depthSettings);
    rib::Diagnostics diag(&std::cerr);
    rd::RibBuilder builder(diag, "light.rib");
    rib::readString("Format 128 128 1\nProjection \"perspective\" \"fov\" 60\nWorldBegin\nWorldEnd\n",
                    "light.rib", builder, diag);
    rd::DepthMapMatrices m = rd::depthMapMatrices(builder.scenes().front());
    rd::ExrOptions opts;
    opts.colour = false;
    opts.extra = depth.film.aovChannels("z");
    opts.matrices["worldToCamera"] = m.worldToCamera;
    opts.matrices["worldToScreen"] = m.worldToScreen;
    rd::writeExr(dir() + "/light.z.exr", 128, 128, depth.pixels, opts);
    rd::makeShadow(dir() + "/light.z.exr", dir() + "/rendered.shd");
    Rendered r = renderRib(searchPath() + "Format 32 32 1\nPixelSamples 1 1\n"
                           "Projection \"orthographic\"\nScreenWindow -4 4 -4 4\nWorldBegin\n"
                           "Surface \"shadowlook\" \"map\" \"" + dir() + "/rendered.shd\"\n" +
                           wall + "WorldEnd\n");
    // pixel (x, y) sees the wall at (-4 + (x + 0.5) / 4, 4 - (y + 0.5) / 4)
    EXPECT_NEAR(r.at(16, 16).r, 0.0, 1e-6) << "behind the occluder";
    EXPECT_NEAR(r.at(13, 13).r, 0.0, 1e-6) << "behind the occluder, near its corner";
    EXPECT_NEAR(r.at(10, 16).r, 1.0, 1e-6) << "beside the shadow";
    EXPECT_NEAR(r.at(2, 2).r, 1.0, 1e-6) << "in the open";
    // a light whose shadowname is the map: shadowed by the map alone (no shadow ray), so
    // the occluder's shadow is there even with the occluder left out of the scene
    Rendered lit = renderRib("Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                             "ScreenWindow -4 4 -4 4\nWorldBegin\n"
                             "LightSource \"shadowspot\" 1 \"from\" [0 0 0] \"to\" [0 0 1] "
                             "\"coneangle\" 1.2 \"intensity\" 36 \"shadowname\" \"" + dir() +
                             "/rendered.shd\"\nSurface \"matte\"\n" + wall + "WorldEnd\n");
    EXPECT_NEAR(lit.at(16, 16).r, 0.0, 1e-6) << "the map's shadow";
    EXPECT_GT(lit.at(10, 16).r, 0.5) << "lit beside it";
}
