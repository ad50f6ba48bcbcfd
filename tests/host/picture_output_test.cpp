// picture_output_test.cpp: a Display whose name is not OpenEXR (.tif, .png, ...) is that
// format, written through OpenImageIO and quantized as Quantize says (RI's default: 8
// bits, dither 0.5); a secondary display too. Before, such files held OpenEXR data.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render_harness.h"
#include "texture/texture_backend.h"

namespace {

// The first bytes of a file.
std::string magic(const std::string& file, size_t n) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes(n, '\0');
    in.read(bytes.data(), std::streamsize(n));
    return bytes;
}

// Renders a constant square of Cs (0.2, 0.4, 0.6) that fills a 16 x 16 frame, with the
// given options, and writes its files as the command does.
void render(const std::string& options) {
    const std::string messages = rd::test::renderRibToFiles(
        options +
        "Format 16 16 1\nPixelSamples 1 1\nProjection \"orthographic\"\n"
        "Translate 0 0 5\nWorldBegin\nSurface \"constant\"\nColor [0.2 0.4 0.6]\n"
        "Polygon \"P\" [-2 -2 0  2 -2 0  2 2 0  -2 2 0]\nWorldEnd\n");
    EXPECT_EQ(messages.find("warning"), std::string::npos) << messages;
}

// Channels [0, channels) of pixel (8, 8) of a picture, as floats of full scale 1.
std::vector<float> centre(const std::string& file, int channels) {
    rd::ImageInfo info;
    std::string error;
    EXPECT_TRUE(rd::textureBackend().describe(file, info, &error)) << error;
    EXPECT_EQ(info.width, 16);
    EXPECT_EQ(info.channels, channels);
    std::vector<float> v(static_cast<size_t>(channels));
    EXPECT_TRUE(rd::textureBackend().read(file, 0, 8, 9, 8, 9, channels, v.data(),
                                          sizeof(float) * size_t(channels),
                                          sizeof(float) * size_t(channels), &error))
        << error;
    return v;
}

}  // namespace

TEST(PictureOutput, ADisplaysNameGivesItsFormat) {
    const std::string dir = rd::test::scratchDir("pictures");
    std::filesystem::create_directories(dir);
    render("Display \"" + dir +
           "/out.tif\" \"tiff\" \"rgba\"\n"
           "Display \"+" +
           dir + "/cs.png\" \"file\" \"Cs\"\n");
    EXPECT_EQ(magic(dir + "/out.tif", 4), std::string("II*\0", 4));
    EXPECT_EQ(magic(dir + "/cs.png", 4), "\x89PNG");
    // RI's default Quantize: 8 bits with a dither of half a level
    const std::vector<float> rgba = centre(dir + "/out.tif", 4);
    EXPECT_NEAR(rgba[1], 0.4f, 1.0f / 255);
    EXPECT_NEAR(rgba[3], 1.0f, 1e-6f);
    EXPECT_NEAR(centre(dir + "/cs.png", 3)[2], 0.6f, 1.0f / 255);
    // Quantize "rgba" 0 ...: floats; 65535: 16 bits
    render("Quantize \"rgba\" 0 0 0 0\nDisplay \"" + dir +
           "/float.tif\" \"file\" \"rgb\"\n");
    EXPECT_NEAR(centre(dir + "/float.tif", 3)[0], 0.2f, 1e-7f);
    render("Quantize \"rgba\" 65535 0 65535 0.5\nDisplay \"" + dir +
           "/deep.png\" \"file\" \"rgb\"\n");
    EXPECT_NEAR(centre(dir + "/deep.png", 3)[0], 0.2f, 1.0f / 65535);
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.exr"));
}
