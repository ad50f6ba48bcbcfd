// rib_reader_test.cpp: tests of the RIB reader. A MockTarget records every call as one
// line of text ("sphere 1 -1 1 360"), so each test states the RIB it feeds in and the
// exact calls and diagnostics it expects; error tests pin the `file:line: error:` text
// because editors and users rely on it.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <unistd.h>

#include "rib/param_decl.h"
#include "rib/reader.h"

namespace {

using rib::ParamList;
using rib::SourceLoc;

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string fmtParams(const ParamList& pl) {
    std::string out;
    for (const rib::Param& p : pl.params) {
        out += " " + p.name + ":" + rib::paramTypeName(p.type);
        if (p.arraySize > 1) out += "[" + std::to_string(p.arraySize) + "]";
        out += std::string(":") + rib::storageClassName(p.storage) + "=";
        std::string vals;
        for (float f : p.floats) vals += (vals.empty() ? "" : ",") + num(f);
        for (int i : p.ints) vals += (vals.empty() ? "" : ",") + std::to_string(i);
        for (const std::string& s : p.strings) vals += (vals.empty() ? "" : ",") + s;
        out += vals;
    }
    return out;
}

class MockTarget : public rib::Target {
public:
    std::vector<std::string> calls;
    std::vector<int> lines;

    void add(L loc, std::string s) {
        calls.push_back(std::move(s));
        lines.push_back(loc.line);
    }
    static std::string nums(std::initializer_list<double> v) {
        std::string s;
        for (double d : v) s += " " + num(d);
        return s;
    }

