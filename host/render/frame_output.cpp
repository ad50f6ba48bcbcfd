// frame_output.cpp: a rendered frame's image file (frame_output.h).
#include "frame_output.h"

#include <algorithm>
#include <filesystem>

#include "film/exr_output.h"
#include "scene/depth_map.h"

namespace rd {

std::string frameOutputName(const Scene& scene, const std::string& override, size_t frame,
                            size_t frames) {
    std::string name = override;
    if (name.empty()) name = scene.display.name;
    if (name.empty())
        name = std::filesystem::path(scene.sourceFile).stem().string() + ".exr";
    // Several frames sharing one name (-o, or no Display: the scene stem) are numbered,
    // else each frame would overwrite the one before.
    if (frames > 1 && (!override.empty() || scene.display.name.empty())) {
        std::filesystem::path p(name);
        name = (p.parent_path() / (p.stem().string() + "." + std::to_string(frame + 1) +
                                   p.extension().string()))
                   .string();
    }
    return name;
}

namespace {

// The header every image of the frame carries: how it was made.
ExrOptions imageOptions(const Film& film, const RenderStats& st, bool halfFloat,
                        const std::string& scenePath) {
    ExrOptions opts;
    opts.halfFloat = halfFloat;
    opts.metadata["software"] = "RayDrive " RAYDRIVE_VERSION;
    opts.metadata["raydrive:device"] = st.device;
    opts.metadata["raydrive:scene"] = scenePath;
    opts.metadata["raydrive:stop"] = st.stopReason;
    opts.metadata["raydrive:estimated_error"] = std::to_string(st.estimatedError);
    // (how the error was estimated: samples' spread or two replicates)
    opts.metadata["raydrive:sampler"] = st.features.sobol ? "sobol" : "independent";
    opts.metadata["raydrive:samples"] = std::to_string(st.filmSamples);
    if (film.cropped()) {
        opts.dataX = film.cropX0, opts.dataY = film.cropY0;
        opts.displayWidth = film.width, opts.displayHeight = film.height;
    }
    return opts;
}

void addAovChannels(ExrOptions& opts, const Film& film, std::vector<std::string> wanted) {
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    for (const std::string& a : wanted)
        for (Channel& c : film.aovChannels(a)) {
            c.values = film.crop(c.values);
            opts.extra.push_back(std::move(c));
        }
}

void writeImage(const std::string& out, const Film& film, const ExrOptions& opts) {
    const int outW = film.cropped() ? film.cropX1 - film.cropX0 : film.width;
    const int outH = film.cropped() ? film.cropY1 - film.cropY0 : film.height;
    writeExr(out, outW, outH, film.crop(film.resolve()), opts);
}

// A secondary display (Display "+name"): its AOVs in a file of their own. One AOV alone
// takes the channels a viewer shows: R, G, B for three, Y for one.
void writeAovDisplay(const AovDisplay& d, const Film& film, ExrOptions opts) {
    opts.colour = !d.colour.empty();
    opts.alpha = d.colour == "rgba";
    addAovChannels(opts, film, d.aovs);
    if (d.aovs.size() == 1 && !opts.colour && opts.extra.size() == 1) opts.extra[0].name = "Y";
    if (d.aovs.size() == 1 && !opts.colour && opts.extra.size() == 3)
        for (size_t k = 0; k < 3; ++k) opts.extra[k].name = std::string(1, "RGB"[k]);
    writeImage(d.name, film, opts);
}

}  // namespace

void writeFrameImage(const std::string& out, const Scene& scene, const Film& film,
                     const RenderStats& st, const std::vector<std::string>& aovs,
                     bool halfFloat, const std::string& scenePath) {
    const ExrOptions common = imageOptions(film, st, halfFloat, scenePath);
    ExrOptions opts = common;
    opts.alpha = scene.display.mode != "rgb";
    if (scene.display.mode == "z") {  // a depth map: Z and the camera's matrices
        opts.colour = false;
        DepthMapMatrices m = depthMapMatrices(scene);
        opts.matrices["worldToCamera"] = m.worldToCamera;
        opts.matrices["worldToScreen"] = m.worldToScreen;
    }
    std::vector<std::string> wanted = scene.aovs;
    wanted.insert(wanted.end(), aovs.begin(), aovs.end());
    // Pixels never reached are filled from neighbours: say which, always.
    if (st.unsampledPixels > 0) wanted.push_back("filled");
    addAovChannels(opts, film, wanted);
    writeImage(out, film, opts);
    for (const AovDisplay& d : scene.aovDisplays) writeAovDisplay(d, film, common);
}

}  // namespace rd
