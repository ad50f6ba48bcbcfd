// exr_compare.cpp: exr_compare A.exr B.exr TOLERANCE: exits 0 when the two images have the
// same size and every RGBA value agrees within TOLERANCE (absolute), 1 otherwise, printing
// the largest difference. The Oclgrind cases compare its render with PoCL's.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "host/film/exr_output.h"

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: exr_compare A.exr B.exr TOLERANCE\n");
        return 2;
    }
    try {
        int wa = 0, ha = 0, wb = 0, hb = 0;
        const auto a = rd::readExr(argv[1], wa, ha), b = rd::readExr(argv[2], wb, hb);
        if (wa != wb || ha != hb) {
            std::printf("sizes differ: %dx%d against %dx%d\n", wa, ha, wb, hb);
            return 1;
        }
        double worst = 0;
        for (size_t i = 0; i < a.size(); ++i)
            for (double d : {double(a[i].r) - b[i].r, double(a[i].g) - b[i].g,
                             double(a[i].b) - b[i].b, double(a[i].a) - b[i].a})
                worst = std::isnan(d) ? INFINITY : std::fmax(worst, std::fabs(d));
        std::printf("%dx%d, largest difference %.3g (tolerance %s)\n", wa, ha, worst, argv[3]);
        return worst <= std::atof(argv[3]) ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "exr_compare: %s\n", e.what());
        return 2;
    }
}
