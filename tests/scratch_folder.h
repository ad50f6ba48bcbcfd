// scratch_folder.h: a test process's scratch folder, TempDir()/name.<pid> (CTest runs two
// test processes at a time: a folder shared by name had one test truncate a file another
// read), removed with everything in it when the process exits, so that a run of the suite
// leaves nothing behind in the temporary folder (it left one folder a test and run).
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <string>

namespace rd::test {

inline std::string scratchFolder(const std::string& name) {
    struct Made {
        std::set<std::string> dirs;
        ~Made() {
            for (const std::string& d : dirs) {
                std::error_code ec;  // (at exit: nothing to report a failure to)
                std::filesystem::remove_all(d, ec);
            }
        }
    };
    static Made made;
    const std::string dir = (std::filesystem::path(::testing::TempDir()) /
                             (name + "." + std::to_string(getpid())))
                                .string();
    std::filesystem::create_directories(dir);
    made.dirs.insert(dir);
    return dir;
}

}  // namespace rd::test
