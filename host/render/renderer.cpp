// renderer.cpp: the render loop. Reads as the algorithm: analyse, build, upload, then per
// tile: refill (generate_eye), trace (intersect_closest), shade, trace shadows
// (intersect_shadow), add them (accumulate_shadows), retire (retire_samples).
#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bvh/sah_builder.h"
#include "cl/include/ray.h"
#include "ocl/buffer.h"

namespace rd {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

const std::vector<std::string> kRenderSources = {"generate_eye.cl", "intersect.cl",
                                                 "shade_builtin.cl", "retire.cl"};

}  // namespace

Renderer::Renderer(const ClContext& ctx, const RenderSettings& settings)
    : m_ctx(ctx), m_settings(settings) {}

RenderStats Renderer::render(const Scene& scene, Film& film) {
    auto t0 = Clock::now();
    RenderStats st;
    st.device = m_ctx.name();
    st.platform = m_ctx.info().platformName;
    st.features = analyse(scene);
    const Features& f = st.features;

    // Scene -> BVH -> device arrays
    auto tb = Clock::now();
    std::vector<Aabb> bounds(scene.triangles.size());
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        Aabb b;
        for (const rt_float4* v : {&t.v0, &t.v1, &t.v2}) {
            const float p[3] = {v->x, v->y, v->z};
            b.grow(p);
        }
        bounds[i] = b;
    }
    Bvh bvh = buildBvh(bounds);
    st.bvhBuildMs = msSince(tb);
    st.triangles = scene.triangles.size();
    st.bvhNodes = bvh.nodes.size();
    st.droppedPrims = bvh.droppedPrims;

    Program program(m_ctx, assembleClSource(kRenderSources), buildOptions(f));
    st.program = program.info();
    Profiler prof(m_ctx);
    Kernel generateEye(m_ctx, program.get(), "generate_eye", prof);
    Kernel intersectClosest(m_ctx, program.get(), "intersect_closest", prof);
    Kernel shade(m_ctx, program.get(), "shade", prof);
    Kernel intersectShadow(m_ctx, program.get(), "intersect_shadow", prof);
    Kernel accumulateShadows(m_ctx, program.get(), "accumulate_shadows", prof);
    Kernel retire(m_ctx, program.get(), "retire_samples", prof);

    Camera cam = scene.deviceCamera();
    DeviceBuffer<Camera> camBuf(m_ctx, std::vector<Camera>{cam});
    DeviceBuffer<BvhNode> nodes(m_ctx, bvh.nodes);
    DeviceBuffer<uint32_t> primIndex(m_ctx, bvh.primIndices);
    DeviceBuffer<Triangle> tris(m_ctx, scene.triangles);
    DeviceBuffer<TriangleAttr> attrs(m_ctx, scene.attrs);
    DeviceBuffer<rt_float4> normals =
        f.smoothNormals ? DeviceBuffer<rt_float4>(m_ctx, scene.normals)
                        : DeviceBuffer<rt_float4>(m_ctx, 0);
    DeviceBuffer<Material> materials(m_ctx, scene.materials);
    DeviceBuffer<Light> lights(m_ctx, scene.lights);

    // The pool: one slot per eye sample of a batch, plus light_count shadow slots each.
    const int spp = cam.spp_x * cam.spp_y;
    const uint32_t nl = f.shadowRays ? f.lightCount : 0;
    size_t pool = std::max<size_t>(m_settings.poolCapacity, size_t(spp));
    int tileSide = std::max(1, int(std::sqrt(double(pool / size_t(spp)))));
    tileSide = std::min(tileSide, std::max(cam.width, cam.height));
    pool = size_t(tileSide) * size_t(tileSide) * size_t(spp);
    st.poolCapacity = pool;
    DeviceBuffer<rt_float4> origin(m_ctx, pool), direction(m_ctx, pool), weight(m_ctx, pool);
    DeviceBuffer<RayState> state(m_ctx, pool);
    DeviceBuffer<RayHit> hits(m_ctx, pool);
    DeviceBuffer<SampleTotal> totals(m_ctx, pool);
    DeviceBuffer<rt_float4> shOrigin(m_ctx, pool * nl), shDirection(m_ctx, pool * nl),
        shWeight(m_ctx, pool * nl);
    DeviceBuffer<RayState> shState(m_ctx, pool * nl);
    shState.fillZero();
    film.width = cam.width;
    film.height = cam.height;
    DeviceBuffer<PixelAccum> filmBuf(m_ctx, size_t(cam.width) * size_t(cam.height));
    filmBuf.fillZero();
    st.sceneSetupMs = msSince(t0);

    const int rounds = f.transparency ? f.maxTransparentDepth : 1;
    for (int ty = 0; ty < cam.height; ty += tileSide) {
        for (int tx = 0; tx < cam.width; tx += tileSide) {
            const int tw = std::min(tileSide, cam.width - tx);
            const int th = std::min(tileSide, cam.height - ty);
            const cl_uint pixels = cl_uint(tw * th), n = pixels * cl_uint(spp);
            ++st.tiles;
            st.eyeRays += n;
            generateEye.launch(n, camBuf, cl_int(tx), cl_int(ty), cl_int(tw), n, origin,
                               direction, weight, state, totals);
            uint64_t tracedBefore = 0;
            for (int round = 0; round < rounds; ++round) {
                intersectClosest.launch(n, n, nodes, primIndex, tris, origin, direction, state,
                                        hits);
                if (rounds > 1) {
                    // Continuation rounds end when no ray of the batch is left alive.
                    uint64_t traced = intersectClosest.peekActive();
                    if (round > 0 && traced == tracedBefore) break;
                    tracedBefore = traced;
                }
                shade.launch(n, n, tris, attrs, normals, materials, lights, f.lightCount,
                             origin, direction, weight, state, hits, totals, shOrigin,
                             shDirection, shWeight, shState);
                if (nl > 0) {
                    intersectShadow.launch(size_t(n) * nl, cl_uint(n * nl), nodes, primIndex,
                                           tris, shOrigin, shDirection, shState);
                    accumulateShadows.launch(n, n, nl, shWeight, shState, totals);
                }
            }
            retire.launch(pixels, cl_int(tx), cl_int(ty), cl_int(tw), pixels,
                          cl_int(cam.width), cl_int(spp), totals, filmBuf);
            prof.collect();
        }
    }
    m_ctx.finish();
    prof.collect();
    for (Kernel* k : {&generateEye, &intersectClosest, &shade, &intersectShadow,
                      &accumulateShadows, &retire})
        k->collectActive();
    st.kernels = prof.stats();
    st.continuationRays = st.kernels["intersect_closest"].activeItems - st.eyeRays;
    st.shadowRays = st.kernels["intersect_shadow"].activeItems;
    film.pixels = filmBuf.download();
    st.nonfiniteSamples = film.nonfiniteCount();
    st.elapsedSec = msSince(t0) / 1000.0;
    return st;
}

}  // namespace rd
