// program_cache_test.cpp: program binaries are cached on disk keyed by source, options and
// device; a changed option misses; a broken source reports the compiler's build log.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdlib>
#include <unistd.h>

#include "ocl/program.h"
#include "render/render_programs.h"
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

// PoCL caches its builds itself; asking it for a binary costs a second compile of every
// kernel (SPD teapot cold: 10.4 s against 4.1 s), so there RayDrive keeps a stamp that
// counts the builds, and the binary (which loads faster than PoCL's cached build) only
// from the kBinaryAfterBuilds-th build of the same program on. With PoCL's cache off
// (POCL_KERNEL_CACHE=0), or on another driver, it keeps the binary from the first.
TEST(ProgramCache, OnPoclTheDriversCacheHoldsTheBuild) {
    const ClContext& ctx = test::testContext();
    if (!ctx.info().isPocl()) GTEST_SKIP() << "not a PoCL device";
    std::string dir = freshDir("stamp");
    {
        Program first(ctx, kSource, "-DONE=3", dir);
        EXPECT_TRUE(first.info().driverCache);
        EXPECT_FALSE(first.info().cacheHit);
        ASSERT_TRUE(std::filesystem::exists(first.info().cacheFile));
        EXPECT_EQ(std::filesystem::path(first.info().cacheFile).extension(), ".pocl");
        EXPECT_LT(std::filesystem::file_size(first.info().cacheFile), 100u) << "a stamp";
        for (int b = 2; b < kBinaryAfterBuilds; ++b) {
            Program again(ctx, kSource, "-DONE=3", dir);
            EXPECT_TRUE(again.info().cacheHit);
            EXPECT_EQ(std::filesystem::path(again.info().cacheFile).extension(), ".pocl");
        }
        Program last(ctx, kSource, "-DONE=3", dir);  // the binary is kept from this build
        EXPECT_EQ(std::filesystem::path(last.info().cacheFile).extension(), ".clbin");
        EXPECT_GT(std::filesystem::file_size(last.info().cacheFile), 100u);
        Program fromBinary(ctx, kSource, "-DONE=3", dir);
        EXPECT_TRUE(fromBinary.info().cacheHit);
        EXPECT_EQ(fromBinary.info().cacheFile, last.info().cacheFile);
    }
    ::setenv("POCL_KERNEL_CACHE", "0", 1);
    Program own(ctx, kSource, "-DONE=4", dir);
    ::unsetenv("POCL_KERNEL_CACHE");
    EXPECT_FALSE(own.info().driverCache);
    EXPECT_FALSE(own.info().cacheHit);
    EXPECT_EQ(std::filesystem::path(own.info().cacheFile).extension(), ".clbin");
    EXPECT_GT(std::filesystem::file_size(own.info().cacheFile), 100u);
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

// The trace program is built with the -D options its source names only (as whole
// words), and keeps every other option: scenes that differ in what only shading reads
// share it.
TEST(ProgramCache, OptionsUsedByKeepWhatTheSourceReads) {
    const std::string source = "#ifdef RT_A\nint x = RT_AB;\n#endif\n";
    EXPECT_EQ(optionsUsedBy(source, "-cl-std=CL1.2 -DRT_A -DRT_B=3 -DRT_AB=1 -DRT_ABC -DRT"),
              "-cl-std=CL1.2 -DRT_A -DRT_AB=1");
    EXPECT_EQ(optionsUsedBy(source, ""), "");
}

// A render builds two programs: the trace stages' and the shading's. An edit of the
// shader's code (another shader, the same scene) builds a new shading program and finds
// the trace program in the cache (same key, a hit); the image is the new shader's.
TEST(ProgramCache, AShaderEditRebuildsTheShadingAlone) {
    const std::string dir = freshDir("shader-edit");
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/edit_a.sl") << "surface edit_a() { Oi = 1; Ci = 0.25; }\n";
    std::ofstream(dir + "/edit_b.sl") << "surface edit_b() { Oi = 1; Ci = 0.75; }\n";
    auto scene = [&](const char* shader) {
        return "Option \"searchpath\" \"shader\" [\"" + dir +
               ":&\"]\nFormat 8 8 1\nProjection \"orthographic\"\nWorldBegin\nSurface \"" +
               shader + "\"\nPolygon \"P\" [-2 -2 1  2 -2 1  2 2 1  -2 2 1]\nWorldEnd\n";
    };
    test::Rendered a = test::renderRib(scene("edit_a")), b = test::renderRib(scene("edit_b"));
    EXPECT_EQ(a.stats.traceProgram.cacheKey, b.stats.traceProgram.cacheKey);
    EXPECT_TRUE(b.stats.traceProgram.cacheHit);
    EXPECT_NE(a.stats.shadeProgram.cacheKey, b.stats.shadeProgram.cacheKey);
    EXPECT_FLOAT_EQ(a.at(4, 4).r, 0.25f);
    EXPECT_FLOAT_EQ(b.at(4, 4).r, 0.75f);
    // each program's options are among the scene's, the trace program's fewer
    for (const std::string* o : {&b.stats.traceProgram.options, &b.stats.shadeProgram.options}) {
        std::istringstream in(*o);
        for (std::string opt; in >> opt;)
            EXPECT_NE(b.stats.program.options.find(opt), std::string::npos) << opt;
    }
    EXPECT_LT(b.stats.traceProgram.options.size(), b.stats.program.options.size());
    std::filesystem::remove_all(dir);
}
