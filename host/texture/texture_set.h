// texture_set.h: the scene's textures on the device (cl/include/texture.h). Names the
// shaders may pass to texture(), environment() or shadow() are looked up on the texture
// search path; each found file is opened through the texture backend (OpenImageIO's
// ImageCache: any tiled or scanline format); a picture that is not a mip-map is first
// made into one, as `raydrive txmake` would, in the cache folder. The device gets a table
// of textures, a page table and a tile cache of fixed size: a cache that holds every tile
// never evicts (sets up to 16 MiB are uploaded at once); a smaller one streams tiles as
// lookups ask for them, least recently used evicted first.
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cl/include/texture.h"
#include "ocl/buffer.h"
#include "rib/diagnostics.h"

namespace rd {

struct TextureStats {
    size_t textures = 0;         // files in use (broken ones included)
    size_t cacheTiles = 0;       // capacity of the device tile cache
    size_t totalTiles = 0;       // tiles of every level of every texture
    bool resident = false;       // everything uploaded up front
    uint64_t lookups = 0;        // texture()/environment()/shadow() calls on the device
    uint64_t missedLookups = 0;  // calls that met an absent tile (shaded again)
    uint64_t tilesUploaded = 0;
    uint64_t bytesUploaded = 0;
    uint64_t retryPasses = 0;    // shade launches again for points that missed
    uint64_t unresolved = 0;     // points given up on (the cache cannot hold their tiles)
    double hitRate() const {
        return lookups ? 1.0 - double(missedLookups) / double(lookups) : 1.0;
    }
};

class TextureSet {
public:
    TextureSet(std::vector<std::string> searchPath, std::string cacheDir, rib::Diagnostics& diag,
               rib::SourceLoc where);
    ~TextureSet();
    // A string a texture-using shader may pass as a map name: files that are not there are
    // reported only when a shader asks for them (so "raytrace" or "rgb" cost nothing).
    void addCandidate(const std::string& name);
    bool empty() const { return m_tex.empty(); }
    // (rsl::stringId(name), texture index) of every candidate, for the generated lookup.
    std::vector<std::pair<int, int>> ids() const;
    const std::string& name(size_t index) const { return m_tex[index].name; }
    const TexInfo& info(size_t index) const { return m_tex[index].info; }
    // The program's part that knows the textures: rd_tex_index(), textureinfo(), then
    // texture_lookup.clh.
    std::string deviceSource() const;

    // The device side; capacityTiles 0 picks min(every tile, 256 MiB of tiles).
    void createDevice(const ClContext& ctx, size_t capacityTiles);
    DeviceBuffer<TexInfo> infoBuf;
    DeviceBuffer<uint32_t> pageBuf;
    DeviceBuffer<rt_float4> tileBuf;
    DeviceBuffer<TexRequest> requestBuf;  // what the last launches asked for
    DeviceBuffer<uint32_t> counterBuf;    // [0] requests, [1] lookups, [2] missed, [3] pass
    DeviceBuffer<uint32_t> usedBuf;       // per cache slot: the last pass that used it
    static constexpr size_t kMaxRequests = 8192;
    static constexpr size_t kPreloadTiles = 1024;  // 16 MiB: uploaded before rendering

    // Loads what the requests name into the cache and uploads it with the page table;
    // a request for a broken or unknown texture is reported once per (texture, shader).
    void serve(const std::vector<TexRequest>& requests,
               const std::vector<std::string>& shaderNames);
    TextureStats& stats() { return m_stats; }

private:
    struct Texture {
        std::string name, file, problem;  // problem: why it is broken ("" when fine)
        TexInfo info{};
        std::vector<int> levelW, levelH;
    };
    void open(Texture& t);
    void openFile(Texture& t, bool mayConvert);  // t.file is there
    bool loadTile(const Texture& t, uint32_t level, uint32_t tx, uint32_t ty,
                  std::vector<rt_float4>& out);
    std::string find(const std::string& name) const;

    std::vector<std::string> m_path;
    std::string m_cacheDir;
    rib::Diagnostics& m_diag;
    rib::SourceLoc m_where;
    std::vector<Texture> m_tex;
    std::map<std::string, size_t> m_byName;
    std::vector<uint32_t> m_pages;                 // host copy of the page table
    std::vector<std::pair<uint32_t, uint32_t>> m_slotOwner;  // (texture, page) per slot
    std::vector<uint64_t> m_slotUsed;              // serve() round that last asked for it
    uint64_t m_round = 0;
    std::set<std::pair<uint32_t, uint32_t>> m_reported;  // (texture or id, shader)
    const ClContext* m_ctx = nullptr;
    TextureStats m_stats;
    std::string m_readError;  // the backend's last read failure
};

}  // namespace rd
