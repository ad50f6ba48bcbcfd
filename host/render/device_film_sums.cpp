// device_film_sums.cpp: the end-of-frame film sums on the device (device_film_sums.h).
#include "device_film_sums.h"

#include "film/film_error_batch.h"

namespace rd {

namespace {
size_t batchesOf(size_t pixels) { return (pixels + kPixelBatch - 1) / kPixelBatch; }
}  // namespace

DeviceFilmSums::DeviceFilmSums(const ClContext& ctx, cl_program program, Profiler& prof,
                               const DeviceBuffer<PixelAccum>& filmBuf, const Film& film)
    : m_filmBuf(filmBuf),
      m_count(cl_uint(film.pixels.size())),
      m_width(cl_uint(film.width)),
      m_sums(ctx, program, "film_sums", prof),
      m_sumsHost(3 * batchesOf(film.pixels.size())),
      m_countsHost(4 * batchesOf(film.pixels.size())),
      m_tallyHost(2 * batchesOf(film.pixels.size())),
      m_sumsBuf(ctx, m_sumsHost),
      m_countsBuf(ctx, m_countsHost),
      m_tallyBuf(ctx, m_tallyHost) {
    const bool window = film.cropX1 > 0;  // (else every pixel counts)
    m_crop = {{cl_uint(window ? film.cropX0 : 0), cl_uint(window ? film.cropX1 : film.width),
               cl_uint(window ? film.cropY0 : 0),
               cl_uint(window ? film.cropY1 : film.height)}};
}

void DeviceFilmSums::launch() {
    m_sums.launch(batchesOf(m_count), m_count, m_width, m_crop, m_filmBuf, m_sumsBuf,
                  m_countsBuf, m_tallyBuf);
    m_sumsBuf.syncToHost(/*blocking=*/false);
    m_countsBuf.syncToHost(/*blocking=*/false);
    m_tallyBuf.syncToHost(/*blocking=*/false);
}

FilmSummary DeviceFilmSums::summary() const {
    const size_t batches = batchesOf(m_count);
    std::vector<FilmErrorSums> part(batches);
    FilmSummary s;
    for (size_t b = 0; b < batches; ++b) {
        part[b].var = m_sumsHost[3 * b];
        part[b].mean = m_sumsHost[3 * b + 1];
        part[b].replicateVar = m_sumsHost[3 * b + 2];
        part[b].withVar = m_countsHost[4 * b];
        part[b].withMean = m_countsHost[4 * b + 1];
        part[b].withReplicates = m_countsHost[4 * b + 2];
        s.tally.unsampled += m_countsHost[4 * b + 3];
        s.tally.samples += m_tallyHost[2 * b];
        s.tally.nonfinite += m_tallyHost[2 * b + 1];
    }
    s.error = filmErrorOfBatches(part);
    return s;
}

}  // namespace rd
