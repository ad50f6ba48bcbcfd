// render_harness.h: renders a RIB string through the real pipeline (reader, Ri state
// machine, BVH, kernels on the default OpenCL device) and returns the resolved image, for
// render tests that check pixels against analytic values.
#pragma once
#include <string>
#include <vector>

#include "film/film.h"
#include "ocl/context.h"
#include "render/renderer.h"

namespace rd::test {

struct Rendered {
    int width = 0, height = 0;
    std::vector<Rgba> pixels;
    Film film;  // the raw sums: sample counts, AOVs
    RenderStats stats;
    uint32_t count(int x, int y) const { return film.pixels[size_t(y) * size_t(width) + x].count; }
    const Rgba& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + x]; }
    // Mean of one channel (0..3) over a rectangle [x0, x1) x [y0, y1).
    double mean(int channel, int x0, int y0, int x1, int y1) const;
};

// A scratch folder of this test process, created: TempDir()/name.<pid>. CTest runs the
// tests two at a time, each in its own process; a folder shared by name had one test
// truncate a shader file while another compiled it.
std::string scratchDir(const std::string& name);
// Writes `text` to `path` (replacing it).
void writeFile(const std::string& path, const std::string& text);

// A scratch folder (scratchDir) holding the shaders `sources` lists as (name, source):
// name.sl each.
template <size_t N>
std::string shaderFolder(const std::string& name, const char* const (&sources)[N][2]) {
    const std::string dir = scratchDir(name);
    for (const auto& s : sources) writeFile(dir + "/" + s[0] + ".sl", s[1]);
    return dir;
}

// The context every test shares (building one per test would dominate the run time).
const ClContext& testContext();

// The scene of one RIB world (WorldBegin and WorldEnd added), failing the calling test on
// any error: its quadrics and solids in the order declared.
Scene sceneOfWorld(const std::string& world);

// Fails the calling test (gtest) if the RIB has errors; renders the first world block.
// Unless the RIB gives a PixelFilter, a box one pixel wide: the tests' references are
// exact pixel coverages and per-pixel values (RI's default gaussian 2 2 blends a pixel
// with its neighbours; tests/host/pixel_filter_test.cpp renders it).
Rendered renderRib(const std::string& rib, const RenderSettings& settings = {});

// A patch at z = 5 seen head on (orthographic, 16 x 16 pixels over 0.1 units, spp x spp
// samples) with the surface call `surface` (a shader in `dir`), under `above`: geometry
// in an attribute block with a constant surface of colour (1, 0.5, 0.25).
std::string patchUnder(const std::string& dir, int spp, const std::string& surface,
                       const std::string& above);

// Renders the first world block of a RIB as the command does and writes its files (its
// Display's name, else the scene's, and its secondary displays); fails the calling test
// on an error. Returns the diagnostics' text (warnings).
std::string renderRibToFiles(const std::string& rib);

}  // namespace rd::test
