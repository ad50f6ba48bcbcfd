// ri_geometry.cpp: the Ri geometry calls. C passes a parameter's values as a bare
// pointer, so each call first counts its primitive's uniform, varying, vertex and
// facevarying values (RI 3.2 section 5) from its own arguments; RIB needs no such count,
// as its arrays carry their lengths, and the reader then checks the two against each
// other.
#include <algorithm>
#include <string>

#include "ri.h"
#include "ri_context.h"
#include "ri_params.h"

using namespace rd::ri;

namespace {

long long total(const RtInt* v, long long n) {
    long long s = 0;
    for (long long i = 0; v && i < n; ++i) s += std::max(0, v[i]);
    return s;
}

// The points a list of indices refers to: its largest index plus one.
long long pointsOf(const RtInt* indices, long long n) {
    long long most = -1;
    for (long long i = 0; indices && i < n; ++i)
        most = std::max<long long>(most, indices[i]);
    return most + 1;
}

ClassCounts allOf(long long uniform, long long varying, long long vertex,
                  long long faceVarying) {
    return ClassCounts{uniform, varying, vertex, faceVarying};
}

const ClassCounts kQuadric = allOf(1, 4, 4, 4);

}  // namespace

extern "C" {

RtVoid RiPolygonV(RtInt nvertices, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiPolygon"))
        c->send("Polygon", {}, {n, tokens, values},
                allOf(1, nvertices, nvertices, nvertices));
}
RtVoid RiPolygon(RtInt nvertices, ...) {
    RI_VARARGS(nvertices, RiPolygonV(nvertices, vp.n(), vp.t(), vp.v()));
}

RtVoid RiGeneralPolygonV(RtInt nloops, RtInt nverts[], RtInt n, RtToken tokens[],
                         RtPointer values[]) {
    if (Context* c = Context::current("RiGeneralPolygon")) {
        const long long points = total(nverts, nloops);
        c->send("GeneralPolygon", {ints(nverts, nloops)}, {n, tokens, values},
                allOf(1, points, points, points));
    }
}
RtVoid RiGeneralPolygon(RtInt nloops, RtInt nverts[], ...) {
    RI_VARARGS(nverts, RiGeneralPolygonV(nloops, nverts, vp.n(), vp.t(), vp.v()));
}

RtVoid RiPointsPolygonsV(RtInt npolys, RtInt nverts[], RtInt verts[], RtInt n,
                         RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiPointsPolygons")) {
        const long long corners = total(nverts, npolys),
                        points = pointsOf(verts, corners);
        c->send("PointsPolygons", {ints(nverts, npolys), ints(verts, corners)},
                {n, tokens, values}, allOf(npolys, points, points, corners));
    }
}
RtVoid RiPointsPolygons(RtInt npolys, RtInt nverts[], RtInt verts[], ...) {
    RI_VARARGS(verts, RiPointsPolygonsV(npolys, nverts, verts, vp.n(), vp.t(), vp.v()));
}

RtVoid RiPointsGeneralPolygonsV(RtInt npolys, RtInt nloops[], RtInt nverts[],
                                RtInt verts[], RtInt n, RtToken tokens[],
                                RtPointer values[]) {
    if (Context* c = Context::current("RiPointsGeneralPolygons")) {
        const long long loops = total(nloops, npolys), corners = total(nverts, loops),
                        points = pointsOf(verts, corners);
        c->send("PointsGeneralPolygons",
                {ints(nloops, npolys), ints(nverts, loops), ints(verts, corners)},
                {n, tokens, values}, allOf(npolys, points, points, corners));
    }
}
RtVoid RiPointsGeneralPolygons(RtInt npolys, RtInt nloops[], RtInt nverts[],
                               RtInt verts[], ...) {
    RI_VARARGS(verts, RiPointsGeneralPolygonsV(npolys, nloops, nverts, verts, vp.n(),
                                               vp.t(), vp.v()));
}

RtVoid RiPatchV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiPatch")) {
        const bool cubic = type && std::string(type) == "bicubic";
        c->send("Patch", {string(type)}, {n, tokens, values},
                allOf(1, 4, cubic ? 16 : 4, 4));
    }
}
RtVoid RiPatch(RtToken type, ...) {
    RI_VARARGS(type, RiPatchV(type, vp.n(), vp.t(), vp.v()));
}

RtVoid RiPatchMeshV(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap,
                    RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiPatchMesh")) {
        const bool cubic = type && std::string(type) == "bicubic";
        bool uper = false, vper = false;
        long long up = 0, uvar = 0, vp = 0, vvar = 0;
        std::string why;
        // (counts that do not fit the rules stay 0: the reader says why)
        if (!(uwrap && rib::wrapMode(uwrap, uper) && vwrap &&
              rib::wrapMode(vwrap, vper) &&
              rib::spanCount(cubic, uper, nu, c->feed().ustep(), up, uvar, why) &&
              rib::spanCount(cubic, vper, nv, c->feed().vstep(), vp, vvar, why)))
            up = uvar = vp = vvar = 0;
        c->send("PatchMesh",
                {string(type), integer(nu), string(uwrap), integer(nv), string(vwrap)},
                {n, tokens, values},
                allOf(up * vp, uvar * vvar, (long long)std::max(0, nu) * std::max(0, nv),
                      uvar * vvar));
    }
}
RtVoid RiPatchMesh(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, ...) {
    RI_VARARGS(vwrap, RiPatchMeshV(type, nu, uwrap, nv, vwrap, vp.n(), vp.t(), vp.v()));
}

