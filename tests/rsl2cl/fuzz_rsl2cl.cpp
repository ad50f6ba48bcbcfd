// fuzz_rsl2cl.cpp: libFuzzer entry point for the RSL front end and code generator (built
// with clang++, ASan and UBSan, fatal: see CMakeLists.txt). Any input must give
// diagnostics, never a crash, a sanitizer report or a hang. Its first run (session 20)
// found undefined #if arithmetic; deep inputs beyond its size limit are in
// preprocess_test and errors_test.
#include <cstdint>
#include <string>

#include "compiler.h"
#include "emit_cl.h"
#include "info.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > 16384) return 0;  // the size of a shader; deep nesting has its own tests
    const std::string src(reinterpret_cast<const char*>(data), size);
    rsl::Diagnostics diag;
    rsl::Program prog;
    const bool ok = rsl::compileSource(src, "fuzz.sl", {}, prog, diag);
    if (ok) rsl::dumpAst(prog);
    for (const auto& sh : prog.shaders) rsl::formatInfo(rsl::collectInfo(*sh));
    if (!ok) return 0;
    for (const auto& sh : prog.shaders) {  // light coefficients, hoisting, the emitters
        rsl::Diagnostics d;
        rsl::emitOpenCL(*sh, prog, d,
                        1 + int(size % 15));  // any number of colour channels
    }
    return 0;
}
