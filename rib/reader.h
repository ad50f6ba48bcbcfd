// reader.h: the entry points of the RIB reader. A reader tokenizes ASCII RIB (plain or
// gzip-compressed), types each request's parameter list, checks argument counts, array
// lengths and Begin/End nesting, and calls the matching Target virtual. Problems go to
// Diagnostics as `file:line: error: ...`; the reader skips the bad request and goes on,
// so one typo does not hide the rest of a scene's errors.
#pragma once
#include <cstddef>
#include <string>

#include "diagnostics.h"
#include "target.h"

namespace rib {

struct ReadOptions {
    // Arrays longer than this are refused with an error instead of being allocated: a
    // corrupt or hostile file must not exhaust memory.
    size_t maxArrayValues = 100000000;
    // Warn about requests that are accepted but not implemented yet (Exposure, Hider...).
    bool warnUnsupported = true;
};

// Reads a RIB file (gzip-compressed or plain). Returns true when no errors were reported
// while reading it.
bool readFile(const std::string& path, Target& target, Diagnostics& diag,
              const ReadOptions& options = ReadOptions());

// Reads RIB text held in memory; `name` is the file name used in messages.
bool readString(const std::string& text, const std::string& name, Target& target,
                Diagnostics& diag, const ReadOptions& options = ReadOptions());

}  // namespace rib
