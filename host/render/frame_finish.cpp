// frame_finish.cpp: the end of a frame (frame_finish.h). The reads back are queued
// without waiting, so they overlap the profiler's reads; one finish waits for them all.
#include "frame_finish.h"

#include "imager_stage.h"
#include "render_summary.h"

namespace rd {
namespace {

// Every kernel the frame ran, for their active work-item counts.
std::vector<Kernel*> frameKernels(const FrameDevice& d, const FrameEnd& e) {
    std::vector<Kernel*> kernels = d.k.all();
    if (e.pixelTests)
        for (Kernel* t : e.pixelTests->kernels()) kernels.push_back(t);
    if (e.filmSums) kernels.push_back(&e.filmSums->kernel());
    return kernels;
}

}  // namespace

void finishFrame(const FrameDevice& d, const FrameEnd& e, RenderStats& st,
                 rib::Diagnostics& diag, std::chrono::steady_clock::time_point t0) {
    const Features& f = d.f;
    if (d.shading.imager) {  // the Imager shader on the finished image (also a stopped one)
        d.filmBuf.syncToHost();
        e.film.imaged = applyImager(d.ctx, e.shadeProgram, d.prof, e.film, d.ds.params);
    } else {  // the film's sync overlaps the profiler's reads; collectActive waits for it
        d.filmBuf.syncToHost(/*blocking=*/false);
    }
    if (e.filmSums) e.filmSums->launch();
    d.aovBuf.syncToHost(/*blocking=*/false);
    d.shaderAovBuf.syncToHost(/*blocking=*/false);
    std::vector<uint32_t> num, texCounts;
    d.numerics.downloadInto(num, /*blocking=*/false);
    if (f.textures) d.textures.counterBuf.downloadInto(texCounts, /*blocking=*/false);
    d.prof.collect();
    Kernel::collectActive(frameKernels(d, e));
    if (d.treelets) d.treelets->collectActive();
    d.ctx.finish();  // the copies above
    st.kernels = d.prof.stats();
    st.timeline = d.prof.timeline();
    if (f.textures) {
        d.textures.stats().lookups = texCounts[1];
        d.textures.stats().missedLookups = texCounts[2];
        st.textures = d.textures.stats();
    }
    summariseRays(st, num, f.maxTransparentDepth, diag,
                  rib::SourceLoc{d.scene.sourceFile, 0});
    const std::optional<FilmSummary> filmSummary =
        e.filmSums ? std::optional<FilmSummary>(e.filmSums->summary()) : std::nullopt;
    summariseFilm(st, e.film, f.sobol, e.twoSamplesAPixel,
                  filmSummary ? &*filmSummary : nullptr);
    st.passes = e.planner.passes();
    st.elapsedSec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    summariseOccupancy(st, d.treelets != nullptr, d.prof.launchGapsMs());
    st.errorVsTime.push_back({st.elapsedSec, st.totalRays(), st.estimatedError});
}

}  // namespace rd
