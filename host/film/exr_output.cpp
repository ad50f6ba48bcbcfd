// exr_output.cpp: OpenEXR writing and reading through the OpenEXR library.
#include "exr_output.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <cstdio>
#include <stdexcept>

#include "replace_file.h"
#include "run_in_parts.h"

namespace rd {

void writeExr(const std::string& path, int width, int height, const std::vector<Rgba>& pixels,
              const ExrOptions& options) {
    if (width <= 0 || height <= 0 || pixels.size() != size_t(width) * size_t(height))
        throw std::runtime_error("cannot write " + path + ": bad image size");
    try {
        writeReplacing(path, [&](const std::string& tmp) {
            Imath::Box2i display(
                Imath::V2i(0, 0),
                Imath::V2i((options.displayWidth ? options.displayWidth : width) - 1,
                           (options.displayHeight ? options.displayHeight : height) - 1));
            Imath::Box2i data(
                Imath::V2i(options.dataX, options.dataY),
                Imath::V2i(options.dataX + width - 1, options.dataY + height - 1));
            Imf::Header header(display, data);
            header.compression() = Imf::ZIP_COMPRESSION;
            for (const auto& [k, v] : options.metadata)
                header.insert(k, Imf::StringAttribute(v));
            for (const auto& [k, m] : options.matrices)
                header.insert(k, Imf::M44fAttribute(Imath::M44f(
                                     m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8],
                                     m[9], m[10], m[11], m[12], m[13], m[14], m[15])));
            Imf::PixelType type = options.halfFloat ? Imf::HALF : Imf::FLOAT;
            const char* names[] = {"R", "G", "B", "A"};
            int channels = !options.colour ? 0 : options.alpha ? 4 : 3;
            for (int c = 0; c < channels; ++c)
                header.channels().insert(names[c], Imf::Channel(type));
            // OpenEXR does not convert on write: a HALF channel needs a half buffer.
            Imf::FrameBuffer fb;
            std::vector<Imath::half> halves;
            if (options.halfFloat) {
                halves.resize(pixels.size() * 4);
                for (size_t i = 0; i < pixels.size(); ++i) {
                    const float* p = &pixels[i].r;
                    for (int c = 0; c < 4; ++c) halves[4 * i + c] = Imath::half(p[c]);
                }
            }
            size_t comp = options.halfFloat ? sizeof(Imath::half) : sizeof(float);
            // OpenEXR addresses pixel (x, y) of the data window at base + x*xs + y*ys.
            const ptrdiff_t origin =
                ptrdiff_t(options.dataX) + ptrdiff_t(options.dataY) * width;
            char* base =
                (options.halfFloat
                     ? reinterpret_cast<char*>(halves.data())
                     : reinterpret_cast<char*>(const_cast<Rgba*>(pixels.data()))) -
                origin * ptrdiff_t(4 * comp);
            for (int c = 0; c < channels; ++c)
                fb.insert(names[c], Imf::Slice(type, base + c * comp, 4 * comp,
                                               4 * comp * size_t(width)));
            for (const Channel& c : options.extra) {
                if (c.values.size() != pixels.size())
                    throw std::runtime_error("AOV channel " + c.name +
                                             " has the wrong size");
                header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
                fb.insert(c.name,
                          Imf::Slice(Imf::FLOAT,
                                     reinterpret_cast<char*>(
                                         const_cast<float*>(c.values.data())) -
                                         origin * ptrdiff_t(sizeof(float)),
                                     sizeof(float), sizeof(float) * size_t(width)));
            }
            {
                // Its ZIP blocks compressed on the host's cores: a 512x512 RGBA image
                // took 57 ms on one, a fifth of an SPD scene's whole command.
                if (Imf::globalThreadCount() == 0)
                    Imf::setGlobalThreadCount(int(hostThreads()));
                Imf::OutputFile file(tmp.c_str(), header);
                file.setFrameBuffer(fb);
                file.writePixels(height);
            }
        });
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot write " + path + ": " + e.what());
    }
}

std::vector<Rgba> readExr(const std::string& path, int& width, int& height) {
    try {
        Imf::InputFile file(path.c_str());
        Imath::Box2i dw = file.header().dataWindow();
        width = dw.max.x - dw.min.x + 1;
        height = dw.max.y - dw.min.y + 1;
        std::vector<Rgba> px(size_t(width) * size_t(height), Rgba{0, 0, 0, 1});
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(px.data()) -
                     (size_t(dw.min.x) + size_t(dw.min.y) * size_t(width)) * sizeof(Rgba);
        const char* names[] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(Rgba),
                                           sizeof(Rgba) * size_t(width), 1, 1,
                                           c == 3 ? 1.0 : 0.0));
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return px;
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot read " + path + ": " + e.what());
    }
}

}  // namespace rd
