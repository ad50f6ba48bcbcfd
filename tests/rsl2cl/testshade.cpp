// testshade.cpp: the OpenCL side of the rsl2cl test harness (see testshade.h).
#define CL_TARGET_OPENCL_VERSION 120
#include "testshade.h"

#include <CL/cl.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/glm.hpp>
#include <sstream>

#include "compiler.h"

namespace ts {
namespace {

struct Cl {
    cl_context ctx = nullptr;
    cl_command_queue q = nullptr;
    cl_device_id dev = nullptr;
    bool ok = false;
    Cl() {
        cl_uint np = 0;
        if (clGetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0) return;
        std::vector<cl_platform_id> ps(np);
        clGetPlatformIDs(np, ps.data(), nullptr);
        for (cl_platform_id p : ps) {
            if (clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 1, &dev, nullptr) == CL_SUCCESS) break;
            dev = nullptr;
        }
        if (!dev) return;
        cl_int err;
        ctx = clCreateContext(nullptr, 1, &dev, nullptr, nullptr, &err);
        if (err != CL_SUCCESS) return;
        q = clCreateCommandQueue(ctx, dev, 0, &err);
        ok = err == CL_SUCCESS;
    }
};

Cl& cl() {
    static Cl c;
    return c;
}

std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The globals as the kernel takes and returns them (ts_main copies them into RslGlobals,
// colours through the channels: rsl_rgb_color, rsl_color_rgb): 15 float4 + 8 floats
const int kGlobalFloats = 68;
// 3 ints (+pad) + 2 x 8 float4 + outputs + up to 8 lights' coefficients (float4)
const int kEvalFloats = 4 + 2 * 8 * 4 + 32 + 8 * 4;
// field order of RslGlobals
enum { fP, fN, fNg, fI, fE, fdPdu, fdPdv, fCs, fOs, fCi, fOi, fL, fCl, fOl, fPs };

// The inverse of a 4x4 matrix of 16 floats (either order: the inverse of the transpose
// is the transpose of the inverse), in double.
void invertRowMajor4(const float* in, float* out) {
    glm::dmat4 m;
    for (int i = 0; i < 16; ++i) (&m[0][0])[i] = in[i];
    const glm::dmat4 inv = glm::inverse(m);
    for (int i = 0; i < 16; ++i) out[i] = float((&inv[0][0])[i]);
}

std::string fl(float x) {
    std::ostringstream s;
    s.precision(9);
    s << x << "f";
    std::string r = s.str();
    if (r.find_first_of(".e") == std::string::npos) r.insert(r.size() - 1, ".0");
    return r;
}

std::string sceneKey(const Scene& sc) {
    std::ostringstream s;
    s.precision(9);
    for (const Light& l : sc.lights)
        s << l.L[0] << "," << l.L[1] << "," << l.L[2] << "," << l.Cl[0] << "," << l.Cl[1] << ","
          << l.Cl[2] << ";";
    s << sc.ambient[0] << "," << sc.ambient[1] << "," << sc.ambient[2] << ";" << sc.cameraOffset[0]
      << "," << sc.cameraOffset[1] << "," << sc.cameraOffset[2] << ";";
    for (const std::vector<Message>* ms : {&sc.lightParams, &sc.attributes, &sc.options}) {
        for (const Message& m : *ms) {
            s << m.light << ":" << m.name << "=";
            for (float v : m.values) s << v << ",";
        }
        s << "|";
    }
    return s.str();
}

// One fake message service: answers (light,) name, n from `ms`.
std::string messageService(const std::string& sig, const std::vector<Message>& ms, bool byLight) {
    std::ostringstream s;
    s << sig << " {\n";
    for (const Message& m : ms) {
        s << "  if (" << (byLight ? "light == " + std::to_string(m.light) + " && " : "")
          << "nameId == " << rsl::stringId(m.name) << " && n == " << m.values.size() << ") {";
        for (size_t i = 0; i < m.values.size(); ++i) s << " out[" << i << "] = " << fl(m.values[i]) << ";";
        s << " return 1; }\n";
    }
    s << "  (void)nameId; (void)out; (void)n;" << (byLight ? " (void)g; (void)light;" : "")
      << "\n  return 0;\n}\n";
    return s.str();
}

}  // namespace

bool deviceAvailable() { return cl().ok; }

std::vector<Point> grid(int n) {
    std::vector<Point> pts;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            Point p;
            p.s = p.u = n > 1 ? float(i) / float(n - 1) : 0.5f;
            p.t = p.v = n > 1 ? float(j) / float(n - 1) : 0.5f;
            p.P[0] = 4 * p.s - 2;
            p.P[1] = 4 * p.t - 2;
            p.E[2] = 5;
            for (int k = 0; k < 3; ++k) p.I[k] = p.P[k] - p.E[k];
            for (int k = 0; k < 3; ++k) p.Ps[k] = p.P[k] + (k == 2 ? 1.0f : 0.0f);
            pts.push_back(p);
        }
    return pts;
}

