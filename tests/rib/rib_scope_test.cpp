// rib_scope_test.cpp: where requests may appear (options before WorldBegin, geometry in
// World or an object, lights in World, motion blocks), RiErrorHandler semantics (print,
// ignore, abort; from ReadOptions or an ErrorHandler request), and archives (ReadArchive
// relative to the reading file and along the search path, inline archives, the nesting
// limit).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "../scratch_folder.h"
#include "rib_corpus.h"

namespace {

using ribtest::readRib;
using Lines = std::vector<std::string>;

TEST(RibScope, GeometryNeedsWorldOrObject) {
    ribtest::ReadResult r = readRib(
        "Sphere 1 -1 1 360\nObjectBegin 1 Sphere 1 -1 1 360 ObjectEnd\n"
        "WorldBegin\nSphere 1 -1 1 360\nWorldEnd\nDisk 0 1 360");
    EXPECT_EQ(r.msgs, (Lines{"t.rib:1: error: Sphere outside WorldBegin/WorldEnd",
                             "t.rib:6: error: Disk outside WorldBegin/WorldEnd"}));
    EXPECT_EQ(r.target.calls.size(), 6u);
}

TEST(RibScope, OptionsBeforeWorld) {
    ribtest::ReadResult r = readRib(
        "WorldBegin\nFormat 10 10 1\nProjection \"perspective\"\nMakeShadow \"a\" \"b\"\n"
        "ObjectBegin 1\nHider \"hidden\"\nLightSource \"l\" 1\nObjectEnd\nWorldEnd\n"
        "LightSource \"l\" 2");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:2: error: Format is an option: not allowed inside "
                     "WorldBegin/WorldEnd",
                     "t.rib:3: error: Projection is an option: not allowed inside "
                     "WorldBegin/WorldEnd",
                     "t.rib:4: error: MakeShadow is not allowed inside WorldBegin/WorldEnd",
                     "t.rib:6: error: Hider is an option: not allowed inside "
                     "ObjectBegin/ObjectEnd",
                     "t.rib:7: error: LightSource is not allowed inside ObjectBegin/ObjectEnd"}));
    // (a light after the world, before the next, is the next world's, in camera space:
    // no error; Render.LightBeforeWorldBeginIsInCameraSpace renders one)
}

// Deep nesting is read in linear time: which blocks are open is counted, not looked up
// along the stack for every request (300k nested AttributeBegin took minutes; now well
// under a second). CTest's timeout for this executable (tests/rib/CMakeLists.txt) is the
// guard.
TEST(RibScope, DeepNestingReadsInLinearTime) {
    const int n = 300000;
    std::string rib = "WorldBegin\n";
    for (int i = 0; i < n; ++i) rib += "AttributeBegin\n";
    rib += "Sphere 1 -1 1 360\n";
    for (int i = 0; i < n; ++i) rib += "AttributeEnd\n";
    rib += "WorldEnd\n";
    ribtest::ReadResult r = readRib(rib);
    EXPECT_TRUE(r.msgs.empty());
    EXPECT_EQ(r.target.calls.size(), size_t(2 * n + 3));
    // the counts follow the stack: an unmatched end is still reported after all of it
    r = readRib(rib + "AttributeEnd\n");
    EXPECT_EQ(r.msgs, (Lines{"t.rib:" + std::to_string(2 * n + 4) +
                             ": error: AttributeEnd without AttributeBegin"}));
}

TEST(RibScope, BlockNesting) {
    ribtest::ReadResult r = readRib(
        "WorldBegin\nFrameBegin 1\nWorldBegin\nObjectBegin 1\nObjectBegin 2\nObjectEnd\n"
        "SolidBegin \"merge\"\nSolidBegin \"primitive\"\nSolidBegin \"union\"\nSolidEnd\n"
        "ObjectInstance 9\nWorldEnd");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:2: error: FrameBegin is not allowed inside WorldBegin",
                     "t.rib:3: error: WorldBegin is not allowed inside WorldBegin",
                     "t.rib:5: error: ObjectBegin is not allowed inside ObjectBegin",
                     "t.rib:7: error: SolidBegin: unknown operation \"merge\" (primitive, "
                     "union, intersection, difference)",
                     "t.rib:9: error: SolidBegin inside a primitive solid (at t.rib:8)",
                     "t.rib:11: error: ObjectInstance of undefined object \"9\""}));
}

