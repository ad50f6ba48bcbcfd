// rib_writer_test.cpp: RibWriter round trips. Reading a RIB, writing it back (ASCII or
// binary) and reading that must give exactly the same Target calls, for the test corpus
// (every request) and for the real-world SPD scenes, which must also read with no
// diagnostics at all.
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "rib/writer.h"
#include "rib_corpus.h"

namespace {

using ribtest::readRib;
using ribtest::RecordingTarget;

// Reads `text`, sending the calls both to a recorder and to a writer; returns the
// written RIB.
std::string readAndWrite(const std::string& text, rib::RibWriter::Encoding enc,
                         RecordingTarget& rec, int& errors) {
    rib::ReadOptions opts;
    opts.expandArchives = false;
    std::ostringstream written;
    {
        rib::RibWriter writer(written, enc);
        rib::Diagnostics diag;
        rib::readString(text, "in.rib", writer, diag, opts);
        errors = diag.errorCount();
    }
    rib::Diagnostics diag2;
    rib::readString(text, "in.rib", rec, diag2, opts);
    return written.str();
}

void expectRoundTrip(const std::string& text, rib::RibWriter::Encoding enc) {
    RecordingTarget first, second;
    int errors = 0;
    std::string out = readAndWrite(text, enc, first, errors);
    EXPECT_EQ(errors, 0);
    rib::ReadOptions opts;
    opts.expandArchives = false;
    std::ostringstream msgs;
    rib::Diagnostics diag(&msgs);
    EXPECT_TRUE(rib::readString(out, "out.rib", second, diag, opts)) << msgs.str();
    EXPECT_EQ(first.calls, second.calls);
}

TEST(RibWriter, CorpusRoundTripsAscii) {
    for (const std::string& text : ribtest::corpus())
        expectRoundTrip(text, rib::RibWriter::Encoding::Ascii);
}

TEST(RibWriter, CorpusRoundTripsBinary) {
    for (const std::string& text : ribtest::corpus())
        expectRoundTrip(text, rib::RibWriter::Encoding::Binary);
}

TEST(RibWriter, KitchenSinkReadsCleanlyAndCoversEveryRequest) {
    rib::ReadOptions opts;
    opts.expandArchives = false;
    ribtest::ReadResult r = readRib(ribtest::kKitchenSink, opts);
    EXPECT_TRUE(r.ok);
    EXPECT_EQ(r.msgs, std::vector<std::string>{});
    std::set<std::string> seen;
    for (const std::string& c : r.target.calls) seen.insert(c.substr(0, c.find(' ')));
    // Every Target virtual (105) is exercised.
    EXPECT_EQ(seen.size(), 105u);
}

TEST(RibWriter, AsciiOutputIsReadable) {
    std::ostringstream out;
    {
        rib::RibWriter w(out);
        rib::SourceLoc loc{"x", 1};
        w.worldBegin(loc);
        rib::ParamList pl;
        rib::Param p;
        p.name = "Kd";
        p.floats = {0.5f};
        pl.params.push_back(p);
        w.surface(loc, "plastic", pl);
        float bound[6] = {-1, 1, -1, 1, -1, 1};
        w.procedural(loc, "DelayedReadArchive", {"a \"q\".rib"}, bound);
        w.depthOfField(loc, HUGE_VALF, 0, 0);
        w.worldEnd(loc);
    }
    EXPECT_EQ(out.str(),
              "WorldBegin\n  Surface \"plastic\" \"uniform float Kd\" [ 0.5 ]\n"
              "  Procedural \"DelayedReadArchive\" [ \"a \\\"q\\\".rib\" ] [ -1 1 -1 1 -1 1 ]\n"
              "  DepthOfField\nWorldEnd\n");
}

std::vector<std::string> spdScenes() {
    std::vector<std::string> out;
    const std::string dir = "/work/shared/scenes/spd/";
    if (DIR* d = opendir(dir.c_str())) {
        while (dirent* e = readdir(d)) {
            std::string n = e->d_name;
            if (n.size() > 7 && n.substr(n.size() - 7) == ".rib.gz") out.push_back(dir + n);
        }
        closedir(d);
    }
    std::sort(out.begin(), out.end());
    return out;
}

TEST(RibWriter, SpdScenesReadCleanlyAndRoundTrip) {
    std::vector<std::string> scenes = spdScenes();
    if (scenes.empty()) GTEST_SKIP() << "no SPD scenes at /work/shared/scenes/spd";
    for (const std::string& path : scenes) {
        SCOPED_TRACE(path);
        RecordingTarget first;
        std::ostringstream msgs;
        rib::Diagnostics diag(&msgs);
        EXPECT_TRUE(rib::readFile(path, first, diag));
        EXPECT_EQ(diag.errorCount(), 0);
        EXPECT_EQ(diag.warningCount(), 0);
        EXPECT_EQ(msgs.str(), "");
        EXPECT_GT(first.calls.size(), 10u);
        for (auto enc : {rib::RibWriter::Encoding::Ascii, rib::RibWriter::Encoding::Binary}) {
            std::ostringstream written;
            {
                rib::RibWriter w(written, enc);
                rib::Diagnostics d;
                rib::readFile(path, w, d);
            }
            RecordingTarget second;
            rib::Diagnostics d2;
            EXPECT_TRUE(rib::readString(written.str(), "out.rib", second, d2));
            EXPECT_EQ(first.calls, second.calls);
        }
    }
}

}  // namespace
