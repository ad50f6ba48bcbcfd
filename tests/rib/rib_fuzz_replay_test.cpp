// rib_fuzz_replay_test.cpp: the fuzz target's checks over a few hundred deterministic
// mutations of the test corpus (ASCII and binary encodings: flipped, inserted, deleted,
// duplicated and truncated bytes, spliced requests, extreme numbers), so builds without
// clang/libFuzzer (CI uses g++) still exercise the reader on hostile input.
#include <gtest/gtest.h>

#include <sstream>

#include "fuzz_rib.h"
#include "rib_corpus.h"

namespace {

struct Rng {
    uint64_t s;
    uint32_t next() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<uint32_t>(s >> 33);
    }
    size_t below(size_t n) { return n ? next() % n : 0; }
};

std::vector<std::string> seeds() {
    std::vector<std::string> out = ribtest::corpus();
    for (const std::string& text : ribtest::corpus()) {
        std::ostringstream bin;
        {
            rib::RibWriter w(bin, rib::RibWriter::Encoding::Binary);
            rib::Diagnostics d;
            rib::readString(text, "t.rib", w, d);
        }
        out.push_back(bin.str());
    }
    return out;
}

std::string mutate(std::string s, Rng& rng, const std::vector<std::string>& pool) {
    static const char* tokens[] = {" 1e30 ", " -2147483648 ", " nan ", " [ ", " ] ",
                                   " \"",    " 0 ",           " -1 ",  " 99999999 ",
                                   " WorldBegin ", " MotionBegin [0 1] ", " \xcb\xff\xff\xff\xff",
                                   " \xa6\x07", " ObjectBegin 1 ", " ArchiveEnd "};
    int rounds = 1 + static_cast<int>(rng.below(4));
    for (int k = 0; k < rounds; ++k) {
        size_t pos = rng.below(s.size() + 1);
        switch (rng.below(7)) {
            case 0:
                if (!s.empty()) s[rng.below(s.size())] ^= static_cast<char>(1 << rng.below(8));
                break;
            case 1:
                s.insert(pos, 1, static_cast<char>(rng.below(256)));
                break;
            case 2:
                s.erase(pos, rng.below(64));
                break;
            case 3: {
                size_t len = rng.below(128);
                std::string piece = s.substr(pos, len);
                s.insert(rng.below(s.size() + 1), piece);
                break;
            }
            case 4:
                s.resize(pos);
                break;
            case 5: {
                const std::string& other = pool[rng.below(pool.size())];
                size_t from = rng.below(other.size());
                s.insert(pos, other.substr(from, rng.below(256)));
                break;
            }
            default:
                s.insert(pos, tokens[rng.below(sizeof tokens / sizeof *tokens)]);
        }
    }
    return s;
}

TEST(RibFuzzReplay, MutatedInputsNeverCrashAndRoundTrip) {
    const std::vector<std::string> pool = seeds();
    Rng rng{20240601};
    int mismatches = 0;
    for (int i = 0; i < 400; ++i) {
        std::string input = mutate(pool[rng.below(pool.size())], rng, pool);
        ribtest::FuzzOutcome o =
            ribtest::fuzzOne(reinterpret_cast<const uint8_t*>(input.data()), input.size());
        if (!o.roundTripOk && ++mismatches <= 3)
            ADD_FAILURE() << "mutant " << i << " does not round-trip: " << o.detail;
    }
    EXPECT_EQ(mismatches, 0);
}

TEST(RibFuzzReplay, SeedsRoundTrip) {
    for (const std::string& s : seeds()) {
        ribtest::FuzzOutcome o =
            ribtest::fuzzOne(reinterpret_cast<const uint8_t*>(s.data()), s.size());
        EXPECT_TRUE(o.roundTripOk) << o.detail;
    }
}

}  // namespace
