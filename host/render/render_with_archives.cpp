// render_with_archives.cpp: the read-render rounds of render_with_archives.h.
#include "render_with_archives.h"

#include <iostream>
#include <sstream>

#include "stop.h"

namespace rd {

RenderStats renderWithArchives(Renderer& renderer, const RibReadFn& read, const Scene& first,
                               size_t frame, Film& film, rib::Diagnostics& diag) {
    RenderStats st = renderer.render(first, film, diag);
    std::set<std::string> loaded;
    std::vector<Scene> scenes;
    while (!st.proceduralsReached.empty() && !stopSignal()) {
        std::set<std::string> files;
        for (const std::string& key : st.proceduralsReached) {
            loaded.insert(key);
            files.insert(key.substr(key.find('|') + 1));
        }
        // What the RIB said before was said already; pass on only the archives' own words.
        std::ostringstream said;
        rib::Diagnostics again(&said);
        scenes = read(loaded, again);
        std::istringstream lines(said.str());
        for (std::string line; std::getline(lines, line);)
            for (const std::string& f : files)
                if (!f.empty() && line.find(f) != std::string::npos) {
                    std::cerr << line << "\n";
                    break;
                }
        if (frame >= scenes.size()) break;
        film = Film();
        st = renderer.render(scenes[frame], film, diag);
    }
    st.archivesLoaded = loaded.size();
    return st;
}

}  // namespace rd
