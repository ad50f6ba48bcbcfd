// render_harness.cpp: the in-process render used by the render tests.
#include "render_harness.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "../scratch_folder.h"
#include "ocl/device.h"
#include "render/frame_output.h"
#include "render/render_with_archives.h"
#include "rib/reader.h"
#include "scene/rib_builder.h"

namespace rd::test {

std::string scratchDir(const std::string& name) {
    return scratchFolder(name);
}

double Rendered::mean(int channel, int x0, int y0, int x1, int y1) const {
    double sum = 0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++n) {
            const Rgba& p = at(x, y);
            sum += channel == 0 ? p.r : channel == 1 ? p.g : channel == 2 ? p.b : p.a;
        }
    return n ? sum / n : 0.0;
}

// Never destroyed: released in the exit handlers, after the OpenCL implementation's own
// statics may be gone, it crashed Oclgrind's teardown (tests/oclgrind).
const ClContext& testContext() {
    static const ClContext* ctx = new ClContext(selectDevice(""));
    return *ctx;
}

Scene sceneOfWorld(const std::string& world) {
    std::ostringstream err;
    rib::Diagnostics diag(&err);
    RibBuilder b(diag, "probe.rib");
    rib::readString("WorldBegin\n" + world + "\nWorldEnd\n", "probe.rib", b, diag);
    EXPECT_EQ(diag.errorCount(), 0) << err.str();
    return b.scenes().empty() ? Scene() : b.scenes().back();
}

Rendered renderRib(const std::string& rib, const RenderSettings& settings) {
    rib::Diagnostics diag(&std::cerr);
    RibBuilder builder(diag, "test.rib");
    builder.setPixelFilter("box", 1, 1);  // (render_harness.h: unless the RIB gives one)
    rib::readString(rib, "test.rib", builder, diag);
    EXPECT_EQ(diag.errorCount(), 0) << diag.lastMessage();
    Rendered out;
    if (builder.scenes().empty()) {
        ADD_FAILURE() << "no world block rendered";
        return out;
    }
    Renderer renderer(testContext(), settings);
    Film film;
    auto readAgain = [&](const std::set<std::string>& loaded, rib::Diagnostics& d) {
        RibBuilder b(d, "test.rib");
        b.setPixelFilter("box", 1, 1);
        b.setLoadedProcedurals(loaded);
        rib::readString(rib, "test.rib", b, d);
        return std::move(b.scenes());
    };
    out.stats = renderWithArchives(renderer, readAgain, builder.scenes().front(), 0, film, diag);
    out.width = film.width;
    out.height = film.height;
    out.pixels = film.resolve();
    out.film = std::move(film);
    return out;
}

std::string renderRibToFiles(const std::string& rib) {
    std::ostringstream messages;
    rib::Diagnostics diag(&messages);
    RibBuilder builder(diag, "test.rib");
    rib::readString(rib, "test.rib", builder, diag);
    EXPECT_EQ(diag.errorCount(), 0) << messages.str();
    if (builder.scenes().empty()) {
        ADD_FAILURE() << "no world block rendered";
        return messages.str();
    }
    const Scene& s = builder.scenes()[0];
    Renderer renderer(testContext(), {});
    Film film;
    const RenderStats st = renderer.render(s, film, diag);
    writeFrameImage(frameOutputName(s, "", 0, 1), s, film, st, {}, false, "test.rib");
    return messages.str();
}

std::string patchUnder(const std::string& dir, int spp, const std::string& surface,
                       const std::string& above) {
    return "Option \"searchpath\" \"shader\" [\"" + dir +
           ":&\"]\nFormat 16 16 1\nPixelSamples " + std::to_string(spp) + " " +
           std::to_string(spp) +
           "\nProjection \"orthographic\"\nScreenWindow -0.05 0.05 -0.05 "
           "0.05\nWorldBegin\n"
           "AttributeBegin\nSurface \"constant\"\nColor [1 0.5 0.25]\n" +
           above + "AttributeEnd\nSurface " + surface +
           "\nPolygon \"P\" [-1 -1 5  1 -1 5  1 1 5  -1 1 5]\nWorldEnd\n";
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
}

}  // namespace rd::test
