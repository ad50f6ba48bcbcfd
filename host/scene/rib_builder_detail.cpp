// rib_builder_detail.cpp: level of detail (RI 3.2 section 4.1.5). Detail gives the
// current object's bound; its area in raster space, times RelativeDetail, is the detail,
// and DetailRange shows the geometry that follows (to the end of the attribute block)
// only within its range. A ray tracer has no REYES grids to dissolve between
// representations, so the transitions are cut at their middles: representations whose
// ranges meet (upper transition of one = lower of the next) show exactly one at a time.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rib_builder.h"

namespace rd {

void RibBuilder::relativeDetail(L loc, float r) {
    if (!(r > 0.0f)) return m_diag.error(loc, "RelativeDetail must be above 0");
    m_options.render.relativeDetail = r;
}

void RibBuilder::detail(L loc, const float bound[6]) {
    if (!m_inWorld)
        return m_diag.error(loc, "Detail is only valid inside WorldBegin/WorldEnd");
    float corners[24];
    for (int c = 0; c < 8; ++c) {
        corners[3 * c] = bound[(c & 1) ? 1 : 0];
        corners[3 * c + 1] = bound[(c & 2) ? 3 : 2];
        corners[3 * c + 2] = bound[(c & 4) ? 5 : 4];
    }
    Attributes& a = m_attrStack.back();
    // (inside ObjectBegin the current transform is the object's own: no raster size)
    if (m_defining || !transformPoints("object", "raster", corners, 8)) {
        a.detail = -1.0f;
        return;
    }
    float lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    bool behind = false;  // a corner at or behind the eye: as near as can be
    for (int c = 0; c < 8; ++c) {
        behind |= !(corners[3 * c + 2] > 0.0f) && m_world.camera.perspective;
        for (int k = 0; k < 2; ++k)
            lo[k] = std::min(lo[k], corners[3 * c + k]),
            hi[k] = std::max(hi[k], corners[3 * c + k]);
    }
    const float area = (hi[0] - lo[0]) * (hi[1] - lo[1]);
    a.detail = behind || !std::isfinite(area) ? std::numeric_limits<float>::max()
                                              : area * m_world.render.relativeDetail;
}

void RibBuilder::detailRange(L loc, float minVisible, float lowerTransition,
                             float upperTransition, float maxVisible) {
    if (!(minVisible <= lowerTransition && lowerTransition <= upperTransition &&
          upperTransition <= maxVisible))
        return m_diag.error(loc,
                            "DetailRange needs minvisible <= lowertransition <= "
                            "uppertransition <= maxvisible");
    Attributes& a = m_attrStack.back();
    if (a.detail < 0.0f) {
        m_diag.warning(loc, m_defining
                                ? "DetailRange inside ObjectBegin has no raster size; "
                                  "every representation is kept"
                                : "DetailRange without a Detail bound; ignored");
        a.lodHidden = false;
        return;
    }
    // each transition cut at its middle (in double: the ends may be RI_INFINITY)
    const double from = 0.5 * (double(minVisible) + double(lowerTransition));
    const double to = 0.5 * (double(upperTransition) + double(maxVisible));
    const double d = a.detail;
    a.lodHidden =
        !(d >= from && (d < to || (to >= double(std::numeric_limits<float>::max()))));
}

bool RibBuilder::shown(L loc, const char* request) {
    return inWorld(loc, request) && !m_attrStack.back().lodHidden;
}

}  // namespace rd
