// bench_rsl2cl.cpp: compile time of every standard shader (rsl2cl/shaders/*.sl) in
// three stages: the rsl2cl front end (preprocess + parse + type check), the OpenCL C code
// generation, and the OpenCL build on the default device (rd::selectDevice(""): PoCL
// when present) of the runtime + that one shader + a trivial kernel calling it. Every
// build is cold: no RayDrive program cache (cache dir ""), POCL_KERNEL_CACHE=0, and a
// unique comment in each source. Median of N runs (default 5) per stage; prints a table
// and the totals.  Usage: bench_rsl2cl [runs] [shader-dir]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "compiler.h"
#include "emit_cl.h"
#include "ocl/context.h"
#include "ocl/device.h"
#include "ocl/program.h"

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// The renderer's services, stubbed: no lights, identity spaces, no messages.
const char* kServices =
    "int rsl_light_count(void) { return 0; }\n"
    "int rsl_light(int l, const RslGlobals* g, float4 Ps, float4* L, float4* Cl) {\n"
    "  (void)l; (void)g; (void)Ps; *L = (float4)(0.0f); *Cl = (float4)(0.0f); return "
    "0;\n}\n"
    "float4 rsl_ambient(const RslGlobals* g) { (void)g; return (float4)(0.0f); }\n"
    "RslMatrix rsl_space_matrix(const RslSpaces* sp, int space) {\n"
    "  (void)sp; (void)space; return rsl_mscalar(1.0f);\n}\n"
    "int rsl_lightsource_param(const RslGlobals* g, int light, int nameId, float* out, "
    "int n) {\n"
    "  (void)g; (void)light; (void)nameId; (void)out; (void)n; return 0;\n}\n"
    "int rsl_shader_param(const RslGlobals* g, int kind, int nameId, float* out, int n) "
    "{\n"
    "    (void)g; (void)kind; (void)nameId; (void)out; (void)n; return 0;\n}\n"
    "int rsl_attribute(const RslGlobals* g, int nameId, float* out, int n) {\n"
    "    (void)g; (void)nameId; (void)out; (void)n; return 0;\n}\n"
    "int rsl_option(const RslSpaces* sp, int nameId, float* out, int n) {\n"
    "  (void)sp; (void)nameId; (void)out; (void)n; return 0;\n}\n"
    "float4 rsl_texture_service(RslEval* ev, int kind, int id, int channel, float4 p, "
    "float4 dpdu,\n"
    "                           float4 dpdv, float width, float blur, float fill, float4 "
    "extra) {\n"
    "  (void)ev; (void)kind; (void)id; (void)channel; (void)p; (void)dpdu; (void)dpdv; "
    "(void)width;\n"
    "  (void)blur; (void)extra; return (float4)(fill, fill, fill, 0.0f);\n}\n"
    "float rsl_textureinfo_service(int id, int what, float* out, int n) {\n"
    "  (void)id; (void)what; (void)out; (void)n; return 0.0f;\n}\n";

std::string kernelFor(const rsl::EmittedShader& sh) {
    bool light = sh.kind == "light";
    std::ostringstream k;
    k << "__kernel void bench_main(__global const float* params, __global float* out) {\n"
         "  RslGlobals g; float* gp = (float*)&g;\n"
         "  for (int i = 0; i < (int)(sizeof(RslGlobals) / 4); ++i) gp[i] = 0.0f;\n"
         "  g.P = (float4)((float)get_global_id(0), 0.0f, 0.0f, 0.0f);\n"
         "  g.N = g.Ng = (float4)(0.0f, 0.0f, 1.0f, 0.0f);\n";
    if (light) {
        k << "  " << sh.functionName << "(&g, params);\n  out[get_global_id(0)] = g.Cl.x;\n}\n";
    } else {
        k << "  RslEval ev; ev.deriv = 0; ev.mode_light = -1; ev.mode_trace = -1; ev.trace_count = 0;\n"
          << "  " << sh.functionName << "(&g, params, &ev);\n  out[get_global_id(0)] = g.Ci.x;\n}\n";
    }
    return k.str();
}

struct Row {
    std::string name;
    double front = 0, emit = 0, build = 0;
    bool ok = true;
};

}  // namespace

int main(int argc, char** argv) {
    int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
    std::string dir = argc > 2 ? argv[2] : std::string(RSL2CL_SHADER_DIR);
    setenv("POCL_KERNEL_CACHE", "0", 1);  // before the platform is loaded
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".sl") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    if (files.empty()) {
        std::fprintf(stderr, "no .sl files in %s\n", dir.c_str());
        return 1;
    }
    std::string runtime = rsl::runtimeSource() + kServices;

    rd::DeviceInfo dev = rd::selectDevice("");
    rd::ClContext ctx(dev);
    std::printf("device: %s (%s), %d runs per stage, median\n\n", dev.name.c_str(),
                dev.platformName.c_str(), runs);
    std::printf("%-16s %14s %10s %18s\n", "shader", "front end ms", "emit ms", "OpenCL build ms");

    std::vector<Row> rows;
    int serial = 0;
    for (const std::string& path : files) {
        Row row;
        row.name = std::filesystem::path(path).stem().string();
        std::vector<double> tf, te, tb;
        for (int r = 0; r < runs && row.ok; ++r) {
            rsl::Diagnostics diag;
            auto prog = std::make_unique<rsl::Program>();
            auto t0 = Clock::now();
            bool ok = rsl::compileFile(path, {}, *prog, diag);
            tf.push_back(msSince(t0));
            if (!ok || prog->shaders.empty()) {
                std::fprintf(stderr, "%s: front end failed:\n%s", path.c_str(), diag.text().c_str());
                row.ok = false;
                break;
            }
            t0 = Clock::now();
            rsl::EmittedShader sh = rsl::emitOpenCL(*prog->shaders[0], *prog, diag);
            te.push_back(msSince(t0));
            if (!sh.ok) {
                std::fprintf(stderr, "%s: code generation failed:\n%s", path.c_str(), diag.text().c_str());
                row.ok = false;
                break;
            }
            std::string src = "/* bench run " + std::to_string(serial++) + " */\n" + runtime +
                              sh.source + "\n" + kernelFor(sh);
            try {
                t0 = Clock::now();
                rd::Program p(ctx, src, "-cl-std=CL1.2", "");
                tb.push_back(msSince(t0));
            } catch (const std::exception& ex) {
                std::fprintf(stderr, "%s: OpenCL build failed: %s\n", path.c_str(), ex.what());
                row.ok = false;
            }
        }
        row.front = median(tf);
        row.emit = median(te);
        row.build = median(tb);
        if (row.ok)
            std::printf("%-16s %14.3f %10.3f %18.1f\n", row.name.c_str(), row.front, row.emit, row.build);
        else
            std::printf("%-16s %14s %10s %18s\n", row.name.c_str(), "-", "-", "FAILED");
        rows.push_back(row);
    }
    double f = 0, e = 0, b = 0;
    bool allOk = true;
    for (const Row& r : rows) {
        f += r.front, e += r.emit, b += r.build;
        allOk = allOk && r.ok;
    }
    std::printf("%-16s %14.3f %10.3f %18.1f\n", "TOTAL", f, e, b);
    return allOk ? 0 : 1;
}