    void frameBegin(L l, int f) override { add(l, "frameBegin " + std::to_string(f)); }
    void frameEnd(L l) override { add(l, "frameEnd"); }
    void worldBegin(L l) override { add(l, "worldBegin"); }
    void worldEnd(L l) override { add(l, "worldEnd"); }
    void attributeBegin(L l) override { add(l, "attributeBegin"); }
    void attributeEnd(L l) override { add(l, "attributeEnd"); }
    void transformBegin(L l) override { add(l, "transformBegin"); }
    void transformEnd(L l) override { add(l, "transformEnd"); }
    void format(L l, int x, int y, float a) override {
        add(l, "format" + nums({double(x), double(y), a}));
    }
    void frameAspectRatio(L l, float a) override {
        add(l, "frameAspectRatio" + nums({a}));
    }
    void screenWindow(L l, float a, float b, float c, float d) override {
        add(l, "screenWindow" + nums({a, b, c, d}));
    }
    void projection(L l, const std::string& n, const ParamList& p) override {
        add(l, "projection " + n + fmtParams(p));
    }
    void clipping(L l, float n, float f) override { add(l, "clipping" + nums({n, f})); }
    void pixelSamples(L l, float x, float y) override {
        add(l, "pixelSamples" + nums({x, y}));
    }
    void display(L l, const std::string& n, const std::string& t, const std::string& m,
                 const ParamList& p) override {
        add(l, "display " + n + " " + t + " " + m + fmtParams(p));
    }
    void option(L l, const std::string& n, const ParamList& p) override {
        add(l, "option " + n + fmtParams(p));
    }
    void attribute(L l, const std::string& n, const ParamList& p) override {
        add(l, "attribute " + n + fmtParams(p));
    }
    void color(L l, const std::vector<float>& c) override {
        std::string s = "color";
        for (float f : c) s += " " + num(f);
        add(l, s);
    }
    void opacity(L l, const std::vector<float>& c) override {
        std::string s = "opacity";
        for (float f : c) s += " " + num(f);
        add(l, s);
    }
    void surface(L l, const std::string& n, const ParamList& p) override {
        add(l, "surface " + n + fmtParams(p));
    }
    void lightSource(L l, const std::string& n, const std::string& h,
                     const ParamList& p) override {
        add(l, "lightSource " + n + " " + h + fmtParams(p));
    }
    void illuminate(L l, const std::string& h, bool on) override {
        add(l, "illuminate " + h + (on ? " on" : " off"));
    }
    void shadingRate(L l, float r) override { add(l, "shadingRate" + nums({r})); }
    void sides(L l, int n) override { add(l, "sides " + std::to_string(n)); }
    void orientation(L l, const std::string& o) override { add(l, "orientation " + o); }
    void reverseOrientation(L l) override { add(l, "reverseOrientation"); }
    void identity(L l) override { add(l, "identity"); }
    void transform(L l, const float m[16]) override { add(l, "transform" + mat(m)); }
    void concatTransform(L l, const float m[16]) override {
        add(l, "concatTransform" + mat(m));
    }
    void translate(L l, float x, float y, float z) override {
        add(l, "translate" + nums({x, y, z}));
    }
    void rotate(L l, float a, float x, float y, float z) override {
        add(l, "rotate" + nums({a, x, y, z}));
    }
    void scale(L l, float x, float y, float z) override {
        add(l, "scale" + nums({x, y, z}));
    }
    void polygon(L l, const ParamList& p) override { add(l, "polygon" + fmtParams(p)); }
    void pointsPolygons(L l, const std::vector<int>& nv, const std::vector<int>& v,
                        const ParamList& p) override {
        std::string s = "pointsPolygons [";
        for (int i : nv) s += " " + std::to_string(i);
        s += " ] [";
        for (int i : v) s += " " + std::to_string(i);
        add(l, s + " ]" + fmtParams(p));
    }
    void sphere(L l, float r, float z0, float z1, float t, const ParamList& p) override {
        add(l, "sphere" + nums({r, z0, z1, t}) + fmtParams(p));
    }
    void declare(L l, const std::string& n, const std::string& d) override {
        add(l, "declare " + n + " " + d);
    }

private:
    static std::string mat(const float m[16]) {
        std::string s;
        for (int i = 0; i < 16; ++i) s += " " + num(m[i]);
        return s;
    }
};

// Reads `text` as "t.rib"; returns the calls, with diagnostics in `msgs`.
struct Result {
    bool ok = false;
    std::vector<std::string> calls;
    std::vector<std::string> msgs;
    MockTarget target;
};

std::vector<std::string> splitLines(const std::string& s) {
    std::vector<std::string> out;
    std::istringstream in(s);
    std::string line;
    while (std::getline(in, line)) out.push_back(line);
    return out;
}

Result read(const std::string& text) {
    Result r;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    r.ok = rib::readString(text, "t.rib", r.target, diag);
    r.calls = r.target.calls;
    r.msgs = splitLines(out.str());
    return r;
}

using Lines = std::vector<std::string>;

// Expects `text` to read without diagnostics into exactly `calls`.
void expectCalls(const std::string& text, const Lines& calls) {
    Result r = read(text);
    EXPECT_TRUE(r.ok) << text;
    EXPECT_EQ(r.msgs, Lines{}) << text;
    EXPECT_EQ(r.calls, calls) << text;
}

// Reads `text` inside WorldBegin/WorldEnd (on the first and a last line of their own, so
// line numbers stay those of `text`), for geometry and lights, which are only valid
// there; the worldBegin/worldEnd calls are left out of the result.
Result readW(const std::string& text) {
    Result r = read("WorldBegin " + text + "\nWorldEnd");
    if (!r.calls.empty() && r.calls.front() == "worldBegin") r.calls.erase(r.calls.begin());
    if (!r.calls.empty() && r.calls.back() == "worldEnd") r.calls.pop_back();
    r.target.lines.erase(r.target.lines.begin());
    r.target.lines.pop_back();
    return r;
}

void expectWorldCalls(const std::string& text, const Lines& calls) {
    Result r = readW(text);
    EXPECT_TRUE(r.ok) << text;
    EXPECT_EQ(r.msgs, Lines{}) << text;
    EXPECT_EQ(r.calls, calls) << text;
}

// --- Requests, plain and bracketed -------------------------------------------------

TEST(RibRequests, Blocks) {
    expectCalls(
        "FrameBegin 1 WorldBegin AttributeBegin TransformBegin TransformEnd "
        "AttributeEnd WorldEnd FrameEnd",
        {"frameBegin 1", "worldBegin", "attributeBegin", "transformBegin", "transformEnd",
         "attributeEnd", "worldEnd", "frameEnd"});
    expectCalls("FrameBegin [7] FrameEnd", {"frameBegin 7", "frameEnd"});
}

TEST(RibRequests, OptionsPlainAndBracketed) {
    expectCalls("Format 640 480 1\nFormat [320 240 1.5]",
                {"format 640 480 1", "format 320 240 1.5"});
    expectCalls("FrameAspectRatio 1.5 FrameAspectRatio [2]",
                {"frameAspectRatio 1.5", "frameAspectRatio 2"});
    expectCalls("ScreenWindow -1 1 -0.75 0.75 ScreenWindow [-2 2 -1 1]",
                {"screenWindow -1 1 -0.75 0.75", "screenWindow -2 2 -1 1"});
    expectCalls("Clipping 0.1 1000 Clipping [1 10]",
                {"clipping 0.1 1000", "clipping 1 10"});
    expectCalls("PixelSamples 2 2 PixelSamples [4 3]",
                {"pixelSamples 2 2", "pixelSamples 4 3"});
    expectCalls("Projection \"perspective\" \"fov\" 45",
                {"projection perspective fov:float:uniform=45"});
    expectCalls("Projection \"orthographic\"", {"projection orthographic"});
    expectCalls("Display \"out.exr\" \"file\" \"rgba\" \"compression\" \"zip\"",
                {"display out.exr file rgba compression:string:uniform=zip"});
    expectCalls("Option \"limits\" \"integer bucketsize\" [16 16]",
                {"option limits bucketsize:integer:uniform=16,16"});
}

TEST(RibRequests, Attributes) {
    expectCalls("Color 1 0 0 Color [0 1 0.5]", {"color 1 0 0", "color 0 1 0.5"});
    expectCalls("Opacity 0.5 0.5 0.5 Opacity [1 1 1]",
                {"opacity 0.5 0.5 0.5", "opacity 1 1 1"});
    expectCalls("Attribute \"identifier\" \"name\" [\"ball\"]",
                {"attribute identifier name:string:uniform=ball"});
    expectCalls("Surface \"plastic\" \"Kd\" 0.5 \"Ks\" [0.25]",
                {"surface plastic Kd:float:uniform=0.5 Ks:float:uniform=0.25"});
    expectCalls("Surface \"matte\"", {"surface matte"});
    expectCalls("ShadingRate 1 ShadingRate [0.5]", {"shadingRate 1", "shadingRate 0.5"});
    expectCalls("Sides 1 Sides [2]", {"sides 1", "sides 2"});
    expectCalls("Orientation \"lh\" Orientation \"rh\" ReverseOrientation",
                {"orientation lh", "orientation rh", "reverseOrientation"});
}

TEST(RibRequests, LightsWithIntegerAndStringHandles) {
    expectWorldCalls(
        "LightSource \"pointlight\" 1 \"intensity\" 10 \"from\" [0 1 2]\n"
        "LightSource \"distantlight\" \"key\" \"lightcolor\" [1 0.5 0.25]\n"
        "Illuminate 1 0 Illuminate \"key\" 1",
        {"lightSource pointlight 1 intensity:float:uniform=10 "
         "from:point:uniform=0,1,2",
         "lightSource distantlight key lightcolor:color:uniform=1,0.5,0.25",
         "illuminate 1 off", "illuminate key on"});
}

TEST(RibRequests, Transformations) {
    expectCalls(
        "Identity Translate 1 2 3 Translate [4 5 6] Rotate 90 0 0 1 "
        "Rotate [45 1 0 0] Scale 2 2 2 Scale [1 -1 1]",
        {"identity", "translate 1 2 3", "translate 4 5 6", "rotate 90 0 0 1",
         "rotate 45 1 0 0", "scale 2 2 2", "scale 1 -1 1"});
    const std::string m = " 1 0 0 0 0 1 0 0 0 0 1 0 1 2 3 1";
    expectCalls("Transform [" + m + "] ConcatTransform [" + m + "] ConcatTransform" + m,
                {"transform" + m, "concatTransform" + m, "concatTransform" + m});
}

TEST(RibRequests, Geometry) {
    expectWorldCalls("Sphere 1 -1 1 360 Sphere [2 -0.5 0.5 180] \"Cs\" [1 0 0]",
                {"sphere 1 -1 1 360", "sphere 2 -0.5 0.5 180 Cs:color:varying=1,0,0"});
    expectWorldCalls("Polygon \"P\" [0 0 0 1 0 0 1 1 0]",
                {"polygon P:point:vertex=0,0,0,1,0,0,1,1,0"});
    expectWorldCalls("PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0]",
                {"pointsPolygons [ 3 3 ] [ 0 1 2 0 2 3 ] "
                 "P:point:vertex=0,0,0,1,0,0,1,1,0,0,1,0"});
}

TEST(RibRequests, FormerlyUnsupportedOptionsNowReadCleanly) {
    // Once skipped with a warning; now forwarded (to virtuals this mock leaves alone).
    Result r = read(
        "Exposure 1 2.2\nQuantize \"rgba\" 255 0 255 0.5\n"
        "PixelFilter \"gaussian\" 2 2\nHider \"hidden\" \"jitter\" 1\nSides 2");
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.calls, Lines{"sides 2"});
    EXPECT_EQ(r.msgs, Lines{});
}

