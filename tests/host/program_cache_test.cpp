// program_cache_test.cpp: program binaries are cached on disk keyed by source, options and
// device; a changed option misses; a broken source reports the compiler's build log.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "ocl/program.h"
#include "render_harness.h"

using namespace rd;

namespace {
std::string freshDir(const char* name) {
    auto dir = std::filesystem::temp_directory_path() /
               (std::string("raydrive-") + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    return dir.string();
}
const char* kSource = "__kernel void add_one(__global int* x) { x[get_global_id(0)] += ONE; }";
}  // namespace

TEST(ProgramCache, SecondBuildIsACacheHit) {
    std::string dir = freshDir("cache");
    const ClContext& ctx = test::testContext();
    Program first(ctx, kSource, "-DONE=1", dir);
    EXPECT_FALSE(first.info().cacheHit);
    EXPECT_TRUE(std::filesystem::exists(first.info().cacheFile));
    Program second(ctx, kSource, "-DONE=1", dir);
    EXPECT_TRUE(second.info().cacheHit);
    EXPECT_EQ(first.info().cacheKey, second.info().cacheKey);
    Program other(ctx, kSource, "-DONE=2", dir);
    EXPECT_FALSE(other.info().cacheHit) << "options are part of the key";
    std::filesystem::remove_all(dir);
}

TEST(ProgramCache, CorruptCacheFileIsRebuilt) {
    std::string dir = freshDir("corrupt");
    const ClContext& ctx = test::testContext();
    std::string file;
    {
        Program p(ctx, kSource, "-DONE=1", dir);
        file = p.info().cacheFile;
    }
    { std::ofstream(file, std::ios::binary) << "garbage"; }
    Program again(ctx, kSource, "-DONE=1", dir);
    EXPECT_FALSE(again.info().cacheHit);
    std::filesystem::remove_all(dir);
}

TEST(ProgramCache, BuildFailureShowsTheLog) {
    const ClContext& ctx = test::testContext();
    try {
        Program p(ctx, "__kernel void broken(__global int* x) { x[0] = undeclared_name; }", "",
                  "");
        FAIL() << "expected a build failure";
    } catch (const std::runtime_error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("build failed"), std::string::npos) << msg;
        EXPECT_NE(msg.find("undeclared_name"), std::string::npos) << msg;
    }
}

TEST(ProgramCache, IncludesAreResolvedOnce) {
    std::string src = assembleClSource({"intersect.cl", "sort_by_shader.cl"});
    EXPECT_EQ(src.find("#include \""), std::string::npos);
    size_t first = src.find("typedef struct BvhNode");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(src.find("typedef struct BvhNode", first + 1), std::string::npos);
    EXPECT_THROW(assembleClSource({"no_such_file.cl"}), std::runtime_error);
}
