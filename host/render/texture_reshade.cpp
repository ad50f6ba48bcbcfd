// texture_reshade.cpp: the serve-and-shade-again passes of texture_reshade.h.
#include "texture_reshade.h"

#include <algorithm>
#include <cmath>

namespace rd {

TextureReshade::TextureReshade(const ClContext& ctx, TextureSet& textures, size_t pool,
                               size_t shaders, bool enabled)
    : m_textures(textures), m_a(ctx, enabled ? pool : 0), m_b(ctx, enabled ? pool : 0),
      m_count(ctx, shaders + 1) {
    m_count.fillZero();
}

void TextureReshade::run(const std::vector<uint32_t>& offsets,
                         const std::vector<std::string>& shaderNames, const ShadeRuns& shade) {
    DeviceBuffer<uint32_t>* src = &m_a;
    DeviceBuffer<uint32_t>* dst = &m_b;
    double share = 1.0;  // of the waiting points, shaded in one pass
    uint64_t lastTotal = ~uint64_t(0), lastLaunched = 0;
    for (int pass = 0;; ++pass) {
        std::vector<uint32_t> again = m_count.download();
        std::vector<uint32_t> reqCount = m_textures.counterBuf.downloadFirst(1);
        uint64_t total = 0;
        for (uint32_t c : again) total += c;
        if (reqCount[0] > 0) {  // tiles asked for, and broken maps to report
            std::vector<TexRequest> req = m_textures.requestBuf.downloadFirst(
                std::min<size_t>(reqCount[0], TextureSet::kMaxRequests));
            const uint32_t zero = 0;
            m_textures.counterBuf.uploadRange(0, &zero, 1);
            m_textures.serve(req, shaderNames);
        }
        if (total == 0) return;
        if (pass >= 4096) {  // the cache cannot hold what these points need
            m_textures.stats().unresolved += total;
            m_count.fillZero();
            return;
        }
        // When the waiting points need more tiles than the cache holds they evict each
        // other's: shade fewer of them at a time (the rest wait in the list) until each
        // pass finishes some.
        if (lastTotal != ~uint64_t(0)) {
            const uint64_t done = lastTotal - std::min(lastTotal, total);
            if (done * 10 < lastLaunched) share = std::max(share * 0.5, 1.0 / 65536);
            else if (done * 2 >= lastLaunched) share = std::min(1.0, share * 2);
        }
        lastTotal = total;
        std::vector<uint32_t> launch(again.size());
        bool partial = false;
        lastLaunched = 0;
        for (size_t s = 0; s < again.size(); ++s) {
            launch[s] = std::min<uint32_t>(again[s], uint32_t(std::ceil(double(again[s]) * share)));
            partial |= launch[s] < again[s];
            lastLaunched += launch[s];
        }
        m_count.fillZero();
        ++m_textures.stats().retryPasses;
        shade(launch, offsets, *src, *dst);
        if (partial) {  // the points not shaded now go after the new misses
            std::vector<uint32_t> now = m_count.download();
            for (size_t s = 0; s < again.size(); ++s) {
                src->copyTo(*dst, offsets[s] + launch[s], offsets[s] + now[s], again[s] - launch[s]);
                now[s] += again[s] - launch[s];
            }
            m_count.upload(now);
        }
        std::swap(src, dst);
    }
}

}  // namespace rd
