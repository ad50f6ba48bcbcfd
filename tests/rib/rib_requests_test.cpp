// rib_requests_test.cpp: the RI 3.2 requests added to the reader: their argument forms
// (named filters and bases, the bare DepthOfField, ColorSamples-sized colors, optional
// SubdivisionMesh tags) and the array-length rules checked before a primitive is
// forwarded (each violation is a file:line error and the request is skipped).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "rib_corpus.h"

namespace {

using Lines = std::vector<std::string>;

// Reads `text` inside WorldBegin/WorldEnd on the same line; returns calls minus those two.
ribtest::ReadResult world(const std::string& text) {
    ribtest::ReadResult r = ribtest::readRib("WorldBegin " + text + "\nWorldEnd");
    if (!r.target.calls.empty()) r.target.calls.erase(r.target.calls.begin());
    if (!r.target.calls.empty()) r.target.calls.pop_back();
    return r;
}

TEST(RibNewRequests, OptionForms) {
    ribtest::ReadResult r = ribtest::readRib(
        "PixelFilter \"sinc\" 4 4 DepthOfField DepthOfField [8 0.05 3] Shutter [0 0.5] "
        "Exposure 1.5 2.2 Quantize \"z\" 0 0 0 0 CropWindow 0.25 0.75 0 1 "
        "ColorSamples [1 1 1 0 0 0] [0.5 0 0.5 0 0.5 0] Color 0.5 0.25 Opacity [1 1]");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(r.target.calls,
              (Lines{"pixelFilter \"sinc\" 4 4", "depthOfField inf 0 0",
                     "depthOfField 8 0.0500000007 3", "shutter 0 0.5", "exposure 1.5 2.20000005",
                     "quantize \"z\" 0 0 0 0", "cropWindow 0.25 0.75 0 1",
                     "colorSamples [ 1 1 1 0 0 0 ] [ 0.5 0 0.5 0 0.5 0 ]", "color [ 0.5 0.25 ]",
                     "opacity [ 1 1 ]"}));
    r = ribtest::readRib("Color 1 0 0 0\nColorSamples [1 1 1] [1 1]\nColor [1 2]");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: Color expects 3 numbers (ColorSamples), got 4",
                     "t.rib:2: error: ColorSamples needs two arrays of 3n numbers (nRGB, "
                     "RGBn), got 3 and 2",
                     "t.rib:3: error: Color expects 3 numbers (ColorSamples), got 2"}));
    r = ribtest::readRib("Format 1000000 1000000 1\nFormat 0 10 1");
    EXPECT_EQ(r.msgs.size(), 2u);
    EXPECT_EQ(r.msgs[0], "t.rib:1: error: Format 1000000x1000000 is out of range (1..65536 "
                         "pixels, positive pixel aspect or -1)");
    EXPECT_TRUE(ribtest::readRib("Format 256 192 -1").msgs.empty());  // (-1: the default)
}

TEST(RibNewRequests, BasisByNameOrMatrix) {
    ribtest::ReadResult r = ribtest::readRib(
        "Basis \"bezier\" 3 [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] 4\nBasis \"nurbs\" 1 \"power\" 4");
    ASSERT_EQ(r.target.calls.size(), 1u);
    EXPECT_EQ(r.target.calls[0],
              "basis \"bezier\" [ -1 3 -3 1 3 -6 3 0 -3 3 0 0 1 0 0 0 ] 3 \"\" "
              "[ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ] 4");
    EXPECT_EQ(r.msgs, Lines{"t.rib:2: error: Basis: unknown basis \"nurbs\" (bezier, b-spline, "
                            "catmull-rom, hermite, power)"});
}

