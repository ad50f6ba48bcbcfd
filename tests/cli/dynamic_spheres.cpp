// dynamic_spheres.cpp: a DynamicLoad procedural for the command-line tests (RI 3.2
// section 5.7). Its data is "PATH DEPTH": Subdivide makes a sphere and, while DEPTH > 0,
// a DynamicLoad procedural of itself with DEPTH - 1 one unit along x, so DEPTH 2 gives
// three spheres in a row through two levels of procedurals.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ri.h"

namespace {
struct Blind {
    std::string path;
    int depth = 0;
};
}  // namespace

extern "C" {

RtPointer ConvertParameters(RtString data) {
    auto* b = new Blind;
    char path[1024] = {0};
    if (std::sscanf(data, "%1023s %d", path, &b->depth) != 2) b->depth = 0;
    b->path = path;
    return b;
}

RtVoid Subdivide(RtPointer blind, RtFloat) {
    const Blind* b = static_cast<const Blind*>(blind);
    RiAttributeBegin();
    RiSphere(0.4f, -0.4f, 0.4f, 360.0f, RI_NULL);
    RiAttributeEnd();
    if (b->depth <= 0) return;
    const std::string next = b->path + " " + std::to_string(b->depth - 1);
    RtString* args = static_cast<RtString*>(std::malloc(2 * sizeof(RtString)));
    args[0] = const_cast<char*>(b->path.c_str());  // (RiProcedural copies them at once)
    args[1] = const_cast<char*>(next.c_str());
    RtBound bound = {0.5f, 10.0f, -1.0f, 1.0f, -1.0f, 1.0f};
    RiTransformBegin();
    RiTranslate(1.0f, 0.0f, 0.0f);
    RiProcedural(args, bound, RiProcDynamicLoad, RiProcFree);
    RiTransformEnd();
}

RtVoid Free(RtPointer blind) {
    delete static_cast<Blind*>(blind);
}
}
