// exr_compare.cpp: exr_compare A.exr B.exr TOLERANCE: exits 0 when the two images have the
// same data window and every RGBA value agrees within TOLERANCE (absolute), 1 otherwise,
// printing the largest difference. The Oclgrind cases compare its render with PoCL's.
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

// The R, G, B, A channels as floats, 4 a pixel; `window` gets the data window.
static std::vector<float> readRgba(const char* path, Imath::Box2i& window) {
    Imf::InputFile in(path);
    window = in.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<float> px(size_t(w) * h * 4, 0.0f);
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B", "A"};
    char* base = reinterpret_cast<char*>(px.data()) -
                 (size_t(window.min.x) + size_t(window.min.y) * w) * 4 * sizeof(float);
    for (int c = 0; c < 4; ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 4 * sizeof(float),
                                       size_t(w) * 4 * sizeof(float)));
    in.setFrameBuffer(fb);
    in.readPixels(window.min.y, window.max.y);
    return px;
}

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: exr_compare A.exr B.exr TOLERANCE\n");
        return 2;
    }
    try {
        Imath::Box2i wa, wb;
        const std::vector<float> pa = readRgba(argv[1], wa), pb = readRgba(argv[2], wb);
        if (wa != wb) {
            std::printf("data windows differ\n");
            return 1;
        }
        const int w = wa.max.x - wa.min.x + 1, h = wa.max.y - wa.min.y + 1;
        double worst = 0;
        for (size_t i = 0; i < pa.size(); ++i) {
            const double d = double(pa[i]) - pb[i];
            worst = std::isnan(d) ? INFINITY : std::fmax(worst, std::fabs(d));
        }
        std::printf("%dx%d, largest difference %.3g (tolerance %s)\n", w, h, worst, argv[3]);
        return worst <= std::atof(argv[3]) ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exr_compare: %s\n", e.what());
        return 2;
    }
}
