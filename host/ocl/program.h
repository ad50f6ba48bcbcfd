// program.h: turns embedded OpenCL sources into a built program. The host resolves
// #include itself (so the source that is hashed is the source that is built), passes the
// scene's -D options, shows the build log on failure, and caches program binaries on disk
// keyed by hash(source + options + device + driver): a second render of the same scene
// skips the compiler (reported as a cache hit in --stats). PoCL caches its builds itself:
// there a stamp counts the program's builds, and the binary is kept from the
// kBinaryAfterBuilds-th on.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "context.h"

namespace rd {

// The sources embedded by cl/embed.cmake, by file name.
const std::map<std::string, std::string>& embeddedClSources();

// Concatenates `files` with every `#include "x"` replaced by x's text, once per file.
// Throws std::runtime_error naming the including file for an unknown include.
std::string assembleClSource(const std::vector<std::string>& files);
// The same, with generated sources (by name) that may be listed or included too.
std::string assembleClSource(const std::vector<std::string>& files,
                             const std::map<std::string, std::string>& generated);

// $RAYDRIVE_CACHE_DIR, else $XDG_CACHE_HOME/raydrive, else ~/.cache/raydrive; empty when
// caching is off (RAYDRIVE_NO_CACHE set, or no home directory).
std::string defaultProgramCacheDir();

struct ProgramBuildInfo {
    bool cacheHit = false;  // built before: the binary cached, or the driver's cache has it
    bool driverCache = false;  // PoCL's own cache holds the build (cacheFile: a stamp,
                               // until kBinaryAfterBuilds builds make it the binary)
    double buildMs = 0;     // wall time to get an executable program
    std::string cacheKey;   // 16 hex digits
    std::string cacheFile;  // empty when caching is off
    std::string options;
};

// On PoCL, the builds of one program after which its binary is cached too (program.cpp).
constexpr int kBinaryAfterBuilds = 16;

class Program {
public:
    Program(const ClContext& ctx, const std::string& source, const std::string& options,
            const std::string& cacheDir = defaultProgramCacheDir());
    ~Program();
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    cl_program get() const { return m_program; }
    const ProgramBuildInfo& info() const { return m_info; }

private:
    bool tryBinary(const std::string& path);
    void buildFromSource(const std::string& source);
    void saveBinary(const std::string& path) const;
    // The builds a stamp counts (0: no stamp); a stamp of `builds`.
    static int stampedBuilds(const std::string& path);
    static void saveStamp(const std::string& path, int builds);
    std::string buildLog() const;

    const ClContext& m_ctx;
    cl_program m_program = nullptr;
    ProgramBuildInfo m_info;
};

}  // namespace rd
