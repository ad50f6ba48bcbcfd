// embree_peer.h: the peer bench_trace measures RayDrive against: Embree 3 over the same
// triangles (its default BVH or its watertight RTC_SCENE_FLAG_ROBUST mode), one ray a
// call (rtcIntersect1, rtcOccluded1) or in streams (rtcIntersect1M, rtcOccluded1M), on
// every hardware thread.
#pragma once
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "bench_inputs.h"

struct EmbreeScene {
    RTCDevice device;
    RTCScene scene;
    // robust: RTC_SCENE_FLAG_ROBUST, Embree's watertight mode (its default is not)
    explicit EmbreeScene(const Mesh& m, bool robust = false) {
        // (Embree's default configuration: its set_affinity=1, tried beside PoCL's pinned
        // threads, halved its Mrays/s on the 2-core development machine)
        device = rtcNewDevice(nullptr);
        scene = rtcNewScene(device);
        if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        float* v = (float*)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0,
                                                   RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                   3 * m.tris.size());
        unsigned* idx = (unsigned*)rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
            m.tris.size());
        for (size_t t = 0; t < m.tris.size(); ++t) {
            const rt_float4* p[3] = {&m.tris[t].v0, &m.tris[t].v1, &m.tris[t].v2};
            for (int k = 0; k < 3; ++k) {
                v[9 * t + 3 * k] = p[k]->x;
                v[9 * t + 3 * k + 1] = p[k]->y;
                v[9 * t + 3 * k + 2] = p[k]->z;
                idx[3 * t + k] = unsigned(3 * t + k);
            }
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene, g);
        rtcReleaseGeometry(g);
        const auto t0 = std::chrono::steady_clock::now();
        rtcCommitScene(scene);
        buildMs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() *
            1e3;
    }
    double buildMs = 0;  // rtcCommitScene: the BVH build
    ~EmbreeScene() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }
    // Closest hits (t, prim) or occlusion, over all hardware threads, each a contiguous
    // share of the rays (as PoCL's work-groups take them): one rtcIntersect1 or
    // rtcOccluded1 per ray, or with `stream` one rtcIntersect1M / rtcOccluded1M call per
    // thread (`coherent`: the coherent-stream hint, for primary rays).
    void trace(const Rays& r, bool shadow, std::vector<RayHit>& out, bool stream = false,
               bool coherent = false) const {
        out.resize(r.org.size());
        const size_t n = r.org.size();
        unsigned nt = std::max(1u, std::thread::hardware_concurrency());
        std::vector<std::thread> th;
        for (unsigned t = 0; t < nt; ++t)
            th.emplace_back([&, t] {
                RTCIntersectContext ctx;
                rtcInitIntersectContext(&ctx);
                if (stream)
                    ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                         : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
                const size_t b = n * t / nt, e = n * (t + 1) / nt;
                auto ray = [&](size_t i) {
                    RTCRayHit rh;
                    rh.ray.org_x = r.org[i].x, rh.ray.org_y = r.org[i].y,
                    rh.ray.org_z = r.org[i].z;
                    rh.ray.dir_x = r.dir[i].x, rh.ray.dir_y = r.dir[i].y,
                    rh.ray.dir_z = r.dir[i].z;
                    rh.ray.tnear = r.org[i].w, rh.ray.tfar = r.dir[i].w;
                    rh.ray.mask = ~0u, rh.ray.flags = 0, rh.ray.time = 0,
                    rh.ray.id = unsigned(i);
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    return rh;
                };
                auto result = [&](size_t i, const RTCRayHit& rh) {
                    if (shadow) {
                        out[i].prim = rh.ray.tfar < 0 ? 0 : RT_NO_HIT;
                    } else {
                        out[i].t = rh.ray.tfar;
                        out[i].prim = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                                          ? RT_NO_HIT
                                          : rh.hit.primID;
                    }
                };
                if (stream) {
                    std::vector<RTCRayHit> rays(e - b);
                    for (size_t i = b; i < e; ++i) rays[i - b] = ray(i);
                    if (shadow)
                        rtcOccluded1M(scene, &ctx, &rays[0].ray, unsigned(e - b),
                                      sizeof(RTCRayHit));
                    else
                        rtcIntersect1M(scene, &ctx, rays.data(), unsigned(e - b),
                                       sizeof(RTCRayHit));
                    for (size_t i = b; i < e; ++i) result(i, rays[i - b]);
                    return;
                }
                for (size_t i = b; i < e; ++i) {
                    RTCRayHit rh = ray(i);
                    if (shadow)
                        rtcOccluded1(scene, &ctx, &rh.ray);
                    else
                        rtcIntersect1(scene, &ctx, &rh);
                    result(i, rh);
                }
            });
        for (auto& t : th) t.join();
    }
};
