// material_binding.cpp: the scene's materials bound to their shaders: each one's surface
// shader and block, where its per-point parameters go (ShaderSet::bindMaterials), and
// the per-material table of every kind's shader that surface() and its kin read
// (ShaderSet::shaderBlocks).
#include <algorithm>
#include <map>

#include "compiler.h"
#include "emit_cl.h"
#include "message_services.h"
#include "shader_set.h"

namespace rd {

// surface(), displacement(), atmosphere(), incident(), opposite(): per material, each
// kind's shader and block (message_services.h ShaderBlocks), when `used`.
ShaderBlocks ShaderSet::shaderBlocks(const ShadingSetup& out,
                                     const BoundSurfaces& surfaces,
                                     const BoundVolumes& volumes, bool used) const {
    ShaderBlocks blocks;
    blocks.shaders[0] = surfaces.shaders;
    auto kindIndex = [&](int kind, const rsl::EmittedShader* sh) {
        auto& list = blocks.shaders[kind];
        auto it = std::find(list.begin(), list.end(), sh);
        if (it != list.end()) return int32_t(it - list.begin());
        list.push_back(sh);
        return int32_t(list.size() - 1);
    };
    for (size_t mi = 0; used && mi < out.materials.size(); ++mi) {
        const Material& m = out.materials[mi];
        const uint32_t r = m_scene.materials[mi].shader;
        std::array<int32_t, 2 * ShaderBlocks::kKinds> e{};
        for (int kind = 0; kind < ShaderBlocks::kKinds; ++kind) e[2 * kind] = -1;
        if (r < surfaces.shader.size() && !surfaces.shaders.empty())
            e[0] = int32_t(m.shader), e[1] = int32_t(m.params);
        // a kind's shader by its index among the kind's bound calls (1-based, 0: none)
        auto boundAs = [&](int kind, uint32_t index, const auto& bound) {
            if (index == 0 || index > bound.size() || !bound[index - 1].first) return;
            e[2 * kind] = kindIndex(kind, bound[index - 1].first);
            e[2 * kind + 1] = bound[index - 1].second;
        };
        boundAs(
            1,
            (m.flags & RT_MATERIAL_DISPLACEMENT_MASK) >> RT_MATERIAL_DISPLACEMENT_SHIFT,
            volumes.displacements);
        boundAs(2,
                (m.flags & RT_MATERIAL_ATMOSPHERE_MASK) >> RT_MATERIAL_ATMOSPHERE_SHIFT,
                volumes.atmospheres);
        boundAs(3, (m.flags & RT_MATERIAL_INTERIOR_MASK) >> RT_MATERIAL_INTERIOR_SHIFT,
                volumes.interiors);
        boundAs(4,
                mi < m_scene.materialExterior.size() ? m_scene.materialExterior[mi] : 0,
                volumes.exteriors);
        blocks.materials.push_back(e);
    }
    return blocks;
}

// The scene's materials with their surface shader's index and block, and where each
// one's per-point parameters go in its surface's and its displacement's blocks
// (ShadingSetup::pointParamLayout). The values are those its primitives carry
// (ShaderRef::pointParams of its surface call), whichever shader takes them.
void ShaderSet::bindMaterials(ShadingSetup& out, const BoundSurfaces& surfaces,
                              const BoundVolumes& volumes) {
    out.materials = m_scene.materials;
    out.maxPointParams = m_scene.maxPointParams;
    const size_t most = size_t(out.maxPointParams);
    // (per surface and displacement call: its offsets, warned about once)
    std::map<std::pair<uint32_t, uint32_t>, std::vector<int32_t>> displacementOffsets;
    for (Material& m : out.materials) {
        uint32_t r = m.shader;
        const uint32_t d =
            (m.flags & RT_MATERIAL_DISPLACEMENT_MASK) >> RT_MATERIAL_DISPLACEMENT_SHIFT;
        m.shader = r < surfaces.shader.size() ? surfaces.shader[r] : 0;
        m.params = r < surfaces.block.size() ? surfaces.block[r] : 0;
        if (most == 0) continue;
        std::vector<int32_t> lay(pointParamLayoutStride(most), -1);
        const std::vector<int32_t> none;
        const std::vector<int32_t>& given =
            r < surfaces.pointParams.size() ? surfaces.pointParams[r] : none;
        lay[0] = int32_t(std::min(given.size(), most));
        std::copy_n(given.begin(), size_t(lay[0]), lay.begin() + 1);
        const bool carried =
            r < m_scene.surfaceRefs.size() && !m_scene.surfaceRefs[r].pointParams.empty();
        if (carried && d > 0 && d <= volumes.displacements.size() &&
            volumes.displacements[d - 1].first) {
            auto [it, fresh] = displacementOffsets.try_emplace({r, d});
            if (fresh) {
                ShaderRef call = m_scene.displacements[d - 1];
                call.pointParams = m_scene.surfaceRefs[r].pointParams;
                it->second =
                    pointParamOffsets(*volumes.displacements[d - 1].first, call, m_diag);
            }
            std::copy_n(it->second.begin(), std::min(it->second.size(), most),
                        lay.begin() + 1 + std::ptrdiff_t(most));
        }
        out.pointParamLayout.insert(out.pointParamLayout.end(), lay.begin(), lay.end());
    }
}

}  // namespace rd
