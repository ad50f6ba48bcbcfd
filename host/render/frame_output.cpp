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

void writeFrameImage(const std::string& out, const Scene& scene, const Film& film,
                     const RenderStats& st, const std::vector<std::string>& aovs,
                     bool halfFloat, const std::string& scenePath) {
    ExrOptions opts;
    opts.alpha = scene.display.mode != "rgb";
    if (scene.display.mode == "z") {  // a depth map: Z and the camera's matrices
        opts.colour = false;
        DepthMapMatrices m = depthMapMatrices(scene);
        opts.matrices["worldToCamera"] = m.worldToCamera;
        opts.matrices["worldToScreen"] = m.worldToScreen;
    }
    opts.halfFloat = halfFloat;
    opts.metadata["software"] = "RayDrive " RAYDRIVE_VERSION;
    opts.metadata["raydrive:device"] = st.device;
    opts.metadata["raydrive:scene"] = scenePath;
    opts.metadata["raydrive:stop"] = st.stopReason;
    opts.metadata["raydrive:estimated_error"] = std::to_string(st.estimatedError);
    // (how the error was estimated: samples' spread or two replicates)
    opts.metadata["raydrive:sampler"] = st.features.sobol ? "sobol" : "independent";
    opts.metadata["raydrive:samples"] = std::to_string(st.filmSamples);
    std::vector<std::string> wanted = scene.aovs;
    wanted.insert(wanted.end(), aovs.begin(), aovs.end());
    // Pixels never reached are filled from neighbours: say which, always.
    if (st.unsampledPixels > 0) wanted.push_back("filled");
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    for (const std::string& a : wanted)
        for (Channel& c : film.aovChannels(a)) {
            c.values = film.crop(c.values);
            opts.extra.push_back(std::move(c));
        }
    int outW = film.width, outH = film.height;
    if (film.cropped()) {
        opts.dataX = film.cropX0, opts.dataY = film.cropY0;
        opts.displayWidth = film.width, opts.displayHeight = film.height;
        outW = film.cropX1 - film.cropX0, outH = film.cropY1 - film.cropY0;
    }
    writeExr(out, outW, outH, film.crop(film.resolve()), opts);
}

}  // namespace rd
