// rib_builder_point_params.cpp: primitive variables that give a shader parameter a value
// per point (RI: a varying, vertex, facevarying or uniform variable named like a
// parameter of the surface shader gives that parameter its value on the primitive,
// interpolated over it). Each kind of geometry turns them into per-vertex values of
// its triangles (one vertex per triangle corner when some are facevarying or per face):
// polygons from their vertices, patches and NuPatch from their sub-patch or knot-span
// corners, subdivision meshes refined with the cage, points per disc, diced quadrics
// from their 4 (u, v) corners; exact quadrics keep the 4 corner values. The values are
// moved to world ("current") space and stored for the device, which interpolates them
// at each hit (shade_common.clh) and hands them to the shader in place of its
// parameters (rsl_abi.h, PER-POINT PARAMETERS). Cs, Os and st given per point (or per
// face, or per face-vertex) ride the same paths on every geometry and end in the mesh's
// own colours and st (takeStandardPointValues).
#include <algorithm>
#include <map>
#include <set>

#include "rib_builder.h"
#include "rib_builder_util.h"
#include "tessellate_nurbs.h"

namespace rd {
namespace {

using Kind = VertexData::Kind;

// Values a parameter has in all (floats, ints or strings).
size_t valueCount(const rib::Param& p) {
    return p.type == rib::ParamType::String    ? p.strings.size()
           : p.type == rib::ParamType::Integer ? p.ints.size()
                                               : p.floats.size();
}

bool kindOf(const rib::Param& p, Kind* kind) {
    if (p.arraySize != 1) return false;
    switch (p.type) {
    case rib::ParamType::Float: *kind = Kind::Float; return true;
    case rib::ParamType::Color: *kind = Kind::Color; return p.components() >= 3;
    case rib::ParamType::Point: *kind = Kind::Point; return true;
    case rib::ParamType::Vector: *kind = Kind::Vector; return true;
    case rib::ParamType::Normal: *kind = Kind::Normal; return true;
    default: return false;
    }
}

// A variable's values three floats at a time: a colour of n > 3 channels is carried in
// ceil(n / 3) pieces (VertexData::PointParam), anything else in one.
struct Piece {
    const rib::Param* param;
    int index;  // its floats 3 index .. 3 index + 2 of each value
    rib::StorageClass storage;
};

std::vector<Piece> piecesOf(const std::vector<const rib::Param*>& list) {
    std::vector<Piece> out;
    for (const rib::Param* p : list)
        for (int k = 0; k < pointParamEntries(p->components()); ++k)
            out.push_back({p, k, p->storage});
    return out;
}

// A piece's per-vertex values to fill (n of them).
VertexData::PointParam pointParamFor(const Piece& p, size_t n) {
    VertexData::PointParam out;
    out.name = p.param->name;
    kindOf(*p.param, &out.kind);
    out.floats = p.param->components();
    out.piece = p.index;
    out.v.assign(n, glm::vec3(0.0f));
    return out;
}

// One per-vertex PointParam for each piece of the listed variables, its value at vertex
// i being at(piece, i): the loop every kind of geometry shares.
template <class At>
void appendPointParams(const std::vector<const rib::Param*>& list, VertexData& mesh, At at) {
    for (const Piece& p : piecesOf(list)) {
        VertexData::PointParam out = pointParamFor(p, mesh.p.size());
        for (size_t i = 0; i < out.v.size(); ++i) out.v[i] = at(p, i);
        mesh.params.push_back(std::move(out));
    }
}

// Value i of a piece (0 where the values run out).
glm::vec3 valueAt(const Piece& p, size_t i) {
    const std::vector<float>& f = p.param->floats;
    const size_t n =
        size_t(p.param->components() * p.param->arraySize);  // ("float[2] st")
    if (n == 1) return glm::vec3(i < f.size() ? f[i] : 0.0f, 0.0f, 0.0f);
    if (n * i + n > f.size()) return glm::vec3(0.0f);
    glm::vec3 v(0.0f);
    for (size_t c = 0, j = 3 * size_t(p.index); c < 3 && j < n; ++c, ++j)
        v[int(c)] = f[n * i + j];
    return v;
}

// The sub-patch (or NURBS knot span, when `order` > 0) that parameter x is in, of n,
// and where in it (0..1): sub-patches split [0, 1] evenly; span i of a NURBS runs from
// knot[order - 1 + i] to knot[order + i] (empty ones, at repeated knots, are skipped).
void spanAt(float x, int n, const std::vector<float>& knot, int order, int* i, float* f) {
    if (order <= 0 || knot.size() < size_t(order + n)) {
        const float X = x * float(n);
        *i = std::clamp(int(std::floor(X)), 0, n - 1);
        *f = X - float(*i);
        return;
    }
    *i = n - 1;
    for (int k = 0; k < n; ++k)
        if (x < knot[size_t(order + k)]) {
            *i = k;
            break;
        }
    const float k0 = knot[size_t(order - 1 + *i)], k1 = knot[size_t(order + *i)];
    *f = k1 > k0 ? std::clamp((x - k0) / (k1 - k0), 0.0f, 1.0f) : 0.0f;
}

// The vertex and triangle each vertex of a mesh came from.
struct Corner {
    size_t vertex = 0, triangle = 0;
};

// Values of a face (uniform) or a face's corner (facevarying) differ between the faces
// that share a vertex: then the mesh gets one vertex per triangle corner. Returns where
// each vertex came from (its triangle only when split: only those values need it).
std::vector<Corner> splitCornersIfNeeded(const std::vector<const rib::Param*>& list,
                                         VertexData& mesh) {
    bool perCorner = false;
    for (const rib::Param* p : list)
        perCorner |= p->storage == rib::StorageClass::FaceVarying ||
                     p->storage == rib::StorageClass::Uniform;
    std::vector<Corner> src(mesh.p.size());
    if (!perCorner) {
        for (size_t i = 0; i < src.size(); ++i) src[i].vertex = i;
        return src;
    }
    VertexData split;
    src.clear();
    for (size_t t = 0; 3 * t + 2 < mesh.tris.size(); ++t)
        for (int c = 0; c < 3; ++c) {
            const size_t v = size_t(mesh.tris[3 * t + c]);
            split.p.push_back(mesh.p[v]);
            if (mesh.st.size() == mesh.p.size()) split.st.push_back(mesh.st[v]);
            if (mesh.n.size() == mesh.p.size()) split.n.push_back(mesh.n[v]);
            if (mesh.cs.size() == mesh.p.size()) split.cs.push_back(mesh.cs[v]);
            if (mesh.os.size() == mesh.p.size()) split.os.push_back(mesh.os[v]);
            if (mesh.csN.size() == mesh.p.size()) split.csN.push_back(mesh.csN[v]);
            if (mesh.osN.size() == mesh.p.size()) split.osN.push_back(mesh.osN[v]);
            split.tris.push_back(int(src.size()));
            src.push_back({v, t});
        }
    mesh = std::move(split);
    return src;
}

}  // namespace

bool isStandardPrimvar(const std::string& name) {
    static const std::set<std::string> standard = {"P", "Pw", "Pz", "N", "Np", "Cs", "Os", "s",
                                                   "t", "st", "width", "constantwidth"};
    return standard.count(name) != 0;
}

bool givesOneValue(const rib::Param& p) {
    // one value for the whole primitive, whatever its class, is read as constant (the
    // reader accepts it: "Cs" [1 0 0] on a sphere)
    const size_t per = size_t(std::max(1, p.components() * p.arraySize));
    return p.storage == rib::StorageClass::Constant || valueCount(p) == per;
}

std::vector<const rib::Param*> pointParamsOf(const rib::ParamList* params,
                                             bool withStandard) {
    std::vector<const rib::Param*> out;
    if (!params) return out;
    Kind kind;
    for (const rib::Param& p : params->params)
        if (!isStandardPrimvar(p.name) && !givesOneValue(p) && kindOf(p, &kind) &&
            out.size() < size_t(kMaxPointParams))
            out.push_back(&p);
    if (!withStandard) return out;
    auto perPoint = [&](const char* name, rib::ParamType type, int arraySize) {
        const rib::Param* p = params->find(name);
        return p && p->type == type && p->arraySize == arraySize && !givesOneValue(*p)
                   ? p
                   : nullptr;
    };
    for (const char* name : {"Cs", "Os"})
        if (const rib::Param* p = perPoint(name, rib::ParamType::Color, 1);
            p && p->components() >= 3)
            out.push_back(p);
    const rib::Param* s = perPoint("s", rib::ParamType::Float, 1);
    const rib::Param* t = perPoint("t", rib::ParamType::Float, 1);
    if (const rib::Param* st = perPoint("st", rib::ParamType::Float, 2)) {
        out.push_back(st);
    } else if (s && t) {
        out.push_back(s);
        out.push_back(t);
    }
    return out;
}

void takeStandardPointValues(VertexData& mesh, int channels) {
    const size_t n = mesh.p.size();
    std::vector<glm::vec3> s, t;  // "s" and "t" given apart
    while (!mesh.params.empty()) {
        const std::string name = mesh.params.back().name;
        size_t first = mesh.params.size() - 1;  // a colour's pieces: the run of its name
        while (first > 0 && mesh.params[first - 1].name == name) --first;
        const auto piece = mesh.params.begin() + std::ptrdiff_t(first);
        if (name == "st") {
            mesh.st.resize(n);
            for (size_t i = 0; i < n && i < piece->v.size(); ++i)
                mesh.st[i] = glm::vec2(piece->v[i]);
        } else if (name == "s" || name == "t") {
            (name == "s" ? s : t) = piece->v;
        } else if (name == "Cs" || name == "Os") {
            const bool opacity = name == "Os";
            if (channels <= 3) {
                (opacity ? mesh.os : mesh.cs) = piece->v;
            } else {
                std::vector<VertexData::Channels>& out = opacity ? mesh.osN : mesh.csN;
                out.assign(n, VertexData::Channels{});
                for (auto q = piece; q != mesh.params.end(); ++q)
                    for (size_t i = 0; i < n && i < q->v.size(); ++i)
                        for (int c = 0; c < 3 && 3 * q->piece + c < channels; ++c)
                            out[i][size_t(3 * q->piece + c)] = q->v[i][c];
            }
        } else {
            break;  // a shader parameter: the standard ones follow them all
        }
        mesh.params.erase(piece, mesh.params.end());
    }
    if (s.size() == n && t.size() == n) {
        mesh.st.resize(n);
        for (size_t i = 0; i < n; ++i) mesh.st[i] = glm::vec2(s[i].x, t[i].x);
    }
}

void RibBuilder::readPointParams(const rib::ParamList& params, const std::vector<int>& nverts,
                                 const std::vector<int>& verts, VertexData& mesh) {
    const std::vector<const rib::Param*> list =
        pointParamsOf(&params, /*withStandard=*/true);
    if (list.empty()) return;
    const size_t np = mesh.p.size();
    bool perCorner = false;  // some value belongs to a face or a face's corner
    for (const rib::Param* p : list)
        perCorner |= p->storage == rib::StorageClass::FaceVarying ||
                     p->storage == rib::StorageClass::Uniform;
    if (perCorner) {
        // one vertex per face-vertex: every other per-vertex value is copied to it
        const size_t nfv = verts.size();
        auto spread = [&](auto& v) {
            if (v.size() != np) return;
            auto copy = v;
            v.resize(nfv);
            for (size_t i = 0; i < nfv; ++i)
                v[i] = verts[i] >= 0 && size_t(verts[i]) < np ? copy[size_t(verts[i])] : copy[0];
        };
        spread(mesh.p), spread(mesh.n), spread(mesh.st), spread(mesh.cs), spread(mesh.os);
        spread(mesh.csN), spread(mesh.osN);
        mesh.tris.clear();
        std::vector<int> corner(nfv);
        for (size_t i = 0; i < nfv; ++i) corner[i] = int(i);
        size_t offset = 0;
        for (int count : nverts) {  // the faces pointsPolygons took (it reported the rest)
            bool ok = count >= 3 && offset + size_t(count) <= nfv;
            for (int k = 0; ok && k < count; ++k)
                ok = verts[offset + k] >= 0 && size_t(verts[offset + k]) < np;
            if (ok) triangulateConvex(&corner[offset], count, mesh.tris);
            offset += size_t(std::max(count, 0));
        }
    }
    std::vector<int> faceOf;  // face index of each face-vertex
    for (size_t f = 0; f < nverts.size(); ++f)
        faceOf.insert(faceOf.end(), size_t(std::max(nverts[f], 0)), int(f));
    appendPointParams(list, mesh, [&](const Piece& p, size_t i) {
        size_t src = i;  // the value's index for vertex i
        if (perCorner) {
            if (p.storage == rib::StorageClass::FaceVarying) src = i;
            else if (p.storage == rib::StorageClass::Uniform)
                src = i < faceOf.size() ? size_t(faceOf[i]) : 0;
            else src = verts[i] >= 0 && size_t(verts[i]) < np ? size_t(verts[i]) : 0;
        }
        return valueAt(p, src);
    });
    takeStandardPointValues(mesh, m_world.colors.slots());
}

void RibBuilder::generalPolygonPointParams(const rib::ParamList& params,
                                           const std::vector<int>& nloops,
                                           const std::vector<int>& nverts,
                                           const std::vector<int>& verts,
                                           const std::vector<int>& faceIndex, VertexData& mesh) {
    const std::vector<const rib::Param*> list = pointParamsOf(&params, true);
    if (list.empty()) return;
    // where each polygon's face-vertices start in `verts` (its loops one after another)
    std::vector<size_t> first(nloops.size() + 1, 0);
    for (size_t f = 0, l = 0; f < nloops.size(); ++f) {
        first[f + 1] = first[f];
        for (int k = 0; k < nloops[f] && l < nverts.size(); ++k, ++l)
            first[f + 1] += size_t(std::max(nverts[l], 0));
    }
    const std::vector<Corner> src = splitCornersIfNeeded(list, mesh);
    appendPointParams(list, mesh, [&](const Piece& p, size_t i) {
        const size_t point = src[i].vertex;
        const size_t face = src[i].triangle < faceIndex.size() ? size_t(faceIndex[src[i].triangle]) : 0;
        size_t at = point;  // varying, vertex: the point's value
        if (p.storage == rib::StorageClass::Uniform) at = face;
        if (p.storage == rib::StorageClass::FaceVarying && face < nloops.size())
            for (size_t j = first[face]; j < first[face + 1] && j < verts.size(); ++j)
                if (size_t(verts[j]) == point) {  // this polygon's corner at the point
                    at = j;
                    break;
                }
        return valueAt(p, at);
    });
}

void RibBuilder::patchPointParams(const rib::ParamList& params, const PatchGrid& grid,
                                  const std::vector<glm::vec2>& uv,
                                  const std::vector<int>& faceIndex, VertexData& mesh) {
    std::vector<const rib::Param*> list = pointParamsOf(&params, true);
    if (list.empty() || uv.size() != mesh.p.size()) return;
    // varying values sit on the sub-patches' corners: one more than the sub-patches
    // across a direction unless it wraps (RI); a bilinear mesh's vertex values too
    const int gu = grid.nupatches + (grid.uperiodic ? 0 : 1);
    const int gv = grid.nvpatches + (grid.vperiodic ? 0 : 1);
    // vertex values sit on the control points: nu x nv of a bicubic mesh or a NuPatch
    const bool nurbs = grid.uorder > 0;
    auto carried = [&](const rib::Param* p) {
        const size_t n = valueCount(*p) / size_t(p->components() * p->arraySize);
        if ((nurbs || grid.bicubic) && p->storage == rib::StorageClass::Vertex)
            return n == size_t(grid.nu) * size_t(grid.nv);
        return p->storage == rib::StorageClass::Uniform
                   ? n == size_t(grid.nupatches * grid.nvpatches)
                   : n == size_t(gu * gv);
    };
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](const rib::Param* p) {
                                  return isStandardPrimvar(p->name) && !carried(p);
                              }),
               list.end());
    for (const rib::Param* p : list)
        if (!carried(p)) return;
    // A NuPatch's vertex values: a surface of their own over its knots and weights
    // (evalNuPatch at the vertex's (u, v)), one a piece, made at its first vertex
    std::map<std::pair<const rib::Param*, int>, NuPatchInput> nurbsOf;
    auto nurbsValue = [&](const Piece& p, glm::vec2 at) {
        NuPatchInput& in = nurbsOf[{p.param, p.index}];
        if (in.positions.empty()) {
            in.nu = grid.nu, in.uorder = grid.uorder, in.uknot = grid.uknot;
            in.nv = grid.nv, in.vorder = grid.vorder, in.vknot = grid.vknot;
            in.rational = !grid.weights.empty();
            for (size_t k = 0; k < size_t(grid.nu) * size_t(grid.nv); ++k) {
                const glm::vec3 v = valueAt(p, k);
                const float w =
                    in.rational && k < grid.weights.size() ? grid.weights[k] : 1.0f;
                in.positions.insert(in.positions.end(), {v.x * w, v.y * w, v.z * w});
                if (in.rational) in.positions.push_back(w);
            }
        }
        return evalNuPatch(in, at.x, at.y).p;
    };
    const std::vector<Corner> src = splitCornersIfNeeded(list, mesh);
    appendPointParams(list, mesh, [&](const Piece& p, size_t i) {
        const glm::vec2 at = uv[src[i].vertex];
        if (nurbs && p.storage == rib::StorageClass::Vertex) return nurbsValue(p, at);
        if (p.storage == rib::StorageClass::Uniform) {
            const size_t t = src[i].triangle;
            return valueAt(p, t < faceIndex.size() ? size_t(faceIndex[t]) : 0);
        }
        if (grid.bicubic && p.storage == rib::StorageClass::Vertex) {
            // the sub-patch's own basis over its 4 x 4 control points' values, picked as
            // the tessellator picks its points (every step-th, wrapping when periodic)
            int pu, pv;
            float fu, fv, wu[4], wv[4];
            spanAt(at.x, grid.nupatches, {}, 0, &pu, &fu);
            spanAt(at.y, grid.nvpatches, {}, 0, &pv, &fv);
            basisWeights(grid.ubasis, fu, wu);
            basisWeights(grid.vbasis, fv, wv);
            glm::vec3 v(0.0f);
            for (int b = 0; b < 4; ++b)
                for (int a = 0; a < 4; ++a) {
                    const int iu = (pu * grid.ubasis.step + a) % grid.nu;
                    const int iv = (pv * grid.vbasis.step + b) % grid.nv;
                    v += wu[a] * wv[b] *
                         valueAt(p, size_t(iv) * size_t(grid.nu) + size_t(iu));
                }
            return v;
        }
        // bilinear between the corners of the sub-patch the vertex is in
        int i0, j0;
        float fu, fv;
        spanAt(at.x, grid.nupatches, grid.uknot, grid.uorder, &i0, &fu);
        spanAt(at.y, grid.nvpatches, grid.vknot, grid.vorder, &j0, &fv);
        const int i1 = (i0 + 1) % gu, j1 = (j0 + 1) % gv;
        auto c = [&](int a, int b) { return valueAt(p, size_t(b * gu + a)); };
        return (1 - fu) * (1 - fv) * c(i0, j0) + fu * (1 - fv) * c(i1, j0) +
               (1 - fu) * fv * c(i0, j1) + fu * fv * c(i1, j1);
    });
}