TEST(RibNewRequests, QuadricsAndProcedurals) {
    ribtest::ReadResult r = world(
        "Cylinder [1 -1 1 360] Cone 2 1 90 Disk 0.5 1 360 Torus 1 .2 0 360 180 "
        "Paraboloid 1 0 2 360 Hyperboloid 1 0 0 0 1 1 360");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(r.target.calls,
              (Lines{"cylinder 1 -1 1 360 { }", "cone 2 1 90 { }", "disk 0.5 1 360 { }",
                     "torus 1 0.200000003 0 360 180 { }", "paraboloid 1 0 2 360 { }",
                     "hyperboloid [ 1 0 0 ] [ 0 1 1 ] 360 { }"}));
    // Not expanding (what a RIB writer wants): the procedural reaches the target.
    rib::ReadOptions keep;
    keep.expandArchives = false;
    ribtest::ReadResult p = ribtest::readRib(
        "WorldBegin Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1 -1 1]\nWorldEnd",
        keep);
    EXPECT_EQ(p.msgs, Lines{});
    ASSERT_EQ(p.target.calls.size(), 3u);
    EXPECT_EQ(p.target.calls[1],
              "procedural \"DelayedReadArchive\" [ \"a.rib\" ] [ -1 1 -1 1 -1 1 ]");
}

// DelayedReadArchive and RunProgram are expanded in place, inside an attribute block.
TEST(RibNewRequests, ProceduralsAreExpanded) {
    std::string dir = ::testing::TempDir();
    {
        std::ofstream(dir + "/delayed.rib") << "Sphere 1 -1 1 360\n";
        std::ofstream prog(dir + "/prog.sh");
        prog << "#!/bin/sh\nread detail data\nprintf \"Disk 0 $data 360\\n\\377\"\n";
    }
    std::string run = "sh " + dir + "/prog.sh";
    ribtest::ReadResult r = world(
        "Procedural \"DelayedReadArchive\" [\"" + dir + "/delayed.rib\"] [-1 1 -1 1 -1 1] "
        "Procedural \"RunProgram\" [\"" + run + "\" \"2.5\"] [-1 1 -1 1 -1 1]");
    EXPECT_EQ(r.msgs, Lines{});
    EXPECT_EQ(r.target.calls, (Lines{"attributeBegin", "sphere 1 -1 1 360 { }", "attributeEnd",
                                     "attributeBegin", "disk 0 2.5 360 { }", "attributeEnd"}));
}

// A RunProgram program that misbehaves is a file:line error, never a hung or exhausted
// reader: one that never answers is stopped at the time limit (0.5 s here, the read
// over within 5 s), one that writes without end at the output limit (1 MiB here), one
// that fails reports its exit status. One that ends well without the 0377 byte answered
// with all it wrote.
TEST(RibNewRequests, RunProgramIsBoundedInTimeAndOutput) {
    rib::ReadOptions opts;
    opts.runProgramSeconds = 0.5;
    opts.runProgramMaxBytes = size_t(1) << 20;
    auto run = [&](const std::string& program) {
        return ribtest::readRib("WorldBegin\nProcedural \"RunProgram\" [\"" + program +
                                    "\" \"x\"] [-1 1 -1 1 -1 1]\nWorldEnd",
                                opts);
    };
    const auto t0 = std::chrono::steady_clock::now();
    ribtest::ReadResult hang = run("sleep 30");
    EXPECT_LT(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
        5.0);
    EXPECT_EQ(
        hang.msgs,
        Lines{
            "t.rib:2: error: RunProgram \"sleep 30\": no answer within 0.5 s (stopped)"});
    ribtest::ReadResult flood = run("yes Sphere");
    EXPECT_EQ(flood.msgs, Lines{"t.rib:2: error: RunProgram \"yes Sphere\": more than "
                                "1048576 bytes of output (stopped)"});
    ribtest::ReadResult failed = run("exit 3");
    EXPECT_EQ(failed.msgs,
              Lines{"t.rib:2: error: RunProgram \"exit 3\": failed (exit status 3)"});
    ribtest::ReadResult plain = run("echo Sphere 1 -1 1 360");
    EXPECT_EQ(plain.msgs, Lines{});
    EXPECT_EQ(plain.target.calls,
              (Lines{"worldBegin", "attributeBegin", "sphere 1 -1 1 360 { }",
                     "attributeEnd", "worldEnd"}));
}

