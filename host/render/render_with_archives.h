// render_with_archives.h: rendering with DelayedReadArchive loaded when a ray first
// reaches its bound. The RIB is read with every such archive kept as a box; a render
// that meets one stops at once and names what it reached; the RIB is read again with
// those archives loaded and the frame rendered again, until no ray meets an archive
// still unloaded (archives inside archives take one more round each). An archive no ray
// reaches is never read.
#pragma once
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "renderer.h"

namespace rd {

// Reads the RIB into its world blocks with the archives `loaded` (keys) read at once.
using RibReadFn =
    std::function<std::vector<Scene>(const std::set<std::string>& loaded, rib::Diagnostics&)>;

// Renders world block `frame` (first: as already read with nothing loaded) into film;
// the stats are the final render's, with archivesLoaded set.
RenderStats renderWithArchives(Renderer& renderer, const RibReadFn& read, const Scene& first,
                               size_t frame, Film& film, rib::Diagnostics& diag);

}  // namespace rd
