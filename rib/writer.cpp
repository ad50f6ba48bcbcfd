// writer.cpp: RibWriter. One method per Target virtual, each writing its request's name
// and then its arguments in the order the reader's requests.def signature expects them
// (a1, a2, ... are the arguments in that order), then the parameter list.
#include "writer.h"

#include <cmath>

#include "param_decl.h"

namespace rib {

RibWriter::RibWriter(std::ostream& out, Encoding encoding) {
    if (encoding == Encoding::Binary)
        m_e = std::make_unique<BinaryEmitter>(out);
    else
        m_e = std::make_unique<AsciiEmitter>(out);
}

RibWriter::~RibWriter() {
    finish();
}

void RibWriter::finish() {
    if (m_finished) return;
    m_finished = true;
    m_e->finish();
}

void RibWriter::record(const std::string& type, const std::string& text) {
    const std::string lead = type == "comment" ? "# " : type == "structure" ? "##" : "";
    size_t start = 0;
    while (start <= text.size()) {
        size_t end = text.find_first_of("\r\n", start);
        if (end == std::string::npos) end = text.size();
        const std::string piece = text.substr(start, end - start);
        if (!piece.empty() || text.empty())
            m_e->line(lead + piece, m_indent > 0 ? m_indent : 0);
        if (end == text.size()) break;
        start = end + 1;
    }
}

void RibWriter::req(const char* name) {
    m_e->request(name, m_indent > 0 ? m_indent : 0);
}

void RibWriter::params(const ParamList& pl) {
    for (const Param& p : pl.params) {
        std::string decl = std::string(storageClassName(p.storage)) + " " +
                           paramTypeName(p.type);
        if (p.arraySize > 1) decl += "[" + std::to_string(p.arraySize) + "]";
        m_e->string(decl + " " + p.name);
        if (p.type == ParamType::String)
            m_e->stringArray(p.strings);
        else if (p.type == ParamType::Integer)
            m_e->intArray(p.ints);
        else
            m_e->floatArray(p.floats);
    }
}

void RibWriter::basisArg(const std::string& name, const float m[16]) {
    if (!name.empty())
        m_e->string(name);
    else
        m_e->floatArray(std::vector<float>(m, m + 16));
}

void RibWriter::frameBegin(L, int a1) {
    req("FrameBegin");
    m_e->integer(a1);
    ++m_indent;
}

void RibWriter::frameEnd(L) {
    --m_indent;
    req("FrameEnd");
}

void RibWriter::worldBegin(L) {
    req("WorldBegin");
    ++m_indent;
}

void RibWriter::worldEnd(L) {
    --m_indent;
    req("WorldEnd");
}

void RibWriter::attributeBegin(L) {
    req("AttributeBegin");
    ++m_indent;
}

void RibWriter::attributeEnd(L) {
    --m_indent;
    req("AttributeEnd");
}

void RibWriter::transformBegin(L) {
    req("TransformBegin");
    ++m_indent;
}

void RibWriter::transformEnd(L) {
    --m_indent;
    req("TransformEnd");
}

void RibWriter::format(L, int a1, int a2, float a3) {
    req("Format");
    m_e->integer(a1);
    m_e->integer(a2);
    m_e->number(a3);
}

void RibWriter::frameAspectRatio(L, float a1) {
    req("FrameAspectRatio");
    m_e->number(a1);
}

void RibWriter::screenWindow(L, float a1, float a2, float a3, float a4) {
    req("ScreenWindow");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
}

void RibWriter::projection(L, const std::string& a1, const ParamList& a2) {
    req("Projection");
    m_e->string(a1);
    params(a2);
}

void RibWriter::clipping(L, float a1, float a2) {
    req("Clipping");
    m_e->number(a1);
    m_e->number(a2);
}

void RibWriter::clippingPlane(L, float x, float y, float z, float nx, float ny,
                              float nz) {
    req("ClippingPlane");
    for (float v : {x, y, z, nx, ny, nz}) m_e->number(v);
}

void RibWriter::camera(L, S name, P params) {
    req("Camera");
    m_e->string(name);
    this->params(params);
}

void RibWriter::pixelSamples(L, float a1, float a2) {
    req("PixelSamples");
    m_e->number(a1);
    m_e->number(a2);
}

void RibWriter::display(L, const std::string& a1, const std::string& a2, const std::string& a3, const ParamList& a4) {
    req("Display");
    m_e->string(a1);
    m_e->string(a2);
    m_e->string(a3);
    params(a4);
}

void RibWriter::displayChannel(L, const std::string& a1, const ParamList& a2) {
    req("DisplayChannel");
    m_e->string(a1);
    params(a2);
}

void RibWriter::option(L, const std::string& a1, const ParamList& a2) {
    req("Option");
    m_e->string(a1);
    params(a2);
}

void RibWriter::attribute(L, const std::string& a1, const ParamList& a2) {
    req("Attribute");
    m_e->string(a1);
    params(a2);
}

void RibWriter::color(L, const std::vector<float>& a1) {
    req("Color");
    m_e->floatArray(a1);
}

void RibWriter::opacity(L, const std::vector<float>& a1) {
    req("Opacity");
    m_e->floatArray(a1);
}

void RibWriter::surface(L, const std::string& a1, const ParamList& a2) {
    req("Surface");
    m_e->string(a1);
    params(a2);
}

void RibWriter::lightSource(L, const std::string& a1, const std::string& a2, const ParamList& a3) {
    req("LightSource");
    m_e->string(a1);
    m_e->string(a2);
    params(a3);
}

void RibWriter::illuminate(L, const std::string& a1, bool a2) {
    req("Illuminate");
    m_e->string(a1);
    m_e->integer(a2 ? 1 : 0);
}

void RibWriter::shadingRate(L, float a1) {
    req("ShadingRate");
    m_e->number(a1);
}

void RibWriter::sides(L, int a1) {
    req("Sides");
    m_e->integer(a1);
}

void RibWriter::orientation(L, const std::string& a1) {
    req("Orientation");
    m_e->string(a1);
}

void RibWriter::reverseOrientation(L) {
    req("ReverseOrientation");
}

void RibWriter::identity(L) {
    req("Identity");
}

void RibWriter::transform(L, const float a1[16]) {
    req("Transform");
    m_e->floatArray(std::vector<float>(a1, a1 + 16));
}

void RibWriter::concatTransform(L, const float a1[16]) {
    req("ConcatTransform");
    m_e->floatArray(std::vector<float>(a1, a1 + 16));
}

void RibWriter::translate(L, float a1, float a2, float a3) {
    req("Translate");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
}

void RibWriter::rotate(L, float a1, float a2, float a3, float a4) {
    req("Rotate");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
}

void RibWriter::scale(L, float a1, float a2, float a3) {
    req("Scale");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
}

void RibWriter::declare(L, const std::string& a1, const std::string& a2) {
    req("Declare");
    m_e->string(a1);
    m_e->string(a2);
}

void RibWriter::exposure(L, float a1, float a2) {
    req("Exposure");
    m_e->number(a1);
    m_e->number(a2);
}

void RibWriter::imager(L, S a1, P a2) {
    req("Imager");
    m_e->string(a1);
    params(a2);
}

void RibWriter::quantize(L, S a1, int a2, int a3, int a4, float a5) {
    req("Quantize");
    m_e->string(a1);
    m_e->integer(a2);
    m_e->integer(a3);
    m_e->integer(a4);
    m_e->number(a5);
}

void RibWriter::pixelVariance(L, float a1) {
    req("PixelVariance");
    m_e->number(a1);
}

void RibWriter::pixelFilter(L, S a1, float a2, float a3) {
    req("PixelFilter");
    m_e->string(a1);
    m_e->number(a2);
    m_e->number(a3);
}

void RibWriter::hider(L, S a1, P a2) {
    req("Hider");
    m_e->string(a1);
    params(a2);
}

void RibWriter::colorSamples(L, Floats a1, Floats a2) {
    req("ColorSamples");
    m_e->floatArray(a1);
    m_e->floatArray(a2);
}

void RibWriter::relativeDetail(L, float a1) {
    req("RelativeDetail");
    m_e->number(a1);
}

void RibWriter::cropWindow(L, float a1, float a2, float a3, float a4) {
    req("CropWindow");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
}

void RibWriter::depthOfField(L, float a1, float a2, float a3) {
    req("DepthOfField");
    if (std::isinf(a1) && a1 > 0 && a2 == 0 && a3 == 0) return;  // bare form: pinhole
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
}

void RibWriter::shutter(L, float a1, float a2) {
    req("Shutter");
    m_e->number(a1);
    m_e->number(a2);
}

void RibWriter::errorHandler(L, S a1) {
    req("ErrorHandler");
    m_e->string(a1);
}

void RibWriter::matte(L, bool a1) {
    req("Matte");
    m_e->integer(a1 ? 1 : 0);
}

void RibWriter::shadingInterpolation(L, S a1) {
    req("ShadingInterpolation");
    m_e->string(a1);
}

void RibWriter::geometricRepresentation(L, S a1) {
    req("GeometricRepresentation");
    m_e->string(a1);
}

void RibWriter::textureCoordinates(L, float a1, float a2, float a3, float a4, float a5, float a6, float a7, float a8) {
    req("TextureCoordinates");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    m_e->number(a5);
    m_e->number(a6);
    m_e->number(a7);
    m_e->number(a8);
}

void RibWriter::bound(L, const float a1[6]) {
    req("Bound");
    m_e->floatArray(std::vector<float>(a1, a1 + 6));
}

void RibWriter::detail(L, const float a1[6]) {
    req("Detail");
    m_e->floatArray(std::vector<float>(a1, a1 + 6));
}

void RibWriter::detailRange(L, float a1, float a2, float a3, float a4) {
    req("DetailRange");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
}

void RibWriter::geometricApproximation(L, S a1, float a2) {
    req("GeometricApproximation");
    m_e->string(a1);
    m_e->number(a2);
}

void RibWriter::displacement(L, S a1, P a2) {
    req("Displacement");
    m_e->string(a1);
    params(a2);
}

void RibWriter::atmosphere(L, S a1, P a2) {
    req("Atmosphere");
    m_e->string(a1);
    params(a2);
}

void RibWriter::interior(L, S a1, P a2) {
    req("Interior");
    m_e->string(a1);
    params(a2);
}

void RibWriter::exterior(L, S a1, P a2) {
    req("Exterior");
    m_e->string(a1);
    params(a2);
}

void RibWriter::deformation(L, S a1, P a2) {
    req("Deformation");
    m_e->string(a1);
    params(a2);
}

void RibWriter::areaLightSource(L, S a1, S a2, P a3) {
    req("AreaLightSource");
    m_e->string(a1);
    m_e->string(a2);
    params(a3);
}

void RibWriter::perspective(L, float a1) {
    req("Perspective");
    m_e->number(a1);
}

void RibWriter::skew(L, float a1, float a2, float a3, float a4, float a5, float a6, float a7) {
    req("Skew");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    m_e->number(a5);
    m_e->number(a6);
    m_e->number(a7);
}

void RibWriter::coordinateSystem(L, S a1) {
    req("CoordinateSystem");
    m_e->string(a1);
}

void RibWriter::scopedCoordinateSystem(L, S a1) {
    req("ScopedCoordinateSystem");
    m_e->string(a1);
}

void RibWriter::resourceBegin(L) {
    req("ResourceBegin");
    ++m_indent;
}

void RibWriter::resourceEnd(L) {
    --m_indent;
    req("ResourceEnd");
}

void RibWriter::resource(L, S name, S type, P p) {
    req("Resource");
    m_e->string(name);
    m_e->string(type);
    params(p);
}

void RibWriter::coordSysTransform(L, S a1) {
    req("CoordSysTransform");
    m_e->string(a1);
}

void RibWriter::motionBegin(L, Floats a1) {
    req("MotionBegin");
    m_e->floatArray(a1);
    ++m_indent;
}

void RibWriter::motionEnd(L) {
    --m_indent;
    req("MotionEnd");
}

void RibWriter::solidBegin(L, S a1) {
    req("SolidBegin");
    m_e->string(a1);
    ++m_indent;
}

void RibWriter::solidEnd(L) {
    --m_indent;
    req("SolidEnd");
}

void RibWriter::objectBegin(L, S a1) {
    req("ObjectBegin");
    m_e->string(a1);
    ++m_indent;
}

void RibWriter::objectEnd(L) {
    --m_indent;
    req("ObjectEnd");
}

void RibWriter::objectInstance(L, S a1) {
    req("ObjectInstance");
    m_e->string(a1);
}

void RibWriter::archiveBegin(L, S a1, P a2) {
    req("ArchiveBegin");
    m_e->string(a1);
    params(a2);
    ++m_indent;
}

void RibWriter::archiveEnd(L) {
    --m_indent;
    req("ArchiveEnd");
}

void RibWriter::readArchive(L, S a1, P a2) {
    req("ReadArchive");
    m_e->string(a1);
    params(a2);
}

}  // namespace rib