bool Shade::compileSource(const std::string& rsl, const std::string& name, std::string* err) {
    rsl::Diagnostics diag;
    auto prog = std::make_unique<rsl::Program>();
    bool ok = rsl::compileSource(rsl, name, {}, *prog, diag);
    if (ok && !prog->shaders.empty()) {
        shader = rsl::emitOpenCL(*prog->shaders[0], *prog, diag, colorChannels);
        ok = shader.ok;
    } else {
        ok = false;
    }
    diagnostics = diag.text();
    if (err) *err = diagnostics;
    if (ok) {
        params.assign(shader.paramFloats, 0.0f);
        for (const rsl::ParamSlot& p : shader.params) {
            for (int i = 0; i < p.size; ++i) params[p.offset + i] = p.defaults[i];
            if (p.rgbDefault) setParam(p.name, p.defaults);  // into the channels
        }
    }
    m_builtFor.clear();
    return ok;
}

bool Shade::compileFile(const std::string& path, std::string* err) {
    std::string name = path.substr(path.find_last_of('/') + 1);
    return compileSource(slurp(path), name, err);
}

void Shade::setParam(const std::string& name, const std::vector<float>& values) {
    for (const rsl::ParamSlot& p : shader.params) {
        if (p.name != name) continue;
        for (size_t i = 0; i < values.size() && int(i) < p.size; ++i)
            params[p.offset + i] = values[i];
        if (p.type.base != rsl::BaseType::Color || colorChannels <= 3) continue;
        // RGB values (each element's first three) repeated over the channels
        const int per = p.size / std::max(1, p.arraySize);
        for (int e = 0; e < p.size / per; ++e)
            for (int i = 3; i < per; ++i)
                params[p.offset + e * per + i] = params[p.offset + e * per + i % 3];
    }
}

