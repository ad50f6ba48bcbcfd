// ri_render_target.cpp: each world block given through the Ri API rendered as it ends.
#include "ri_render_target.h"

#include <new>

#include "ocl/check.h"
#include "ocl/device.h"
#include "render/frame_output.h"
#include "render/renderer.h"

namespace rd::ri {

RenderTarget::RenderTarget(rib::Diagnostics& diag,
                           std::function<void(const std::string&)> failed)
    : RibBuilder(diag, "ri"), m_diag(diag), m_failed(std::move(failed)) {
    setDeferProcedurals(false);
}

RenderTarget::~RenderTarget() = default;

void RenderTarget::worldEnd(L loc) {
    const size_t before = scenes().size();
    RibBuilder::worldEnd(loc);
    if (scenes().size() == before) return;  // (the builder refused the block)
    const size_t frame = m_frames++;
    try {
        if (!m_ctx) m_ctx = std::make_unique<ClContext>(selectDevice(""));
        const Scene& scene = scenes().back();
        RenderSettings settings;
        settings.progress = false;
        Renderer renderer(*m_ctx, settings);
        Film film;
        const RenderStats st = renderer.render(scene, film, m_diag);
        // (numbered from the second frame on: how many there will be is not known yet)
        writeFrameImage(frameOutputName(scene, "", frame, frame + 1), scene, film, st, {},
                        false, "ri");
    } catch (const std::bad_alloc&) {
        m_failed("out of memory on the host rendering frame " +
                 std::to_string(frame + 1));
    } catch (const std::exception& e) {
        m_failed("frame " + std::to_string(frame + 1) + " not rendered: " + e.what());
    }
    scenes().pop_back();  // (rendered: its memory goes back)
}

}  // namespace rd::ri
