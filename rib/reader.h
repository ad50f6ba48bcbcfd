// reader.h: the entry points of the RIB reader. A reader tokenizes RIB (ASCII, binary
// encoded or both mixed; plain or gzip-compressed), types each request's parameter
// list, checks argument counts, array lengths, valid scopes and Begin/End nesting, and
// calls the matching Target virtual. Problems go to
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
    // Warn about requests that are accepted but not implemented yet.
    bool warnUnsupported = true;
    // The error handler in force when reading starts (RiErrorHandler: print, ignore,
    // abort); an `ErrorHandler` request in the file changes it until the read ends.
    ErrorMode errorHandler = ErrorMode::Print;
    // ReadArchive and inline archives (ArchiveBegin/End) are read by the reader and the
    // target sees their contents. When false the target gets readArchive/archiveBegin/
    // archiveEnd calls instead (what a RIB writer wants).
    bool expandArchives = true;
    // ReadArchive nesting deeper than this is an error (an archive reading itself).
    int maxArchiveDepth = 16;
    // Where ReadArchive looks after the reading file's own directory: ':'-separated
    // directories; `Option "searchpath" "archive"` in the file replaces it ("&" = old).
    std::string archiveSearchPath;
    // Format resolutions above this are refused.
    int maxResolution = 65536;
    // A RunProgram procedural's program must answer within this time and output
    // (run_program.h); past either it is stopped and the procedural is an error.
    double runProgramSeconds = 60;
    size_t runProgramMaxBytes = size_t(1) << 30;
};

// The name messages give the standard input.
inline constexpr const char* kStandardInputName = "stdin";

// Reads a RIB file (gzip-compressed or plain; "-" reads the standard input, named
// "stdin" in messages). Returns true when no errors were reported while reading it.
bool readFile(const std::string& path, Target& target, Diagnostics& diag,
              const ReadOptions& options = ReadOptions());

// Reads RIB text held in memory; `name` is the file name used in messages.
bool readString(const std::string& text, const std::string& name, Target& target,
                Diagnostics& diag, const ReadOptions& options = ReadOptions());

}  // namespace rib