bool Shade::buildOnDevice(const Scene& sc, std::string* log) {
    if (!cl().ok) {
        if (log) *log = "no OpenCL device";
        return false;
    }
    std::string key = sceneKey(sc);
    if (m_program && m_builtFor == key) return true;
    std::ostringstream src;
    // LIGHT COEFFICIENTS (rsl_abi.h): run(modeLight = kCoefficients) fills Out::CiLight
    if (!sc.lights.empty()) src << "#define RSL_LIGHT_COEFS " << sc.lights.size() << "\n";
    if (colorChannels > 3) {  // each RGB value twice over (Shade::colorChannels)
        const int n = colorChannels;
        std::string to, from;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 3; ++j)
                to += std::string(to.empty() ? "" : ",") +
                      (i % 3 == j ? fl(3.0f / float(n)) : "0.0f");
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < n; ++i)
                from +=
                    std::string(from.empty() ? "" : ",") + (i % 3 == j ? "1.0f" : "0.0f");
        src << "#define RSL_COLOR_LANES " << (n <= 7 ? 8 : 16)
            << "\n#define RSL_COLOR_SAMPLES " << n << "\n#define RSL_NRGB " << to
            << "\n#define RSL_RGBN " << from << "\n";
    }
    src << rsl::runtimeSource();
    // the fake renderer services
    src << "__constant float ts_lights[] = {0";
    for (const Light& l : sc.lights)
        for (int k = 0; k < 3; ++k) src << ", " << fl(l.L[k]) << ", " << fl(l.Cl[k]);
    src << "};\n#define TS_NLIGHTS " << sc.lights.size() << "\n";
    src << "int rsl_light_count(void) { return TS_NLIGHTS; }\n"
           "int rsl_light(int l, const RslGlobals* g, float4 Ps, float4* L,\n"
           "              rsl_color* Cl) {\n"
           "  (void)g; (void)Ps; if (l < 0 || l >= TS_NLIGHTS) return 0;\n"
           "  __constant float* x = ts_lights + 1 + 6 * l;\n"
           "  *L = (float4)(x[0], x[2], x[4], 0.0f);\n"
           "  *Cl = rsl_rgb_color((float4)(x[1], x[3], x[5], 0.0f));\n"
           "  return 1;\n}\n";
    src << "rsl_color rsl_ambient(const RslGlobals* g) {\n"
           "  (void)g; return rsl_rgb_color((float4)("
        << fl(sc.ambient[0]) << ", " << fl(sc.ambient[1]) << ", " << fl(sc.ambient[2])
        << ", 0.0f)); }\n";
    // shader and object space come from the block; the service only knows camera
    src << "RslMatrix rsl_space_matrix(const RslSpaces* sp, int space, int inverse) {\n"
           "  (void)sp; RslMatrix m = rsl_mscalar(1.0f);\n"
           "  if (space == RSL_SPACE_CAMERA) m.r[3] = (float4)("
        << fl(sc.cameraOffset[0]) << ", " << fl(sc.cameraOffset[1]) << ", "
        << fl(sc.cameraOffset[2])
        << ", 1.0f);\n  return inverse ? rsl_minverse(m) : m;\n}\n";
    src << messageService(
               "int rsl_lightsource_param(const RslGlobals* g, int light, int nameId, "
               "float* out, int n)",
               sc.lightParams, true)
        << messageService(
               "int rsl_attribute(const RslGlobals* g, int nameId, float* out, int n)",
               sc.attributes, false)
        << messageService(
               "int rsl_option(const RslSpaces* sp, int nameId, float* out, int n)",
               sc.options, false)
        << "int rsl_shader_param(const RslGlobals* g, int kind, int nameId, float* out, "
           "int n) {\n"
           "  (void)g; (void)kind; (void)nameId; (void)out; (void)n; return 0;\n}\n";
    // no textures here: every lookup gives its fill value
    src << "float4 rsl_texture_service(RslEval* ev, int kind, int id, int channel, float4 p, float4 dpdu,\n"
    "                           float4 dpdv, float width, float blur, float fill, float4 extra) {\n"
    "  (void)ev; (void)kind; (void)id; (void)channel; (void)p; (void)dpdu; (void)dpdv; (void)width;\n"
    "  (void)blur; (void)extra; return (float4)(fill, fill, fill, 0.0f);\n}\n"
    "float rsl_textureinfo_service(int id, int what, float* out, int n) {\n"
    "  (void)id; (void)what; (void)out; (void)n; return 0.0f;\n}\n";
    src << shader.source << "\n";
    bool light = shader.kind == "light";
    if (!shader.prepFunction.empty())  // the instance's uniform work (hoist.h), run first
        src << "__kernel void ts_prep(__global float* params) { " << shader.prepFunction
            << "(params, params); }\n";
    const std::string gf = std::to_string(kGlobalFloats);
    src << "__kernel void ts_main(__global const float* gin, __global const float* "
           "params,\n"
           "                      int mode_light, int mode_trace, __global float* out) "
           "{\n"
           "  int i = get_global_id(0);\n"
           "  __global const float4* gi = (__global const float4*)(gin + i * " +
               gf +
               ");\n"
               "  __global const float* gs = gin + i * " +
               gf +
               " + 60;\n"
               "  RslGlobals g;\n"
               "  g.P = gi[0]; g.N = gi[1]; g.Ng = gi[2]; g.I = gi[3]; g.E = gi[4];\n"
               "  g.dPdu = gi[5]; g.dPdv = gi[6];\n"
               "  g.Cs = rsl_rgb_color(gi[7]); g.Os = rsl_rgb_color(gi[8]);\n"
               "  g.Ci = rsl_rgb_color(gi[9]); g.Oi = rsl_rgb_color(gi[10]);\n"
               "  g.L = gi[11]; g.Cl = rsl_rgb_color(gi[12]); g.Ol = "
               "rsl_rgb_color(gi[13]);\n"
               "  g.Ps = gi[14];\n"
               "  g.u = gs[0]; g.v = gs[1]; g.s = gs[2]; g.t = gs[3]; g.du = gs[4]; g.dv "
               "= gs[5];\n"
               "  g.ncomps = (float)RSL_CHANNELS; g.time = gs[7];\n"
               "  g.light_cache_count = 0; g.light_cache = 0; g.lights_off = 0u;\n"
               "  g.rng_pixel = g.rng_sample = g.rng_depth = 0u;\n"
               "  g.st_footprint = (float4)(0.0f);\n"
               "  g.texctx = 0;\n  g.loops_cut = 0;\n  g.scene_params = params;\n"
               "  g.material = 0;\n  g.ray_depth = 0u;\n"
               "  RslEval ev; ev.deriv = 0; ev.mode_light = max(mode_light, -1);\n"
               "  ev.mode_trace = mode_trace; ev.trace_count = 0;\n"
               "#ifdef RSL_LIGHT_COEFS\n"
               "  ev.coefs = mode_light == -2;\n"
               "  for (int k = 0; k < RSL_LIGHT_COEFS; ++k) ev.Ci_light[k] = "
               "(rsl_color)(-12345.0f);\n"
               "#endif\n"
               "  for (int k = 0; k < RSL_MAX_TRACE; ++k) {\n"
               "    ev.trace_org[k] = (float4)(0); ev.trace_dir[k] = (float4)(0);\n"
               "  }\n"
               "  for (int k = 0; k < RSL_MAX_OUTPUT_FLOATS; ++k) ev.outputs[k] = "
               "-12345.0f;\n"
        << (light ? "  (void)ev; " + shader.functionName + "(&g, params);\n"
                  : "  " + shader.functionName + "(&g, params, &ev);\n")
        << "  __global float* o = out + i * " << (kGlobalFloats + kEvalFloats) << ";\n"
        << "  __global float4* go = (__global float4*)o;\n"
           "  go[0] = g.P; go[1] = g.N; go[2] = g.Ng; go[3] = g.I; go[4] = g.E;\n"
           "  go[5] = g.dPdu; go[6] = g.dPdv;\n"
           "  go[7] = rsl_color_rgb(g.Cs); go[8] = rsl_color_rgb(g.Os);\n"
           "  go[9] = rsl_color_rgb(g.Ci); go[10] = rsl_color_rgb(g.Oi);\n"
           "  go[11] = g.L; go[12] = rsl_color_rgb(g.Cl); go[13] = rsl_color_rgb(g.Ol);\n"
           "  go[14] = g.Ps;\n"
           "  o[60] = g.u; o[61] = g.v; o[62] = g.s; o[63] = g.t; o[64] = g.du; o[65] = "
           "g.dv;\n"
           "  o[66] = g.ncomps; o[67] = g.time;\n"
        << "  o += " + gf +
               "; o[0] = (float)ev.trace_count;\n"
               "  for (int k = 0; k < RSL_MAX_TRACE; ++k) {\n"
               "    vstore4(ev.trace_org[k], 0, o + 4 + 4 * k);\n"
               "    vstore4(ev.trace_dir[k], 0, o + 36 + 4 * k);\n"
               "  }\n"
               "  for (int k = 0; k < RSL_MAX_OUTPUT_FLOATS; ++k) o[68 + k] = "
               "ev.outputs[k];\n"
               "#ifdef RSL_LIGHT_COEFS\n"
               "  for (int k = 0; k < min(RSL_LIGHT_COEFS, 8); ++k)\n"
               "    vstore4(rsl_color_rgb(ev.Ci_light[k]), 0, o + 100 + 4 * k);\n"
               "#endif\n}\n";
    std::string text = src.str();
    const char* p = text.c_str();
    cl_int err;
    cl_program prog = clCreateProgramWithSource(cl().ctx, 1, &p, nullptr, &err);
    err = clBuildProgram(prog, 1, &cl().dev, "-cl-std=CL1.2", nullptr, nullptr);
    if (err != CL_SUCCESS) {
        size_t n = 0;
        clGetProgramBuildInfo(prog, cl().dev, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string b(n, '\0');
        clGetProgramBuildInfo(prog, cl().dev, CL_PROGRAM_BUILD_LOG, n, &b[0], nullptr);
        if (log) *log = b + "\n---- source ----\n" + shader.source;
        clReleaseProgram(prog);
        return false;
    }
    if (m_program) clReleaseProgram(static_cast<cl_program>(m_program));
    m_program = prog;
    m_builtFor = key;
    return true;
}

