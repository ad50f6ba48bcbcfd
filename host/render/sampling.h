// sampling.h: adaptive sampling as RenderDrive did it. The first pass takes one eye sample
// per block of pixels (2x2: 1/4 ray per pixel) and then brings every pixel to the minimum
// (two samples: a variance needs two; that needs no film to decide, so it streams on in
// the same pass); each later pass adds samples where neighbouring pixels disagree
// (discontinuities) or a pixel's estimated error is high, doubling those pixels' counts
// (a small pass: quadrupling), until the final quality: PixelSamples, an error target or
// a time budget. The film's error is estimated from whole-sample variance.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cl/include/film.h"
#include "film/film_error.h"

namespace rd {

struct SamplingSettings {
    int firstPassBlock = 2;     // first pass: one sample per block x block pixels
    uint32_t minSamples = 2;    // every pixel gets this many (a variance needs two)
    uint32_t maxSamples = 4;    // per pixel; PixelSamples x*y unless a target is given
    float pixelError = 0.01f;   // per-pixel relative standard error to stop refining at
    float contrast = 0.05f;     // neighbour difference (relative) that marks an edge
    // Each pass re-tests only the pixels whose answer can have changed (sampled in the
    // last pass or next to one, an error above this pass's pixel error, or near the
    // moving brightness floor); false re-tests every pixel. The passes are the same
    // either way (Sampling/IncrementalPlan.IsExact).
    bool incremental = true;
    // A visit of at least this many pixels (a full test) is split across planThreads
    // threads (0: the host's cores, at most 8); the pass is the same for any count.
    size_t parallelPixels = 32768;
    unsigned planThreads = 0;
    // A pass that asks for fewer samples than this (0: none) gives its pixels two more
    // doublings at once (within maxSamples; while that stays within four times this): a
    // pass costs as many rounds as its rays' depth however few they are, and the last
    // passes of a frame are small (SPD teapot at 9 samples a pixel: 72 rounds, pool fill
    // 0.635; with a 64th of the frame's pixels, 4096, 61 rounds, 0.749, 290 samples more).
    uint32_t smallPass = 0;
};

// The pixels of [x0, x1) x [y0, y1) of an image `width` wide in the order the renderer
// samples them: 16x16 tiles in rows, each tile in Morton order, so that eight
// consecutive eye rays (a packet, cl/lib/packet_traverse.clh) cover a 4x2 block, not a
// row of eight (SPD teapot's and tetra's intersect_closest: 0.82-0.97 of the time with
// rows).
std::vector<uint32_t> tileOrder(int width, int x0, int x1, int y0, int y1);

// Samples of one pass for one pixel: indices [first, first + count) of its sequence.
struct PixelRequest {
    uint32_t pixel, first, count;
};

// The test of every pixel, done elsewhere: on the device (device_pixel_tests.h,
// cl/kernels/pixel_tests.cl), where the first adaptive pass's test of a 512x512 frame's
// pixels had left the device idle for 3.5 ms of SPD tetra's 110 ms. Its answers are the
// planner's own, bit for bit.
class PixelTester {
public:
    virtual ~PixelTester() = default;
    // Every pixel's pixelMean into meanOf (-1 without samples), and each batch of
    // RT_FILM_BATCH pixels' sum of the means >= 0 and their number (groupSums,
    // groupCounts: one each a batch), summed in double in pixel order.
    virtual void means(float* meanOf, double* groupSums, double* groupCounts) = 0;
    // The test of every pixel of the planner's tile order, the film as the last call to
    // means() found it when `meansTaken` (else as it is now): for its k-th pixel,
    // request[2k] the samples its request asks for (0: none; kBusy: marked in `busy`,
    // empty: none) and request[2k + 1] their first index; relErr[pixel] the error the
    // planner keeps (-inf: never again; NaN: its own). Valid until the next call.
    static constexpr uint32_t kBusy = ~0u;
    struct Answers {
        const uint32_t* request;
        const float* relErr;
    };
    virtual Answers test(bool meansTaken, float floor, float pixelError,
                         const std::vector<uint8_t>& busy) = 0;
};

class SamplePlanner {
public:
    // Only the pixels in [x0, x1) x [y0, y1) (the crop window) are sampled.
    SamplePlanner(int width, int height, int x0, int x1, int y0, int y1,
                  const SamplingSettings& settings);
    // The next pass, pixels in tile order (16x16 tiles, for coherent rays); empty when
    // every pixel has met the final quality. `pixelError` overrides the setting for this
    // pass (an error target or a time budget tightens it as the render goes on).
    // Pixels marked in `busy` (samples of theirs still in flight, when a pass is planned
    // while the last one's tail drains) are neither tested nor sampled: their film entries
    // are partial. The next pass tests them and their neighbours.
    // (The requests are valid until the next call.)
    const std::vector<PixelRequest>& nextPass(const FilmPixels& film, float pixelError,
                                              const std::vector<uint8_t>& busy = {});
    int passes() const { return m_pass; }
    // The last pass's brightness floor of the relative error: a tenth of the mean pixel
    // value (relativeErrorFloor), kept up to date from the pixels each pass changed.
    float lastFloor() const { return m_lastFloor; }
    // The mean the last pass used for a pixel (its own and as a neighbour): pixelMean of
    // its film entry then; negative for a pixel without samples.
    float meanUsed(uint32_t pixel) const { return m_meanOf[pixel]; }
    // After the first pass every pixel has the minimum; when that is also the maximum,
    // no later pass can add a sample (unless some were dropped as NaN/Inf), so the film
    // need not be read back to plan one.
    bool firstPassIsFinal() const {
        return m_pass > 0 && m_settings.minSamples >= m_settings.maxSamples;
    }
    const SamplingSettings& settings() const { return m_settings; }
    // Passes that test every pixel do so through `tester` (null: here); it must outlive
    // the planner's use.
    void setTester(PixelTester* tester) { m_tester = tester; }
    const std::vector<uint32_t>& pixelOrder() const { return m_tileOrder; }
    // Each pixel's place in pixelOrder(); ~0u off the crop window.
    const std::vector<uint32_t>& pixelRank() const { return m_tileRank; }

private:
    // For each of `count` pixels: its relative error (pixelRelativeError against `floor`)
    // and whether its mean differs from a neighbour's by more than the contrast setting.
    void measure(const FilmPixels& film, const uint32_t* pixels, size_t count, float floor,
                 float* relErr, uint8_t* edge) const;
    // A pixel with `n` samples, measured as above; sets *keptErr to the relative error when
    // it is tested (-inf when the pixel has its maximum: it never needs more).
    bool needsMore(uint32_t n, float relErr, bool edge, float pixelError, float* keptErr) const;
    // Pixels a pass must test: the last pass's pixels (sampled or left busy), and those
    // neighbours of the ones whose mean moved that now differ from them by more than the
    // contrast (a pixel whose film and neighbours' means are as when it was last tested
    // answers as it did, so "no"); empty when every pixel is to be tested.
    std::vector<uint8_t> pixelsToTest(bool all) const;
    // Calls f on every pixel of that set (some more than once). A neighbour of a pixel
    // whose mean moved answers as before unless the two means now differ by more than the
    // contrast (its samples, its error and its other neighbours are as when it answered
    // "no"): only those are tested again (SPD tetra at 9 samples a pixel visited 52k
    // pixels a pass, five times those it sampled).
    template <class F>
    void forEachToTest(F&& f) const {
        for (uint32_t pixel : m_lastPass) f(pixel);
        for (uint32_t pixel : m_meanMoved) {
            const std::array<uint32_t, 5> around = neighbourhood(pixel);
            for (int k = 1; k < 5; ++k)
                if (contrasts(m_meanOf[around[k]], m_meanOf[pixel])) f(around[k]);
        }
    }
    // Whether a pixel of mean m differs from a neighbour of mean mq by more than the
    // contrast setting (a neighbour without samples, mq < 0, never does; symmetric
    // otherwise, bit for bit).
    bool contrasts(float m, float mq) const {
        return mq >= 0.0f &&
               std::fabs(m - mq) > m_settings.contrast * std::max(0.1f, 0.5f * (m + mq));
    }
    // What decides each pixel's answer in a pass's visit of its pixels (nextPass).
    struct PassVisit {
        const FilmPixels& film;
        const std::vector<uint8_t>& busy;  // samples in flight: not tested, deferred
        const std::vector<uint8_t>& test;  // pixelsToTest; empty: every pixel is tested
        float floor, pixelError;
        bool floorFell;  // the brightness floor fell below the last pass's
    };
    // One thread's share of a visit: its requests, the pixels sampled and those left busy
    // (deferred: tested next pass, with their neighbours).
    struct PassPart {
        std::vector<PixelRequest> out;
        std::vector<uint32_t> sampled, deferred;
    };
    // Plans the pixels [begin, end) of a visit into `part`.
    void planPart(const PassVisit& v, const uint32_t* begin, const uint32_t* end,
                  PassPart& part);
    // Whether a pixel off the test set answers "no" again without a test: its error is
    // within the pass's pixel error and has not grown (or, under a fallen floor, grown by
    // at most the floors' ratio: that bound is then kept as its error).
    bool answersNoAgain(const PassVisit& v, uint32_t pixel);
    // Requests twice the pixel's samples, at least the minimum, at most the maximum.
    void requestMore(const PixelAccum& p, uint32_t pixel, PassPart& part) const;
    // The parts' requests into m_out and their pixels into m_lastPass, in order (sampled
    // ones first, then the deferred).
    void joinParts(const std::vector<PassPart>& parts);
    const std::vector<PixelRequest>& firstBlockPass();
    std::vector<uint32_t> testSetInTileOrder() const;
    // The pass the tester's test of every pixel gives.
    const std::vector<PixelRequest>& passFromTester(const FilmPixels& film, float floor,
                                                    float pixelError,
                                                    const std::vector<uint8_t>& busy);
    // The pass's requests (m_out), as the smallPass rule leaves them; the pass counted.
    const std::vector<PixelRequest>& endPass(const FilmPixels& film, float floor,
                                             float pixelError);
    // The smallPass rule on a pass's requests.
    void jumpSmallPass(const FilmPixels& film, std::vector<PixelRequest>& out) const;
    // Threads for a visit of this many pixels.
    size_t threadsFor(size_t pixels) const;
    // A pixel and its four neighbours (itself again at the image's border).
    std::array<uint32_t, 5> neighbourhood(uint32_t pixel) const;
    // relativeErrorFloor(film), updated from the pixels the last pass changed.
    float brightnessFloor(const FilmPixels& film);
    static constexpr uint32_t kOutside = ~0u;  // m_tileRank of a pixel off the crop window
    int m_width, m_height;
    SamplingSettings m_settings;
    std::vector<uint32_t> m_tileOrder;  // pixel indices in tile order
    std::vector<uint32_t> m_tileRank;   // each pixel's place in m_tileOrder
    int m_pass = 0;
    bool m_tested = false;  // an adaptive pass has tested every pixel (m_relErr, m_meanOf)
    bool m_meansByTester = false;  // m_meanOf as m_tester's means() gave them
    std::vector<uint32_t> m_lastPass;  // the pixels the last pass sampled or left busy
    // Those of them whose mean this pass's brightnessFloor found changed (a pixel left busy
    // pass after pass keeps its mean while its samples are in flight: its neighbours need
    // no new test; SPD teapot at 9 samples a pixel visited 40k pixels a pass, half of them
    // the busy ones' neighbours).
    std::vector<uint32_t> m_meanMoved;
    std::vector<float> m_relErr;       // each pixel's relative error when last tested
    float m_lastFloor = 0;
    float m_lastPixelError = 0;
    std::vector<float> m_meanOf;  // each pixel's mean in the floor's sum (< 0: not in it)
    double m_meanSum = 0, m_meanCount = 0;
    PixelTester* m_tester = nullptr;
    // The last pass's requests: their memory, first taken by the first pass (one or two
    // requests a pixel, while the scene is built), serves every later pass without a page
    // fault in the render loop.
    std::vector<PixelRequest> m_out;
};

}  // namespace rd