TEST(RibRequests, VersionLineIsAccepted) {
    expectCalls("version 3.04\nSides 1", {"sides 1"});
}

TEST(RibRequests, LocationsAreRequestLines) {
    Result r = readW("\n\nSides 1\n\n  Sphere 1\n -1 1 360");
    EXPECT_EQ(r.target.lines, (std::vector<int>{3, 5}));
}

// --- Parameter typing ----------------------------------------------------------------

TEST(RibParams, InlineDeclarations) {
    expectCalls(
        "Surface \"s\" \"uniform color foo\" [1 2 3] \"varying float s\" [1 2] "
        "\"string[2] names\" [\"a\" \"b\"] \"point P\" [1 2 3] "
        "\"float[2] st\" [0 1 2 3] \"int n\" 4 \"constant matrix m\" "
        "[1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]",
        {"surface s foo:color:uniform=1,2,3 s:float:varying=1,2 "
         "names:string[2]:uniform=a,b P:point:uniform=1,2,3 "
         "st:float[2]:uniform=0,1,2,3 n:integer:uniform=4 "
         "m:matrix:constant=1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1"});
}

TEST(RibParams, Declare) {
    expectCalls(
        "Declare \"tint\" \"uniform color\"\nDeclare \"count\" \"integer\"\n"
        "Declare \"uv\" \"varying float[2]\"\n"
        "Surface \"s\" \"tint\" [1 0 0] \"count\" 3 \"uv\" [0 0 1 1]",
        {"declare tint uniform color", "declare count integer",
         "declare uv varying float[2]",
         "surface s tint:color:uniform=1,0,0 count:integer:uniform=3 "
         "uv:float[2]:varying=0,0,1,1"});
}

