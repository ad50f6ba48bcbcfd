// archives_test.cpp: DelayedReadArchive loaded only when a ray first reaches its bound
// (render_with_archives.h): in view it renders as if read at once, behind the camera it
// is never read, an archive inside an archive takes another round, and one out of view
// that a shadow ray reaches casts its shadow.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "render_harness.h"

using rd::test::Rendered;
using rd::test::renderRib;

namespace {

std::string archiveDir() {
    static std::string d = [] {
        std::string p = rd::test::scratchDir("raydrive_archives");
        std::filesystem::create_directories(p);
        std::ofstream(p + "/sphere.rib") << "Sphere 1 -1 1 360\n";
        std::ofstream(p + "/outer.rib") << "Procedural \"DelayedReadArchive\" [\"" + p +
                                               "/sphere.rib\"] [-1 1 -1 1 -1 1]\n";
        std::ofstream(p + "/occluder.rib")
            << "Polygon \"P\" [3 -0.5 2  4 -0.5 2  4 0.5 2  3 0.5 2]\n";
        return p;
    }();
    return d;
}

const char* kView = "Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                    "ScreenWindow -2 2 -2 2\nWorldBegin\nSurface \"constant\"\n";

std::string delayed(const std::string& file, const std::string& where) {
    return "AttributeBegin\n" + where + "\nProcedural \"DelayedReadArchive\" [\"" +
           archiveDir() + "/" + file + "\"] [-1 1 -1 1 -1 1]\nAttributeEnd\n";
}

}  // namespace

TEST(Archives, LoadedWhenARayReachesTheirBoundOnly) {
    ::testing::internal::CaptureStderr();
    Rendered img = renderRib(std::string(kView) + delayed("sphere.rib", "Translate 0 0 5") +
                             delayed("never.rib", "Translate 0 0 -50") + "WorldEnd\n");
    std::string err = ::testing::internal::GetCapturedStderr();
    Rendered direct = renderRib(std::string(kView) + "Translate 0 0 5\nSphere 1 -1 1 360\nWorldEnd\n");
    EXPECT_EQ(img.stats.archivesLoaded, 1u);
    EXPECT_EQ(err.find("never.rib"), std::string::npos) << "an archive no ray reaches is not read: " << err;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) EXPECT_EQ(img.at(x, y).a, direct.at(x, y).a) << x << " " << y;
    EXPECT_EQ(img.at(16, 16).a, 1.0f);
}

TEST(Archives, AnArchiveInsideAnArchiveTakesAnotherRound) {
    Rendered img = renderRib(std::string(kView) + delayed("outer.rib", "Translate 0 0 5") + "WorldEnd\n");
    EXPECT_EQ(img.stats.archivesLoaded, 2u);
    EXPECT_EQ(img.at(16, 16).a, 1.0f);
    EXPECT_EQ(img.at(1, 1).a, 0.0f);
}

// The occluder's archive is out of view (x in [3, 4] at z = 2); a distant light along
// (-1, 0, 1) throws its shadow onto the wall at z = 5 over x in [0, 1].
TEST(Archives, AShadowRayLoadsAnArchiveOutOfView) {
    Rendered img = renderRib("Format 32 32 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
                             "ScreenWindow -2 2 -2 2\nWorldBegin\n"
                             "LightSource \"distantlight\" 1 \"from\" [1 0 -1] \"to\" [0 0 0]\n"
                             "Surface \"matte\"\n" +
                             delayed("occluder.rib", "Translate 3.5 0 2\nScale 0.5 0.5 0.1\nTranslate -3.5 0 -2") +
                             "Polygon \"P\" [-8 -8 5  8 -8 5  8 8 5  -8 8 5]\nWorldEnd\n");
    EXPECT_EQ(img.stats.archivesLoaded, 1u);
    EXPECT_NEAR(img.at(20, 16).r, 0.0, 1e-6) << "x = 0.56: in the shadow";
    EXPECT_GT(img.at(8, 16).r, 0.5) << "x = -0.94: lit";
}
