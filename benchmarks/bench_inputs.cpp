// bench_inputs.cpp: bench_trace's meshes and rays (bench_inputs.h).
#include "bench_inputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>

#include "render/sampling.h"

// A field of `count` spheres, each diced into about `perSphere` triangles, scattered in a
// 10x10x10 box: many objects, open space between them, as a scene has.
Mesh sphereField(int count, int perSphere, const std::string& name) {
    Mesh m{{}, name};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 1);
    int nu = std::max(4, int(std::sqrt(perSphere / 2.0)) * 1),
        nv = std::max(3, perSphere / (2 * nu));
    for (int s = 0; s < count; ++s) {
        float cx = 10 * u(rng) - 5, cy = 10 * u(rng) - 5, cz = 10 * u(rng) - 5;
        float r = 0.05f + 0.4f * u(rng) * u(rng);
        auto P = [&](int i, int j) {
            float th = 2 * float(M_PI) * i / nu,
                  ph = float(M_PI) * j / nv - float(M_PI) / 2;
            return rt_float4{cx + r * std::cos(ph) * std::cos(th),
                             cy + r * std::cos(ph) * std::sin(th), cz + r * std::sin(ph),
                             0};
        };
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                m.tris.push_back({P(i, j), P(i + 1, j), P(i + 1, j + 1)});
                m.tris.push_back({P(i, j), P(i + 1, j + 1), P(i, j + 1)});
            }
    }
    return m;
}

// A triangle mesh from an OFF file (polygons fanned into triangles), scaled and centred
// into the same 10x10x10 box, e.g. the Stanford bunny from Debian's libcgal-demo
// (run_trace.sh fetches it; it is not ours to commit).
Mesh loadOff(const std::string& path) {
    std::ifstream in(path);
    std::string word;
    auto next = [&]() -> std::string {  // the next token, comments skipped
        while (in >> word) {
            if (word[0] != '#') return word;
            std::getline(in, word);
        }
        throw std::runtime_error(path + ": truncated OFF file");
    };
    if (!in || next() != "OFF") throw std::runtime_error(path + ": not an OFF file");
    const size_t nv = std::stoul(next()), nf = std::stoul(next());
    next();  // edges
    std::vector<rt_float4> v(nv);
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    for (rt_float4& p : v) {
        p = {std::stof(next()), std::stof(next()), std::stof(next()), 0};
        const float c[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a)
            lo[a] = std::min(lo[a], c[a]), hi[a] = std::max(hi[a], c[a]);
    }
    const float scale = 10.0f / std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    for (rt_float4& p : v)
        p = {(p.x - 0.5f * (lo[0] + hi[0])) * scale,
             -(p.y - 0.5f * (lo[1] + hi[1])) * scale,
             (p.z - 0.5f * (lo[2] + hi[2])) * scale, 0};
    Mesh m{{}, std::filesystem::path(path).stem().string()};
    for (size_t f = 0; f < nf; ++f) {
        const size_t k = std::stoul(next());
        std::vector<size_t> idx(k);
        for (size_t& i : idx) {
            i = std::stoul(next());
            if (i >= nv) throw std::runtime_error(path + ": vertex index out of range");
        }
        for (size_t j = 1; j + 1 < k; ++j)
            m.tris.push_back({v[idx[0]], v[idx[j]], v[idx[j + 1]]});
    }
    return m;
}

// Primary rays through side x side pixels, in the order the renderer samples them
// (rd::tileOrder: 16x16 tiles, Morton order within a tile) or in scanline order.
Rays primaryRays(int side, const std::string& order) {
    Rays r;
    std::vector<uint32_t> pixels = rd::tileOrder(side, 0, side, 0, side);
    if (order == "scanline") std::sort(pixels.begin(), pixels.end());
    for (uint32_t pixel : pixels) {
        const int x = int(pixel % uint32_t(side)), y = int(pixel / uint32_t(side));
        float sx = (x + 0.5f) / side * 2 - 1, sy = (y + 0.5f) / side * 2 - 1;
        float len = std::sqrt(sx * sx * 0.36f + sy * sy * 0.36f + 1);
        r.org.push_back({0, 0, -16, 0});
        r.dir.push_back({sx * 0.6f / len, sy * 0.6f / len, 1 / len, 1e30f});
    }
    return r;
}

// Secondary rays from the primary hits: cosine-ish random directions (diffuse) or toward
// a point light (shadow). Rays whose primary ray missed are left out.
Rays secondaryRays(const Mesh& m, const Rays& prim, const std::vector<RayHit>& hits,
                   bool shadow) {
    Rays r;
    std::mt19937 rng(11);
    std::normal_distribution<float> g;
    const rt_float4 light{20, 30, -20, 0};
    for (size_t i = 0; i < hits.size(); ++i) {
        if (hits[i].prim == RT_NO_HIT) continue;
        const Triangle& t = m.tris[hits[i].prim];
        float px = prim.org[i].x + hits[i].t * prim.dir[i].x;
        float py = prim.org[i].y + hits[i].t * prim.dir[i].y;
        float pz = prim.org[i].z + hits[i].t * prim.dir[i].z;
        float ex = t.v1.x - t.v0.x, ey = t.v1.y - t.v0.y, ez = t.v1.z - t.v0.z;
        float fx = t.v2.x - t.v0.x, fy = t.v2.y - t.v0.y, fz = t.v2.z - t.v0.z;
        float nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
        float nl = std::sqrt(nx * nx + ny * ny + nz * nz);
        nx /= nl, ny /= nl, nz /= nl;
        if (nx * prim.dir[i].x + ny * prim.dir[i].y + nz * prim.dir[i].z > 0)
            nx = -nx, ny = -ny, nz = -nz;
        float dx, dy, dz, tmax = 1e30f;
        if (shadow) {
            dx = light.x - px, dy = light.y - py, dz = light.z - pz;
            tmax = std::sqrt(dx * dx + dy * dy + dz * dz);
            dx /= tmax, dy /= tmax, dz /= tmax;
            tmax *= 0.9999f;
        } else {
            dx = nx + g(rng), dy = ny + g(rng), dz = nz + g(rng);  // ~cosine lobe
            float l = std::sqrt(dx * dx + dy * dy + dz * dz);
            dx /= l, dy /= l, dz /= l;
        }
        r.org.push_back({px + 1e-4f * nx, py + 1e-4f * ny, pz + 1e-4f * nz, 0});
        r.dir.push_back({dx, dy, dz, tmax});
    }
    return r;
}
