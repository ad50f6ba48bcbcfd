// ri_render_target.h: what RiBegin(RI_NULL) sends its calls to: the scene builder, which
// renders each world block as it ends, on the OpenCL device RAYDRIVE_DEVICE names (else
// the default one, opened at the first WorldEnd), and writes its image as the raydrive
// command would (frame_output.h; without a Display, ri.exr, then ri.2.exr, ...).
// DelayedReadArchive is read at once: the calls cannot be replayed to load an archive
// when a ray first reaches it, as the command does with its file.
#pragma once
#include <functional>
#include <memory>
#include <string>

#include "ocl/context.h"
#include "scene/rib_builder.h"

namespace rd::ri {

class RenderTarget : public RibBuilder {
public:
    // `failed` is told why a frame could not be rendered or written.
    RenderTarget(rib::Diagnostics& diag, std::function<void(const std::string&)> failed);
    ~RenderTarget() override;
    void worldEnd(L loc) override;

private:
    rib::Diagnostics& m_diag;
    std::function<void(const std::string&)> m_failed;
    std::unique_ptr<ClContext> m_ctx;
    size_t m_frames = 0;
};

}  // namespace rd::ri
