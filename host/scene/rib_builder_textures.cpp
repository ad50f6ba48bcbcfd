// rib_builder_textures.cpp: the RIB's texture-making requests (MakeTexture,
// MakeLatLongEnvironment, MakeCubeFaceEnvironment, MakeShadow), carried out when read,
// as PRMan does. Relative file names are taken from the RIB's folder, where the render
// also looks for textures.
#include <array>
#include <filesystem>
#include <utility>

#include "rib_builder.h"
#include "texture/texture_maker.h"

namespace rd {
namespace fs = std::filesystem;

namespace {

std::string besideRib(const std::string& rib, const std::string& name) {
    if (name.empty() || fs::path(name).is_absolute()) return name;
    fs::path dir = fs::path(rib).parent_path();
    return dir.empty() ? name : (dir / name).string();
}

MakeTextureOptions options(const std::string& swrap, const std::string& twrap,
                           const std::string& filter, float swidth, float twidth) {
    MakeTextureOptions o;
    o.swrap = swrap.empty() ? "black" : swrap;
    o.twrap = twrap.empty() ? "black" : twrap;
    o.filter = filter;
    o.swidth = swidth;
    o.twidth = twidth;
    return o;
}

}  // namespace

// After a frame of this RIB was built, the request may read what that frame renders (a
// depth map for MakeShadow, PRMan's two-pass shadows): it waits until then
// (makeTexturesBefore); before any frame it is carried out at once.
template <typename F>
void RibBuilder::makeTextureFile(L loc, const char* request, const std::string& output, F&& make) {
    auto run = [this, loc, request = std::string(request), output, make] {
        try {
            make();
        } catch (const std::exception& e) {
            m_diag.error(loc, request + ": " + e.what() + " (\"" + output + "\" not made)");
        }
    };
    if (m_scenes.empty()) run();
    else m_deferredMakes.emplace_back(m_scenes.size(), run);
}

void RibBuilder::makeTexturesBefore(size_t scene) {
    for (auto& [before, make] : m_deferredMakes)
        if (before == scene && make) std::exchange(make, nullptr)();
}

void RibBuilder::makeTexture(L loc, S picture, S texture, S swrap, S twrap, S filter,
                             float swidth, float twidth, P) {
    make2dTexture(loc, "MakeTexture", picture, texture,
                  options(swrap, twrap, filter, swidth, twidth));
}

void RibBuilder::make2dTexture(L loc, const char* request, S picture, S texture,
                               const MakeTextureOptions& o) {
    const std::string rib = m_options.sourceFile;
    makeTextureFile(loc, request, texture, [rib, picture = std::string(picture),
                                            texture = std::string(texture), o] {
        rd::makeTexture(besideRib(rib, picture), besideRib(rib, texture), o);
    });
}

// MakeBump: a height map for bump(), which reads its first channel as a texture's, so
// it is made as MakeTexture makes one (PRMan's own bump format held the slopes instead).
void RibBuilder::makeBump(L loc, S picture, S texture, S swrap, S twrap, S filter,
                          float swidth, float twidth, P) {
    make2dTexture(loc, "MakeBump", picture, texture,
                  options(swrap, twrap, filter, swidth, twidth));
}

void RibBuilder::makeLatLongEnvironment(L loc, S picture, S texture, S filter, float swidth,
                                        float twidth, P) {
    const std::string rib = m_options.sourceFile;
    const MakeTextureOptions o = options("periodic", "clamp", filter, swidth, twidth);
    makeTextureFile(loc, "MakeLatLongEnvironment", texture,
                    [rib, picture = std::string(picture), texture = std::string(texture), o] {
                        rd::makeLatLongEnvironment(besideRib(rib, picture),
                                                   besideRib(rib, texture), o);
                    });
}

void RibBuilder::makeCubeFaceEnvironment(L loc, rib::Target::Strings faces, S texture,
                                         float fov, S filter, float swidth, float twidth, P) {
    const std::string rib = m_options.sourceFile;
    const MakeTextureOptions o = options("periodic", "clamp", filter, swidth, twidth);
    makeTextureFile(loc, "MakeCubeFaceEnvironment", texture,
                    [rib, faces = std::vector<std::string>(faces),
                     texture = std::string(texture), fov, o] {
                        if (faces.size() != 6) throw std::runtime_error("needs six faces");
                        std::array<std::string, 6> f;
                        for (size_t i = 0; i < 6; ++i) f[i] = besideRib(rib, faces[i]);
                        rd::makeCubeFaceEnvironment(f, besideRib(rib, texture), fov, o);
                    });
}

void RibBuilder::makeShadow(L loc, S picture, S texture, P) {
    const std::string rib = m_options.sourceFile;
    makeTextureFile(loc, "MakeShadow", texture,
                    [rib, picture = std::string(picture), texture = std::string(texture)] {
                        rd::makeShadow(besideRib(rib, picture), besideRib(rib, texture));
                    });
}

}  // namespace rd
