// rib_binary_test.cpp: binary-encoded RIB (RI 3.2 appendix C). Scenes are encoded by
// hand with BinaryEmitter's low-level encodings (every number and string form, request
// and string definitions, float arrays, ASCII mixed in) and must give exactly the calls
// of the same scene in ASCII; malformed binary is reported, never crashes.
#include <gtest/gtest.h>

#include <sstream>

#include "rib/emitter.h"
#include "rib/writer.h"
#include "rib_corpus.h"

namespace {

using ribtest::readRib;
using Lines = std::vector<std::string>;

TEST(RibBinary, EveryNumberForm) {
    std::ostringstream bin;
    rib::BinaryEmitter e(bin);
    bin << "WorldBegin\n";  // ASCII first, binary after, in one stream
    e.request("Sphere", 0);
    e.byte(0200);  // 1-byte integer 2
    e.byte(2);
    e.fixedPoint(-1.5, 2, 1);  // 0205: 8.8 fixed point
    e.ieeeDouble(0.75);        // 0245
    e.byte(0201);              // 2-byte integer 360
    e.byte(1);
    e.byte(104);
    e.request("Sphere", 0);  // second use: only 0246 <code>
    e.fixedPoint(0.25, 1, 1);  // 0204: .b
    e.fixedPoint(-3, 4, 0);    // 0203: 4-byte integer
    e.ieeeFloat(3.5f);
    e.fixedPoint(1.0 / 65536, 2, 2);  // 0211: ._b b
    bin << " WorldEnd";
    ribtest::ReadResult b = readRib(bin.str());
    ribtest::ReadResult a = readRib(
        "WorldBegin Sphere 2 -1.5 0.75 360 Sphere 0.25 -3 3.5 1.52587890625e-05 WorldEnd");
    EXPECT_TRUE(b.ok);
    EXPECT_EQ(b.msgs, Lines{});
    EXPECT_EQ(b.target.calls, a.target.calls);
    EXPECT_EQ(a.target.calls.size(), 4u);
}

TEST(RibBinary, StringFormsAndDefinitions) {
    std::ostringstream bin;
    rib::BinaryEmitter e(bin);
    e.request("Attribute", 0);
    e.rawString("identifier");  // short string (0220 + n)
    bin << "\"name\"";          // an ASCII string among binary tokens
    bin << '[';
    e.rawString(std::string(300, 'x'));  // long string, 2-byte length (0241)
    bin << ']';
    e.byte(0315);  // define string 5 = "plastic"
    e.byte(5);
    e.rawString("plastic");
    e.byte(0316);  // define string 700 (2-byte code) = "Kd"
    e.byte(700 >> 8);
    e.byte(700 & 0xff);
    e.rawString("Kd");
    e.request("Surface", 0);
    e.byte(0317);  // reference string 5
    e.byte(5);
    e.byte(0320);  // reference string 700
    e.byte(700 >> 8);
    e.byte(700 & 0xff);
    e.byte(0310);  // float array of 1
    e.byte(1);
    e.byte(0x3f);  // 0.5f big-endian
    e.byte(0);
    e.byte(0);
    e.byte(0);
    ribtest::ReadResult b = readRib(bin.str());
    ribtest::ReadResult a = readRib("Attribute \"identifier\" \"name\" [\"" +
                                    std::string(300, 'x') +
                                    "\"] Surface \"plastic\" \"Kd\" [0.5]");
    EXPECT_EQ(b.msgs, Lines{});
    EXPECT_EQ(b.target.calls, a.target.calls);
    EXPECT_EQ(a.target.calls.size(), 2u);
}

TEST(RibBinary, FloatArraysFeedGeometry) {
    std::ostringstream bin;
    rib::BinaryEmitter e(bin);
    bin << "WorldBegin ";
    e.request("PointsPolygons", 0);
    e.intArray({3, 3});
    e.intArray({0, 1, 2, 0, 2, 3});
    e.string("P");
    e.floatArray({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    bin << " WorldEnd";
    ribtest::ReadResult b = readRib(bin.str());
    ribtest::ReadResult a = readRib(
        "WorldBegin PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0] "
        "WorldEnd");
    EXPECT_EQ(b.msgs, Lines{});
    EXPECT_EQ(b.target.calls, a.target.calls);
}

TEST(RibBinary, WriterOutputMatchesAsciiForTheCorpus) {
    for (const std::string& text : ribtest::corpus()) {
        std::ostringstream bin;
        {
            rib::RibWriter w(bin, rib::RibWriter::Encoding::Binary);
            rib::Diagnostics d;
            rib::readString(text, "t.rib", w, d);
        }
        // Binary output really is binary: no request names spelled out after the
        // definitions, and it reads back to the same calls.
        EXPECT_NE(bin.str().find('\xa6'), std::string::npos);
        ribtest::ReadResult a = readRib(text), b = readRib(bin.str());
        EXPECT_EQ(b.msgs, Lines{});
        EXPECT_EQ(a.target.calls, b.target.calls);
    }
}

TEST(RibBinary, ErrorsAreReportedNotFatal) {
    auto msgs = [](const std::string& s) { return readRib(s).msgs; };
    EXPECT_EQ(msgs(std::string("\xa6\x09 Sides 1", 10)),
              Lines{"t.rib:1: error: encoded request 9 was not defined"});
    EXPECT_EQ(msgs(std::string("Surface \xcf\x03", 10)),
              Lines{"t.rib:1: error: encoded string 3 was not defined"});
    EXPECT_EQ(msgs(std::string("Sides \xa4\x3f", 8)),
              Lines{"t.rib:1: error: truncated binary number"});
    EXPECT_EQ(msgs(std::string("Sides 1 \xe0", 9)),
              Lines{"t.rib:1: error: reserved binary RIB byte 0340"});
    // A float array that claims 2^32-1 elements but has 2: no huge allocation.
    ribtest::ReadResult r =
        readRib(std::string("Color \xcb\xff\xff\xff\xff\x3f\x80\x00\x00\x3f\x80\x00\x00", 14));
    EXPECT_FALSE(r.ok);
    // A long string that claims 4 GB.
    r = readRib(std::string("Surface \xa3\xff\xff\xff\xff" "abc", 16));
    EXPECT_EQ(r.msgs, Lines{"t.rib:1: error: truncated binary string"});
}

TEST(RibBinary, AfterBinaryTheAsciiLinesStillCount) {
    std::string s = std::string("Sides \x80\x01\nSides 2\n", 16);
    ribtest::ReadResult r = readRib(s);
    EXPECT_EQ(r.target.calls, (Lines{"sides 1", "sides 2"}));
    EXPECT_EQ(r.target.lines, (std::vector<int>{1, 2}));
}

}  // namespace
