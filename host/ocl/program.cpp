// program.cpp: source assembly, building with the build log on failure, and the on-disk
// binary cache.
#include "program.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <unistd.h>

#include "check.h"

namespace rd {
namespace {

void appendWithIncludes(const std::string& name, const std::string& from,
                        const std::map<std::string, std::string>& generated,
                        std::set<std::string>& done, std::string& out) {
    if (!done.insert(name).second) return;
    const auto& embedded = embeddedClSources();
    const std::string* text = nullptr;
    if (auto g = generated.find(name); g != generated.end()) text = &g->second;
    else if (auto e = embedded.find(name); e != embedded.end()) text = &e->second;
    if (!text)
        throw std::runtime_error("OpenCL source '" + name + "' not found" +
                                 (from.empty() ? std::string() : " (included from " + from + ")"));
    std::istringstream in(*text);
    std::string line;
    out += "/* ---- " + name + " ---- */\n";
    while (std::getline(in, line)) {
        size_t p = line.find_first_not_of(" \t");
        if (p != std::string::npos && line.compare(p, 8, "#include") == 0) {
            size_t q0 = line.find('"', p), q1 = line.rfind('"');
            if (q0 != std::string::npos && q1 > q0) {
                appendWithIncludes(line.substr(q0 + 1, q1 - q0 - 1), name, generated, done, out);
                continue;
            }
        }
        out += line;
        out += '\n';
    }
}

uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
    for (unsigned char c : s) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

// POCL_KERNEL_CACHE=0 turns PoCL's own cache off.
bool poclCacheDisabled() {
    const char* v = std::getenv("POCL_KERNEL_CACHE");
    return v && std::string(v) == "0";
}

// Writes `bytes` to `path` through a temporary file (readers never see a partial file);
// the cache is an optimisation: failing to write it is never an error.
void writeCacheFile(const std::string& path, const char* bytes, size_t size) {
    std::error_code ec;
    std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
    std::string tmp = path + ".tmp" + std::to_string(::getpid()) + "-" +
                      std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) return;
        out.write(bytes, static_cast<std::streamsize>(size));
        if (!out) return;
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) std::filesystem::remove(tmp, ec);
}

// A stamp holds this text and the number of builds: a file with anything else (cut
// short, overwritten) is not one.
constexpr char kStamp[] = "raydrive: built by PoCL, in its cache; builds ";

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
        .count();
}

}  // namespace

std::string assembleClSource(const std::vector<std::string>& files,
                             const std::map<std::string, std::string>& generated) {
    std::set<std::string> done;
    std::string out;
    for (const std::string& f : files) appendWithIncludes(f, "", generated, done, out);
    return out;
}

std::string assembleClSource(const std::vector<std::string>& files) {
    return assembleClSource(files, {});
}

std::string defaultProgramCacheDir() {
    if (std::getenv("RAYDRIVE_NO_CACHE")) return {};
    if (const char* d = std::getenv("RAYDRIVE_CACHE_DIR")) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME")) return std::string(x) + "/raydrive";
    if (const char* h = std::getenv("HOME")) return std::string(h) + "/.cache/raydrive";
    return {};
}

