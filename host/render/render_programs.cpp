// render_programs.cpp: the trace and shading programs of a render (render_programs.h).
#include "render_programs.h"

#include <cctype>
#include <sstream>

#include "shaders/shader_set.h"

namespace rd {

const std::vector<std::string> kTraceSources = {
    "generate_eye.cl", "intersect.cl", "sort_by_shader.cl", "close_round.cl", "compact.cl",
    "retire.cl",       "treelet.cl",   "pixel_tests.cl", "film_sums.cl"};

namespace {
bool isWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Whether `word` occurs in `text` with no word character on either side.
bool namesWord(const std::string& text, const std::string& word) {
    for (size_t at = text.find(word); at != std::string::npos;
         at = text.find(word, at + 1))
        if ((at == 0 || !isWordChar(text[at - 1])) &&
            (at + word.size() == text.size() || !isWordChar(text[at + word.size()])))
            return true;
    return false;
}
}  // namespace

std::string optionsUsedBy(const std::string& source, const std::string& options) {
    std::istringstream in(options);
    std::string opt, out;
    while (in >> opt) {
        if (opt.rfind("-D", 0) == 0 &&
            !namesWord(source, opt.substr(2, opt.find('=') - 2)))
            continue;
        out += (out.empty() ? "" : " ") + opt;
    }
    return out;
}

RenderPrograms::RenderPrograms(const ClContext& ctx, const ShadingSetup& shading,
                               const std::string& options)
    : options(options) {
    const std::string traceSource = assembleClSource(kTraceSources);
    trace = std::make_unique<Program>(ctx, traceSource, optionsUsedBy(traceSource, options));
    const std::string shadeSource = assembleClSource(shading.sourceOrder, shading.generated);
    shade = std::make_unique<Program>(ctx, shadeSource, optionsUsedBy(shadeSource, options));
}

ProgramBuildInfo RenderPrograms::info() const {
    ProgramBuildInfo i = shade->info();
    i.options = options;
    const ProgramBuildInfo& t = trace->info();
    i.cacheHit = i.cacheHit && t.cacheHit;
    i.driverCache = i.driverCache && t.driverCache;
    i.buildMs += t.buildMs;
    i.cacheKey = t.cacheKey + "+" + i.cacheKey;
    i.cacheFile = t.cacheFile + (t.cacheFile.empty() ? "" : " ") + i.cacheFile;
    return i;
}

}  // namespace rd
