// replace_file.h: a file written under a temporary name beside it and renamed into place,
// so an interrupted or failed write never leaves a file that looks complete (images of
// every format: exr_output.cpp, frame_output.cpp).
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace rd {

// Calls write(temporary) with a name beside `path` (its stem, ".partial-<pid>", its
// extension, which an image library may read the format from), then renames it to
// `path`; on failure removes it and rethrows.
template <typename F>
void writeReplacing(const std::string& path, F&& write) {
    const std::filesystem::path p(path);
    const std::string tmp =
        (p.parent_path() / (p.stem().string() + ".partial-" + std::to_string(::getpid()) +
                            p.extension().string()))
            .string();
    try {
        write(tmp);
        std::filesystem::rename(tmp, path);
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    }
}

}  // namespace rd
