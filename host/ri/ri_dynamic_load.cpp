// ri_dynamic_load.cpp: a DynamicLoad object run in this process, its Ri calls captured.
// The object resolves Ri* against the program that loads it: raydrive exports them
// (ENABLE_EXPORTS, the Ri library linked whole).
#include "ri_dynamic_load.h"

#include <dlfcn.h>

#include "ri.h"
#include "ri_context.h"
#include "rib/run_program.h"

namespace rd::ri {

bool dynamicLoad(const std::string& dso, const std::string& data, float detail,
                 std::string* rib, std::string* why) {
    void* lib = dlopen(dso.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        const char* e = dlerror();
        *why = std::string("cannot load it: ") + (e ? e : "unknown error");
        return false;
    }
    using Convert = RtPointer (*)(RtString);
    using Subdivide = RtVoid (*)(RtPointer, RtFloat);
    using Free = RtVoid (*)(RtPointer);
    auto convert = reinterpret_cast<Convert>(dlsym(lib, "ConvertParameters"));
    auto subdivide = reinterpret_cast<Subdivide>(dlsym(lib, "Subdivide"));
    auto release = reinterpret_cast<Free>(dlsym(lib, "Free"));
    if (!convert || !subdivide || !release) {
        *why = "it lacks ConvertParameters, Subdivide or Free";
        dlclose(lib);
        return false;
    }
    Context::beginCapture();
    std::string text(data);  // (ConvertParameters takes a char*)
    RtPointer blind = convert(text.data());
    subdivide(blind, detail);
    release(blind);
    *rib = Context::endCapture();
    dlclose(lib);
    return true;
}

void enableDynamicLoad() {
    rib::setDynamicLoader(&dynamicLoad);
}

}  // namespace rd::ri
