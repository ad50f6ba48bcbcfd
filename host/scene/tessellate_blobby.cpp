// tessellate_blobby.cpp: RiBlobby's field, evaluated over a grid and polygonised by
// marching tetrahedra (six a cell, so no case table is needed and the surface is closed
// wherever the field is), with smooth normals from the field's gradient.
#include "tessellate_blobby.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>

#include "host/film/run_in_parts.h"

namespace rd {

namespace {

constexpr float kThreshold = 0.5f;
// The most leaves a vertex's value blends: the strongest fields where more blobs reach
// it (dense blobs would otherwise list hundreds a vertex); a vertex no blob reaches
// takes the mean of at most this many leaves (else 0).
constexpr size_t kLeavesAVertex = 8;

// Wyvill's soft-object falloff of r^2 (1 at 0, 0.5 at r = 0.5, 0 from r = 1 on).
float falloff(float r2) {
    if (r2 >= 1.0f) return 0.0f;
    return 1.0f + r2 * (-22.0f / 9.0f + r2 * (17.0f / 9.0f - r2 * (4.0f / 9.0f)));
}

struct Instruction {
    int op = 0;                    // RI opcode
    std::vector<int> operands;     // operators: earlier results
    glm::mat4 toUnit{1.0f};        // primitives: object space to the blob's space
    glm::vec3 a{0.0f}, b{0.0f};    // a segment's ends, in the blob's space
    float value = 0.0f;            // a constant, or a segment's radius
    glm::vec3 lo{0.0f}, hi{0.0f};  // a bounded primitive's object-space box
    bool bounded = false;
};

glm::mat4 matrixAt(const std::vector<float>& f, size_t at) {
    glm::mat4 m;  // RI row-vector matrices are glm's column-major arrays as they are
    for (int i = 0; i < 16; ++i) (&m[0][0])[i] = f[at + size_t(i)];
    return m;
}

// The box of the unit cube's image under m (the blob's reach: r < 1 inside it).
void boxOf(const glm::mat4& m, glm::vec3 lo, glm::vec3 hi, Instruction& in) {
    in.lo = glm::vec3(INFINITY), in.hi = glm::vec3(-INFINITY);
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y,
                          (c & 4) ? hi.z : lo.z);
        const glm::vec3 q = glm::vec3(m * glm::vec4(p, 1.0f));
        in.lo = glm::min(in.lo, q), in.hi = glm::max(in.hi, q);
    }
    in.bounded = std::isfinite(in.lo.x + in.lo.y + in.lo.z + in.hi.x + in.hi.y + in.hi.z);
}

// m * (p, 1) as glm computes it, bit for bit ((c0 x + c1 y) + (c2 z + c3)), inline: as
// glm's call it took half of a dense blobby's polygonisation.
inline glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) {
    return (glm::vec3(m[0]) * p.x + glm::vec3(m[1]) * p.y) +
           (glm::vec3(m[2]) * p.z + glm::vec3(m[3]));
}

