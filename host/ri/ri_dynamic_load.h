// ri_dynamic_load.h: DynamicLoad procedurals (RI 3.2 section 5.7) for programs that link
// the Ri library, raydrive among them: the shared object's ConvertParameters, Subdivide
// and Free run in this process, its Ri calls are written as RIB into memory, and the RIB
// reader reads that RIB in place of the procedural (rib/run_program.h).
#pragma once
#include <string>

namespace rd::ri {

// rib::DynamicLoader: loads `dso`, runs ConvertParameters(data), Subdivide(blind, detail)
// and Free(blind) with the calls captured in *rib. False, with *why, when the object
// cannot be loaded or lacks one of the three functions.
bool dynamicLoad(const std::string& dso, const std::string& data, float detail,
                 std::string* rib, std::string* why);

// Makes the RIB reader run DynamicLoad procedurals through dynamicLoad.
void enableDynamicLoad();

}  // namespace rd::ri