TEST(RibParams, Predefined) {
    expectWorldCalls(
        "Polygon \"P\" [0 0 0 1 0 0 1 1 0] \"N\" [0 0 1 0 0 1 0 0 1] "
        "\"Cs\" [1 0 0 1 0 0 1 0 0] \"Os\" [1 1 1 1 1 1 1 1 1] \"s\" [0 1 1] "
        "\"t\" [0 0 1] \"st\" [0 0 1 0 1 1] \"Np\" [0 0 1] \"Pz\" [1 2 3]",
        {"polygon P:point:vertex=0,0,0,1,0,0,1,1,0 N:normal:varying=0,0,1,0,0,1,0,0,1 "
         "Cs:color:varying=1,0,0,1,0,0,1,0,0 Os:color:varying=1,1,1,1,1,1,1,1,1 "
         "s:float:varying=0,1,1 t:float:varying=0,0,1 "
         "st:float[2]:varying=0,0,1,0,1,1 Np:normal:uniform=0,0,1 "
         "Pz:float:vertex=1,2,3"});
    expectWorldCalls("Polygon \"Pw\" [0 0 0 1 1 0 0 1 1 1 0 1]",
                {"polygon Pw:hpoint:vertex=0,0,0,1,1,0,0,1,1,1,0,1"});
}

TEST(RibParams, UndeclaredTakeTypeFromValues) {
    expectCalls("Surface \"x\" \"Kd\" 1 \"texturename\" \"a.tex\" \"list\" [1 2 3]",
                {"surface x Kd:float:uniform=1 texturename:string:uniform=a.tex "
                 "list:float:uniform=1,2,3"});
}

TEST(RibParams, DeclareOverridesPredefined) {
    expectCalls("Declare \"s\" \"string\" Surface \"x\" \"s\" \"hello\"",
                {"declare s string", "surface x s:string:uniform=hello"});
}