TEST(RibNewRequests, PolygonFamilyChecks) {
    ribtest::ReadResult r = world(
        "GeneralPolygon [3 2] \"P\" [0 0 0 1 0 0 1 1 0 0 0 0 1 1 1]\n"
        "GeneralPolygon [4] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "PointsGeneralPolygons [2] [3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "PointsGeneralPolygons [1] [3] [0 1 5] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"varying float q\" [1 2]");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: GeneralPolygon loop with 2 vertices (needs at least 3)",
                     "t.rib:2: error: GeneralPolygon nverts add up to 4 but \"P\" has 3 points",
                     "t.rib:3: error: PointsGeneralPolygons nloops add up to 2 but nverts has "
                     "1 entries",
                     "t.rib:4: error: PointsGeneralPolygons vertex index 5 out of range (3)",
                     "t.rib:5: error: Polygon: varying \"q\" has 2 values, needs 3"}));
    EXPECT_EQ(r.target.calls, Lines{});
}

TEST(RibNewRequests, PatchChecks) {
    std::string p16 = "\"P\" [";
    for (int i = 0; i < 48; ++i) p16 += " 0";
    p16 += "]";
    ribtest::ReadResult r = world(
        "Patch \"bicubic\" \"P\" [0 0 0 1 0 0 0 1 0 1 1 0]\n"
        "Patch \"trilinear\" \"P\" [0 0 0]\n"
        "PatchMesh \"bilinear\" 3 \"nonperiodic\" 3 \"nonperiodic\" \"P\" [0 0 0 1 0 0]\n"
        "PatchMesh \"bicubic\" 5 \"nonperiodic\" 4 \"nonperiodic\" " + p16 + "\n"
        "PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"sometimes\" " + p16 + "\n"
        "PatchMesh \"bicubic\" 4 \"periodic\" 4 \"nonperiodic\" " + p16 + "\n"
        "Basis \"b-spline\" 1 \"b-spline\" 1 PatchMesh \"bicubic\" 4 \"periodic\" 4 "
        "\"nonperiodic\" " + p16);
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: Patch \"bicubic\" needs 16 points, got 4",
                     "t.rib:2: error: Patch: unknown type \"trilinear\" (bilinear, bicubic)",
                     "t.rib:3: error: PatchMesh has 2 points but nu*nv = 9",
                     "t.rib:4: error: PatchMesh nu = 5: nonperiodic cubic needs 4 + k*3 vertices",
                     "t.rib:5: error: PatchMesh: wrap modes must be \"periodic\" or "
                     "\"nonperiodic\"",
                     "t.rib:6: error: PatchMesh nu = 4: periodic cubic needs a positive "
                     "multiple of the basis step (3) vertices"}));
    ASSERT_EQ(r.target.calls.size(), 2u);  // basis, and the b-spline periodic mesh
}

TEST(RibNewRequests, NuPatchAndTrimCurveChecks) {
    ribtest::ReadResult r = world(
        "NuPatch 2 2 [0 0 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1 1 0 0 1 0 1 0 1 1 1 0 1]\n"
        "NuPatch 2 3 [0 0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1]\n"
        "NuPatch 2 2 [0 1 0 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1]\n"
        "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"Pw\" [0 0 0 1]\n"
        "TrimCurve [1] [2] [0 0 1] [0] [1] [2] [0 1] [0 1] [1 1]\n"
        "TrimCurve [2] [2] [0 0 1 1] [0] [1] [2] [0 1] [0 1] [1 1]\n"
        "TrimCurve [1] [2] [0 0 1 1] [0] [1] [2] [0 1] [0] [1 1]");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: NuPatch uknot has 3 values, needs nu + uorder = 4",
                     "t.rib:2: error: NuPatch nu = 2 must be at least uorder = 3 (>= 1)",
                     "t.rib:3: error: NuPatch uknot decreases at 2",
                     "t.rib:4: error: NuPatch has 1 point but nu*nv = 4",
                     "t.rib:5: error: TrimCurve knot has 3 values, needs sum(n + order) = 4",
                     "t.rib:6: error: TrimCurve: order, n, min and max need one value per "
                     "curve (2)",
                     "t.rib:7: error: TrimCurve v has 1 values, needs sum(n) = 2"}));
}