TEST(RibScope, MotionBlocks) {
    ribtest::ReadResult ok = readRib(
        "MotionBegin [0 1] Translate 0 0 0 Translate 1 0 0 MotionEnd\n"
        "WorldBegin MotionBegin [0 1] Sphere 1 -1 1 360 Sphere 2 -2 2 360 MotionEnd "
        "WorldEnd");
    EXPECT_EQ(ok.msgs, Lines{});
    EXPECT_EQ(ok.target.calls.front(), "motionBegin [ 0 1 ]");
    ribtest::ReadResult r = readRib(
        "MotionBegin [0 1]\nTranslate 0 0 0\nRotate 1 0 0 1\nMotionEnd\n"
        "MotionBegin [0 1]\nSides 1\nScale 1 1 1\nMotionEnd\n"
        "MotionBegin [1 0]\nMotionBegin [0 1]\nMotionBegin [0 1]\nMotionEnd\n"
        "MotionBegin [0 0.5 1]\nTranslate 1 0 0\nTranslate 1 0 0\nTranslate 1 0 0\n"
        "Translate 1 0 0\nMotionEnd");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:3: error: MotionBegin at t.rib:1 mixes Translate and Rotate",
                     "t.rib:4: error: MotionBegin at t.rib:1 has 2 times but 1 request",
                     "t.rib:6: error: Sides is not allowed inside MotionBegin/MotionEnd",
                     "t.rib:8: error: MotionBegin at t.rib:5 has 2 times but 1 request",
                     "t.rib:9: error: MotionBegin times must not decrease",
                     "t.rib:11: error: MotionBegin is not allowed inside "
                     "MotionBegin/MotionEnd",
                     "t.rib:12: error: MotionBegin at t.rib:10 has 2 times but 0 requests",
                     "t.rib:17: error: MotionBegin at t.rib:13 has 3 times but more "
                     "requests"}));
}

TEST(RibErrorHandler, IgnoreAndAbortFromOptions) {
    const char* text = "Bogus 1\nSides 1\nSides 7\nSides 2";
    rib::ReadOptions opts;
    opts.errorHandler = rib::ErrorMode::Ignore;
    ribtest::RecordingTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    EXPECT_TRUE(rib::readString(text, "t.rib", t, diag, opts));
    EXPECT_EQ(out.str(), "");
    EXPECT_EQ(diag.ignoredCount(), 2);
    EXPECT_EQ(t.calls, (Lines{"sides 1", "sides 2"}));  // bad requests still skipped
    EXPECT_EQ(diag.mode(), rib::ErrorMode::Print);       // restored after the read

    opts.errorHandler = rib::ErrorMode::Abort;
    ribtest::ReadResult r = readRib("Sides 1\nBogus 1\nSides 2\nBogus", opts);
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.msgs, Lines{"t.rib:2: error: unknown request \"Bogus\""});
    EXPECT_EQ(r.target.calls, Lines{"sides 1"});
}

TEST(RibErrorHandler, ErrorHandlerRequest) {
    ribtest::ReadResult r = readRib(
        "ErrorHandler \"ignore\"\nBogus\nErrorHandler \"print\"\nBogus2\n"
        "ErrorHandler \"explode\"\nErrorHandler \"abort\"\nBogus3\nSides 1");
    EXPECT_EQ(r.msgs, (Lines{"t.rib:4: error: unknown request \"Bogus2\"",
                             "t.rib:5: error: ErrorHandler: unknown handler \"explode\" "
                             "(print, ignore, abort)",
                             "t.rib:7: error: unknown request \"Bogus3\""}));
    EXPECT_EQ(r.target.calls, (Lines{"errorHandler \"ignore\"", "errorHandler \"print\"",
                                     "errorHandler \"abort\""}));
}