RtVoid RiNuPatchV(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax,
                  RtInt nv, RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax,
                  RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiNuPatch")) {
        const long long us = std::max(0, nu - uorder + 1),
                        vs = std::max(0, nv - vorder + 1);
        const long long points = (long long)std::max(0, nu) * std::max(0, nv);
        c->send("NuPatch",
                {integer(nu), integer(uorder), floats(uknot, (long long)nu + uorder),
                 number(umin), number(umax), integer(nv), integer(vorder),
                 floats(vknot, (long long)nv + vorder), number(vmin), number(vmax)},
                {n, tokens, values},
                allOf(us * vs, (us + 1) * (vs + 1), points, (us + 1) * (vs + 1)));
    }
}
RtVoid RiNuPatch(RtInt nu, RtInt uorder, RtFloat uknot[], RtFloat umin, RtFloat umax,
                 RtInt nv, RtInt vorder, RtFloat vknot[], RtFloat vmin, RtFloat vmax,
                 ...) {
    RI_VARARGS(vmax, RiNuPatchV(nu, uorder, uknot, umin, umax, nv, vorder, vknot, vmin,
                                vmax, vp.n(), vp.t(), vp.v()));
}

RtVoid RiTrimCurve(RtInt nloops, RtInt ncurves[], RtInt order[], RtFloat knot[],
                   RtFloat min[], RtFloat max[], RtInt n[], RtFloat u[], RtFloat v[],
                   RtFloat w[]) {
    if (Context* c = Context::current("RiTrimCurve")) {
        const long long curves = total(ncurves, nloops), points = total(n, curves);
        const long long knots = points + total(order, curves);
        c->send("TrimCurve",
                {ints(ncurves, nloops), ints(order, curves), floats(knot, knots),
                 floats(min, curves), floats(max, curves), ints(n, curves),
                 floats(u, points), floats(v, points), floats(w, points)});
    }
}

#define RI_QUADRIC(Fn, Call, Values, ...)                                          \
    RtVoid Ri##Fn##V(__VA_ARGS__, RtInt n, RtToken tokens[], RtPointer values[]) { \
        if (Context* c = Context::current("Ri" #Fn))                               \
            c->send(#Fn, Values, {n, tokens, values}, kQuadric);                   \
    }                                                                              \
    RtVoid Ri##Fn(__VA_ARGS__, ...) {                                              \
        RI_VARARGS(thetamax, Call);                                                \
    }
RI_QUADRIC(Sphere, RiSphereV(radius, zmin, zmax, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(radius), number(zmin), number(zmax), number(thetamax)}),
           RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax)
RI_QUADRIC(Cylinder, RiCylinderV(radius, zmin, zmax, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(radius), number(zmin), number(zmax), number(thetamax)}),
           RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax)
RI_QUADRIC(Paraboloid, RiParaboloidV(rmax, zmin, zmax, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(rmax), number(zmin), number(zmax), number(thetamax)}),
           RtFloat rmax, RtFloat zmin, RtFloat zmax, RtFloat thetamax)
RI_QUADRIC(Cone, RiConeV(height, radius, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(height), number(radius), number(thetamax)}), RtFloat height,
           RtFloat radius, RtFloat thetamax)
RI_QUADRIC(Disk, RiDiskV(height, radius, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(height), number(radius), number(thetamax)}), RtFloat height,
           RtFloat radius, RtFloat thetamax)
RI_QUADRIC(Torus,
           RiTorusV(majorradius, minorradius, phimin, phimax, thetamax, vp.n(), vp.t(),
                    vp.v()),
           (Values{number(majorradius), number(minorradius), number(phimin),
                   number(phimax), number(thetamax)}),
           RtFloat majorradius, RtFloat minorradius, RtFloat phimin, RtFloat phimax,
           RtFloat thetamax)
RI_QUADRIC(Hyperboloid, RiHyperboloidV(point1, point2, thetamax, vp.n(), vp.t(), vp.v()),
           (Values{number(point1[0]), number(point1[1]), number(point1[2]),
                   number(point2[0]), number(point2[1]), number(point2[2]),
                   number(thetamax)}),
           RtPoint point1, RtPoint point2, RtFloat thetamax)
#undef RI_QUADRIC

RtVoid RiPointsV(RtInt npoints, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiPoints"))
        c->send("Points", {}, {n, tokens, values}, allOf(1, npoints, npoints, npoints));
}
RtVoid RiPoints(RtInt npoints, ...) {
    RI_VARARGS(npoints, RiPointsV(npoints, vp.n(), vp.t(), vp.v()));
}

