// rib_builder_display.cpp: the RIB's image requests: Display (the image and its mode;
// secondary "+name" displays as files of AOVs), DisplayChannel (an AOV's type),
// PixelFilter and Quantize.
#include <algorithm>
#include <iterator>
#include <sstream>

#include "pixel_filter.h"
#include "rib_builder.h"

namespace rd {

void RibBuilder::pixelFilter(L loc, const std::string& filter, float xwidth,
                             float ywidth) {
    if (!(xwidth > 0) || !(ywidth > 0) || !(xwidth <= 64) || !(ywidth <= 64)) {
        m_diag.error(loc, "PixelFilter widths must be in (0, 64] pixels");
        return;
    }
    std::string name = filter;
    if (!pixelFilterKnown(name)) {
        m_diag.warning(loc, "PixelFilter \"" + filter +
                                "\" is not known (box, triangle, gaussian, catmull-rom, "
                                "separable-catmull-rom, sinc, mitchell, blackman-harris, "
                                "lanczos, disk, bessel); using gaussian");
        name = "gaussian";
    }
    Camera probe{};
    if (!setCameraFilter(probe, name, xwidth, ywidth))
        m_diag.warning(loc, "PixelFilter \"" + name + "\" changes sign more than " +
                                std::to_string(RT_FILTER_FLIPS) +
                                " times across its width; a box of that width is used");
    m_options.camera.pixelFilter = name;
    m_options.camera.filterWidth[0] = xwidth;
    m_options.camera.filterWidth[1] = ywidth;
}

void RibBuilder::quantize(L loc, const std::string& type, int one, int min, int max,
                          float dither) {
    if (type != "rgba") return;  // ("z": depth maps are floats)
    if (one < 0 || min > max || one > 65535 || !(dither >= 0 && dither <= 1e3f)) {
        m_diag.error(loc, "Quantize \"rgba\" " + std::to_string(one) + " " +
                              std::to_string(min) + " " + std::to_string(max) +
                              ": one must be in [0, 65535], min <= max, a dither >= 0");
        return;
    }
    m_options.quantize = {one, min, max, dither};
}

void RibBuilder::display(L loc, const std::string& name, const std::string& type,
                         const std::string& mode, const rib::ParamList&) {
    // A mode is a list: "rgba", "rgba,float mask", "color diffuse,z"; colour first.
    std::vector<std::string> entries = aovModeEntries(loc, mode);
    std::string colour;
    if (!entries.empty() && (entries[0] == "rgb" || entries[0] == "rgba" ||
                             entries[0] == "rgbz" || entries[0] == "rgbaz")) {
        colour = entries[0];
        entries.erase(entries.begin());
        if (colour.back() == 'z') {  // (RI's "rgbz", "rgbaz": the colour and depth)
            colour.pop_back();
            entries.insert(entries.begin(), "z");
        }
    }
    // The file's format follows its name (OpenEXR, or a picture: .tif, .png, .jpg ...),
    // a secondary display's too.
    static const char* known[] = {"file", "openexr", "exr",  "zfile", "shadow",
                                  "tiff", "png",     "jpeg", "targa"};
    if (std::none_of(std::begin(known), std::end(known),
                     [&](const char* k) { return type == k; }))
        m_diag.warning(loc, "display type \"" + type +
                                "\" is written as a file, in the format its name says");
    if (!name.empty() && name[0] == '+') {
        // A secondary display: a file of its own with the AOVs its mode names.
        if (name.size() == 1) {
            m_diag.warning(loc, "secondary display with no file name; ignored");
            return;
        }
        m_options.aovDisplays.push_back({name.substr(1), entries, colour, loc});
        return;
    }
    // "zfile" and "shadow" are depth maps (mode "z"): one channel Z and the camera's
    // matrices, for MakeShadow
    const bool depth = mode == "z" || type == "zfile" || type == "shadow";
    if (!depth && colour.empty() && !(mode.empty() && entries.empty()))
        m_diag.warning(loc, "display mode \"" + mode +
                                "\" has no rgb or rgba: written as rgba" +
                                (entries.empty() ? "" : " with its AOVs"));
    m_options.display = {name, type, depth ? "z" : colour == "rgb" ? "rgb" : "rgba", loc};
    if (depth) {
        m_options.aovs.push_back("z");
        return;
    }
    for (const std::string& a : entries) addAov(a);
}

std::vector<std::string> RibBuilder::aovModeEntries(L loc, const std::string& mode) {
    // Each entry is a name, or "[class] type name" (PRMan's inline declaration).
    std::vector<std::string> names;
    std::stringstream list(mode);
    for (std::string entry; std::getline(list, entry, ',');) {
        std::istringstream words(entry);
        std::vector<std::string> w;
        for (std::string x; words >> x;) w.push_back(x);
        if (w.empty()) continue;
        const std::string& aov = w.back();
        for (size_t i = 0; i + 1 < w.size(); ++i) {
            if (w[i] == "varying" || w[i] == "uniform") continue;
            if (w[i] == "float" || w[i] == "color" || w[i] == "point" ||
                w[i] == "vector" || w[i] == "normal")
                m_options.aovTypes[aov] = w[i];
            else
                m_diag.warning(loc, "AOV \"" + aov + "\": type \"" + w[i] +
                                        "\" is not an AOV type (float, color, point, "
                                        "vector, normal); ignored");
        }
        names.push_back(aov);
    }
    return names;
}

void RibBuilder::addAov(const std::string& name) {
    if (std::find(m_options.aovs.begin(), m_options.aovs.end(), name) ==
        m_options.aovs.end())
        m_options.aovs.push_back(name);
}

void RibBuilder::displayChannel(L loc, const std::string& channel,
                                const rib::ParamList&) {
    // "float z", "varying color diffuse": declares the channel's type; it is also
    // written into the image (as PRMan's channels are, once a display names them)
    for (const std::string& a : aovModeEntries(loc, channel)) addAov(a);
}

}  // namespace rd
