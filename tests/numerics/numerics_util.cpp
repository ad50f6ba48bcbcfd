// numerics_util.cpp: the report line, the render that keeps its diagnostics, RIB helpers.
#include "numerics_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "rib/reader.h"
#include "scene/rib_builder.h"

namespace rd::numerics {

bool report(const std::string& name, double tolerance, double measured) {
    std::printf("NUMERICS case=%s tolerance=%.3g measured=%.3g\n", name.c_str(), tolerance,
                measured);
    std::fflush(stdout);
    return measured <= tolerance;
}

Diagnosed renderWithDiagnostics(const std::string& rib, const RenderSettings& settings) {
    std::ostringstream text;
    rib::Diagnostics diag(&text);
    RibBuilder builder(diag, "test.rib");
    builder.setPixelFilter("box", 1, 1);  // (as renderRib: per-pixel references)
    rib::readString(rib, "test.rib", builder, diag);
    Diagnosed out;
    if (builder.scenes().empty()) {
        ADD_FAILURE() << "no world block rendered\n" << text.str();
        return out;
    }
    Renderer renderer(rd::test::testContext(), settings);
    Film film;
    out.image.stats = renderer.render(builder.scenes().front(), film, diag);
    out.image.width = film.width;
    out.image.height = film.height;
    out.image.pixels = film.resolve();
    out.image.film = std::move(film);
    out.messages = text.str();
    out.warnings = diag.warningCount();
    out.errors = diag.errorCount();
    return out;
}

int countOf(const std::string& text, const std::string& needle) {
    int n = 0;
    for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
    return n;
}

std::string camera(int res, double fovDeg, int spp) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "Format %d %d 1\nPixelSamples %d %d\nProjection \"perspective\" \"fov\" %.9g\n",
                  res, res, spp, spp, fovDeg);
    return buf;
}

std::string squareAtZ(double z, double h) {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "Polygon \"P\" [%.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g]\n",
                  -h, -h, z, h, -h, z, h, h, z, -h, h, z);
    return buf;
}

double maxAbs(const rd::test::Rendered& img) {
    double m = 0;
    for (const Rgba& p : img.pixels)
        m = std::fmax(m, std::fmax(std::fmax(std::fabs(p.r), std::fabs(p.g)),
                                   std::fmax(std::fabs(p.b), std::fabs(p.a))));
    return m;
}

bool allFinite(const rd::test::Rendered& img) {
    for (const Rgba& p : img.pixels)
        if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b) ||
            !std::isfinite(p.a))
            return false;
    return true;
}

}  // namespace rd::numerics
