// fuzz_rib.cpp: libFuzzer entry point for the RIB reader and writer (built only with
// clang: see CMakeLists.txt). Run e.g. `fuzz_rib -max_total_time=60 corpus/`; a crash,
// sanitizer report or round-trip mismatch is a bug.
#include <cstdlib>

#include "fuzz_rib.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (!ribtest::fuzzOne(data, size).roundTripOk) std::abort();
    return 0;
}
