// fuzz_rib.h: the body of the RIB fuzz target, shared by the libFuzzer entry point
// (fuzz_rib.cpp, clang only) and the replay test run by every build. One input is read
// into a RibWriter and into a RecordingTarget; the writer's output must then read back
// without errors into exactly the same calls. Archives are not expanded, so no input
// can make the reader open files.
#pragma once
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "recording_target.h"
#include "rib/reader.h"
#include "rib/writer.h"

namespace ribtest {

struct FuzzOutcome {
    bool roundTripOk = true;
    std::string detail;
};

inline FuzzOutcome fuzzOne(const uint8_t* data, size_t size) {
    const std::string input(reinterpret_cast<const char*>(data), size);
    rib::ReadOptions opts;
    opts.expandArchives = false;
    opts.maxArrayValues = 1 << 20;
    std::ostringstream written;
    {
        rib::RibWriter writer(written);
        rib::Diagnostics diag(nullptr, 100);
        rib::readString(input, "fuzz.rib", writer, diag, opts);
    }
    RecordingTarget first, second;
    rib::Diagnostics diag1(nullptr, 100);
    rib::readString(input, "fuzz.rib", first, diag1, opts);
    std::ostringstream msgs;
    rib::Diagnostics diag2(&msgs, 100);
    rib::readString(written.str(), "written.rib", second, diag2, opts);
    FuzzOutcome out;
    if (first.calls != second.calls) {
        out.roundTripOk = false;
        size_t i = 0;
        while (i < first.calls.size() && i < second.calls.size() &&
               first.calls[i] == second.calls[i])
            ++i;
        out.detail = "call " + std::to_string(i) + ": " +
                     (i < first.calls.size() ? first.calls[i] : "(none)") + " vs " +
                     (i < second.calls.size() ? second.calls[i] : "(none)") + "\n" +
                     msgs.str();
    }
    return out;
}

}  // namespace ribtest