TEST(RibNewRequests, SubdivisionMeshChecks) {
    const std::string P = " \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]";
    ribtest::ReadResult r = world(
        "SubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 1] [3]" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2] [0 1] [3]" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"crease\"] [2 1] [0 1] []" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"corner\"] [1 1] [9] [3]" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"hole\"] [1 0] [1] []" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4] [0 1 2 3] [\"hole\"] [1 0] [0 1] []" + P +
        "\nSubdivisionMesh \"catmull-clark\" [4 3] [0 1 2 3]" + P);
    EXPECT_EQ(r.target.calls.size(), 1u);
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:2: error: SubdivisionMesh nargs has 1 entries, needs 2 per tag (2)",
                     "t.rib:3: error: SubdivisionMesh tag \"crease\" needs more "
                     "intargs/floatargs than given",
                     "t.rib:4: error: SubdivisionMesh corner vertex index 9 out of range (4)",
                     "t.rib:5: error: SubdivisionMesh hole face index 1 out of range (1)",
                     "t.rib:6: error: SubdivisionMesh nargs call for 1 intargs and 0 "
                     "floatargs, got 2 and 0",
                     "t.rib:7: error: SubdivisionMesh nverts add up to 7 but verts has 4 "
                     "entries"}));
}

TEST(RibNewRequests, CurvesPointsBlobbyChecks) {
    ribtest::ReadResult r = world(
        "Curves \"cubic\" [5] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]\n"
        "Curves \"linear\" [2 2] \"nonperiodic\" \"P\" [0 0 0 1 0 0 2 0 0]\n"
        "Curves \"spline\" [2] \"nonperiodic\" \"P\" [0 0 0 1 0 0]\n"
        "Points \"P\" [0 0 0 1 1 1] \"varying float width\" [1 2 3]\n"
        "Blobby 1 [1001 0] [0 0 0]\n"
        "Blobby 2 [1000 0 0 2 0 3] [1]\n"
        "Blobby 1 [1000 0 6 0] [1] []\n"
        "Blobby 2 [1000 0] [1] []\n"
        "Blobby 1 [42] [] []");
    EXPECT_EQ(r.target.calls, Lines{"blobby 1 [ 1000 0 6 0 ] [ 1 ] [ ] { }"});
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: Curves curve with 5 vertices: nonperiodic cubic needs "
                     "4 + k*3 vertices",
                     "t.rib:2: error: Curves nvertices add up to 4 but \"P\" has 3 points",
                     "t.rib:3: error: Curves: unknown type \"spline\" (linear, cubic)",
                     "t.rib:4: error: Points: varying \"width\" has 3 values, needs 2",
                     "t.rib:5: error: Blobby expects a string array as argument 4",
                     "t.rib:6: error: Blobby expects a string array as argument 4",
                     "t.rib:8: error: Blobby nleaf is 2 but the code has 1 primitive",
                     "t.rib:9: error: Blobby code at 1: unknown opcode 42"}));
}

TEST(RibNewRequests, HugeCountsAreRefusedWithoutAllocating) {
    ribtest::ReadResult r = world(
        "PatchMesh \"bilinear\" 2000000000 \"nonperiodic\" 2000000000 \"nonperiodic\" "
        "\"P\" [0 0 0]\nPointsPolygons [2147483647] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]");
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: PatchMesh has 1 point but nu*nv = 4000000000000000000",
                     "t.rib:2: error: PointsPolygons nverts add up to 2147483647 but verts "
                     "has 3 entries"}));
}

}  // namespace