TEST(RibParams, Accessors) {
    Result r = read(
        "Surface \"x\" \"Kd\" 0.5 \"int n\" 3 \"name\" \"a\" \"color c\" [1 2 3] "
        "\"f\" 7");
    ASSERT_TRUE(r.ok);
    ParamList pl;
    // Rebuild via the reader through a target that keeps the list.
    struct Keep : rib::Target {
        ParamList pl;
        void surface(L, const std::string&, const ParamList& p) override { pl = p; }
    } keep;
    rib::Diagnostics diag;
    ASSERT_TRUE(
        rib::readString("Surface \"x\" \"Kd\" 0.5 \"int n\" 3 \"name\" \"a\" "
                        "\"color c\" [1 2 3] \"f\" 7 \"g\" 1",
                        "t.rib", keep, diag));
    pl = keep.pl;
    EXPECT_FLOAT_EQ(pl.getFloat("Kd", 0), 0.5f);
    EXPECT_FLOAT_EQ(pl.getFloat("n", 0), 3.f);
    EXPECT_FLOAT_EQ(pl.getFloat("missing", 9), 9.f);
    EXPECT_EQ(pl.getInt("n", 0), 3);
    EXPECT_EQ(pl.getInt("f", 0), 7);  // a float param read as int
    EXPECT_EQ(pl.getInt("name", -1), -1);
    EXPECT_EQ(pl.getString("name", ""), "a");
    EXPECT_EQ(pl.getString("Kd", "def"), "def");
    float out[3], def[3] = {9, 9, 9};
    pl.get3("c", out, def);
    EXPECT_EQ(std::vector<float>(out, out + 3), (std::vector<float>{1, 2, 3}));
    pl.get3("g", out, def);
    EXPECT_EQ(std::vector<float>(out, out + 3), (std::vector<float>{1, 1, 1}));
    pl.get3("nope", out, def);
    EXPECT_EQ(std::vector<float>(out, out + 3), (std::vector<float>{9, 9, 9}));
    ASSERT_NE(pl.find("c"), nullptr);
    EXPECT_EQ(pl.find("c")->components(), 3);
    EXPECT_EQ(pl.find("nope"), nullptr);
}

TEST(RibParams, DeclParser) {
    rib::ParamDecl d;
    std::string name;
    EXPECT_TRUE(rib::parseParamDecl("varying hpoint [ 3 ] q", true, d, name));
    EXPECT_EQ(d.type, rib::ParamType::HPoint);
    EXPECT_EQ(d.storage, rib::StorageClass::Varying);
    EXPECT_EQ(d.arraySize, 3);
    EXPECT_EQ(name, "q");
    EXPECT_FALSE(rib::parseParamDecl("float", true, d, name));
    EXPECT_FALSE(rib::parseParamDecl("uniform", false, d, name));
    EXPECT_FALSE(rib::parseParamDecl("float[0] x", true, d, name));
    EXPECT_FALSE(rib::parseParamDecl("float x y", true, d, name));
    EXPECT_FALSE(rib::parseParamDecl("blob x", true, d, name));
}

TEST(RibParams, TypeErrors) {
    Result r = read(
        "Surface \"x\" \"point p\" [1 2]\nSurface \"x\" \"float Kd\" \"a\"\n"
        "Surface \"x\" \"int n\" 1.5\nSurface \"x\" \"bogus type\" 1\n"
        "Surface \"x\" \"Kd\"\nSurface \"x\" 3 4\nDeclare \"a\" \"sideways\"");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, Lines{});
    EXPECT_EQ(
        r.msgs,
        (Lines{"t.rib:1: error: Surface: parameter \"p\" (point) needs a multiple of 3 "
               "values, got 2",
               "t.rib:2: error: Surface: parameter \"Kd\" is declared float but has "
               "string values",
               "t.rib:3: error: Surface: parameter \"n\" is declared integer but has "
               "non-integer values",
               "t.rib:4: error: Surface: bad parameter declaration \"bogus type\"",
               "t.rib:5: error: Surface: parameter \"Kd\" has no value",
               "t.rib:6: error: Surface: expected a parameter name, got the number "
               "3.000000",
               "t.rib:7: error: Declare: bad declaration \"sideways\" for \"a\""}));
}

// --- Lexical details ------------------------------------------------------------------

TEST(RibLexer, CommentsAndStrings) {
    expectCalls(
        "##RenderMan RIB\n# a comment Sphere 1 2 3 4\n"
        "Surface \"a\\\"b\\\\c\\n\\td\\101\\7\" # trailing\nSides 2#x\n",
        {"surface a\"b\\c\n\tdA\a", "sides 2"});
}

TEST(RibLexer, NumberForms) {
    expectCalls("Translate +1 -.5 2. Scale 1e2 -2.5E-1 .25e+1",
                {"translate 1 -0.5 2", "scale 100 -0.25 2.5"});
    expectCalls("Color[1 0 0]Surface\"x\"\"Kd\"[.5]",
                {"color 1 0 0", "surface x Kd:float:uniform=0.5"});
}

