// exr_output_test.cpp: the OpenEXR writer round-trips float and half RGBA and RGB, keeps
// metadata, and never leaves a partial file behind when it cannot write.
#include <gtest/gtest.h>

#include <filesystem>

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <unistd.h>

#include "film/exr_output.h"

using namespace rd;

namespace {
std::string tempPath(const char* name) {
    return (std::filesystem::temp_directory_path() /
            (std::string(name) + std::to_string(::getpid()) + ".exr"))
        .string();
}
std::vector<Rgba> gradient(int w, int h) {
    std::vector<Rgba> px;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            px.push_back({x / float(w), y / float(h), 0.125f, (x + y) % 2 ? 1.0f : 0.5f});
    return px;
}
}  // namespace

TEST(ExrOutput, FloatRgbaRoundTripsExactly) {
    std::string path = tempPath("rgba");
    auto px = gradient(7, 5);
    ExrOptions o;
    o.metadata["raydrive:device"] = "test device";
    writeExr(path, 7, 5, px, o);
    int w = 0, h = 0;
    auto back = readExr(path, w, h);
    ASSERT_EQ(w, 7);
    ASSERT_EQ(h, 5);
    for (size_t i = 0; i < px.size(); ++i) {
        EXPECT_EQ(back[i].r, px[i].r);
        EXPECT_EQ(back[i].a, px[i].a);
    }
    Imf::InputFile f(path.c_str());
    auto* attr = f.header().findTypedAttribute<Imf::StringAttribute>("raydrive:device");
    ASSERT_NE(attr, nullptr);
    EXPECT_EQ(attr->value(), "test device");
    std::filesystem::remove(path);
}

TEST(ExrOutput, HalfAndRgbModes) {
    std::string path = tempPath("half");
    auto px = gradient(4, 4);
    ExrOptions o;
    o.halfFloat = true;
    o.alpha = false;
    writeExr(path, 4, 4, px, o);
    Imf::InputFile f(path.c_str());
    EXPECT_EQ(f.header().channels().findChannel("A"), nullptr);
    ASSERT_NE(f.header().channels().findChannel("R"), nullptr);
    EXPECT_EQ(f.header().channels().findChannel("R")->type, Imf::HALF);
    int w, h;
    auto back = readExr(path, w, h);
    for (size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(back[i].g, px[i].g, 1e-3);
    std::filesystem::remove(path);
}

TEST(ExrOutput, FailureLeavesNoFile) {
    std::string dir = (std::filesystem::temp_directory_path() / "raydrive-no-such-dir").string();
    std::filesystem::remove_all(dir);
    EXPECT_THROW(writeExr(dir + "/x.exr", 2, 2, gradient(2, 2), {}), std::runtime_error);
    EXPECT_FALSE(std::filesystem::exists(dir));
    EXPECT_THROW(writeExr(tempPath("bad"), 3, 3, gradient(2, 2), {}), std::runtime_error);
}

// A crop window is written as the data window inside the full display window.
TEST(ExrOutput, CropWindowIsTheDataWindow) {
    std::string path = tempPath("crop");
    ExrOptions o;
    o.dataX = 3, o.dataY = 2, o.displayWidth = 10, o.displayHeight = 8;
    writeExr(path, 4, 3, gradient(4, 3), o);
    Imf::InputFile f(path.c_str());
    EXPECT_EQ(f.header().dataWindow().min.x, 3);
    EXPECT_EQ(f.header().dataWindow().max.y, 4);
    EXPECT_EQ(f.header().displayWindow().max.x, 9);
    int w, h;
    auto back = readExr(path, w, h);
    ASSERT_EQ(w, 4);
    ASSERT_EQ(h, 3);
    EXPECT_EQ(back[5].r, gradient(4, 3)[5].r);
    std::filesystem::remove(path);
}
