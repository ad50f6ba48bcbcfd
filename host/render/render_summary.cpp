// render_summary.cpp: the figures a finished render reports (render_summary.h).
#include "render_summary.h"

#include <algorithm>
#include <string>

#include "cl/include/numerics_slots.h"
#include "film/film_error.h"

namespace rd {

void summariseRays(RenderStats& st, const std::vector<uint32_t>& num, int maxTransparentDepth,
                   rib::Diagnostics& diag, const rib::SourceLoc& where) {
    auto active = [&](const char* name) {
        auto it = st.kernels.find(name);
        return it == st.kernels.end() ? uint64_t(0) : it->second.activeItems;
    };
    // (the treelet path's first rounds take each ray once, as the intersect kernels do)
    const uint64_t closestRays = active("intersect_closest") + active("treelet_closest_root");
    st.continuationRays = closestRays > st.eyeRays ? closestRays - st.eyeRays : 0;
    st.shadowRays = active("intersect_shadow") + active("treelet_shadow_root") +
                    active("treelet_shadow_walk_begin");
    st.shadeNonfinite = num[RT_NUM_NONFINITE], st.shadeNegative = num[RT_NUM_NEGATIVE];
    st.shadeHuge = num[RT_NUM_HUGE], st.shadeDenormal = num[RT_NUM_DENORMAL];
    st.transparentDepthCut = num[RT_NUM_TRANSPARENT_DEPTH];
    st.specularDepthCut = num[RT_NUM_SPECULAR_DEPTH];
    st.rouletteEnded = num[RT_NUM_ROULETTE], st.traceCallsIgnored = num[RT_NUM_TRACE_LIMIT];
    st.shaderLoopsCut = num[RT_NUM_LOOP_CUT];
    if (st.shaderLoopsCut > 0)
        diag.warning(where, "a shader loop ran past " +
                                std::to_string(kShaderLoopPasses) +
                                " passes at " + std::to_string(st.shaderLoopsCut) +
                                " shading point(s) and was cut there (a loop that never ends "
                                "would hang the device)");
    if (st.shadeNonfinite + st.shadeNegative + st.shadeHuge > 0)
        diag.warning(where, "shaders produced " + std::to_string(st.shadeNonfinite) +
                                " NaN/Inf, " + std::to_string(st.shadeNegative) +
                                " negative opacity and " + std::to_string(st.shadeHuge) +
                                " huge (> 1e10) results; left out of the image");
    if (st.overflowRays > 0)
        diag.warning(where, std::to_string(st.overflowRays) +
                                " traced ray(s) dropped: more in flight than the ray pool and "
                                "its spill stack hold; " + std::to_string(st.reissuedSamples) +
                                " sample(s) traced again, the rest kept what they had "
                                "(lower maxspeculardepth or trace fewer rays per hit)");
    if (st.traceCallsIgnored > 0)
        diag.warning(where, std::to_string(st.traceCallsIgnored) +
                                " trace() call(s) past the " + std::to_string(st.features.traceSlots) +
                                " a shaded point records were ignored (their rays not traced)");
    if (st.transparentDepthCut > 0)
        diag.warning(where, std::to_string(st.transparentDepthCut) +
                                " ray(s) stopped after " + std::to_string(maxTransparentDepth) +
                                " transparent surfaces; raise Attribute \"trace\" "
                                "\"maxtransparentdepth\"");
}

void summariseFilm(RenderStats& st, Film& film, bool sobol, bool twoSamplesAPixel,
                   const FilmSummary* onDevice) {
    if (twoSamplesAPixel) {
        const FilmError e = onDevice ? onDevice->error : estimateFilmErrors(film.pixels);
        st.estimatedError = e.of(sobol);
        film.errorScale = 1.0 / e.spreadOverstates(sobol);
    } else {
        st.estimatedError = -1.0;
    }
    const Film::Tally tally = onDevice ? onDevice->tally : film.tally();
    st.nonfiniteSamples = tally.nonfinite;
    st.unsampledPixels = tally.unsampled;
    st.filmSamples = tally.samples;
}

void summariseOccupancy(RenderStats& st, bool treelets, double launchGapsMs) {
    if (auto it = st.kernels.find(treelets ? "treelet_closest_root" : "intersect_closest");
        it != st.kernels.end() && it->second.launches > 0)
        st.poolFill = double(it->second.activeItems) /
                      (double(it->second.launches) * double(st.poolCapacity));
    double deviceMs = 0;
    for (const auto& [name, ks] : st.kernels) deviceMs += ks.deviceMs;
    const double loopMs = st.elapsedSec * 1e3 - st.sceneSetupMs;
    if (loopMs > 0) st.deviceBusy = std::min(1.0, deviceMs / loopMs);
    // Idle time after the host waits (the round ends, planning, the film's sync and tally
    // at the end) is the host's; the runtime's gaps between queued kernels are not.
    st.launchGapsMs = launchGapsMs;
    if (st.elapsedSec > 0) {
        st.hostOverhead = std::max(0.0, loopMs - deviceMs) / (st.elapsedSec * 1e3);
        st.hostSyncOverhead =
            std::max(0.0, loopMs - deviceMs - st.launchGapsMs) / (st.elapsedSec * 1e3);
    }
}

}  // namespace rd