TEST(RibLexer, NanAndInfPassThrough) {
    expectCalls("Translate nan inf -inf", {"translate nan inf -inf"});
}

TEST(RibLexer, MalformedNumbers) {
    Result r = read(
        "Sides 1\nTranslate 1.2.3 0 0\nScale 3e 1 1\nRotate -x 0 0 1\n"
        "Translate 1e999 0 0\nSides 2");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, (Lines{"sides 1", "sides 2"}));
    EXPECT_EQ(r.msgs, (Lines{"t.rib:2: error: malformed number \"1.2.3\"",
                             "t.rib:3: error: malformed number \"3e\"",
                             "t.rib:4: error: malformed number \"-x\"",
                             "t.rib:5: error: number out of range \"1e999\""}));
}

// The largest float as written with nine digits lies just beyond FLT_MAX but rounds to it:
// it reads back (the fuzz target's round trip of a binary -FLT_MAX failed on it); a
// number that rounds to infinity is still out of range.
TEST(RibLexer, NumbersThatRoundToTheLargestFloatAreInRange) {
    Result r = read("Translate 3.40282347e+38 -3.40282347e+38 0\nTranslate 3.5e38 0 0");
    EXPECT_EQ(r.calls, (Lines{"translate 3.40282e+38 -3.40282e+38 0"}));
    EXPECT_EQ(r.msgs, (Lines{"t.rib:2: error: number out of range \"3.5e38\""}));
}

TEST(RibLexer, UnterminatedStringAndBracket) {
    Result r = read("Sides 1\nColor [1 0 0\nSides 2\nSurface \"abc");
    EXPECT_EQ(r.calls, (Lines{"sides 1", "sides 2"}));
    EXPECT_EQ(r.msgs, (Lines{"t.rib:2: error: unterminated '['",
                             "t.rib:4: error: unterminated string"}));
}

TEST(RibLexer, MultiLineStringCountsLines) {
    Result r = read("Surface \"a\nb\"\nFoo");
    EXPECT_EQ(r.msgs, Lines{"t.rib:3: error: unknown request \"Foo\""});
}

TEST(RibLexer, BinaryRibIsDecoded) {
    // 0246 <code> after 0314 <code> "Sides" defines and calls an encoded request; 0201
    // is a two-byte integer. (More in rib_binary_test.cpp.)
    const char bytes[] = "\xcc\x01\x95Sides\xa6\x01\x81\x00\x02 Sides 1";
    Result r = read(std::string(bytes, sizeof bytes - 1));
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.calls, (Lines{"sides 2", "sides 1"}));
    EXPECT_EQ(r.msgs, Lines{});
}

// --- Errors and recovery ---------------------------------------------------------------

TEST(RibErrors, UnknownRequestIsSkipped) {
    Result r =
        read("Sides 1\nFooBar 1 2 [3 \"x\"] \"y\"\nMakeBrickMap \"a.rib\"\nSides 2");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, (Lines{"sides 1", "sides 2"}));
    EXPECT_EQ(r.msgs, (Lines{"t.rib:2: error: unknown request \"FooBar\"",
                             "t.rib:3: error: unknown request \"MakeBrickMap\""}));
}

TEST(RibErrors, WrongArgumentCounts) {
    Result r = readW(
        "Sphere 1 -1 1\nSphere [1 -1 1 360 5]\nSphere 1 -1 1 360 5\n"
        "ShadingRate\nFormat 640.5 480 1\nDisplay \"a\" \"b\"\n"
        "PointsPolygons 3 [0 1 2]\nOrientation \"lh\" \"rh\"\n"
        "ConcatTransform [1 2 3]\nSphere 1 1 1 1");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, Lines{"sphere 1 1 1 1"});
    EXPECT_EQ(r.msgs,
              (Lines{"t.rib:1: error: Sphere expects 4 numbers, got 3",
                     "t.rib:2: error: Sphere expects 4 numbers, got 5",
                     "t.rib:3: error: Sphere expects 4 numbers, got 5",
                     "t.rib:4: error: ShadingRate expects 1 number, got 0",
                     "t.rib:5: error: Format expects an integer as argument 1",
                     "t.rib:6: error: Display expects a string as argument 3",
                     "t.rib:7: error: PointsPolygons expects an integer array as "
                     "argument 1",
                     "t.rib:8: error: Orientation has too many arguments",
                     "t.rib:9: error: ConcatTransform expects 16 numbers, got 3"}));
}

