// render_summary.h: the figures a finished render reports (--stats), derived from the
// kernels' counters and the numerics counters, and the warnings they call for.
#pragma once
#include <cstdint>
#include <vector>

#include "device_film_sums.h"
#include "film/film.h"
#include "renderer.h"
#include "rib/diagnostics.h"

namespace rd {

// Rays by kind from the kernels' active counts (st.kernels, st.eyeRays set), the shader
// numerics (numerics.clh's RT_NUM_* order), and warnings for shader results left out,
// rays dropped and rays cut by maxtransparentdepth.
void summariseRays(RenderStats& st, const std::vector<uint32_t>& numerics,
                   int maxTransparentDepth, rib::Diagnostics& diag, const rib::SourceLoc& where);

// The finished film's estimated error (none without two samples a pixel: -1, with no
// pass over the film), its error channel's scale under the Sobol sampler, and its
// tally: whole samples, pixels left out, samples left out as NaN/Inf.
// `onDevice`: the film's error and tally as the device summed them (device_film_sums.h);
// null: taken here.
void summariseFilm(RenderStats& st, Film& film, bool sobol, bool twoSamplesAPixel,
                   const FilmSummary* onDevice = nullptr);

// Pool fill (rays traced a round over the capacity), device busy (kernel time over the
// sampling loop's wall time), host overhead (the rest, over the frame) and, of that, the
// host synchronisation overhead (without the runtime's gaps between kernels already
// queued). st.kernels, elapsedSec and sceneSetupMs set.
void summariseOccupancy(RenderStats& st, bool treelets, double launchGapsMs);

}  // namespace rd
