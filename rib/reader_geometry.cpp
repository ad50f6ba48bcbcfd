// reader_geometry.cpp: the geometric primitives. Before a primitive is forwarded its
// arrays are checked against each other as RI 3.2 defines them (vertex counts against
// "P", index ranges, PatchMesh nu*nv and Basis steps, NuPatch knots = n + order,
// TrimCurve and SubdivisionMesh tag shapes, Curves segment rules, Blobby code) and so
// are the lengths of vertex/varying/facevarying primitive variables. Counts are summed
// in 64 bits, so no hostile count can overflow or cause an allocation.
#include "reader_impl.h"
#include "run_program.h"

namespace rib {
namespace detail {

long long sum(const std::vector<int>& v) {
    long long s = 0;
    for (int x : v) s += x;
    return s;
}

// The vertex positions of a primitive: "P" (3 floats a point), "Pw" (4) or "Pz" (1).
// Returns the number of points, or -1 after reporting why there are none.
long long Reader::countPoints(const char* req, const ParamList& params,
                              const SourceLoc& loc) {
    const Param* P = nullptr;
    size_t per = 3;
    const char* names[] = {"P", "Pw", "Pz"};
    const size_t pers[] = {3, 4, 1};
    for (int i = 0; i < 3 && !P; ++i) {
        const Param* q = params.find(names[i]);
        if (q && !q->floats.empty()) {
            P = q;
            per = pers[i];
        }
    }
    if (!P) {
        error(loc, std::string(req) + " requires \"P\"");
        return -1;
    }
    if (P->floats.size() % per != 0) {
        error(loc, std::string(req) + " \"" + P->name + "\" needs a multiple of " +
                       std::to_string(per) + " values, got " +
                       std::to_string(P->floats.size()));
        return -1;
    }
    return static_cast<long long>(P->floats.size() / per);
}

// Checks the length of every vertex, varying and facevarying (and constant) variable;
// a count of -1 skips that class. Uniform ones are checked too when `uniform` >= 0 and
// the variable was declared uniform explicitly or by Declare (undeclared values default
// to uniform and are not checked).
bool Reader::checkVaryingCounts(const char* req, const ParamList& params,
                                long long uniform, long long varying, long long vertex,
                                long long faceVarying, const SourceLoc& loc) {
    for (const Param& p : params.params) {
        // (uniform: one a face; -1: not checked, the caller has no count)
        const long long want =
            ClassCounts{uniform, varying, vertex, faceVarying}.of(p.storage);
        if (want < 0) continue;
        size_t values = p.type == ParamType::String    ? p.strings.size()
                        : p.type == ParamType::Integer ? p.ints.size()
                                                       : p.floats.size();
        long long per = static_cast<long long>(p.components()) * p.arraySize;
        if (per <= 0) continue;
        long long have = static_cast<long long>(values) / per;
        // One value for the whole primitive ("Cs" [1 0 0] on a sphere) is a common idiom
        // that targets read as constant; anything else must match.
        if (have != want && have != 1) {
            error(loc, std::string(req) + ": " + storageClassName(p.storage) + " \"" +
                           p.name + "\" has " + std::to_string(have) + " values, needs " +
                           std::to_string(want));
            return false;
        }
    }
    return true;
}

bool Reader::checkIndices(const char* req, const std::vector<int>& idx, long long n,
                          const char* what, const SourceLoc& loc) {
    for (int v : idx) {
        if (v < 0 || v >= n) {
            error(loc, std::string(req) + " " + what + " index " + std::to_string(v) +
                           " out of range (" + std::to_string(n) + ")");
            return false;
        }
    }
    return true;
}

bool Reader::checkPointsPolygons(const Args& a, const SourceLoc& loc) {
    const std::vector<int>& nverts = a.intArrays[0];
    const std::vector<int>& verts = a.intArrays[1];
    for (size_t i = 0; i < nverts.size(); ++i) {
        if (nverts[i] < 3) {
            error(loc, "PointsPolygons polygon " + std::to_string(i) + " has " +
                           std::to_string(nverts[i]) + " vertices (needs at least 3)");
            return false;
        }
    }
    long long total = sum(nverts);
    if (total != static_cast<long long>(verts.size())) {
        error(loc, "PointsPolygons nverts add up to " + std::to_string(total) +
                       " but verts has " + std::to_string(verts.size()) + " entries");
        return false;
    }
    long long npoints = countPoints("PointsPolygons", a.params, loc);
    if (npoints < 0) return false;
    for (int v : verts) {
        if (v < 0 || v >= npoints) {
            error(loc, "PointsPolygons vertex index " + std::to_string(v) +
                           " out of range (" +
                           plural(static_cast<size_t>(npoints), "point") + " in \"P\")");
            return false;
        }
    }
    return checkVaryingCounts("PointsPolygons", a.params, static_cast<long long>(nverts.size()),
                              npoints, npoints, total, loc);
}

bool Reader::checkPointsGeneralPolygons(const Args& a, const SourceLoc& loc) {
    const char* req = "PointsGeneralPolygons";
    const std::vector<int>& nloops = a.intArrays[0];
    const std::vector<int>& nverts = a.intArrays[1];
    const std::vector<int>& verts = a.intArrays[2];
    for (int l : nloops) {
        if (l < 1) {
            error(loc, std::string(req) + " polygons need at least one loop");
            return false;
        }
    }
    if (sum(nloops) != static_cast<long long>(nverts.size())) {
        error(loc, std::string(req) + " nloops add up to " + std::to_string(sum(nloops)) +
                       " but nverts has " + std::to_string(nverts.size()) + " entries");
        return false;
    }
    for (int n : nverts) {
        if (n < 3) {
            error(loc, std::string(req) + " loop with " + std::to_string(n) +
                           " vertices (needs at least 3)");
            return false;
        }
    }
    long long total = sum(nverts);
    if (total != static_cast<long long>(verts.size())) {
        error(loc, std::string(req) + " nverts add up to " + std::to_string(total) +
                       " but verts has " + std::to_string(verts.size()) + " entries");
        return false;
    }
    long long npoints = countPoints(req, a.params, loc);
    if (npoints < 0 || !checkIndices(req, verts, npoints, "vertex", loc)) return false;
    return checkVaryingCounts(req, a.params, static_cast<long long>(nloops.size()), npoints,
                              npoints, total, loc);
}

bool Reader::checkPatchMesh(const Args& a, const SourceLoc& loc) {
    const std::string type = a.strs[0];
    bool cubic = type == "bicubic";
    if (!cubic && type != "bilinear") {
        error(loc, "PatchMesh: unknown type \"" + type + "\" (bilinear, bicubic)");
        return false;
    }
    bool uper = false, vper = false;
    if (!wrapMode(a.strs[1], uper) || !wrapMode(a.strs[2], vper)) {
        error(loc, "PatchMesh: wrap modes must be \"periodic\" or \"nonperiodic\"");
        return false;
    }
    long long nu = static_cast<long long>(a.nums[0]), nv = static_cast<long long>(a.nums[1]);
    long long up = 0, uvar = 0, vp = 0, vvar = 0;
    std::string why;
    if (!spanCount(cubic, uper, nu, m_ustep, up, uvar, why)) {
        error(loc, "PatchMesh nu = " + std::to_string(nu) + ": " + why);
        return false;
    }
    if (!spanCount(cubic, vper, nv, m_vstep, vp, vvar, why)) {
        error(loc, "PatchMesh nv = " + std::to_string(nv) + ": " + why);
        return false;
    }
    long long npoints = countPoints("PatchMesh", a.params, loc);
    if (npoints < 0) return false;
    if (npoints != nu * nv) {
        error(loc, "PatchMesh has " + plural(static_cast<size_t>(npoints), "point") +
                       " but nu*nv = " + std::to_string(nu * nv));
        return false;
    }
    return checkVaryingCounts("PatchMesh", a.params, up * vp, uvar * vvar, nu * nv,
                              uvar * vvar, loc);
}

bool Reader::checkNuPatch(const Args& a, const SourceLoc& loc) {
    // nums: nu uorder umin umax nv vorder vmin vmax; floatArrays: uknot vknot
    long long n[2] = {static_cast<long long>(a.nums[0]), static_cast<long long>(a.nums[4])};
    long long order[2] = {static_cast<long long>(a.nums[1]),
                          static_cast<long long>(a.nums[5])};
    const char* dir[2] = {"u", "v"};
    for (int d = 0; d < 2; ++d) {
        const std::vector<float>& knot = a.floatArrays[d];
        if (order[d] < 1 || n[d] < order[d]) {
            error(loc, std::string("NuPatch n") + dir[d] + " = " + std::to_string(n[d]) +
                           " must be at least " + dir[d] + "order = " +
                           std::to_string(order[d]) + " (>= 1)");
            return false;
        }
        if (static_cast<long long>(knot.size()) != n[d] + order[d]) {
            error(loc, std::string("NuPatch ") + dir[d] + "knot has " +
                           std::to_string(knot.size()) + " values, needs n" + dir[d] +
                           " + " + dir[d] + "order = " + std::to_string(n[d] + order[d]));
            return false;
        }
        for (size_t i = 1; i < knot.size(); ++i) {
            if (!(knot[i] >= knot[i - 1])) {
                error(loc, std::string("NuPatch ") + dir[d] + "knot decreases at " +
                               std::to_string(i));
                return false;
            }
        }
    }
    long long npoints = countPoints("NuPatch", a.params, loc);
    if (npoints < 0) return false;
    if (npoints != n[0] * n[1]) {
        error(loc, "NuPatch has " + plural(static_cast<size_t>(npoints), "point") +
                       " but nu*nv = " + std::to_string(n[0] * n[1]));
        return false;
    }
    long long up = n[0] - order[0] + 1, vp = n[1] - order[1] + 1;
    return checkVaryingCounts("NuPatch", a.params, up * vp, (up + 1) * (vp + 1),
                              n[0] * n[1], (up + 1) * (vp + 1), loc);
}

bool Reader::checkGeneralPolygon(const Args& a, const SourceLoc& loc) {
    const std::vector<int>& nv = a.intArrays[0];
    for (int k : nv) {
        if (k < 3) {
            error(loc, "GeneralPolygon loop with " + std::to_string(k) +
                           " vertices (needs at least 3)");
            return false;
        }
    }
    if (nv.empty()) {
        error(loc, "GeneralPolygon needs at least one loop");
        return false;
    }
    const long long np = countPoints("GeneralPolygon", a.params, loc);
    if (np < 0) return false;
    if (np != sum(nv)) {
        error(loc, "GeneralPolygon nverts add up to " + std::to_string(sum(nv)) +
                       " but \"P\" has " + plural(static_cast<size_t>(np), "point"));
        return false;
    }
    return checkVaryingCounts("GeneralPolygon", a.params, -1, np, np, np, loc);
}

bool Reader::checkPatch(const Args& a, const SourceLoc& loc) {
    const std::string& type = ArgAt{a}.s(0);
    const bool cubic = type == "bicubic";
    if (!cubic && type != "bilinear") {
        error(loc, "Patch: unknown type \"" + type + "\" (bilinear, bicubic)");
        return false;
    }
    const long long np = countPoints("Patch", a.params, loc);
    if (np < 0) return false;
    if (np != (cubic ? 16 : 4)) {
        error(loc, std::string("Patch \"") + type + "\" needs " + (cubic ? "16" : "4") +
                       " points, got " + std::to_string(np));
        return false;
    }
    return checkVaryingCounts("Patch", a.params, 1, 4, np, 4, loc);
}

// A primitive whose vertex and varying values are one a point: Polygon, Points.
bool Reader::checkPointwise(const char* req, const ParamList& P, const SourceLoc& loc) {
    const long long np = countPoints(req, P, loc);
    return np >= 0 && checkVaryingCounts(req, P, -1, np, np, np, loc);
}

bool Reader::dispatchGeometry(const RequestInfo& info, const Args& a, const SourceLoc& loc) {
    struct PrimitiveScope {  // the request's primitive variables, for its duration
        Target& t;
        PrimitiveScope(Target& target, const ParamList& p) : t(target) {
            t.primitiveVariables(&p);
        }
        ~PrimitiveScope() { t.primitiveVariables(nullptr); }
    } primitiveScope(m_target, a.params);
    return dispatchPolygonsOrPatches(info, a, loc) || dispatchQuadric(info, a, loc) ||
           dispatchOtherGeometry(info, a, loc);
}

bool Reader::dispatchPolygonsOrPatches(const RequestInfo& info, const Args& a,
                                       const SourceLoc& loc) {
    static const std::vector<int> noInts;
    static const std::vector<float> noFloats;
    static const std::vector<std::string> noStrings;
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    switch (info.req) {
        case Req::Polygon:
            if (checkPointwise(info.name, P, loc)) t.polygon(loc, P);
            return true;
        case Req::GeneralPolygon:
            if (checkGeneralPolygon(a, loc)) t.generalPolygon(loc, a.intArrays[0], P);
            return true;
        case Req::PointsPolygons:
            if (checkPointsPolygons(a, loc))
                t.pointsPolygons(loc, a.intArrays[0], a.intArrays[1], P);
            return true;
        case Req::PointsGeneralPolygons:
            if (checkPointsGeneralPolygons(a, loc))
                t.pointsGeneralPolygons(loc, a.intArrays[0], a.intArrays[1], a.intArrays[2],
                                        P);
            return true;
        case Req::Patch:
            if (checkPatch(a, loc)) t.patch(loc, v.s(0), P);
            return true;
        case Req::PatchMesh:
            if (checkPatchMesh(a, loc))
                t.patchMesh(loc, v.s(0), v.n(0), v.s(1), v.n(1), v.s(2), P);
            return true;
        case Req::NuPatch:
            if (checkNuPatch(a, loc))
                t.nuPatch(loc, v.n(0), v.n(1), a.floatArrays[0], v.f(2), v.f(3), v.n(4),
                          v.n(5), a.floatArrays[1], v.f(6), v.f(7), P);
            return true;
        case Req::TrimCurve:
            if (checkTrimCurve(a, loc))
                t.trimCurve(loc, a.intArrays[0], a.intArrays[1], a.floatArrays[0],
                            a.floatArrays[1], a.floatArrays[2], a.intArrays[2],
                            a.floatArrays[3], a.floatArrays[4], a.floatArrays[5]);
            return true;
        case Req::SubdivisionMesh:
            if (!checkSubdivisionMesh(a, loc)) return true;
            if (a.optionalMissing)
                t.subdivisionMesh(loc, v.s(0), a.intArrays[0], a.intArrays[1], noStrings,
                                  noInts, noInts, noFloats, P);
            else
                t.subdivisionMesh(loc, v.s(0), a.intArrays[0], a.intArrays[1],
                                  a.strArrays[0], a.intArrays[2], a.intArrays[3],
                                  a.floatArrays[0], P);
            return true;
        default:
            return false;
    }
}

bool Reader::dispatchQuadric(const RequestInfo& info, const Args& a,
                             const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    switch (info.req) {
        case Req::Sphere:
        case Req::Cylinder:
        case Req::Cone:
        case Req::Disk:
        case Req::Torus:
        case Req::Paraboloid:
        case Req::Hyperboloid:
            break;
        default:
            return false;
    }
    if (!checkVaryingCounts(info.name, P, 1, 4, 4, 4, loc)) return true;
    switch (info.req) {
        case Req::Sphere:
            t.sphere(loc, v.f(0), v.f(1), v.f(2), v.f(3), P);
            break;
        case Req::Cylinder:
            t.cylinder(loc, v.f(0), v.f(1), v.f(2), v.f(3), P);
            break;
        case Req::Cone:
            t.cone(loc, v.f(0), v.f(1), v.f(2), P);
            break;
        case Req::Disk:
            t.disk(loc, v.f(0), v.f(1), v.f(2), P);
            break;
        case Req::Torus:
            t.torus(loc, v.f(0), v.f(1), v.f(2), v.f(3), v.f(4), P);
            break;
        case Req::Paraboloid:
            t.paraboloid(loc, v.f(0), v.f(1), v.f(2), v.f(3), P);
            break;
        default: {  // Hyperboloid
            float p1[3] = {v.f(0), v.f(1), v.f(2)}, p2[3] = {v.f(3), v.f(4), v.f(5)};
            t.hyperboloid(loc, p1, p2, v.f(6), P);
        }
    }
    return true;
}

bool Reader::dispatchOtherGeometry(const RequestInfo& info, const Args& a,
                                   const SourceLoc& loc) {
    const ArgAt v{a};
    const ParamList& P = a.params;
    Target& t = m_target;
    switch (info.req) {
        case Req::Curves:
            if (checkCurves(a, loc)) t.curves(loc, v.s(0), a.intArrays[0], v.s(1), P);
            return true;
        case Req::Points:
            if (checkPointwise(info.name, P, loc)) t.points(loc, P);
            return true;
        case Req::Blobby:
            if (v.n(0) < 0)
                error(loc, "Blobby nleaf must not be negative");
            else if (checkBlobby(a, loc))
                t.blobby(loc, v.n(0), a.intArrays[0], a.floatArrays[0], a.strArrays[0],
                         P);
            return true;
        case Req::Geometry:
            t.geometry(loc, v.s(0), P);
            return true;
        case Req::Procedural:
            dispatchProcedural(a, loc);
            return true;
        case Req::ObjectInstance:
            if (!m_objects.count(v.s(0)))
                error(loc, "ObjectInstance of undefined object \"" + v.s(0) + "\"");
            else
                t.objectInstance(loc, v.s(0));
            return true;
        default:
            return false;
    }
}

// Procedural: a DelayedReadArchive deferred until a ray reaches its bound where the
// target can, else expanded here (RunProgram, DynamicLoad where there is a loader) or
// handed on as a request.
void Reader::dispatchProcedural(const Args& a, const SourceLoc& loc) {
    const ArgAt v{a};
    Target& t = m_target;
    const std::string name = v.s(0);
    const std::vector<std::string>& args = a.strArrays[0];
    size_t want = name == "DelayedReadArchive"                    ? 1
                  : name == "RunProgram" || name == "DynamicLoad" ? 2
                                                                  : 0;
    if (want == 0) {
        error(loc, "Procedural: unknown procedural \"" + name +
                       "\" (DelayedReadArchive, RunProgram, DynamicLoad)");
        return;
    }
    if (args.size() != want) {
        error(loc, "Procedural \"" + name + "\" needs " + plural(want, "argument") +
                       ", got " + std::to_string(args.size()));
        return;
    }
    float bound[6];
    for (size_t i = 0; i < 6; ++i) bound[i] = v.f(i);
    if (m_opts.expandArchives && name == "DelayedReadArchive") {
        std::string file = resolveArchive(args[0]);
        if (t.deferProcedural(loc, name, args, bound, file.empty() ? args[0] : file))
            return;
    }
    if (m_opts.expandArchives &&
        (name != "DynamicLoad" || (dynamicLoader() && t.runsDynamicLoad())))
        expandProcedural(name, args, loc);
    else
        t.procedural(loc, name, args, bound);
}

}  // namespace detail
}  // namespace rib
