// texture_reshade.h: the shading points a texture miss sent back (texture_lookup.clh):
// they committed nothing and sit in a retry list at their shader's run offsets. After
// the shade kernels, the host serves the tiles they asked for and shades them again,
// fewer at a time when the cache cannot hold what they all need, until none is left.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "ocl/buffer.h"
#include "texture/texture_set.h"

namespace rd {

class TextureReshade {
public:
    // Shades runs [offsets[s], + counts[s]) of `sorted`, listing misses in `retry`.
    using ShadeRuns = std::function<void(const std::vector<uint32_t>& counts,
                                         const std::vector<uint32_t>& offsets,
                                         const DeviceBuffer<uint32_t>& sorted,
                                         DeviceBuffer<uint32_t>& retry)>;

    TextureReshade(const ClContext& ctx, TextureSet& textures, size_t pool, size_t shaders,
                   bool enabled);
    // Where the first shade launches list their misses, and the counts per shader.
    DeviceBuffer<uint32_t>& firstList() { return m_a; }
    DeviceBuffer<uint32_t>& counts() { return m_count; }
    // After the first launches: serve the requests and shade the listed points again.
    void run(const std::vector<uint32_t>& offsets, const std::vector<std::string>& shaderNames,
             const ShadeRuns& shade);

private:
    TextureSet& m_textures;
    DeviceBuffer<uint32_t> m_a, m_b, m_count;
};

}  // namespace rd