RtVoid RiCurvesV(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, RtInt n,
                 RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiCurves")) {
        const bool cubic = type && std::string(type) == "cubic";
        bool periodic = false;
        const bool wrapped = wrap && rib::wrapMode(wrap, periodic);
        long long varying = 0;
        for (RtInt i = 0; wrapped && nvertices && i < ncurves; ++i) {
            long long spans = 0, var = 0;
            std::string why;
            if (rib::spanCount(cubic, periodic, nvertices[i], c->feed().vstep(), spans,
                               var, why))
                varying += var;
        }
        const long long vertices = total(nvertices, ncurves);
        c->send("Curves", {string(type), ints(nvertices, ncurves), string(wrap)},
                {n, tokens, values}, allOf(ncurves, varying, vertices, varying));
    }
}
RtVoid RiCurves(RtToken type, RtInt ncurves, RtInt nvertices[], RtToken wrap, ...) {
    RI_VARARGS(wrap, RiCurvesV(type, ncurves, nvertices, wrap, vp.n(), vp.t(), vp.v()));
}

RtVoid RiSubdivisionMeshV(RtToken scheme, RtInt nfaces, RtInt nvertices[],
                          RtInt vertices[], RtInt ntags, RtToken tags[], RtInt nargs[],
                          RtInt intargs[], RtFloat floatargs[], RtInt n, RtToken tokens[],
                          RtPointer values[]) {
    if (Context* c = Context::current("RiSubdivisionMesh")) {
        const long long corners = total(nvertices, nfaces),
                        points = pointsOf(vertices, corners);
        long long nints = 0, nfloats = 0;
        for (RtInt i = 0; nargs && i < ntags; ++i)
            nints += std::max(0, nargs[2 * i]), nfloats += std::max(0, nargs[2 * i + 1]);
        c->send("SubdivisionMesh",
                {string(scheme), ints(nvertices, nfaces), ints(vertices, corners),
                 strings(tags, ntags), ints(nargs, 2LL * ntags), ints(intargs, nints),
                 floats(floatargs, nfloats)},
                {n, tokens, values}, allOf(nfaces, points, points, corners));
    }
}
RtVoid RiSubdivisionMesh(RtToken scheme, RtInt nfaces, RtInt nvertices[],
                         RtInt vertices[], RtInt ntags, RtToken tags[], RtInt nargs[],
                         RtInt intargs[], RtFloat floatargs[], ...) {
    RI_VARARGS(floatargs,
               RiSubdivisionMeshV(scheme, nfaces, nvertices, vertices, ntags, tags, nargs,
                                  intargs, floatargs, vp.n(), vp.t(), vp.v()));
}

RtVoid RiBlobbyV(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[],
                 RtInt nstr, RtToken str[], RtInt n, RtToken tokens[],
                 RtPointer values[]) {
    if (Context* c = Context::current("RiBlobby"))
        c->send(
            "Blobby",
            {integer(nleaf), ints(code, ncode), floats(flt, nflt), strings(str, nstr)},
            {n, tokens, values}, allOf(1, nleaf, nleaf, nleaf));
}
RtVoid RiBlobby(RtInt nleaf, RtInt ncode, RtInt code[], RtInt nflt, RtFloat flt[],
                RtInt nstr, RtToken str[], ...) {
    RI_VARARGS(
        str, RiBlobbyV(nleaf, ncode, code, nflt, flt, nstr, str, vp.n(), vp.t(), vp.v()));
}

RtVoid RiGeometryV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]) {
    if (Context* c = Context::current("RiGeometry"))
        c->send("Geometry", {string(type)}, {n, tokens, values});
}
RtVoid RiGeometry(RtToken type, ...) {
    RI_VARARGS(type, RiGeometryV(type, vp.n(), vp.t(), vp.v()));
}

RtVoid RiProcedural(RtPointer data, RtBound bound, RtProcSubdivFunc subdivfunc,
                    RtProcFreeFunc freefunc) {
    if (Context* c = Context::current("RiProcedural")) {
        const char* name = subdivfunc == RiProcDelayedReadArchive ? "DelayedReadArchive"
                           : subdivfunc == RiProcRunProgram       ? "RunProgram"
                           : subdivfunc == RiProcDynamicLoad      ? "DynamicLoad"
                                                                  : nullptr;
        if (!name) {
            c->error(RIE_UNIMPLEMENT,
                     "RiProcedural: only RiProcDelayedReadArchive, "
                     "RiProcRunProgram and RiProcDynamicLoad are supported");
        } else {
            const long long args = name[0] == 'D' && name[1] == 'e' ? 1 : 2;
            c->send("Procedural",
                    {string(name), strings(static_cast<RtString*>(data), args),
                     number(bound[0]), number(bound[1]), number(bound[2]),
                     number(bound[3]), number(bound[4]), number(bound[5])});
        }
    }
    if (freefunc) freefunc(data);  // (its values were copied)
}

}  // extern "C"
