// frame_output.cpp: a rendered frame's image file (frame_output.h).
#include "frame_output.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <random>

#include "film/exr_output.h"
#include "film/replace_file.h"
#include "scene/depth_map.h"
#include "texture/texture_backend.h"

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

// Whether a file's name asks for a picture (written through OpenImageIO) rather than
// OpenEXR.
bool isPicture(const std::string& name) {
    std::string ext = std::filesystem::path(name).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (const char* e : {".tif", ".tiff", ".png", ".jpg", ".jpeg", ".tga", ".bmp",
                          ".ppm", ".pnm", ".hdr", ".sgi"})
        if (ext == e) return true;
    return false;
}

// A picture's channels (interleaved) quantized as Quantize says (Scene::quantize),
// through OpenImageIO (replace_file.h, as writeExr).
void writePicture(const std::string& out, int width, int height, int channels,
                  std::vector<float> data, const QuantizeSpec& q) {
    if (q.one > 0) {
        std::minstd_rand dither(1);  // (the same noise in every render)
        std::uniform_real_distribution<float> r(-1.0f, 1.0f);
        for (float& v : data)
            v = std::clamp(std::round(float(q.one) * v + q.dither * r(dither)),
                           float(q.min), float(q.max)) /
                float(q.one);
    }
    const int bits = q.one == 0 ? 32 : q.one <= 255 ? 8 : 16;
    writeReplacing(out, [&](const std::string& tmp) {
        textureBackend().writePicture(tmp, width, height, channels, data.data(), bits);
    });
}

// The image to `out`: OpenEXR with its AOV channels, or a picture when the name asks for
// one, which holds the colour (and alpha), or without colour the AOV channels.
void writeImage(const std::string& out, const Film& film, const ExrOptions& opts,
                const QuantizeSpec& quantize) {
    const int outW = film.cropped() ? film.cropX1 - film.cropX0 : film.width;
    const int outH = film.cropped() ? film.cropY1 - film.cropY0 : film.height;
    if (!isPicture(out) || (!opts.colour && opts.extra.empty())) {
        writeExr(out, outW, outH, film.crop(film.resolve()), opts);
        return;
    }
    const size_t n = size_t(outW) * size_t(outH);
    std::vector<const float*> planes;
    std::vector<Rgba> colour;
    if (opts.colour) {
        colour = film.crop(film.resolve());
        for (int c = 0; c < (opts.alpha ? 4 : 3); ++c) planes.push_back(&colour[0].r + c);
    }
    const size_t stride = opts.colour ? 4 : 1;
    for (const Channel& c : opts.extra)
        if (!opts.colour) planes.push_back(c.values.data());
    std::vector<float> data(n * planes.size());
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < planes.size(); ++c)
            data[i * planes.size() + c] = planes[c][i * stride];
    writePicture(out, outW, outH, int(planes.size()), std::move(data), quantize);
}

// A secondary display (Display "+name"): its AOVs in a file of their own. One AOV alone
// takes the channels a viewer shows: R, G, B for three, Y for one.
void writeAovDisplay(const AovDisplay& d, const Film& film, ExrOptions opts,
                     const QuantizeSpec& quantize) {
    opts.colour = !d.colour.empty();
    opts.alpha = d.colour == "rgba";
    addAovChannels(opts, film, d.aovs);
    if (d.aovs.size() == 1 && !opts.colour && opts.extra.size() == 1) opts.extra[0].name = "Y";
    if (d.aovs.size() == 1 && !opts.colour && opts.extra.size() == 3)
        for (size_t k = 0; k < 3; ++k) opts.extra[k].name = std::string(1, "RGB"[k]);
    writeImage(d.name, film, opts, quantize);
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
    writeImage(out, film, opts, scene.quantize);
    for (const AovDisplay& d : scene.aovDisplays)
        writeAovDisplay(d, film, common, scene.quantize);
}

}  // namespace rd