void RibBuilder::blobbyPointParams(const rib::ParamList& params,
                                   const BlobbyLeafWeights& weights, VertexData& mesh) {
    appendPointParams(pointParamsOf(&params, true), mesh, [&](const Piece& p, size_t i) {
        glm::vec3 v(0.0f);
        if (i + 1 < weights.start.size())
            for (size_t k = weights.start[i]; k < weights.start[i + 1]; ++k)
                v += weights.weight[k] * valueAt(p, size_t(weights.leaf[k]));
        return v;
    });
}

void RibBuilder::pointsPointParams(const rib::ParamList& params,
                                   const std::vector<int>& faceIndex, VertexData& mesh) {
    for (const Piece& p : piecesOf(pointParamsOf(&params, true))) {
        VertexData::PointParam out = pointParamFor(p, mesh.p.size());
        for (size_t t = 0; 3 * t + 2 < mesh.tris.size() && t < faceIndex.size(); ++t)
            for (int c = 0; c < 3; ++c)  // each disc has its own vertices
                out.v[size_t(mesh.tris[3 * t + c])] = valueAt(p, size_t(faceIndex[t]));
        mesh.params.push_back(std::move(out));
    }
}

bool subdivPointParamsIn(const rib::ParamList& params, SubdivInput& in) {
    const std::vector<const rib::Param*> list = pointParamsOf(&params, true);
    for (const Piece& p : piecesOf(list)) {
        if (p.storage == rib::StorageClass::Uniform) continue;  // per face: no refining
        const bool faceVarying = p.storage == rib::StorageClass::FaceVarying;
        std::vector<glm::vec3> v(faceVarying ? in.vertices.size() : in.P.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = valueAt(p, i);
        (faceVarying                              ? in.faceVaryingValues
         : p.storage == rib::StorageClass::Vertex ? in.vertexValues
                                                  : in.varyingValues)
            .push_back(std::move(v));
    }
    return !list.empty();
}

void RibBuilder::subdivPointParams(const rib::ParamList& params,
                                   const std::vector<std::vector<glm::vec3>>& refined,
                                   const std::vector<int>& faceIndex, VertexData& mesh) {
    const std::vector<const rib::Param*> list = pointParamsOf(&params, true);
    const std::vector<Piece> pieces = piecesOf(list);
    size_t count[3] = {0, 0, 0}, next[3] = {0, 0, 0};  // vertex, varying, facevarying
    auto kindOf = [](rib::StorageClass c) {
        return c == rib::StorageClass::Vertex    ? 0
               : c == rib::StorageClass::Varying ? 1
                                                 : 2;
    };
    for (const Piece& p : pieces)
        if (p.storage != rib::StorageClass::Uniform) ++count[kindOf(p.storage)];
    // (facevarying values come refined a vertex of the mesh each, split at their seams:
    // only values per face split its corners)
    std::vector<const rib::Param*> perFace;
    for (const rib::Param* p : list)
        if (p->storage == rib::StorageClass::Uniform) perFace.push_back(p);
    const std::vector<Corner> src = splitCornersIfNeeded(perFace, mesh);
    for (const Piece& p : pieces) {
        VertexData::PointParam out = pointParamFor(p, mesh.p.size());
        // refined values: the vertex ones first, then the varying and the facevarying
        // ones (SubdivInput)
        const std::vector<glm::vec3>* r = nullptr;
        if (p.storage != rib::StorageClass::Uniform) {
            const int k = kindOf(p.storage);
            r = &refined.at((k > 0 ? count[0] : 0) + (k > 1 ? count[1] : 0) + next[k]++);
        }
        for (size_t i = 0; i < out.v.size(); ++i) {
            const size_t t = src[i].triangle;
            out.v[i] = r ? (src[i].vertex < r->size() ? (*r)[src[i].vertex] : glm::vec3(0.0f))
                         : valueAt(p, t < faceIndex.size() ? size_t(faceIndex[t]) : 0);
        }
        mesh.params.push_back(std::move(out));
    }
}

void RibBuilder::curvesPointParams(const rib::ParamList& params, const CurvesInput& in,
                                   const std::vector<glm::vec2>& uv,
                                   const std::vector<int>& faceIndex, VertexData& mesh) {
    const std::vector<const rib::Param*> list = pointParamsOf(&params, true);
    if (list.empty() || uv.size() != mesh.p.size()) return;
    const int step = in.cubic ? in.vbasis.step : 1;
    // each curve's first control point and first varying value
    std::vector<size_t> p0(in.nvertices.size() + 1, 0), var0(in.nvertices.size() + 1, 0);
    for (size_t c = 0; c < in.nvertices.size(); ++c) {
        p0[c + 1] = p0[c] + size_t(std::max(in.nvertices[c], 0));
        var0[c + 1] = var0[c] +
                      size_t(std::max(curveVaryingCount(in.cubic, in.nvertices[c], in.periodic, step), 0));
    }
    std::vector<size_t> curveOf(mesh.p.size(), 0);  // a ribbon's vertices are its own
    for (size_t t = 0; 3 * t + 2 < mesh.tris.size() && t < faceIndex.size(); ++t)
        for (int k = 0; k < 3; ++k) curveOf[size_t(mesh.tris[3 * t + k])] = size_t(faceIndex[t]);
    appendPointParams(list, mesh, [&](const Piece& p, size_t i) {
        const size_t c = std::min(curveOf[i], in.nvertices.size() - 1);
        const int n = in.nvertices[c];
        const int segs = std::max(1, curveSegments(in.cubic, n, in.periodic, step));
        const int nvar = std::max(1, curveVaryingCount(in.cubic, n, in.periodic, step));
        // along the curve as its centre line is (tessellate_curves_points.cpp)
        const float x = std::clamp(uv[i].y, 0.0f, 1.0f) * float(segs);
        const int s = std::min(int(x), segs - 1);
        const float t = x - float(s);
        if (p.storage == rib::StorageClass::Uniform) return valueAt(p, c);
        if (p.storage == rib::StorageClass::Vertex && in.cubic) {
            float w[4];
            basisWeights(in.vbasis, t, w);
            glm::vec3 v(0.0f);
            for (int k = 0; k < 4; ++k) v += w[k] * valueAt(p, p0[c] + size_t((s * step + k) % n));
            return v;
        }
        // varying (and a linear curve's vertex values): along each segment
        return (1 - t) * valueAt(p, var0[c] + size_t(s)) +
               t * valueAt(p, var0[c] + size_t((s + 1) % nvar));
    });
}

void RibBuilder::cornerPointParams(const rib::ParamList& params, VertexData& mesh,
                                   bool withStandard) {
    for (const Piece& p : piecesOf(pointParamsOf(&params, withStandard))) {
        VertexData::PointParam out = pointParamFor(p, mesh.p.size());
        // a quadric's varying values are at its (u, v) corners 00, 10, 01, 11 (one value,
        // uniform: everywhere); mesh.st holds each vertex's (u, v)
        const bool corners = valueCount(*p.param) >=
                             4 * size_t(p.param->components() * p.param->arraySize);
        glm::vec3 c[4];
        for (int k = 0; k < 4; ++k) c[k] = valueAt(p, corners ? size_t(k) : 0);
        for (size_t i = 0; i < out.v.size(); ++i) {
            const glm::vec2 uv = i < mesh.st.size() ? mesh.st[i] : glm::vec2(0.0f);
            out.v[i] = (1 - uv.x) * (1 - uv.y) * c[0] + uv.x * (1 - uv.y) * c[1] +
                       (1 - uv.x) * uv.y * c[2] + uv.x * uv.y * c[3];
        }
        mesh.params.push_back(std::move(out));
    }
}

// Object-space values to the device's world space (eye-relative, like P): points by
// the full transform, vectors by its linear part, normals by its inverse transpose.
std::vector<glm::vec3> RibBuilder::pointParamToWorld(const glm::mat4& ctm,
                                                     const VertexData::PointParam& p,
                                                     bool eyeRelative) const {
    switch (p.kind) {
    case Kind::Point: {
        if (eyeRelative) return worldPoints(ctm, p.v);
        std::vector<glm::vec3> out(p.v.size());
        for (size_t i = 0; i < out.size(); ++i) out[i] = xformPoint(ctm, p.v[i]);
        return out;
    }
    case Kind::Vector:
    case Kind::Normal: {
        const glm::mat3 m = p.kind == Kind::Vector ? glm::mat3(ctm)
                                                   : glm::transpose(glm::inverse(glm::mat3(ctm)));
        std::vector<glm::vec3> out(p.v.size());
        for (size_t i = 0; i < out.size(); ++i) out[i] = m * p.v[i];
        return out;
    }
    default: return p.v;
    }
}

uint32_t RibBuilder::quadricPointParams(const rib::ParamList& params, const glm::mat4& ctm) {
    if (pointParamsOf(&params).empty()) return RT_NO_POINT_PARAMS;
    VertexData corners;
    corners.p.resize(4);
    corners.st = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    cornerPointParams(params, corners);
    std::vector<std::vector<glm::vec3>> world;
    for (const VertexData::PointParam& p : corners.params) world.push_back(pointParamToWorld(ctm, p));
    const uint32_t first = uint32_t(m_world.pointParamValues.size());
    for (int c = 0; c < 4; ++c)
        for (const std::vector<glm::vec3>& v : world) m_world.pointParamValues.push_back(f4(v[c]));
    return first;
}

void RibBuilder::startTrianglePointParams() {
    if (m_world.triangleParams.size() < m_world.triangles.size())
        m_world.triangleParams.resize(m_world.triangles.size(), RT_NO_POINT_PARAMS);
}

}  // namespace rd
