// tessellate_blobby.cpp: RiBlobby's field, evaluated over a grid and polygonised by
// marching tetrahedra (six a cell, so no case table is needed and the surface is closed
// wherever the field is), with smooth normals from the field's gradient.
#include "tessellate_blobby.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>

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

// A bounded primitive's field at p (0 outside its box).
float primitiveAt(const Instruction& in, glm::vec3 p) {
    if (glm::any(glm::lessThan(p, in.lo)) || glm::any(glm::greaterThan(p, in.hi)))
        return 0.0f;
    const glm::vec3 q = glm::vec3(in.toUnit * glm::vec4(p, 1.0f));
    if (in.op == 1001) return falloff(glm::dot(q, q));
    const glm::vec3 ab = in.b - in.a;
    const float len2 = glm::dot(ab, ab);
    const float t =
        len2 > 0 ? std::clamp(glm::dot(q - in.a, ab) / len2, 0.0f, 1.0f) : 0.0f;
    const glm::vec3 d = q - (in.a + t * ab);
    return falloff(glm::dot(d, d) / (in.value * in.value));
}

// The field of a program. The usual one, the sum (or maximum) of its primitives, is
// evaluated from a coarse grid of bins listing the bounded primitives that reach each:
// a point costs the few blobs near it, not the program (500 blobs: 9 s -> well under 1).
class Field {
public:
    Field(std::vector<Instruction> code, glm::vec3 lo, glm::vec3 hi)
        : m_code(std::move(code)), m_v(m_code.size()) {
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
    float operator()(glm::vec3 p) {
        if (m_flat) {
            float v = m_rest;
            const glm::ivec3 c = binOf(p);
            for (int k : m_bins[index(c.x, c.y, c.z)]) {
                const float f = primitiveAt(m_code[size_t(k)], p);
                v = m_max ? std::max(v, f) : v + f;
            }
            return std::isfinite(v) ? v : 0.0f;
        }
        for (size_t i = 0; i < m_code.size(); ++i) {
            const Instruction& in = m_code[i];
            float& v = m_v[i];
            auto arg = [&](size_t k) { return m_v[size_t(in.operands[k])]; };
            switch (in.op) {
                case 1000:
                    v = in.value;
                    break;
                case 1001:
                case 1002:
                    v = primitiveAt(in, p);
                    break;
                case 1003:
                    v = 0.0f;
                    break;  // (a repelling plane: no depth file read)
                case 0:
                    v = 0.0f;
                    for (size_t k = 0; k < in.operands.size(); ++k) v += arg(k);
                    break;
                case 1:
                    v = 1.0f;
                    for (size_t k = 0; k < in.operands.size(); ++k) v *= arg(k);
                    break;
                case 2:
                    v = -INFINITY;
                    for (size_t k = 0; k < in.operands.size(); ++k)
                        v = std::max(v, arg(k));
                    break;
                case 3:
                    v = INFINITY;
                    for (size_t k = 0; k < in.operands.size(); ++k)
                        v = std::min(v, arg(k));
                    break;
                case 4:
                    v = arg(0) - arg(1);
                    break;
                case 5:
                    v = arg(1) != 0.0f ? arg(0) / arg(1) : 0.0f;
                    break;
                case 6:
                    v = -arg(0);
                    break;
                default:
                    v = arg(0);
                    break;  // 7: identity
            }
        }
        const float f = m_v.empty() ? 0.0f : m_v.back();
        return std::isfinite(f) ? f : 0.0f;
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
    glm::ivec3 binOf(glm::vec3 p) const {
        return glm::clamp(glm::ivec3(glm::floor((p - m_lo) / m_size)), glm::ivec3(0),
                          m_n - 1);
    }
    size_t index(int x, int y, int z) const {
        return (size_t(z) * size_t(m_n.y) + size_t(y)) * size_t(m_n.x) + size_t(x);
    }
    std::vector<Instruction> m_code;
    std::vector<float> m_v;
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
// whose vertices, on the grid's edges, the cells around an edge share.
class Polygoniser {
public:
    Polygoniser(Field& field, glm::vec3 lo, float h, glm::ivec3 cells, SurfaceMesh& out)
        : m_field(field),
          m_lo(lo),
          m_h(h),
          m_nx(size_t(cells.x) + 1),
          m_ny(size_t(cells.y) + 1),
          m_nz(size_t(cells.z) + 1),
          m_out(out) {
        m_value.resize(m_nx * m_ny * m_nz);
        for (size_t i = 0; i < m_value.size(); ++i)
            m_value[i] = field(at(i)) - kThreshold;
    }
    // Returns false once the mesh passes the vertex cap.
    bool run() {
        for (size_t z = 0; z + 1 < m_nz; ++z)
            for (size_t y = 0; y + 1 < m_ny; ++y)
                for (size_t x = 0; x + 1 < m_nx; ++x) {
                    cell(x, y, z);
                    if (long(m_out.mesh.p.size()) > kMaxMeshVertices) return false;
                }
        return true;
    }

private:
    size_t index(size_t x, size_t y, size_t z) const { return (z * m_ny + y) * m_nx + x; }
    glm::vec3 at(size_t i) const {
        const size_t x = i % m_nx, y = (i / m_nx) % m_ny, z = i / (m_nx * m_ny);
        return m_lo + m_h * glm::vec3(float(x), float(y), float(z));
    }
    void cell(size_t x, size_t y, size_t z) {
        // six tetrahedra about the diagonal from corner 0 to corner 7
        static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7},
                                        {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
        size_t corner[8];
        bool in = false, outside = false;
        for (int c = 0; c < 8; ++c) {
            corner[c] = index(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
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
                triangle(vertex(apex, rest[0]), vertex(apex, rest[1]),
                         vertex(apex, rest[2]));
            } else if (ni == 2) {
                const int a = vertex(inside[0], away[0]), b = vertex(inside[0], away[1]),
                          c = vertex(inside[1], away[1]), d = vertex(inside[1], away[0]);
                triangle(a, b, c);
                triangle(a, c, d);
            }
        }
    }
    // The vertex where the level set crosses grid edge (i, j).
    int vertex(size_t i, size_t j) {
        if (i > j) std::swap(i, j);
        const uint64_t key = uint64_t(i) * uint64_t(m_value.size()) + uint64_t(j);
        auto [it, added] = m_onEdge.emplace(key, int(m_out.mesh.p.size()));
        if (!added) return it->second;
        // on the edge by regula falsi: the linear guess alone is off by up to a hundredth
        // of a blob's radius
        const glm::vec3 pi = at(i), pj = at(j);
        float a = 0.0f, b = 1.0f, fa = m_value[i], fb = m_value[j];
        float t = fa / (fa - fb);
        for (int step = 0; step < 4 && fa != fb; ++step) {
            const float ft = m_field(pi + t * (pj - pi)) - kThreshold;
            if ((ft > 0.0f) == (fa > 0.0f))
                a = t, fa = ft;
            else
                b = t, fb = ft;
            if (fa == fb) break;
            t = a + (b - a) * fa / (fa - fb);
        }
        const glm::vec3 p = pi + t * (pj - pi);
        const float e = 0.25f * m_h;
        const glm::vec3 grad(
            m_field(p + glm::vec3(e, 0, 0)) - m_field(p - glm::vec3(e, 0, 0)),
            m_field(p + glm::vec3(0, e, 0)) - m_field(p - glm::vec3(0, e, 0)),
            m_field(p + glm::vec3(0, 0, e)) - m_field(p - glm::vec3(0, 0, e)));
        const float g = glm::length(grad);
        m_out.mesh.p.push_back(p);
        m_out.st.push_back(glm::vec2(0.0f));  // (no global u, v: RI 3.2 5.6)
        m_out.mesh.n.push_back(g > 0.0f ? -grad / g : glm::vec3(0.0f, 0.0f, 1.0f));
        return it->second;
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
    Field& m_field;
    glm::vec3 m_lo;
    float m_h;
    size_t m_nx, m_ny, m_nz;
    std::vector<float> m_value;  // the field less the threshold at each grid point
    std::unordered_map<uint64_t, int> m_onEdge;
    SurfaceMesh& m_out;
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
    if (!Polygoniser(field, lo, h, n, out).run()) {
        if (err) *err = "more than " + std::to_string(kMaxMeshVertices) + " vertices";
        return false;
    }
    if (weights) weighLeaves(field, program.leafOf, out.mesh.p, *weights);
    return true;
}

}  // namespace rd