std::vector<Out> Shade::run(const std::vector<Point>& pts, const Scene& sc, int modeLight,
                            int modeTrace) {
    std::vector<Out> res;
    std::string log;
    if (!buildOnDevice(sc, &log) || pts.empty()) return res;
    size_t n = pts.size();
    std::vector<float> gin(n * kGlobalFloats, 0.0f);
    for (size_t i = 0; i < n; ++i) {
        float* g = &gin[i * kGlobalFloats];
        const Point& p = pts[i];
        auto set = [&](int f, const float* v) {
            for (int k = 0; k < 3; ++k) g[4 * f + k] = v[k];
        };
        set(fP, p.P); set(fN, p.N); set(fNg, p.Ng); set(fI, p.I); set(fE, p.E);
        set(fCs, p.Cs); set(fOs, p.Os); set(fPs, p.Ps);
        float one[3] = {1, 0, 0}, two[3] = {0, 1, 0};
        set(fdPdu, one); set(fdPdv, two);
        float* sc2 = g + 60;  // u v s t du dv ncomps time
        sc2[0] = p.u;
        sc2[1] = p.v;
        sc2[2] = p.s;
        sc2[3] = p.t;
    }
    cl_int err;
    size_t outFloats = n * (kGlobalFloats + kEvalFloats);
    // the block, then the shader and object matrices (rsl_abi.h, SPACES)
    std::vector<float> pv = params;
    pv.resize(size_t(shader.prepOffset) + size_t(shader.prepFloats), 0.0f);
    // (and their inverses: the tests' matrices are affine, inverted here in double)
    for (int k = 0; k < 16; ++k) {
        pv[shader.spaceOffset + k] = sc.shaderMatrix[k] + (k >= 12 && k < 15 ? sc.shaderOffset[k - 12] : 0.0f);
        pv[shader.spaceOffset + 16 + k] = sc.objectMatrix[k];
    }
    for (int m = 0; m < 2; ++m)
        invertRowMajor4(&pv[size_t(shader.spaceOffset + 16 * m)],
                        &pv[size_t(shader.spaceOffset + 32 + 16 * m)]);
    cl_mem bg = clCreateBuffer(cl().ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, gin.size() * 4, gin.data(), &err);
    cl_mem bp = clCreateBuffer(cl().ctx, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, pv.size() * 4, pv.data(), &err);
    if (!shader.prepFunction.empty()) {
        cl_kernel kp = clCreateKernel(static_cast<cl_program>(m_program), "ts_prep", &err);
        clSetKernelArg(kp, 0, sizeof(cl_mem), &bp);
        size_t one = 1;
        clEnqueueNDRangeKernel(cl().q, kp, 1, nullptr, &one, nullptr, 0, nullptr, nullptr);
        clReleaseKernel(kp);
    }
    cl_mem bo = clCreateBuffer(cl().ctx, CL_MEM_WRITE_ONLY, outFloats * 4, nullptr, &err);
    cl_kernel k = clCreateKernel(static_cast<cl_program>(m_program), "ts_main", &err);
    clSetKernelArg(k, 0, sizeof(cl_mem), &bg);
    clSetKernelArg(k, 1, sizeof(cl_mem), &bp);
    clSetKernelArg(k, 2, sizeof(int), &modeLight);
    clSetKernelArg(k, 3, sizeof(int), &modeTrace);
    clSetKernelArg(k, 4, sizeof(cl_mem), &bo);
    std::vector<float> out(outFloats);
    err = clEnqueueNDRangeKernel(cl().q, k, 1, nullptr, &n, nullptr, 0, nullptr, nullptr);
    if (err == CL_SUCCESS)
        err = clEnqueueReadBuffer(cl().q, bo, CL_TRUE, 0, outFloats * 4, out.data(), 0, nullptr, nullptr);
    clReleaseKernel(k);
    clReleaseMemObject(bg);
    clReleaseMemObject(bp);
    clReleaseMemObject(bo);
    if (err != CL_SUCCESS) return res;
    for (size_t i = 0; i < n; ++i) {
        const float* o = &out[i * (kGlobalFloats + kEvalFloats)];
        Out r;
        for (int c = 0; c < 3; ++c) {
            r.Ci[c] = o[4 * fCi + c];
            r.Oi[c] = o[4 * fOi + c];
            r.L[c] = o[4 * fL + c];
            r.Cl[c] = o[4 * fCl + c];
        }
        const float* e = o + kGlobalFloats;
        r.traceCount = int(e[0]);
        for (int t = 0; t < 8; ++t)
            for (int c = 0; c < 3; ++c) {
                r.org[t][c] = e[4 + 4 * t + c];
                r.dir[t][c] = e[36 + 4 * t + c];
            }
        for (int k = 0; k < 32; ++k) r.outputs[k] = e[68 + k];
        for (int l = 0; l < 8; ++l)
            for (int c = 0; c < 3; ++c) r.CiLight[l][c] = e[100 + 4 * l + c];
        res.push_back(r);
    }
    return res;
}

}  // namespace ts
