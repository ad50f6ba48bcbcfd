// imager_stage.cpp: uploads the resolved pixels, runs imager_apply, reads them back.
#include "imager_stage.h"

namespace rd {

std::vector<Rgba> applyImager(const ClContext& ctx, cl_program program, Profiler& prof,
                              const Film& film, const DeviceBuffer<float>& params) {
    std::vector<Rgba> pixels = film.means();
    static_assert(sizeof(Rgba) == sizeof(rt_float4), "Rgba travels as float4");
    std::vector<rt_float4> data(pixels.size());
    for (size_t i = 0; i < pixels.size(); ++i)
        data[i] = {pixels[i].r, pixels[i].g, pixels[i].b, pixels[i].a};
    DeviceBuffer<rt_float4> buf(ctx, data, CL_MEM_READ_WRITE);  // the imager writes it
    Kernel imager(ctx, program, "imager_apply", prof);
    imager.launch(data.size(), cl_uint(film.width), cl_uint(data.size()), buf, params);
    data = buf.download();
    imager.collectActive();
    for (size_t i = 0; i < pixels.size(); ++i)
        pixels[i] = {data[i].x, data[i].y, data[i].z, data[i].w};
    return pixels;
}

}  // namespace rd