TEST(RibErrors, PointsPolygonsChecks) {
    Result r = readW(
        "PointsPolygons [3] [0 1 3] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "PointsPolygons [3 3] [0 1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "PointsPolygons [3] [0 1 2]\n"
        "PointsPolygons [2] [0 1] \"P\" [0 0 0 1 0 0]\n"
        "PointsPolygons [3] [0 -1 2] \"P\" [0 0 0 1 0 0 1 1 0]\n"
        "Polygon \"float P\" [0 0 0 1]\nPolygon \"Cs\" [1 1 1]");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, Lines{});
    EXPECT_EQ(
        r.msgs,
        (Lines{
            "t.rib:1: error: PointsPolygons vertex index 3 out of range (3 points in "
            "\"P\")",
            "t.rib:2: error: PointsPolygons nverts add up to 6 but verts has 3 entries",
            "t.rib:3: error: PointsPolygons requires \"P\"",
            "t.rib:4: error: PointsPolygons polygon 0 has 2 vertices (needs at least 3)",
            "t.rib:5: error: PointsPolygons vertex index -1 out of range (3 points in "
            "\"P\")",
            "t.rib:6: error: Polygon \"P\" needs a multiple of 3 values, got 4",
            "t.rib:7: error: Polygon requires \"P\""}));
}

TEST(RibErrors, UnbalancedEnd) {
    Result r = read(
        "WorldBegin\nAttributeBegin\n  TransformBegin\nAttributeEnd\n"
        "  TransformEnd\nAttributeEnd\nWorldEnd");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls, (Lines{"worldBegin", "attributeBegin", "transformBegin",
                              "transformEnd", "attributeEnd", "worldEnd"}));
    EXPECT_EQ(r.msgs, Lines{"t.rib:4: error: unbalanced AttributeEnd (open block: "
                            "TransformBegin at t.rib:3)"});
}

TEST(RibErrors, EndWithoutBegin) {
    Result r = read("WorldBegin\nWorldEnd\nAttributeEnd\nFrameEnd\nSides 1");
    EXPECT_EQ(r.calls, (Lines{"worldBegin", "worldEnd", "sides 1"}));
    EXPECT_EQ(r.msgs, (Lines{"t.rib:3: error: AttributeEnd without AttributeBegin",
                             "t.rib:4: error: FrameEnd without FrameBegin"}));
}

TEST(RibErrors, UnclosedAtEof) {
    Result r = read("FrameBegin 1\nWorldBegin\n  AttributeBegin\n  Sphere 1 -1 1 360\n");
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.calls.size(), 4u);
    EXPECT_EQ(r.msgs, (Lines{"t.rib:4: error: AttributeBegin at t.rib:3 never closed",
                             "t.rib:4: error: WorldBegin at t.rib:2 never closed",
                             "t.rib:4: error: FrameBegin at t.rib:1 never closed"}));
}

TEST(RibErrors, StrayValuesAndBrackets) {
    Result r = read("1 2 3\nSides 1 ]\nSides 2");
    EXPECT_EQ(r.calls, Lines{"sides 2"});
    EXPECT_EQ(r.msgs, (Lines{"t.rib:1: error: expected a request name, got \"1\"",
                             "t.rib:2: error: unexpected ']'"}));
}

TEST(RibErrors, ArrayLimit) {
    MockTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    rib::ReadOptions opts;
    opts.maxArrayValues = 4;
    EXPECT_FALSE(
        rib::readString("Polygon \"P\" [1 2 3 4 5 6]\nSides 1", "t.rib", t, diag, opts));
    EXPECT_EQ(t.calls, Lines{"sides 1"});
    EXPECT_EQ(out.str(), "t.rib:1: error: array too large (more than 4 values)\n");
}

TEST(RibErrors, StopsAfterTooManyErrors) {
    std::string text;
    for (int i = 0; i < 50; ++i) text += "Bogus\n";
    MockTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out, 10);
    EXPECT_FALSE(rib::readString(text + "WorldBegin", "t.rib", t, diag));
    EXPECT_EQ(diag.errorCount(), 10);
    EXPECT_EQ(t.calls, Lines{});
}