std::string tempDir() {
    // (one per test process: CTest runs two at a time)
    std::string d = rd::test::scratchFolder("rib_scope_test");
    mkdir((d + "/sub").c_str(), 0755);
    mkdir((d + "/lib").c_str(), 0755);
    return d;
}

void writeFile(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
}

TEST(RibArchive, ReadArchiveRelativeAndSearchPath) {
    std::string d = tempDir();
    writeFile(d + "/sub/a.rib", "Sides 1\nReadArchive \"b.rib\"\n");  // next to a.rib
    writeFile(d + "/sub/b.rib", "Sides 2\n");
    writeFile(d + "/lib/c.rib", "Sides 2\n");
    writeFile(d + "/main.rib",
              "ReadArchive \"sub/a.rib\"\nOption \"searchpath\" \"archive\" [\"" + d +
                  "/lib:&\"]\nReadArchive \"c.rib\"\nReadArchive \"nope.rib\"\nSides 1\n");
    ribtest::RecordingTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    EXPECT_FALSE(rib::readFile(d + "/main.rib", t, diag));
    EXPECT_EQ(out.str(), d + "/main.rib:4: error: ReadArchive: cannot open \"nope.rib\" "
                             "(not found)\n");
    ASSERT_EQ(t.calls.size(), 5u);
    EXPECT_EQ(t.calls[0], "sides 1");
    EXPECT_EQ(t.files[0], d + "/sub/a.rib");
    EXPECT_EQ(t.calls[1], "sides 2");
    EXPECT_EQ(t.files[1], d + "/sub/b.rib");
    EXPECT_EQ(t.calls[3], "sides 2");
    EXPECT_EQ(t.calls[4], "sides 1");
    EXPECT_EQ(t.lines[4], 5);
    EXPECT_EQ(t.files[4], d + "/main.rib");
}

TEST(RibArchive, RecursionIsLimited) {
    std::string d = tempDir();
    writeFile(d + "/self.rib", "Sides 1\nReadArchive \"self.rib\"\n");
    ribtest::RecordingTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    rib::ReadOptions opts;
    opts.maxArchiveDepth = 3;
    EXPECT_FALSE(rib::readFile(d + "/self.rib", t, diag, opts));
    EXPECT_EQ(t.calls.size(), 4u);
    EXPECT_EQ(out.str(), d + "/self.rib:2: error: ReadArchive \"self.rib\": archives nested "
                             "more than 3 deep (does an archive read itself?)\n");
}

TEST(RibArchive, InlineArchivesAndNoExpansion) {
    const char* text =
        "ArchiveBegin \"a\"\nSides 1\nArchiveBegin \"b\" Sides 2 ArchiveEnd\nArchiveEnd\n"
        "ReadArchive \"a\"\nReadArchive \"b\"\nReadArchive \"a\"";
    ribtest::ReadResult r = readRib(text);
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(r.target.calls, (Lines{"sides 1", "sides 2", "sides 1"}));
    EXPECT_EQ(r.target.lines, (std::vector<int>{2, 3, 2}));
    rib::ReadOptions opts;
    opts.expandArchives = false;
    r = readRib(text, opts);
    EXPECT_EQ(r.target.calls,
              (Lines{"archiveBegin \"a\" { }", "sides 1", "archiveBegin \"b\" { }", "sides 2",
                     "archiveEnd", "archiveEnd", "readArchive \"a\" { }",
                     "readArchive \"b\" { }", "readArchive \"a\" { }"}));
    r = readRib("ArchiveBegin \"x\" Sides 1");
    EXPECT_EQ(r.msgs, Lines{"t.rib:1: error: ArchiveBegin \"x\" never closed"});
}

}  // namespace