// A bounded primitive's field at p (0 outside its box).
float primitiveAt(const Instruction& in, glm::vec3 p) {
    if (glm::any(glm::lessThan(p, in.lo)) || glm::any(glm::greaterThan(p, in.hi)))
        return 0.0f;
    const glm::vec3 q = transformPoint(in.toUnit, p);
    if (in.op == 1001) return falloff(glm::dot(q, q));
    const glm::vec3 ab = in.b - in.a;
    const float len2 = glm::dot(ab, ab);
    const float t =
        len2 > 0 ? std::clamp(glm::dot(q - in.a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    const glm::vec3 d = q - (in.a + t * ab);
    return falloff(glm::dot(d, d) / (in.value * in.value));
}

// The grid the field is sampled on: points lo + h (x, y, z), x fastest.
struct Grid {
    glm::vec3 lo;
    float h;
    size_t nx, ny, nz;
    size_t points() const { return nx * ny * nz; }
    size_t index(size_t x, size_t y, size_t z) const { return (z * ny + y) * nx + x; }
    glm::vec3 at(size_t x, size_t y, size_t z) const {
        return lo + h * glm::vec3(float(x), float(y), float(z));
    }
    glm::vec3 at(size_t i) const { return at(i % nx, (i / nx) % ny, i / (nx * ny)); }
};

// The field of a program. The usual one, the sum (or maximum) of its primitives, is
// evaluated from a coarse grid of bins listing the bounded primitives that reach each:
// a point costs the few blobs near it, not the program (500 blobs: 9 s -> well under 1).
class Field {
public:
    Field(std::vector<Instruction> code, glm::vec3 lo, glm::vec3 hi)
        : m_code(std::move(code)) {
        if (m_code.empty()) return;
        const Instruction& last = m_code.back();
        m_flat = last.op == 0 || last.op == 2;
        for (size_t i = 0; i + 1 < m_code.size() && m_flat; ++i)
            m_flat = m_code[i].op >= 1000;
        if (!m_flat) return;
        m_max = last.op == 2;
        m_rest = m_max ? -INFINITY : 0.0f;
        std::vector<int> times(m_code.size(), 0);  // (an operand given twice adds twice)
        for (int k : last.operands) ++times[size_t(k)];
        for (size_t i = 0; i + 1 < m_code.size(); ++i) {
            if (times[i] == 0) continue;
            const Instruction& in = m_code[i];
            const bool reaches = (in.op == 1001 || in.op == 1002) && in.bounded;
            const float unbounded = in.op == 1000 ? in.value : 0.0f;
            if (!reaches)
                m_rest = m_max ? std::max(m_rest, unbounded)
                               : m_rest + float(times[i]) * unbounded;
            else
                for (int t = 0; t < (m_max ? 1 : times[i]); ++t)
                    m_bounded.push_back(int(i));
        }
        const int b = std::clamp(int(std::cbrt(double(m_bounded.size())) * 2.0), 1, 64);
        m_lo = lo;
        m_n = glm::ivec3(b);
        m_size = glm::max((hi - lo) / float(b), glm::vec3(1e-30f));
        m_bins.assign(size_t(b) * size_t(b) * size_t(b), {});
        for (int k : m_bounded) {
            const Instruction& in = m_code[size_t(k)];
            const glm::ivec3 a = binOf(in.lo), z = binOf(in.hi);
            for (int x = a.x; x <= z.x; ++x)
                for (int y = a.y; y <= z.y; ++y)
                    for (int w = a.z; w <= z.z; ++w) m_bins[index(x, y, w)].push_back(k);
        }
    }
    // The field at p; `v` (one float an instruction) holds a program's partial results,
    // so that threads may each evaluate with their own.
    float at(glm::vec3 p, std::vector<float>& v) const {
        if (m_flat) {
            float sum = m_rest;
            const glm::ivec3 c = binOf(p);
            for (int k : m_bins[index(c.x, c.y, c.z)]) {
                const float f = primitiveAt(m_code[size_t(k)], p);
                sum = m_max ? std::max(sum, f) : sum + f;
            }
            return std::isfinite(sum) ? sum : 0.0f;
        }
        v.resize(m_code.size());
        for (size_t i = 0; i < m_code.size(); ++i) {
            const Instruction& in = m_code[i];
            float& r = v[i];
            auto arg = [&](size_t k) { return v[size_t(in.operands[k])]; };
            switch (in.op) {
                case 1000:
                    r = in.value;
                    break;
                case 1001:
                case 1002:
                    r = primitiveAt(in, p);
                    break;
                case 1003:
                    r = 0.0f;
                    break;  // (a repelling plane: no depth file read)
                case 0:
                    r = 0.0f;
                    for (size_t k = 0; k < in.operands.size(); ++k) r += arg(k);
                    break;
                case 1:
                    r = 1.0f;
                    for (size_t k = 0; k < in.operands.size(); ++k) r *= arg(k);
                    break;
                case 2:
                    r = -INFINITY;
                    for (size_t k = 0; k < in.operands.size(); ++k)
                        r = std::max(r, arg(k));
                    break;
                case 3:
                    r = INFINITY;
                    for (size_t k = 0; k < in.operands.size(); ++k)
                        r = std::min(r, arg(k));
                    break;
                case 4:
                    r = arg(0) - arg(1);
                    break;
                case 5:
                    r = arg(1) != 0.0f ? arg(0) / arg(1) : 0.0f;
                    break;
                case 6:
                    r = -arg(0);
                    break;
                default:
                    r = arg(0);
                    break;  // 7: identity
            }
        }
        const float f = v.empty() ? 0.0f : v.back();
        return std::isfinite(f) ? f : 0.0f;
    }
    // The field at every point of `grid` (at(), the same values), on the host's cores.
    // A sum or maximum of primitives adds each primitive over the points in its box
    // rather than looking each point's primitives up: in the same order, so the same
    // sums (a maximum may differ where every field there is below 0 by a rounding).
    void sample(const Grid& grid, std::vector<float>& out) const {
        out.resize(grid.points());
        const size_t slab = grid.nx * grid.ny;
        const size_t parts = grid.points() >= (size_t(1) << 16) ? hostThreads() : 1;
        runInParts(grid.nz, parts, [&](size_t z0, size_t z1, size_t) {
            if (!m_flat) {
                std::vector<float> v;
                for (size_t i = z0 * slab; i < z1 * slab; ++i) out[i] = at(grid.at(i), v);
                return;
            }
            std::fill(out.begin() + ptrdiff_t(z0 * slab),
                      out.begin() + ptrdiff_t(z1 * slab), m_rest);
            for (int k : m_bounded) add(m_code[size_t(k)], grid, z0, z1, out);
            for (size_t i = z0 * slab; i < z1 * slab; ++i)
                if (!std::isfinite(out[i])) out[i] = 0.0f;
        });
    }
    // Calls visit(instruction, field) for each ellipsoid and segment blob whose field is
    // positive at p: of a sum or maximum, those its bins list (an operand given twice,
    // twice); of another program, every one.
    template <class Visit>
    void reaching(glm::vec3 p, Visit visit) const {
        auto one = [&](int k) {
            const Instruction& in = m_code[size_t(k)];
            if (in.op != 1001 && in.op != 1002) return;
            const float f = primitiveAt(in, p);
            if (f > 0.0f) visit(k, f);
        };
        if (m_flat) {
            const glm::ivec3 c = binOf(p);
            for (int k : m_bins[index(c.x, c.y, c.z)]) one(k);
        } else {
            for (size_t k = 0; k < m_code.size(); ++k) one(int(k));
        }
    }

private:
    // A bounded primitive's field added (or maxed) into the grid's points in its box
    // whose z index is in [z0, z1).
    void add(const Instruction& in, const Grid& grid, size_t z0, size_t z1,
             std::vector<float>& out) const {
        // (a point more each way than the box's own: primitiveAt tests the box itself)
        auto span = [&](float a, float b, float origin, size_t n) {
            const float first = std::floor((a - origin) / grid.h) - 1.0f;
            const float last = std::floor((b - origin) / grid.h) + 2.0f;
            return std::pair<size_t, size_t>(size_t(std::clamp(first, 0.0f, float(n))),
                                             size_t(std::clamp(last, 0.0f, float(n))));
        };
        const auto [x0, x1] = span(in.lo.x, in.hi.x, grid.lo.x, grid.nx);
        const auto [y0, y1] = span(in.lo.y, in.hi.y, grid.lo.y, grid.ny);
        const auto [za, zb] = span(in.lo.z, in.hi.z, grid.lo.z, grid.nz);
        for (size_t z = std::max(za, z0); z < std::min(zb, z1); ++z)
            for (size_t y = y0; y < y1; ++y)
                for (size_t x = x0; x < x1; ++x) {
                    const float f = primitiveAt(in, grid.at(x, y, z));
                    float& v = out[grid.index(x, y, z)];
                    v = m_max ? std::max(v, f) : v + f;
                }
    }
    glm::ivec3 binOf(glm::vec3 p) const {
        return glm::clamp(glm::ivec3(glm::floor((p - m_lo) / m_size)), glm::ivec3(0),
                          m_n - 1);
    }
    size_t index(int x, int y, int z) const {
        return (size_t(z) * size_t(m_n.y) + size_t(y)) * size_t(m_n.x) + size_t(x);
    }
    std::vector<Instruction> m_code;
    bool m_flat = false, m_max = false;  // a sum (maximum) of primitives
    float m_rest = 0.0f;                 // of the unbounded ones (constants)
    std::vector<int> m_bounded;
    glm::vec3 m_lo{0.0f}, m_size{1.0f};
    glm::ivec3 m_n{1};
    std::vector<std::vector<int>> m_bins;
};

// The weights of vertices (BlobbyLeafWeights), from the field's primitives that reach
// each; leafOf: an instruction's leaf number.
void weighLeaves(const Field& field, const std::vector<int>& leafOf,
                 const std::vector<glm::vec3>& points, BlobbyLeafWeights& out) {
    const int leaves =
        int(std::count_if(leafOf.begin(), leafOf.end(), [](int l) { return l >= 0; }));
    out.start.assign(1, 0);
    out.leaf.clear(), out.weight.clear();
    std::vector<std::pair<float, int>> near;  // (field, leaf) of the blobs reaching p
    for (const glm::vec3& p : points) {
        near.clear();
        field.reaching(p,
                       [&](int k, float f) { near.emplace_back(f, leafOf[size_t(k)]); });
        if (near.size() > kLeavesAVertex) {  // the strongest: a bound on the lists
            std::nth_element(near.begin(), near.begin() + kLeavesAVertex - 1, near.end(),
                             std::greater<>());
            near.resize(kLeavesAVertex);
        }
        float sum = 0.0f;
        for (const auto& [f, leaf] : near) sum += f;
        if (sum > 0.0f && std::isfinite(sum)) {
            for (const auto& [f, leaf] : near) {
                out.leaf.push_back(leaf);
                out.weight.push_back(f / sum);
            }
        } else if (leaves <= int(kLeavesAVertex)) {
            for (int l = 0; l < leaves; ++l) {
                out.leaf.push_back(l);
                out.weight.push_back(1.0f / float(leaves));
            }
        }
        out.start.push_back(out.leaf.size());
    }
}

// An ellipsoid (1001) or segment blob (1002) whose floats start at `at`, with its reach;
// one that reaches nothing (a singular or non-finite matrix, a segment of radius 0) is
// the constant 0.
Instruction primitiveOf(int op, const std::vector<float>& floats, size_t at) {
    Instruction in;
    in.op = op;
    const glm::mat4 m = matrixAt(floats, op == 1001 ? at : at + 7);
    in.toUnit = glm::inverse(m);
    glm::vec3 blo(-1.0f), bhi(1.0f);
    if (op == 1002) {
        in.a = glm::vec3(floats[at], floats[at + 1], floats[at + 2]);
        in.b = glm::vec3(floats[at + 3], floats[at + 4], floats[at + 5]);
        in.value = std::fabs(floats[at + 6]);
        blo = glm::min(in.a, in.b) - glm::vec3(in.value);
        bhi = glm::max(in.a, in.b) + glm::vec3(in.value);
    }
    boxOf(m, blo, bhi, in);
    const glm::mat4& u = in.toUnit;
    bool finite = true;
    for (int k = 0; k < 16; ++k) finite = finite && std::isfinite((&u[0][0])[k]);
    in.bounded = in.bounded && finite && (op == 1001 || in.value > 0.0f) &&
                 glm::all(glm::greaterThan(in.hi - in.lo, glm::vec3(0.0f)));
    if (!in.bounded) in.op = 1000, in.value = 0.0f;
    return in;
}

// A Blobby's code decoded (the reader checked every index), its primitives bounded.
struct Program {
    std::vector<Instruction> code;
    std::vector<int> leafOf;  // per instruction: its leaf number, or -1 (an operator)
    glm::vec3 lo{INFINITY}, hi{-INFINITY};  // what the bounded primitives reach
    float smallest = INFINITY;              // the narrowest reach: what the grid resolves
    bool repeller = false;                  // a repelling plane (its field 0)
};

Program decode(const std::vector<int>& code, const std::vector<float>& floats) {
    Program out;
    int leaves = 0;
    for (size_t pc = 0; pc < code.size();) {
        Instruction in;
        in.op = code[pc++];
        out.leafOf.push_back(in.op >= 1000 ? leaves++ : -1);
        if (in.op == 1000) {
            in.value = floats[size_t(code[pc++])];
        } else if (in.op == 1001 || in.op == 1002) {
            in = primitiveOf(in.op, floats, size_t(code[pc++]));
            if (in.bounded) {
                out.lo = glm::min(out.lo, in.lo), out.hi = glm::max(out.hi, in.hi);
                const glm::vec3 e = in.hi - in.lo;
                out.smallest = std::min(out.smallest, std::min(e.x, std::min(e.y, e.z)));
            }
        } else if (in.op == 1003) {
            pc += 2;
            out.repeller = true;
        } else {
            const int n = in.op <= 3 ? code[pc++] : in.op <= 5 ? 2 : 1;
            for (int k = 0; k < n; ++k) in.operands.push_back(code[pc++]);
        }
        out.code.push_back(std::move(in));
    }
    return out;
}

// Marching tetrahedra over the field's samples at the grid points: each cell is six
// tetrahedra about its diagonal, each cut by the level set in one or two triangles
// whose vertices, on the grid's edges, the cells around an edge share. The cells are
// walked first, naming each vertex by its edge; the vertices are then placed on the
// host's cores, and the triangles kept, in the walk's order.
class Polygoniser {
public:
    Polygoniser(const Field& field, const Grid& grid, SurfaceMesh& out)
        : m_field(field), m_grid(grid), m_out(out), m_base(out.mesh.p.size()) {
        field.sample(grid, m_value);
        for (float& v : m_value) v -= kThreshold;
    }
    // Returns false once the mesh passes the vertex cap.
    bool run() {
        for (size_t z = 0; z + 1 < m_grid.nz; ++z)
            for (size_t y = 0; y + 1 < m_grid.ny; ++y)
                for (size_t x = 0; x + 1 < m_grid.nx; ++x) {
                    cell(x, y, z);
                    if (long(m_base + m_edges.size()) > kMaxMeshVertices) return false;
                }
        m_onEdge = {};  // (its memory back before the mesh grows)
        placeVertices();
        m_out.mesh.tris.reserve(m_out.mesh.tris.size() + m_tris.size());
        for (size_t t = 0; t < m_tris.size(); t += 3)
            triangle(m_tris[t], m_tris[t + 1], m_tris[t + 2]);
        return true;
    }

private:
    void cell(size_t x, size_t y, size_t z) {
        // six tetrahedra about the diagonal from corner 0 to corner 7
        static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                                        {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
        size_t corner[8];
        bool in = false, outside = false;
        for (int c = 0; c < 8; ++c) {
            corner[c] = m_grid.index(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
            (m_value[corner[c]] > 0.0f ? in : outside) = true;
        }
        if (!in || !outside) return;
        for (const auto& tet : kTets) {
            size_t inside[4], away[4];
            int ni = 0, no = 0;
            for (int k = 0; k < 4; ++k) {
                const size_t v = corner[tet[k]];
                if (m_value[v] > 0.0f)
                    inside[ni++] = v;
                else
                    away[no++] = v;
            }
            if (ni == 1 || ni == 3) {
                const size_t apex = ni == 1 ? inside[0] : away[0];
                const size_t* rest = ni == 1 ? away : inside;
                m_tris.insert(m_tris.end(), {vertex(apex, rest[0]), vertex(apex, rest[1]),
                                             vertex(apex, rest[2])});
            } else if (ni == 2) {
                const int a = vertex(inside[0], away[0]), b = vertex(inside[0], away[1]),
                          c = vertex(inside[1], away[1]), d = vertex(inside[1], away[0]);
                m_tris.insert(m_tris.end(), {a, b, c, a, c, d});
            }
        }
    }
    // The vertex where the level set crosses grid edge (i, j), placed later.
    int vertex(size_t i, size_t j) {
        if (i > j) std::swap(i, j);
        const uint64_t key = uint64_t(i) * uint64_t(m_value.size()) + uint64_t(j);
        auto [it, added] = m_onEdge.emplace(key, int(m_base + m_edges.size()));
        if (added) m_edges.emplace_back(i, j);
        return it->second;
    }
    void placeVertices() {
        const size_t n = m_base + m_edges.size();
        m_out.mesh.p.resize(n);
        m_out.mesh.n.resize(n);
        m_out.st.resize(n, glm::vec2(0.0f));  // (no global u, v: RI 3.2 5.6)
        const size_t parts = m_edges.size() >= 4096 ? hostThreads() : 1;
        runInParts(m_edges.size(), parts, [&](size_t begin, size_t end, size_t) {
            std::vector<float> scratch;
            for (size_t e = begin; e < end; ++e)
                place(m_edges[e].first, m_edges[e].second, m_base + e, scratch);
        });
    }
    // Vertex v on grid edge (i, j): on the level set by regula falsi (the linear guess
    // alone is off by up to a hundredth of a blob's radius), its normal down the field's
    // gradient.
    void place(size_t i, size_t j, size_t v, std::vector<float>& scratch) const {
        auto field = [&](glm::vec3 p) { return m_field.at(p, scratch); };
        const glm::vec3 pi = m_grid.at(i), pj = m_grid.at(j);
        float a = 0.0f, b = 1.0f, fa = m_value[i], fb = m_value[j];
        float t = fa / (fa - fb);
        for (int step = 0; step < 4 && fa != fb; ++step) {
            const float ft = field(pi + t * (pj - pi)) - kThreshold;
            if ((ft > 0.0f) == (fa > 0.0f))
                a = t, fa = ft;
            else
                b = t, fb = ft;
            if (fa == fb) break;
            t = a + (b - a) * fa / (fa - fb);
        }
        const glm::vec3 p = pi + t * (pj - pi);
        const float e = 0.25f * m_grid.h;
        const glm::vec3 grad(
            field(p + glm::vec3(e, 0, 0)) - field(p - glm::vec3(e, 0, 0)),
            field(p + glm::vec3(0, e, 0)) - field(p - glm::vec3(0, e, 0)),
            field(p + glm::vec3(0, 0, e)) - field(p - glm::vec3(0, 0, e)));
        const float g = glm::length(grad);
        m_out.mesh.p[v] = p;
        m_out.mesh.n[v] = g > 0.0f ? -grad / g : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    // Outward (down the field): the winding follows the vertices' normals.
    void triangle(int a, int b, int c) {
        const std::vector<glm::vec3>& p = m_out.mesh.p;
        const glm::vec3 ng =
            glm::cross(p[size_t(b)] - p[size_t(a)], p[size_t(c)] - p[size_t(a)]);
        if (!(glm::dot(ng, ng) > 0.0f)) return;
        const std::vector<glm::vec3>& n = m_out.mesh.n;
        if (glm::dot(ng, n[size_t(a)] + n[size_t(b)] + n[size_t(c)]) < 0.0f)
            std::swap(b, c);
        m_out.mesh.tris.insert(m_out.mesh.tris.end(), {a, b, c});
        m_out.faceIndex.push_back(0);
    }
    const Field& m_field;
    Grid m_grid;
    SurfaceMesh& m_out;
    size_t m_base;               // the mesh's vertices before the blobby's
    std::vector<float> m_value;  // the field less the threshold at each grid point
    std::unordered_map<uint64_t, int> m_onEdge;
    std::vector<std::pair<size_t, size_t>> m_edges;  // each new vertex's grid edge
    std::vector<int> m_tris;                         // the walk's triangles, by vertex
};

}  // namespace

bool tessellateBlobby(const std::vector<int>& code, const std::vector<float>& floats,
                      int cells, SurfaceMesh& out, std::string* err, std::string* note,
                      BlobbyLeafWeights* weights) {
    Program program = decode(code, floats);
    if (program.repeller && note)
        *note = "a repelling plane (opcode 1003) needs a depth file; its field is 0";
    const float smallest = program.smallest;
    if (!(smallest > 0.0f) || !std::isfinite(smallest)) {  // (valid, but no surface)
        if (note) *note = "no ellipsoid or segment blob reaches anywhere: nothing drawn";
        return true;
    }
    // Cells: about 32 across the narrowest blob's reach (16 across its surface), within
    // `cells` a side; one cell of margin so the surface closes inside the grid.
    glm::vec3 lo = program.lo, hi = program.hi;
    const glm::vec3 extent = hi - lo;
    const float longest = std::max(extent.x, std::max(extent.y, extent.z));
    const float h = std::max(smallest / 32.0f, longest / float(std::max(cells, 4)));
    // (the grid set off by an odd fraction of a cell, so that a level set through round
    // numbers, as a lone blob's 0.5, meets no grid point and no triangle degenerates)
    lo -= glm::vec3(1.3183099f * h), hi += glm::vec3(h);
    Field field(std::move(program.code), lo, hi);
    const glm::ivec3 n = glm::max(glm::ivec3(glm::ceil((hi - lo) / h)), glm::ivec3(1));
    const Grid grid{lo, h, size_t(n.x) + 1, size_t(n.y) + 1, size_t(n.z) + 1};
    if (!Polygoniser(field, grid, out).run()) {
        if (err) *err = "more than " + std::to_string(kMaxMeshVertices) + " vertices";
        return false;
    }
    if (weights) weighLeaves(field, program.leafOf, out.mesh.p, *weights);
    return true;
}

}  // namespace rd
