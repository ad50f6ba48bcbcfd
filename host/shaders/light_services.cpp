// light_services.cpp: the light instances' area triangles and the OpenCL services that
// run the lights (light_services.h).
#include "light_services.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <sstream>

#include "compiler.h"
#include "emit_cl.h"

namespace rd {

size_t appendAreaTriangles(const std::vector<std::array<glm::vec3, 3>>& tris,
                           size_t count, std::vector<float>& params) {
    std::vector<double> cdf(count);
    double total = 0;
    for (size_t t = 0; t < count; ++t) {
        const auto& v = tris[t];
        total += 0.5 * double(glm::length(glm::cross(v[1] - v[0], v[2] - v[0])));
        cdf[t] = total;
    }
    params.resize((params.size() + 3) / 4 * 4, 0.0f);
    const size_t at = params.size();
    for (size_t t = 0; t < count; ++t) {
        const auto& v = tris[t];
        const float w = total > 0 ? float(cdf[t] / total) : float(t + 1) / float(count);
        for (int k = 0; k < 3; ++k)
            params.insert(params.end(), {v[k].x, v[k].y, v[k].z,
                                         k == 0 ? (t + 1 == count ? 1.0f : w) : 0.0f});
    }
    return at;
}

namespace {
// __constant int NAME[] = {...}; (one 0 when empty: OpenCL has no empty arrays)
template <typename T>
void table(std::ostream& out, const char* name, const std::vector<T>& values) {
    out << "__constant int " << name << "[] = {";
    for (size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
    if (values.empty()) out << "0";
    out << "};\n";
}

// lightsource("name", var): the light instance's parameter, matched by name id and
// size.
void lightSourceParamService(std::ostream& svc, const BoundLights& lights,
                             uint32_t count) {
    svc << "int rsl_lightsource_param(const RslGlobals* g, int light, int nameId, float* "
           "out, "
           "int n) {\n"
           "    if (light < 0 || light >= "
        << count
        << ") return 0;\n"
           "    __global const float* b = g->scene_params + rd_light_block[light];\n"
           "    switch (rd_light_shader[light]) {\n";
    for (size_t i = 0; i < lights.shaders.size(); ++i) {
        svc << "    case " << i << ":\n";
        for (const rsl::ParamSlot& slot : lights.shaders[i]->params)
            svc << "        if (nameId == " << rsl::stringId(slot.name)
                << " && n == " << slot.size
                << ") { for (int k = 0; k < n; ++k) out[k] = b[" << slot.offset
                << " + k]; return 1; }\n";
        svc << "        return 0;\n";
    }
    svc << "    default: return 0;\n    }\n}\n";
}

// rd_run_light: light instance l run at Ps (an area light at a point on its geometry).
void runLightService(std::ostream& svc, const BoundLights& lights, uint32_t count,
                     bool areas) {
    svc << "/* Runs light instance l at Ps: light-side L, Cl; returns 1 for a solar "
           "light */\n"
           "static int rd_run_light(int l, const RslGlobals* g, float4 Ps, RslGlobals* "
           "out) {\n"
           "    RslGlobals lg = *g;\n    lg.Ps = Ps;\n    lg.L = (float4)(0.0f);\n"
           "    lg.Cl = rsl_f2c(0.0f);\n    lg.Ol = rsl_f2c(0.0f);\n"
           "    if (l < 0 || l >= "
        << count
        << ") { *out = lg; return 0; }\n"
           "    __global const float* d = lg.scene_params;\n"
           "    lg.P = vload4(0, d + rd_light_place[l]);\n"
           "    lg.N = lg.Ng = vload4(1, d + rd_light_place[l]);\n";
    if (areas)  // an area light: a point on its geometry instead, weighted by area
        svc << "    if (rd_light_area_count[l] > 0) {\n"
               "        float4 ap_, an_;\n"
               "        rd_area_point((__global const float4*)(d + "
               "rd_light_area_at[l]),\n"
               "                      rd_light_area_count[l], g, l, &ap_, &an_);\n"
               "        lg.P = ap_;\n        lg.N = lg.Ng = an_;\n    }\n";
    svc << "    switch (rd_light_shader[l]) {\n";
    for (size_t i = 0; i < lights.shaders.size(); ++i)
        svc << "    case " << i << ": " << lights.shaders[i]->functionName
            << "(&lg, d + rd_light_block[l]); break;\n";
    svc << "    default: break;\n    }\n    *out = lg;\n    return RSL_CW(lg.Ol) == "
           "1.0f;\n}\n";
}

// Which lights trace no shadow rays (their shadow maps shadow them) and which are
// ambient.
void lightKindServices(std::ostream& svc, const BoundLights& lights) {
    svc << "static int rd_light_traces_shadows(int l) {\n    switch (l) {\n";
    for (size_t i = 0; i < lights.mapShadowed.size(); ++i)
        if (lights.mapShadowed[i]) svc << "    case " << i << ": return 0;\n";
    svc << "    default: return 1;\n    }\n}\n";
    svc << "static int rd_light_is_ambient(int l) {\n    switch (l) {\n";
    for (size_t i = 0; i < lights.ambient.size(); ++i)
        if (lights.ambient[i]) svc << "    case " << i << ": return 1;\n";
    svc << "    default: return 0;\n    }\n}\n";
}

void lightCacheService(std::ostream& svc) {
    // The light cache (rsl_abi.h): each light runs once per shading point, not once per
    // evaluation mode and illuminance loop.
    // The cache lookup is inlined where lights are read (each shading point reads every
    // light several times: builtins, illuminance loops, coefficients, shadow rays), so
    // repeated reads of one light fold; running a light is a call.
    // clang-format off
    svc << "/* Runs light l at Ps: surface-side L, unshadowed Cl (RSL_CW 1: solar). */\n"
           "static void rd_light_run(int l, const RslGlobals* g, float4 Ps, float4* L, rsl_color* Cl) {\n"
           "    RslGlobals lg;\n    int solar = rd_run_light(l, g, Ps, &lg);\n"
           "    *L = (float4)(-lg.L.x, -lg.L.y, -lg.L.z, 0.0f);\n"
           "    *Cl = rsl_cw0(lg.Cl);\n    RSL_CW(*Cl) = solar ? 1.0f : 0.0f;\n}\n"
           "/* Light l at Ps: from the light cache when Ps is the shading point. */\n"
           "static inline __attribute__((always_inline)) void rd_light_at(int l, const RslGlobals* g,\n"
           "                                                              float4 Ps, float4* L, rsl_color* Cl) {\n"
           "    if (l < 32 && ((g->lights_off >> l) & 1u)) {  /* Illuminate off */\n"
           "        *L = (float4)(0.0f, 0.0f, 1.0f, 0.0f);\n        *Cl = (rsl_color)(0.0f);\n        return;\n    }\n"
           "    if (l < g->light_cache_count && Ps.x == g->P.x && Ps.y == g->P.y && Ps.z == g->P.z) {\n"
           "        *L = g->light_cache->L[l];\n        *Cl = g->light_cache->Cl[l];\n        return;\n    }\n"
           "    rd_light_run(l, g, Ps, L, Cl);\n}\n"
           "static void rd_fill_light_cache(RslGlobals* g, RslLightCache* cache) {\n"
           "    g->light_cache_count = 0;\n"
           "    g->light_cache = cache;\n"
           "    int n = min(rsl_light_count(), RSL_LIGHT_CACHE);\n"
           "    for (int l = 0; l < n; ++l) rd_light_at(l, g, g->P, &cache->L[l], &cache->Cl[l]);\n"
           "    g->light_cache_count = n;\n}\n"
           "inline __attribute__((always_inline)) int rsl_light(int l, const RslGlobals* g, float4 Ps,\n"
           "                                                     float4* L, rsl_color* Cl) {\n"
           "    if (rd_light_is_ambient(l)) return 0;\n"
           "    rd_light_at(l, g, Ps, L, Cl);\n    RSL_CW(*Cl) = 0.0f;\n"
           "    return rsl_cnonzero(*Cl);\n}\n"
           "rsl_color rsl_ambient(const RslGlobals* g) {\n    rsl_color sum = rsl_f2c(0.0f);\n"
           "    for (int l = 0; l < rsl_light_count(); ++l) {\n"
           "        if (!rd_light_is_ambient(l)) continue;\n        float4 L;\n        rsl_color Cl;\n"
           "        rd_light_at(l, g, g->P, &L, &Cl);\n        sum += Cl;\n    }\n"
           "    return rsl_cw0(sum);\n}\n";
    // clang-format on
}
}  // namespace

std::string lightServices(const BoundLights& lights) {
    std::ostringstream svc;
    const uint32_t count = lights.count();
    svc << "int rsl_light_count(void) { return " << count << "; }\n";
    const bool areas = std::any_of(lights.areaCount.begin(), lights.areaCount.end(),
                                   [](size_t n) { return n > 0; });
    table(svc, "rd_light_shader", lights.shaderOf);
    table(svc, "rd_light_block", lights.block);
    table(svc, "rd_light_place", lights.place);
    if (areas) {
        table(svc, "rd_light_area_at", lights.areaAt);
        table(svc, "rd_light_area_count", lights.areaCount);
    }
    lightSourceParamService(svc, lights, count);
    runLightService(svc, lights, count, areas);
    lightKindServices(svc, lights);
    lightCacheService(svc);
    return svc.str();
}

}  // namespace rd
