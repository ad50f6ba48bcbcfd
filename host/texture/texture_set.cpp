// texture_set.cpp: finding, opening and streaming the scene's textures (texture_set.h).
#include "texture_set.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>

#include "texture_backend.h"
#include "texture_maker.h"

namespace rd {
namespace fs = std::filesystem;

TextureSet::TextureSet(std::vector<std::string> searchPath, std::string cacheDir,
                       rib::Diagnostics& diag, rib::SourceLoc where)
    : m_path(std::move(searchPath)), m_cacheDir(std::move(cacheDir)), m_diag(diag),
      m_where(std::move(where)) {}

TextureSet::~TextureSet() = default;

std::string TextureSet::find(const std::string& name) const {
    if (fs::path(name).is_absolute()) return fs::is_regular_file(name) ? name : std::string();
    for (const std::string& dir : m_path) {
        fs::path p = fs::path(dir) / name;
        if (fs::is_regular_file(p)) return p.string();
    }
    return std::string();
}

void TextureSet::addCandidate(const std::string& name) {
    if (name.empty() || name == "raytrace" || m_byName.count(name)) return;
    Texture t;
    t.name = name;
    open(t);
    m_byName[name] = m_tex.size();
    m_tex.push_back(std::move(t));
}

std::vector<std::pair<int, int>> TextureSet::ids() const {
    std::vector<std::pair<int, int>> out;
    for (const auto& [name, index] : m_byName) {
        // the FNV-1a id of rsl::stringId (rsl_abi.h, STRINGS), without the compiler here
        uint32_t h = 2166136261u;
        for (unsigned char c : name) h = (h ^ c) * 16777619u;
        out.push_back({int(h & 0xffffffu), int(index)});
    }
    return out;
}

void TextureSet::open(Texture& t) {
    TexInfo& info = t.info;
    info.flags = RT_TEX_BROKEN;
    info.page_base = uint32_t(m_pages.size());
    t.file = find(t.name);
    if (t.file.empty()) {
        std::string path;
        for (const std::string& d : m_path) path += (path.empty() ? "" : ":") + d;
        t.problem = "file not found on the texture search path (" + path + ")";
        return;
    }
    openFile(t, true);
}

void TextureSet::openFile(Texture& t, bool mayConvert) {
    TexInfo& info = t.info;
    ImageInfo spec;
    std::string error;
    try {
        if (!textureBackend().describe(t.file, spec, &error)) {
            t.problem = "cannot read \"" + t.file + "\": " + error;
            return;
        }
    } catch (const std::exception& e) {
        t.problem = e.what();
        return;
    }
    const int levels = spec.levels;
    const bool made = spec.tiled && !spec.textureformat.empty();
    if (mayConvert && !made && levels == 1 && (spec.width > 1 || spec.height > 1)) {
        // a picture, not a mip-map: make one once, as `raydrive txmake` does, and keep it
        std::error_code ec;
        auto stamp = fs::last_write_time(t.file, ec).time_since_epoch().count();
        size_t key = std::hash<std::string>()(fs::absolute(t.file).string() + std::to_string(stamp));
        fs::path out = fs::path(m_cacheDir) / ("tex-" + std::to_string(key) + ".exr");
        try {
            if (!fs::exists(out)) {
                fs::create_directories(m_cacheDir, ec);
                fs::path tmp = out;
                tmp += ".tmp.exr";
                makeTexture(t.file, tmp.string(), MakeTextureOptions{});
                fs::rename(tmp, out);
            }
        } catch (const std::exception& e) {
            t.problem = std::string("cannot make a mip-map of it: ") + e.what();
            return;
        }
        t.file = out.string();
        openFile(t, false);
        return;
    }
    info.width = uint32_t(spec.width);
    info.height = uint32_t(spec.height);
    info.levels = uint32_t(levels);
    info.channels = uint32_t(std::clamp(spec.channels, 1, 4));
    std::string wraps = spec.wrapmodes.empty() ? "black,black" : spec.wrapmodes;
    size_t comma = wraps.find(',');
    int ws = wrapModeOf(wraps.substr(0, comma));
    int wt = wrapModeOf(comma == std::string::npos ? wraps : wraps.substr(comma + 1));
    info.wrap_s = uint32_t(ws < 0 ? 0 : ws);
    info.wrap_t = uint32_t(wt < 0 ? 0 : wt);
    const std::string& format = spec.textureformat;
    info.flags = 0;
    if (format.find("LatLong") != std::string::npos) info.flags |= RT_TEX_LATLONG;
    if (format.find("Shadow") != std::string::npos) {
        info.flags |= RT_TEX_SHADOW;
        if (!spec.hasMatrices) {
            info.flags = RT_TEX_BROKEN;
            t.problem = "a shadow map without its \"worldtoscreen\" and \"worldtocamera\" matrices";
            return;
        }
        // row-vector matrices (p' = p M): column j of M is output j
        const float* sm = spec.worldToScreen.data();
        const float* cm = spec.worldToCamera.data();
        for (int j = 0; j < 4; ++j) {
            info.world_to_screen[j] = {sm[0 * 4 + j], sm[1 * 4 + j], sm[2 * 4 + j], sm[3 * 4 + j]};
            info.world_to_camera[j] = {cm[0 * 4 + j], cm[1 * 4 + j], cm[2 * 4 + j], cm[3 * 4 + j]};
        }
    }
    uint32_t page = 0;
    for (int l = 0; l < levels; ++l) {
        int w = std::max(1, spec.width >> l), h = std::max(1, spec.height >> l);
        t.levelW.push_back(w);
        t.levelH.push_back(h);
        uint32_t tx = uint32_t((w + RT_TEX_TILE - 1) / RT_TEX_TILE);
        uint32_t ty = uint32_t((h + RT_TEX_TILE - 1) / RT_TEX_TILE);
        info.level_page[l] = page;
        info.level_tiles_x[l] = tx;
        page += tx * ty;
    }
    m_pages.insert(m_pages.end(), page, RT_TEX_ABSENT);
}

bool TextureSet::loadTile(const Texture& t, uint32_t level, uint32_t tx, uint32_t ty,
                          std::vector<rt_float4>& out) {
    out.assign(RT_TEX_TILE_TEXELS, rt_float4{0, 0, 0, 0});
    int x0 = int(tx) * RT_TEX_TILE, y0 = int(ty) * RT_TEX_TILE;
    int x1 = std::min(x0 + RT_TEX_TILE, t.levelW[level]);
    int y1 = std::min(y0 + RT_TEX_TILE, t.levelH[level]);
    if (x1 <= x0 || y1 <= y0) return true;
    return textureBackend().read(t.file, int(level), x0, x1, y0, y1, int(t.info.channels),
                                 &out[0].x, sizeof(rt_float4), sizeof(rt_float4) * RT_TEX_TILE,
                                 &m_readError);
}

std::string TextureSet::deviceSource() const {
    std::ostringstream s;
    s << "static int rd_tex_index(int id) {\n    switch (id) {\n";
    for (const auto& [id, index] : ids()) s << "    case " << id << ": return " << index << ";\n";
    s << "    default: return -1;\n    }\n}\n";
    // textureinfo(): what the host knows of each texture
    s << "float rsl_textureinfo_service(int id, int what, float* out, int n) {\n"
         "    switch (rd_tex_index(id)) {\n";
    uint32_t h = 2166136261u;
    auto sid = [&](const std::string& text) {
        h = 2166136261u;
        for (unsigned char c : text) h = (h ^ c) * 16777619u;
        return int(h & 0xffffffu);
    };
    for (const auto& [id, index] : ids()) {
        const TexInfo& i = m_tex[size_t(index)].info;
        if (i.flags & RT_TEX_BROKEN) continue;
        const char* type = (i.flags & RT_TEX_SHADOW)    ? "shadow"
                           : (i.flags & RT_TEX_LATLONG) ? "environment"
                                                        : "texture";
        s << "    case " << index << ":\n"
          << "        if (what == RSL_TEXINFO_RESOLUTION && n == 2) { out[0] = " << i.width
          << ".0f; out[1] = " << i.height << ".0f; return 1.0f; }\n"
          << "        if (what == RSL_TEXINFO_CHANNELS && n == 1) { out[0] = " << i.channels
          << ".0f; return 1.0f; }\n"
          << "        if (what == RSL_TEXINFO_TYPE && n == 1) { out[0] = " << sid(type)
          << ".0f; return 1.0f; }\n        return 0.0f;\n";
    }
    s << "    default: return 0.0f;\n    }\n}\n#include \"texture_lookup.clh\"\n";
    return s.str();
}

void TextureSet::createDevice(const ClContext& ctx, size_t capacityTiles) {
    m_ctx = &ctx;
    const size_t total = m_pages.size();
    const size_t budget = (size_t(256) << 20) / (sizeof(rt_float4) * RT_TEX_TILE_TEXELS);
    size_t cap = capacityTiles ? capacityTiles : std::min(total, budget);
    cap = std::max<size_t>(cap, std::min<size_t>(total, 64));  // a point's tiles must fit
    cap = std::max<size_t>(cap, 1);
    m_stats.textures = m_tex.size();
    m_stats.totalTiles = total;
    m_stats.cacheTiles = cap;
    m_slotOwner.assign(cap, {UINT32_MAX, UINT32_MAX});
    m_slotUsed.assign(cap, 0);
    std::vector<TexInfo> infos;
    for (const Texture& t : m_tex) infos.push_back(t.info);
    infoBuf = DeviceBuffer<TexInfo>(ctx, infos);
    tileBuf = DeviceBuffer<rt_float4>(ctx, cap * RT_TEX_TILE_TEXELS);
    requestBuf = DeviceBuffer<TexRequest>(ctx, kMaxRequests);
    counterBuf = DeviceBuffer<uint32_t>(ctx, 4);
    counterBuf.fillZero();
    usedBuf = DeviceBuffer<uint32_t>(ctx, cap);
    usedBuf.fillZero();
    m_round = 1;
    const uint32_t first = 1;
    counterBuf.uploadRange(3, &first, 1);
    pageBuf = DeviceBuffer<uint32_t>(ctx, std::max<size_t>(total, 1), CL_MEM_READ_ONLY);
    // Resident: the cache holds every tile, so none is ever evicted. Small sets are
    // uploaded at once; larger ones as lookups ask (a render at a distance reads few
    // tiles of its finest levels: uploading 358 MB up front took 6.1 s where streaming
    // what was used took 3.4 s, benchmarks/README.md).
    m_stats.resident = cap >= total;
    if (m_stats.resident && total <= kPreloadTiles) {  // every tile now: no lookup misses
        std::vector<TexRequest> all;
        for (size_t i = 0; i < m_tex.size(); ++i) {
            const Texture& t = m_tex[i];
            if (t.info.flags & RT_TEX_BROKEN) continue;
            for (uint32_t l = 0; l < t.info.levels; ++l) {
                uint32_t tilesY = uint32_t((t.levelH[l] + RT_TEX_TILE - 1) / RT_TEX_TILE);
                for (uint32_t y = 0; y < tilesY; ++y)
                    for (uint32_t x = 0; x < t.info.level_tiles_x[l]; ++x)
                        all.push_back({uint32_t(i), RT_TEX_TILE_CODE(l, x, y)});
            }
        }
        serve(all, {});
    } else {
        pageBuf.upload(m_pages);
    }
}

void TextureSet::serve(const std::vector<TexRequest>& requests,
                       const std::vector<std::string>& shaderNames) {
    // m_round is the pass that asked: the tiles it used (marked on the device) and the
    // ones loaded for it stay; the next pass is m_round + 1
    const uint64_t pass = m_round;
    if (!m_stats.resident && m_ctx) {
        std::vector<uint32_t> used = usedBuf.download();
        for (size_t s = 0; s < used.size() && s < m_slotUsed.size(); ++s)
            m_slotUsed[s] = std::max<uint64_t>(m_slotUsed[s], used[s]);
    }
    ++m_round;
    if (m_ctx) {
        const uint32_t next = uint32_t(m_round);
        counterBuf.uploadRange(3, &next, 1);
    }
    struct Need {
        uint32_t tex, page, level, tx, ty;
    };
    std::vector<Need> needs;
    std::set<uint32_t> seen;
    for (const TexRequest& r : requests) {
        if ((r.tile >> 24) == 0xffu) {  // a report: a broken or unknown texture was asked for
            uint32_t shader = r.tile & 0xffffffu;
            if (!m_reported.insert({r.tex, shader}).second) continue;
            std::string who = shader < shaderNames.size() ? "shader \"" + shaderNames[shader] + "\""
                                                           : std::string("a shader");
            if (r.tex & 0x80000000u)
                m_diag.warning(m_where, who + " asked for a texture whose name is not known "
                                              "before the render (id " +
                                              std::to_string(r.tex & 0xffffffu) +
                                              "); using the default");
            else if (r.tex < m_tex.size())
                m_diag.warning(m_where, who + " asked for texture \"" + m_tex[r.tex].name +
                                            "\": " + m_tex[r.tex].problem + "; using the default");
            continue;
        }
        if (r.tex >= m_tex.size()) continue;
        const Texture& t = m_tex[r.tex];
        uint32_t level = r.tile >> 24, ty = (r.tile >> 12) & 0xfffu, tx = r.tile & 0xfffu;
        if (level >= t.info.levels || tx >= t.info.level_tiles_x[level]) continue;
        uint32_t page = t.info.page_base + t.info.level_page[level] + ty * t.info.level_tiles_x[level] + tx;
        if (page >= m_pages.size() || !seen.insert(page).second) continue;
        if (m_pages[page] != RT_TEX_ABSENT) {
            m_slotUsed[m_pages[page]] = m_round;
            continue;
        }
        needs.push_back({r.tex, page, level, tx, ty});
    }
    if (needs.empty()) return;
    // free slots first, then the least recently used; the tiles the last pass used or
    // had loaded for it stay, unless that would leave no room at all (then half the
    // cache goes, so the points waiting keep making progress)
    std::vector<uint32_t> victims(m_slotOwner.size());
    for (uint32_t s = 0; s < victims.size(); ++s) victims[s] = s;
    std::stable_sort(victims.begin(), victims.end(), [&](uint32_t a, uint32_t b) {
        bool fa = m_slotOwner[a].first == UINT32_MAX, fb = m_slotOwner[b].first == UINT32_MAX;
        if (fa != fb) return fa;
        return m_slotUsed[a] < m_slotUsed[b];
    });
    size_t room = 0;
    while (room < victims.size() && (m_slotOwner[victims[room]].first == UINT32_MAX ||
                                     m_slotUsed[victims[room]] < pass))
        ++room;
    if (room == 0) room = std::max<size_t>(1, victims.size() / 2);
    victims.resize(room);
    std::vector<rt_float4> texels;
    size_t next = 0;
    for (const Need& n : needs) {
        if (next == victims.size()) break;  // the cache is full of this round's tiles
        Texture& t = m_tex[n.tex];
        if (!loadTile(t, n.level, n.tx, n.ty, texels)) {
            t.problem = "cannot read a tile of \"" + t.file + "\": " + m_readError;
            t.info.flags |= RT_TEX_BROKEN;
            infoBuf.uploadRange(n.tex, &t.info, 1);
            continue;
        }
        uint32_t slot = victims[next++];
        if (m_slotOwner[slot].first != UINT32_MAX) m_pages[m_slotOwner[slot].second] = RT_TEX_ABSENT;
        m_slotOwner[slot] = {n.tex, n.page};
        m_slotUsed[slot] = m_round;
        m_pages[n.page] = slot;
        tileBuf.uploadRange(size_t(slot) * RT_TEX_TILE_TEXELS, texels.data(), texels.size());
        ++m_stats.tilesUploaded;
        m_stats.bytesUploaded += texels.size() * sizeof(rt_float4);
    }
    pageBuf.upload(m_pages);
}

}  // namespace rd
