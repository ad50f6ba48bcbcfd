// tessellate_subdiv.cpp: SubdivisionMesh through OpenSubdiv's Far API (uniform
// refinement + limit projection).
#include "host/scene/tessellate_subdiv.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#ifdef RD_HAVE_OPENSUBDIV
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#endif

namespace rd {
namespace {

bool fail(std::string* err, const std::string& msg) {
    if (err) *err = msg;
    return false;
}

#ifdef RD_HAVE_OPENSUBDIV
struct Vtx {
    glm::vec3 p{0.0f};
    void Clear(void* = nullptr) { p = glm::vec3(0.0f); }
    void AddWithWeight(const Vtx& s, float w) { p += w * s.p; }
};
#endif

}  // namespace

bool validateSubdiv(const SubdivInput& in, std::string* err) {
    if (in.scheme != "catmull-clark" && in.scheme != "loop" && in.scheme != "bilinear")
        return fail(err, "SubdivisionMesh: scheme \"" + in.scheme +
                             "\" is not known (catmull-clark, loop, bilinear)");
    size_t total = 0;
    for (size_t f = 0; f < in.nvertices.size(); ++f) {
        const int n = in.nvertices[f];
        if (n < 3) return fail(err, "SubdivisionMesh: a face needs at least 3 vertices");
        if (n != 3 && in.scheme == "loop")
            return fail(err, "SubdivisionMesh \"loop\": face " + std::to_string(f) +
                                 " has " + std::to_string(n) +
                                 " vertices (Loop subdivides triangles)");
        total += size_t(n);
    }
    if (in.nvertices.empty()) return fail(err, "SubdivisionMesh: no faces");
    if (total != in.vertices.size())
        return fail(err, "SubdivisionMesh: vertices does not match sum(nvertices)");
    for (int v : in.vertices)
        if (v < 0 || size_t(v) >= in.P.size())
            return fail(err, "SubdivisionMesh: vertex index out of range");
    for (const auto& p : in.P)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail(err, "SubdivisionMesh: non-finite position");
    if (in.nargs.size() != 2 * in.tags.size())
        return fail(err, "SubdivisionMesh: nargs must hold 2 values per tag");
    size_t ni = 0, nf = 0;
    for (size_t t = 0; t < in.tags.size(); ++t) {
        int a = in.nargs[2 * t], b = in.nargs[2 * t + 1];
        if (a < 0 || b < 0) return fail(err, "SubdivisionMesh: negative nargs");
        const std::string& tag = in.tags[t];
        if (ni + a > in.intargs.size() || nf + b > in.floatargs.size())
            return fail(err, "SubdivisionMesh: tag arguments run past intargs/floatargs");
        if (tag == "crease" || tag == "corner") {
            for (int k = 0; k < a; ++k)
                if (in.intargs[ni + k] < 0 || size_t(in.intargs[ni + k]) >= in.P.size())
                    return fail(err, "SubdivisionMesh: " + tag + " vertex out of range");
            if (b < 1) return fail(err, "SubdivisionMesh: " + tag + " needs a sharpness");
            if (tag == "crease" && a < 2) return fail(err, "SubdivisionMesh: crease needs 2+ vertices");
        } else if (tag == "hole") {
            for (int k = 0; k < a; ++k)
                if (in.intargs[ni + k] < 0 || size_t(in.intargs[ni + k]) >= in.nvertices.size())
                    return fail(err, "SubdivisionMesh: hole face out of range");
        }
        ni += size_t(a);
        nf += size_t(b);
    }
    if (ni != in.intargs.size() || nf != in.floatargs.size())
        return fail(err, "SubdivisionMesh: nargs do not account for all tag arguments");
    for (const std::vector<glm::vec3>& v : in.faceVaryingValues)
        if (v.size() != in.vertices.size())
            return fail(err, "SubdivisionMesh: " + std::to_string(v.size()) +
                                 " facevarying values where " +
                                 std::to_string(in.vertices.size()) + " are needed");
    return true;
}

#ifdef RD_HAVE_OPENSUBDIV
namespace {

using namespace OpenSubdiv;

// The refinement level, lowered until the refined vertices (about 4x a level: one quad
// per n-gon corner at level 1) fit under the cap beside the `already` there.
int levelWithinCap(const SubdivInput& in, int level, size_t already) {
    level = std::clamp(level, 0, kMaxSubdivLevel);
    double estimate = double(in.vertices.size()) + in.P.size();
    for (int l = 1; l <= level; ++l) estimate *= 4.0;
    while (level > 0 && estimate + double(already) > double(kMaxMeshVertices)) {
        --level;
        estimate /= 4.0;
    }
    return level;
}

// The tags as OpenSubdiv's topology takes them (others are ignored).
struct Tags {
    Sdc::Options opts;
    std::vector<int> creasePairs, corners, holes;
    std::vector<float> creaseW, cornerW;
};

Tags readTags(const SubdivInput& in) {
    Tags out;
    out.opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_NONE);
    out.opts.SetFVarLinearInterpolation(Sdc::Options::FVAR_LINEAR_ALL);
    size_t ni = 0, nf = 0;
    for (size_t t = 0; t < in.tags.size(); ++t) {
        int a = in.nargs[2 * t], b = in.nargs[2 * t + 1];
        const int* ia = in.intargs.data() + ni;
        const float* fa = in.floatargs.data() + nf;
        const std::string& tag = in.tags[t];
        if (tag == "crease") {
            for (int k = 0; k + 1 < a; ++k) {
                out.creasePairs.insert(out.creasePairs.end(), {ia[k], ia[k + 1]});
                out.creaseW.push_back(fa[std::min(k, b - 1)]);
            }
        } else if (tag == "corner") {
            for (int k = 0; k < a; ++k) {
                out.corners.push_back(ia[k]);
                out.cornerW.push_back(fa[std::min(k, b - 1)]);
            }
        } else if (tag == "hole") {
            out.holes.insert(out.holes.end(), ia, ia + a);
        } else if (tag == "interpolateboundary") {
            out.opts.SetVtxBoundaryInterpolation(
                a >= 1 && ia[0] == 2   ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                : a >= 1 && ia[0] == 0 ? Sdc::Options::VTX_BOUNDARY_NONE
                                       : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        }
        ni += size_t(a);
        nf += size_t(b);
    }
    std::sort(out.holes.begin(), out.holes.end());
    out.holes.erase(std::unique(out.holes.begin(), out.holes.end()), out.holes.end());
    return out;
}

// Facevarying values: a channel each, whose values are the corners', one value for the
// corners of a control vertex that agree, so that a seam is where faces disagree.
struct FaceVarying {
    std::vector<std::vector<int>> index;         // per channel: each corner's value
    std::vector<std::vector<glm::vec3>> values;  // per channel
    std::vector<Far::TopologyDescriptor::FVarChannel> channel;
};

FaceVarying faceVaryingChannels(const SubdivInput& in) {
    const size_t channels = in.faceVaryingValues.size();
    FaceVarying out;
    out.index.resize(channels), out.values.resize(channels), out.channel.resize(channels);
    for (size_t ch = 0; ch < channels; ++ch) {
        const std::vector<glm::vec3>& given = in.faceVaryingValues[ch];
        std::vector<std::vector<int>> ofVertex(in.P.size());  // each vertex's values
        std::vector<glm::vec3>& values = out.values[ch];
        out.index[ch].resize(in.vertices.size());
        for (size_t c = 0; c < in.vertices.size(); ++c) {
            std::vector<int>& mine = ofVertex[size_t(in.vertices[c])];
            auto same = std::find_if(mine.begin(), mine.end(), [&](int v) {
                return values[size_t(v)] == given[c];
            });
            if (same == mine.end()) {
                mine.push_back(int(values.size()));
                values.push_back(given[c]);
                same = mine.end() - 1;
            }
            out.index[ch][c] = *same;
        }
        out.channel[ch].numValues = int(values.size());
        out.channel[ch].valueIndices = out.index[ch].data();
    }
    return out;
}

std::unique_ptr<Far::TopologyRefiner> refinerFor(const SubdivInput& in, const Tags& tags,
                                                 FaceVarying& fvar) {
    Far::TopologyDescriptor desc;
    desc.numVertices = int(in.P.size());
    desc.numFaces = int(in.nvertices.size());
    desc.numVertsPerFace = in.nvertices.data();
    desc.vertIndicesPerFace = in.vertices.data();
    desc.numCreases = int(tags.creaseW.size());
    desc.creaseVertexIndexPairs = tags.creasePairs.data();
    desc.creaseWeights = tags.creaseW.data();
    desc.numCorners = int(tags.cornerW.size());
    desc.cornerVertexIndices = tags.corners.data();
    desc.cornerWeights = tags.cornerW.data();
    desc.numHoles = int(tags.holes.size());
    desc.holeIndices = tags.holes.data();
    desc.numFVarChannels = int(fvar.channel.size());
    desc.fvarChannels = fvar.channel.empty() ? nullptr : fvar.channel.data();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    const Sdc::SchemeType type = in.scheme == "loop"       ? Sdc::SCHEME_LOOP
                                 : in.scheme == "bilinear" ? Sdc::SCHEME_BILINEAR
                                                           : Sdc::SCHEME_CATMARK;
    return std::unique_ptr<Far::TopologyRefiner>(
        Factory::Create(desc, Factory::Options(type, tags.opts)));
}

// Values given per control vertex, refined to one per vertex of the last level: vertex
// ones to the limit like P, varying ones linearly.
std::vector<glm::vec3> refinedValues(const Far::TopologyRefiner& refiner,
                                     const Far::PrimvarRefiner& primvar, int level,
                                     const std::vector<glm::vec3>& given, size_t controls,
                                     bool vertex) {
    std::vector<Vtx> v(size_t(refiner.GetNumVerticesTotal()));
    for (size_t i = 0; i < given.size() && i < controls; ++i) v[i].p = given[i];
    Vtx* s = v.data();
    for (int l = 1; l <= level; ++l) {
        Vtx* d = s + refiner.GetLevel(l - 1).GetNumVertices();
        if (vertex)
            primvar.Interpolate(l, s, d);
        else
            primvar.InterpolateVarying(l, s, d);
        s = d;
    }
    const int nv = refiner.GetLevel(level).GetNumVertices();
    std::vector<Vtx> atLimit(static_cast<size_t>(nv));
    if (vertex)
        primvar.Limit(s, atLimit);
    else
        std::copy(s, s + nv, atLimit.begin());
    std::vector<glm::vec3> out(static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) out[size_t(i)] = atLimit[size_t(i)].p;
    return out;
}

// A facevarying channel's values at the limit, per value of the last level.
std::vector<Vtx> faceVaryingLimit(const Far::TopologyRefiner& refiner,
                                  const Far::PrimvarRefiner& primvar, int level, int ch,
                                  const std::vector<glm::vec3>& values) {
    std::vector<Vtx> fv(size_t(refiner.GetNumFVarValuesTotal(ch)));
    for (size_t i = 0; i < values.size(); ++i) fv[i].p = values[i];
    Vtx* s = fv.data();
    for (int l = 1; l <= level; ++l) {
        Vtx* d = s + refiner.GetLevel(l - 1).GetNumFVarValues(ch);
        primvar.InterpolateFaceVarying(l, s, d, ch);
        s = d;
    }
    std::vector<Vtx> out(size_t(refiner.GetLevel(level).GetNumFVarValues(ch)));
    primvar.LimitFaceVarying(s, out, ch);
    return out;
}

// The base face of each refined face: uniform refinement emits a face's children
// consecutively (Catmull-Clark and bilinear: n for an n-gon at level 1, then 4 per quad;
// Loop: 4 per triangle).
std::vector<int> parentFaces(const SubdivInput& in, int level) {
    std::vector<int> parent;
    for (size_t f = 0; f < in.nvertices.size(); ++f)
        parent.insert(parent.end(), in.scheme == "loop" ? 4 : size_t(in.nvertices[f]),
                      int(f));
    for (int l = 2; l <= level; ++l) {
        std::vector<int> next(parent.size() * 4);
        for (size_t f = 0; f < parent.size(); ++f)
            std::fill_n(next.begin() + 4 * f, 4, parent[f]);
        parent.swap(next);
    }
    return parent;
}

// The output's vertices and triangles from the last level: its vertices, or with
// facevarying values one for each of its vertices' combinations of values (a vertex on
// a seam has one a side). vertexOf: each output vertex's vertex, fvarOf: its value in
// each channel.
struct LimitSurface {
    const std::vector<Vtx>&lim, &t1, &t2;
    bool normals;  // the limit tangents' normal at each vertex
};

void emitSurface(const Far::TopologyLevel& last, const LimitSurface& limit,
                 const std::vector<int>& parent, int channels, SurfaceMesh& out,
                 std::vector<int>& vertexOf, std::vector<std::vector<int>>& fvarOf) {
    const int base = int(out.mesh.p.size());
    fvarOf.assign(size_t(channels), {});
    auto emit = [&](int v) {
        out.mesh.p.push_back(limit.lim[size_t(v)].p);
        const glm::vec3 c = glm::cross(limit.t1[size_t(v)].p, limit.t2[size_t(v)].p);
        if (limit.normals)
            out.mesh.n.push_back(glm::length(c) > 0.0f ? glm::normalize(c)
                                                       : glm::vec3(0, 0, 1));
        out.st.emplace_back(0.0f);  // (st given per point comes as values)
        vertexOf.push_back(v);
    };
    if (channels == 0)
        for (int i = 0; i < last.GetNumVertices(); ++i) emit(i);
    // The output vertices made for each value of the first channel (a value belongs to
    // one vertex): usually one, more where another channel has a seam the first has not.
    std::vector<std::vector<int>> outOf(channels > 0 ? size_t(last.GetNumFVarValues(0))
                                                     : 0);
    std::vector<int> corner, key(static_cast<size_t>(channels));
    for (int f = 0; f < last.GetNumFaces(); ++f) {
        if (last.IsFaceHole(f)) continue;
        auto fv = last.GetFaceVertices(f);
        corner.assign(fv.begin(), fv.end());
        for (int k = 0; channels > 0 && k < fv.size(); ++k) {
            for (int ch = 0; ch < channels; ++ch)
                key[size_t(ch)] = last.GetFaceFVarValues(f, ch)[k];
            std::vector<int>& made = outOf[size_t(key[0])];
            auto same = std::find_if(made.begin(), made.end(), [&](int o) {
                for (int ch = 1; ch < channels; ++ch)
                    if (fvarOf[size_t(ch)][size_t(o)] != key[size_t(ch)]) return false;
                return true;
            });
            if (same == made.end()) {
                made.push_back(int(vertexOf.size()));
                emit(fv[k]);
                for (int ch = 0; ch < channels; ++ch)
                    fvarOf[size_t(ch)].push_back(key[size_t(ch)]);
                same = made.end() - 1;
            }
            corner[size_t(k)] = *same;
        }
        for (size_t k = 1; k + 1 < corner.size(); ++k) {
            out.mesh.tris.insert(out.mesh.tris.end(), {base + corner[0], base + corner[k],
                                                       base + corner[k + 1]});
            out.faceIndex.push_back(parent[size_t(f)]);
        }
    }
}

}  // namespace

bool tessellateSubdivisionMesh(const SubdivInput& in, int level, SurfaceMesh& out,
                               std::string* err,
                               std::vector<std::vector<glm::vec3>>* values) {
    if (!validateSubdiv(in, err)) return false;
    // (level 0 has no limit projection for n-gons: always refine at least once)
    level = std::max(levelWithinCap(in, level, out.mesh.p.size()), 1);
    const Tags tags = readTags(in);
    FaceVarying fvar = faceVaryingChannels(in);
    const int channels = int(fvar.channel.size());
    const std::unique_ptr<Far::TopologyRefiner> refiner = refinerFor(in, tags, fvar);
    if (!refiner) return fail(err, "SubdivisionMesh: OpenSubdiv rejected the topology");
    Far::TopologyRefiner::UniformOptions uniform(level);
    uniform.fullTopologyInLastLevel = true;  // needed by PrimvarRefiner::Limit
    refiner->RefineUniform(uniform);

    std::vector<Vtx> buf(size_t(refiner->GetNumVerticesTotal()));
    for (size_t i = 0; i < in.P.size(); ++i) buf[i].p = in.P[i];
    Far::PrimvarRefiner primvar(*refiner);
    Vtx* src = buf.data();
    for (int l = 1; l <= level; ++l) {
        Vtx* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
        primvar.Interpolate(l, src, dst);
        src = dst;
    }
    const Far::TopologyLevel& last = refiner->GetLevel(level);
    const size_t nv = size_t(last.GetNumVertices());
    std::vector<Vtx> lim(nv), t1(nv), t2(nv);
    primvar.Limit(src, lim, t1, t2);
    std::vector<std::vector<glm::vec3>> perVertex;
    if (values) {
        for (const std::vector<glm::vec3>& v : in.vertexValues)
            perVertex.push_back(
                refinedValues(*refiner, primvar, level, v, in.P.size(), true));
        for (const std::vector<glm::vec3>& v : in.varyingValues)
            perVertex.push_back(
                refinedValues(*refiner, primvar, level, v, in.P.size(), false));
    }
    std::vector<std::vector<Vtx>> fvarLimit;
    for (int ch = 0; ch < channels; ++ch)
        fvarLimit.push_back(
            faceVaryingLimit(*refiner, primvar, level, ch, fvar.values[size_t(ch)]));
    const std::vector<int> parent = parentFaces(in, level);
    if (int(parent.size()) != last.GetNumFaces())
        return fail(err, "SubdivisionMesh: unexpected refined face count");
    // (a bilinear surface is its patches, shaded with their own normals: the limit
    // tangents at a vertex are one face's, which its other faces do not share)
    const bool normals =
        out.mesh.n.size() == out.mesh.p.size() && in.scheme != "bilinear";
    std::vector<int> vertexOf;
    std::vector<std::vector<int>> fvarOf;
    emitSurface(last, {lim, t1, t2, normals}, parent, channels, out, vertexOf, fvarOf);
    if (values) {
        for (const std::vector<glm::vec3>& v : perVertex) {
            std::vector<glm::vec3> atOutput(vertexOf.size());
            for (size_t i = 0; i < vertexOf.size(); ++i)
                atOutput[i] = v[size_t(vertexOf[i])];
            values->push_back(std::move(atOutput));
        }
        for (int ch = 0; ch < channels; ++ch) {
            std::vector<glm::vec3> atOutput(vertexOf.size());
            for (size_t i = 0; i < vertexOf.size(); ++i)
                atOutput[i] = fvarLimit[size_t(ch)][size_t(fvarOf[size_t(ch)][i])].p;
            values->push_back(std::move(atOutput));
        }
    }
    return true;
}
#else
bool tessellateSubdivisionMesh(const SubdivInput& in, int level, SurfaceMesh& out,
                               std::string* err, std::vector<std::vector<glm::vec3>>* values) {
    (void)level;
    (void)out;
    (void)values;
    if (!validateSubdiv(in, err)) return false;
    return fail(err, "SubdivisionMesh: built without OpenSubdiv");
}
#endif

}  // namespace rd