TEST(RibErrors, GarbageDoesNotCrash) {
    std::string junk;
    unsigned x = 12345;
    for (int i = 0; i < 20000; ++i) {
        x = x * 1103515245u + 12345u;
        junk += static_cast<char>((x >> 16) & 0x7f);
    }
    MockTarget t;
    rib::Diagnostics diag(nullptr, 1000000);
    rib::readString("Sides 1\n" + junk, "junk.rib", t, diag);
    SUCCEED();
}

// --- Files
// ------------------------------------------------------------------------------

std::string tempPath(const std::string& leaf) {
    // (one name per test process: CTest runs two at a time)
    return ::testing::TempDir() + "/rib_reader_test_" + std::to_string(getpid()) + "_" + leaf;
}

const char* kScene =
    "##RenderMan RIB\nFormat 64 48 1\nProjection \"perspective\" \"fov\" [40]\n"
    "WorldBegin\n  LightSource \"pointlight\" 1 \"from\" [0 2 0]\n  AttributeBegin\n"
    "    Surface \"plastic\" \"Kd\" 0.8\n    Translate 0 0 5\n    Sphere 1 -1 1 360\n"
    "  AttributeEnd\nWorldEnd\n";

TEST(RibFiles, PlainAndGzipReadIdentically) {
    std::string plain = tempPath("scene.rib"), gz = tempPath("scene.rib.gz");
    {
        std::ofstream f(plain, std::ios::binary);
        f << kScene;
    }
    gzFile g = gzopen(gz.c_str(), "wb");
    ASSERT_NE(g, nullptr);
    ASSERT_GT(gzwrite(g, kScene, static_cast<unsigned>(std::strlen(kScene))), 0);
    gzclose(g);

    MockTarget a, b;
    rib::Diagnostics diag;
    EXPECT_TRUE(rib::readFile(plain, a, diag));
    EXPECT_TRUE(rib::readFile(gz, b, diag));
    EXPECT_EQ(diag.errorCount(), 0);
    EXPECT_EQ(a.calls.size(), 10u);
    EXPECT_EQ(a.calls, b.calls);
    EXPECT_EQ(a.lines, b.lines);
    EXPECT_EQ(a.calls[7], "sphere 1 -1 1 360");
    EXPECT_EQ(a.lines[7], 9);
    std::remove(plain.c_str());
    std::remove(gz.c_str());
}

TEST(RibFiles, ErrorsNameTheFile) {
    std::string path = tempPath("bad.rib");
    {
        std::ofstream f(path, std::ios::binary);
        f << "Sides 1\nNope\n";
    }
    MockTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    EXPECT_FALSE(rib::readFile(path, t, diag));
    EXPECT_EQ(out.str(), path + ":2: error: unknown request \"Nope\"\n");
    std::remove(path.c_str());
}

TEST(RibFiles, MissingFile) {
    MockTarget t;
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    EXPECT_FALSE(rib::readFile("/nonexistent/dir/x.rib", t, diag));
    EXPECT_EQ(out.str(),
              "/nonexistent/dir/x.rib: error: cannot open RIB file: No such file or "
              "directory\n");
    EXPECT_EQ(t.calls, Lines{});
}

}  // namespace

// A warning repeated with only its numbers changed (one per mesh of a large file) is
// shown kMaxRepeats times, the last saying so, and the rest are counted and summarised
// once; other warnings are shown as before, and every one is counted.
TEST(Diagnostics, RepeatedWarningsAreSummarised) {
    std::ostringstream out;
    rib::Diagnostics diag(&out);
    for (int i = 1; i <= 12; ++i)
        diag.warning({"a.rib", i}, "degenerate geometry: " + std::to_string(i) + " triangle(s) left out");
    diag.warning({"a.rib", 13}, "something else");
    EXPECT_EQ(diag.warningCount(), 13);
    diag.printSuppressed();
    diag.printSuppressed();  // (said once)
    const std::vector<std::string> lines = splitLines(out.str());
    ASSERT_EQ(lines.size(), size_t(rib::Diagnostics::kMaxRepeats + 2));
    EXPECT_EQ(lines[0], "a.rib:1: warning: degenerate geometry: 1 triangle(s) left out");
    EXPECT_NE(lines[rib::Diagnostics::kMaxRepeats - 1].find("further warnings like this are not shown"),
              std::string::npos);
    EXPECT_EQ(lines[rib::Diagnostics::kMaxRepeats], "a.rib:13: warning: something else");
    EXPECT_EQ(lines.back(), "note: 7 more warning(s) like \"a.rib:1: warning: degenerate geometry: 1 "
                            "triangle(s) left out\" were not shown");
}
