// main.cpp: the `raydrive` command. Parses the command line, reads the RIB, renders each
// world block on the chosen OpenCL device and writes the image; it alone picks the exit
// code: 0 success (also a render ended by its time budget or error target), 1 bad input
// (RIB errors, missing file), 2 usage, 3 device or OpenCL failure, 4 output could not be
// written, 128 + signal when SIGINT/SIGTERM stopped it (the image is still written).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <zlib.h>

#include "ocl/check.h"
#include "ocl/device.h"
#include "render/frame_output.h"
#include "render/render_with_archives.h"
#include "render/renderer.h"
#include "render/stop.h"
#include "ri_dynamic_load.h"
#include "rib/reader.h"
#include "rib/writer.h"
#include "scene/rib_builder.h"
#include "stats/stats_report.h"
#include "stats/timeline_trace.h"
#include "texture/texture_maker.h"

namespace {

int listDevicesCommand() {
    auto devices = rd::listDevices();
    if (devices.empty()) {
        std::cerr << "raydrive: no OpenCL devices found (is an OpenCL ICD such as "
                     "pocl-opencl-icd installed?)\n";
        return 3;
    }
    rd::DeviceInfo chosen;
    try {
        chosen = rd::selectDevice("");
    } catch (const std::exception&) {
    }
    for (const auto& d : devices) {
        std::cout << (d.device == chosen.device ? "* " : "  ") << d.index << ": " << d.name
                  << " [" << d.typeName() << ", " << d.computeUnits << " compute units, "
                  << (d.globalMemBytes >> 20) << " MiB] platform: " << d.platformName
                  << ", " << d.version << ", driver " << d.driverVersion << "\n";
    }
    std::cout << "(* = default; choose with --device N|NAME or RAYDRIVE_DEVICE)\n";
    if (int sig = rd::stopSignal()) return 128 + sig;
    return 0;
}

// raydrive txmake [options] picture texture: makes a tiled, mip-mapped float texture
// (what MakeTexture, MakeLatLongEnvironment and MakeShadow do in a RIB).
int txmakeCommand(int argc, char** argv) {
    CLI::App app{"raydrive txmake: any image into a tiled, mip-mapped float OpenEXR texture"};
    std::string picture, texture, wrap, swrap = "black", twrap = "black", filter = "box";
    bool envlatl = false, shadow = false;
    app.add_option("picture", picture, "input image (TIFF, PNG, JPEG, OpenEXR, HDR, ...)")->required();
    app.add_option("texture", texture, "output texture file")->required();
    app.add_option("--wrap", wrap, "wrap mode for s and t: black, periodic or clamp");
    app.add_option("--swrap", swrap, "wrap mode for s");
    app.add_option("--twrap", twrap, "wrap mode for t");
    app.add_option("--filter", filter, "filter for the mip levels (box, triangle, gaussian, ...)");
    app.add_flag("--envlatl", envlatl, "a lat-long environment map");
    app.add_flag("--shadow", shadow, "a shadow map from a depth image with its matrices");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    rd::MakeTextureOptions o;
    o.swrap = wrap.empty() ? swrap : wrap;
    o.twrap = wrap.empty() ? twrap : wrap;
    o.filter = filter;
    try {
        if (shadow) rd::makeShadow(picture, texture);
        else if (envlatl) rd::makeLatLongEnvironment(picture, texture, o);
        else rd::makeTexture(picture, texture, o);
    } catch (const std::exception& e) {
        std::cerr << "raydrive txmake: error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

// raydrive catrib [--binary] [--gzip] [-o out] in.rib: the RIB read and written back
// through the RI writer (as PRMan's catrib): ASCII or binary encoding, optionally
// gzip-compressed, archives read inline. Errors are reported as a render reports them.
int catribCommand(int argc, char** argv) {
    CLI::App app{"raydrive catrib: a RIB file written back as ASCII or binary RIB"};
    std::string input, output = "-";
    bool binary = false, gzip = false;
    app.add_option("input", input, "RIB file (plain or gzip-compressed)")->required();
    app.add_option("-o,--output", output, "output file (default: standard output)");
    app.add_flag("--binary", binary, "binary-encoded RIB (RI 3.2 appendix C)");
    app.add_flag("--gzip", gzip, "gzip-compress the output");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    std::ostringstream text;
    rib::Diagnostics diag(&std::cerr);
    bool ok;
    {
        rib::RibWriter writer(text, binary ? rib::RibWriter::Encoding::Binary
                                           : rib::RibWriter::Encoding::Ascii);
        ok = rib::readFile(input, writer, diag);
    }
    diag.printSuppressed();
    const std::string bytes = text.str();
    if (gzip) {
        if (output == "-") {
            std::cerr << "raydrive catrib: error: --gzip needs -o FILE\n";
            return 2;
        }
        gzFile f = gzopen(output.c_str(), "wb");
        bool written = f && gzwrite(f, bytes.data(), unsigned(bytes.size())) == int(bytes.size());
        if (!f || gzclose(f) != Z_OK || !written) {
            std::cerr << "raydrive catrib: error: cannot write " << output << "\n";
            return 4;
        }
    } else if (output == "-") {
        std::cout << bytes;
    } else {
        std::ofstream out(output, std::ios::binary);
        if (!(out << bytes)) {
            std::cerr << "raydrive catrib: error: cannot write " << output << "\n";
            return 4;
        }
    }
    return ok ? 0 : 1;
}

// Writes a JSON document to `path` (indented by `indent`, -1: compact); false when it
// cannot be written.
bool writeJson(const std::string& path, const nlohmann::json& doc, int indent = -1) {
    std::ofstream f(path);
    f << doc.dump(indent) << "\n";
    return bool(f);
}

// Freed memory stays in the process for the next allocation: a render's stages each
// allocate tens of megabytes (the parsed arrays, the world's vectors, the BVH build's
// references and nodes, the film) as the last stage frees its own, and glibc handed each
// block back to the kernel, which cleared fresh pages for the next (a third of reading
// a 300k-triangle RIB was page faults, perf). Whole command, medians of 9: a 304k-triangle
// height field 0.528 -> 0.454 s, SPD teapot 0.274 -> 0.248 s; peak memory 205 -> 227 MB.
void keepFreedMemory() {
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // (glibc's largest)
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

// The render command's options: what to render where, and the renderer's settings.
struct RenderCommand {
    std::string scenePath, output, deviceSpec, statsPath, timelinePath, sampler;
    bool quiet = false, halfFloat = false, tessellateQuadrics = false;
    std::vector<std::string> aovs;
    rd::RenderSettings settings;
    // the switches that turn a default off (for comparison)
    bool noShadowPackets = false, noClosestPackets = false, noOverlapPasses = false,
         noPipelineRounds = false, noJumpSmallPasses = false, hostPixelTests = false;
    // The settings for a frame: the options with the switches applied.
    rd::RenderSettings frameSettings() const {
        rd::RenderSettings s = settings;
        if (!sampler.empty()) s.sobol = sampler == "sobol";
        s.progress = !quiet;
        s.shadowPackets = !noShadowPackets;
        s.closestPackets = !noClosestPackets;
        s.overlapPasses = !noOverlapPasses;
        s.pipelineRounds = !noPipelineRounds;
        s.jumpSmallPasses = !noJumpSmallPasses;
        s.devicePixelTests = !hostPixelTests;
        s.timeline = !timelinePath.empty();
        s.extraAovs = aovs;  // (the scene's own AOVs: the renderer reads them)
        return s;
    }
};

void addRenderOptions(CLI::App& app, RenderCommand& c) {
    rd::RenderSettings& s = c.settings;
    app.add_option(
           "scene", c.scenePath,
           "RIB file to render (`-`: the standard input, e.g. a program's RIB through a "
           "pipe), `devices` to list devices (or `raydrive txmake --help`, "
           "`raydrive catrib --help`)")
        ->required();
    app.add_option("-o,--output", c.output, "output file (overrides the RIB's Display)");
    app.add_option("--device", c.deviceSpec,
                   "OpenCL device: index or name substring (default: RAYDRIVE_DEVICE, "
                   "else PoCL CPU)");
    app.add_option("--stats", c.statsPath,
                   "write statistics as JSON to FILE, or a table to -");
    app.add_option(
        "--timeline", c.timelinePath,
        "write every kernel run and the device's idle gaps to FILE, a Chrome trace "
        "(open in ui.perfetto.dev or chrome://tracing)");
    app.add_option("--time", s.timeBudget, "stop after SECONDS and write what is done")
        ->check(CLI::PositiveNumber);
    app.add_option("--error", s.errorTarget, "stop at this relative error (e.g. 0.01)")
        ->check(CLI::PositiveNumber);
    app.add_option(
           "--sampler", c.sampler,
           "sobol (default): Owen-scrambled Sobol samples, the error estimated from "
           "two independent scrambles; or independent: less stratified, more noise "
           "(default: Option \"render\" \"string sampler\")")
        ->check(CLI::IsMember({"independent", "sobol"}));
    app.add_option(
           "--seed", s.seed,
           "which random numbers: another seed renders an independent image of the "
           "same scene (default: Option \"render\" \"int seed\", else 0)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--aov", c.aovs,
                   "extra EXR channels: z, N, samples, error, filled, a shader output "
                   "variable or a global (Cs, Os, Oi, P, Ng, s, t, u, v)");
    app.add_flag("--half", c.halfFloat, "write 16-bit half-float channels");
    app.add_flag("-q,--quiet", c.quiet, "print nothing but errors");
    app.add_option("--texture-cache", s.textureCacheTiles,
                   "device texture cache in tiles of 32x32 (default: Option \"limits\" "
                   "\"texturememory\", else every tile up to 256 MiB)");
    app.add_option(
           "--bvh-width", s.bvhWidth,
           "resident BVH node width, 4, 8 or 16 (default on a CPU device: 16 with "
           "AVX-512, else 8; 4 on other devices)")
        ->check(CLI::IsMember({4, 8, 16}));
    app.add_flag(
        "--no-shadow-packets", c.noShadowPackets,
        "trace shadow rays one a work-item, not in packets of eight (for comparison)");
    app.add_flag(
        "--no-closest-packets", c.noClosestPackets,
        "trace eye and other coherent rays one a work-item, not in packets of eight");
    app.add_flag(
        "--no-overlap-passes", c.noOverlapPasses,
        "let each adaptive pass drain before the next is planned (for comparison)");
    app.add_flag("--no-pipeline-rounds", c.noPipelineRounds,
                 "queue each round's eye rays after the last round's wait, not before it "
                 "(for comparison)");
    app.add_flag(
        "--no-jump-small-passes", c.noJumpSmallPasses,
        "double the samples of a small adaptive pass's pixels, as any pass's, rather "
        "than quadruple them (for comparison)");
    app.add_flag(
        "--host-pixel-tests", c.hostPixelTests,
        "test every pixel of an adaptive pass and sum the film's error estimate on "
        "the host, not the device (the same passes; for comparison)");
    app.add_option(
        "--treelet-budget", s.treeletBytes,
        "trace through treelets of at most BYTES of BVH (default: Option \"limits\" "
        "\"treeletbytes\", else the resident BVH; triangle scenes only)");
    app.add_option(
        "--scene-memory", s.sceneMemoryBytes,
        "device BYTES for the treelets; less than the BVH streams them through a "
        "cache (default: Option \"limits\" \"scenememory\" in KiB, else all)");
    app.add_flag("--tessellate-quadrics", c.tessellateQuadrics,
                 "dice quadrics into triangles instead of intersecting them exactly");
}

// Renders each world block of the RIB `c.scenePath` was read into and writes its image,
// the --stats and --timeline files; returns the exit code. OpenCL and other failures
// throw.
int renderFrames(const RenderCommand& c, rd::RibBuilder& builder, rib::Diagnostics& diag,
                 const std::string& sceneName) {
    auto& scenes = builder.scenes();
    rd::DeviceInfo device = rd::selectDevice(c.deviceSpec);
    rd::ClContext ctx(device);
    rd::installStopSignals();
    nlohmann::json allStats = nlohmann::json::array(),
                   traceEvents = nlohmann::json::array();
    for (size_t i = 0; i < scenes.size() && !rd::stopSignal(); ++i) {
        builder.makeTexturesBefore(i);  // (a MakeShadow of the last frame's depth map)
        rd::Renderer renderer(ctx, c.frameSettings());
        rd::Film film;
        // DelayedReadArchive: read when a ray reaches its bound (the RIB read again)
        auto readAgain = [&](const std::set<std::string>& loaded, rib::Diagnostics& d) {
            rd::RibBuilder b(d, c.scenePath);
            b.setTessellateQuadrics(c.tessellateQuadrics);
            b.setLoadedProcedurals(loaded);
            rib::readFile(c.scenePath, b, d);
            return std::move(b.scenes());
        };
        rd::RenderStats st =
            rd::renderWithArchives(renderer, readAgain, scenes[i], i, film, diag);
        std::string out = rd::frameOutputName(scenes[i], c.output, i, scenes.size());
        try {
            rd::writeFrameImage(out, scenes[i], film, st, c.aovs, c.halfFloat, sceneName);
        } catch (const std::exception& e) {
            std::cerr << "raydrive: error: " << e.what() << "\n";
            return 4;
        }
        if (!c.quiet) {
            std::cerr << "raydrive: wrote " << out << " (" << film.width << "x"
                      << film.height << ", " << st.elapsedSec << " s on " << st.device
                      << ", stopped by " << st.stopReason << ", estimated error ";
            if (st.estimatedError >= 0)
                std::cerr << st.estimatedError << ")\n";
            else  // film_error.cpp: no pixel sampled twice, or a black image
                std::cerr << "none: nothing to measure it on)\n";
        }
        if (st.nonfiniteSamples > 0 && !c.quiet)
            std::cerr << "raydrive: warning: " << st.nonfiniteSamples
                      << " sample(s) with NaN or Inf were left out of the image\n";
        allStats.push_back(rd::statsToJson(st, sceneName, out));
        for (nlohmann::json& e :
             rd::timelineTraceEvents(st.timeline, int(i) + 1,
                                     "frame " + std::to_string(i + 1) + " (" + out + ")"))
            traceEvents.push_back(std::move(e));
    }
    if (c.statsPath == "-") {
        for (const auto& s : allStats) rd::printStatsTable(std::cout, s);
    } else if (!c.statsPath.empty() &&
               !writeJson(c.statsPath, allStats.size() == 1 ? allStats[0] : allStats,
                          2)) {
        std::cerr << "raydrive: error: cannot write stats to " << c.statsPath << "\n";
        return 4;
    }
    if (!c.timelinePath.empty() &&
        !writeJson(c.timelinePath,
                   {{"traceEvents", traceEvents}, {"displayTimeUnit", "ms"}})) {
        std::cerr << "raydrive: error: cannot write the timeline to " << c.timelinePath
                  << "\n";
        return 4;
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    keepFreedMemory();
    rd::ri::enableDynamicLoad();  // (DynamicLoad procedurals in the RIB it reads)
    if (argc > 1 && std::string(argv[1]) == "txmake")
        return txmakeCommand(argc - 1, argv + 1);
    if (argc > 1 && std::string(argv[1]) == "catrib")
        return catribCommand(argc - 1, argv + 1);
    CLI::App app{"RayDrive: a RenderMan renderer on OpenCL, after ART's RenderDrive"};
    RenderCommand c;
    addRenderOptions(app, c);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }
    if (c.scenePath == "devices") return listDevicesCommand();

    rib::Diagnostics diag(&std::cerr);
    // ("-": the standard input, read once, so its archives are read at once)
    const bool standardInput = c.scenePath == "-";
    const std::string sceneName = standardInput ? rib::kStandardInputName : c.scenePath;
    rd::RibBuilder builder(diag, sceneName);
    builder.setTessellateQuadrics(c.tessellateQuadrics);
    builder.setDeferProcedurals(!standardInput);
    rib::readFile(c.scenePath, builder, diag);
    diag.printSuppressed();
    if (diag.errorCount() > 0) {
        std::cerr << "raydrive: " << diag.errorCount() << " error(s) in " << sceneName
                  << "; nothing rendered\n";
        return 1;
    }
    if (builder.scenes().empty()) {
        std::cerr << sceneName
                  << ": error: no WorldBegin/WorldEnd block: nothing to render\n";
        return 1;
    }
    try {
        if (int rc = renderFrames(c, builder, diag, sceneName); rc != 0) return rc;
    } catch (const rd::ClError& e) {
        std::cerr << "raydrive: error: " << e.what() << "\n";
        return 3;
    } catch (const std::bad_alloc&) {
        std::cerr << "raydrive: error: out of memory on the host (a smaller Format, fewer "
                     "PixelSamples or a smaller scene needs less)\n";
        return 3;
    } catch (const std::exception& e) {
        std::cerr << "raydrive: error: " << e.what() << "\n";
        return 3;
    }
    if (int sig = rd::stopSignal()) return 128 + sig;
    return 0;
}