Program::Program(const ClContext& ctx, const std::string& source, const std::string& options,
                 const std::string& cacheDir)
    : m_ctx(ctx) {
    auto t0 = std::chrono::steady_clock::now();
    const DeviceInfo& d = ctx.info();
    // Oclgrind's interpreter (21.10) does not know llvm.experimental.noalias.scope.decl,
    // which its compiler emits where it inlines a function returning a struct (the RSL
    // matrix functions): RSL_NOINLINE_STRUCT_RETURNS keeps those calls (tests/oclgrind).
    // Nor llvm.bitreverse, which its compiler makes of the Sobol sampler's bit reversal:
    // RT_NO_BITREVERSE reverses by a table (rng.clh).
    m_info.options = d.platformName.find("Oclgrind") != std::string::npos
                         ? options + " -DRSL_NOINLINE_STRUCT_RETURNS -DRT_NO_BITREVERSE"
                         : options;
    uint64_t h = fnv1a(source);
    h = fnv1a("\n--options--\n" + m_info.options, h);
    h = fnv1a("\n--device--\n" + d.platformName + "|" + d.name + "|" + d.driverVersion, h);
    char key[17];
    std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(h));
    m_info.cacheKey = key;
    // PoCL keeps its own cache of what it built (the program, and each kernel's
    // work-group function at each local size). Asking it for the program's binary makes
    // it compile every kernel once more for a dynamic local size first: SPD teapot's cold
    // build took 7.1 s that way against 1.4 s (whole commands 10.4 s against 4.1-4.4 s).
    // So on PoCL, with its cache on, the first builds keep only a stamp that counts them;
    // PoCL's cached build then loads in 40-66 ms against 14-23 ms for the binary, so a
    // program built kBinaryAfterBuilds times (an animation's frames) gets the binary too.
    m_info.driverCache = d.isPocl() && !poclCacheDisabled();
    const std::string base = cacheDir.empty() ? std::string() : cacheDir + "/" + m_info.cacheKey;
    if (!base.empty()) m_info.cacheFile = base + ".clbin";
    // RAYDRIVE_DUMP_KERNELS=DIR writes the assembled source with its options as defines,
    // for reading or for building with another compiler.
    if (const char* dump = std::getenv("RAYDRIVE_DUMP_KERNELS")) {
        std::error_code ec;
        std::filesystem::create_directories(dump, ec);
        std::ofstream(std::string(dump) + "/" + m_info.cacheKey + ".cl")
            << "/* options: " << m_info.options << " */\n" << source;
    }
    if (!base.empty() && tryBinary(m_info.cacheFile)) {
        m_info.cacheHit = true;
    } else if (m_info.driverCache) {
        const int builds = base.empty() ? 0 : stampedBuilds(base + ".pocl");
        m_info.cacheHit = builds > 0;
        buildFromSource(source);
        if (!base.empty() && builds + 1 >= kBinaryAfterBuilds) {
            saveBinary(m_info.cacheFile);
        } else if (!base.empty()) {
            m_info.cacheFile = base + ".pocl";
            saveStamp(m_info.cacheFile, builds + 1);
        }
    } else {
        buildFromSource(source);
        if (!base.empty()) saveBinary(m_info.cacheFile);
    }
    m_info.buildMs = msSince(t0);
}

Program::~Program() {
    if (m_program) clReleaseProgram(m_program);
}

std::string Program::buildLog() const {
    size_t n = 0;
    clGetProgramBuildInfo(m_program, m_ctx.device(), CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
    std::string log(n, '\0');
    if (n)
        clGetProgramBuildInfo(m_program, m_ctx.device(), CL_PROGRAM_BUILD_LOG, n, log.data(),
                              nullptr);
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

bool Program::tryBinary(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::string bin((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bin.empty()) return false;
    const unsigned char* ptr = reinterpret_cast<const unsigned char*>(bin.data());
    size_t len = bin.size();
    cl_int status = CL_SUCCESS, err = CL_SUCCESS;
    cl_device_id dev = m_ctx.device();
    cl_program p =
        clCreateProgramWithBinary(m_ctx.context(), 1, &dev, &len, &ptr, &status, &err);
    if (err != CL_SUCCESS || status != CL_SUCCESS) {
        if (p) clReleaseProgram(p);
        return false;  // a stale or foreign binary: rebuild from source
    }
    if (clBuildProgram(p, 1, &dev, m_info.options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
        clReleaseProgram(p);
        return false;
    }
    m_program = p;
    return true;
}

void Program::buildFromSource(const std::string& source) {
    cl_int err = CL_SUCCESS;
    const char* text = source.c_str();
    size_t len = source.size();
    m_program = clCreateProgramWithSource(m_ctx.context(), 1, &text, &len, &err);
    RD_CL_CHECK(err, m_ctx.name());
    cl_device_id dev = m_ctx.device();
    err = clBuildProgram(m_program, 1, &dev, m_info.options.c_str(), nullptr, nullptr);
    if (err != CL_SUCCESS) {
        std::string log = buildLog();
        if (log.size() > 20000) log = log.substr(0, 20000) + "\n... (build log cut)";
        throw std::runtime_error(std::string("OpenCL program build failed on device '") +
                                 m_ctx.name() + "' (" + clErrorName(err) +
                                 ", options: " + m_info.options + "):\n" + log);
    }
}

void Program::saveBinary(const std::string& path) const {
    size_t size = 0;
    if (clGetProgramInfo(m_program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) !=
            CL_SUCCESS ||
        size == 0)
        return;
    std::vector<unsigned char> bin(size);
    unsigned char* ptr = bin.data();
    if (clGetProgramInfo(m_program, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr) !=
        CL_SUCCESS)
        return;
    writeCacheFile(path, reinterpret_cast<const char*>(bin.data()), size);
}

int Program::stampedBuilds(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t n = sizeof kStamp - 1;
    if (text.size() <= n || text.compare(0, n, kStamp) != 0 || text.back() != '\n') return 0;
    const int builds = std::atoi(text.c_str() + n);
    return builds > 0 ? builds : 0;
}

void Program::saveStamp(const std::string& path, int builds) {
    const std::string text = kStamp + std::to_string(builds) + "\n";
    writeCacheFile(path, text.data(), text.size());
}

}  // namespace rd
