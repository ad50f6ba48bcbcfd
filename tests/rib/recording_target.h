// recording_target.h: a test Target that records every one of its calls (all the Target
// virtuals) as a line of text with every argument at full float precision, and the line
// of each call. Two readings give the same sequence of Target calls exactly when their
// `calls` vectors are equal; round-trip, binary and fuzz tests compare these.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "rib/target.h"

namespace ribtest {

using rib::ParamList;

class RecordingTarget : public rib::Target {
public:
    std::vector<std::string> calls;
    std::vector<int> lines;
    std::vector<std::string> files;

    static std::string str(float v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
        return buf;
    }
    static std::string str(int v) { return std::to_string(v); }
    static std::string str(bool v) { return v ? "true" : "false"; }
    static std::string str(const std::string& s) { return "\"" + s + "\""; }
    template <class T>
    static std::string str(const std::vector<T>& v) {
        std::string s = "[";
        for (const T& x : v) s += " " + str(x);
        return s + " ]";
    }
    static std::string arr(const float* v, int n) {
        return str(std::vector<float>(v, v + n));
    }
    static std::string str(const ParamList& pl) {
        std::string out = "{";
        for (const rib::Param& p : pl.params) {
            out += " " + p.name + ":" + rib::paramTypeName(p.type);
            if (p.arraySize > 1) out += "[" + std::to_string(p.arraySize) + "]";
            out += std::string(":") + rib::storageClassName(p.storage) + "=";
            if (p.type == rib::ParamType::String)
                out += str(p.strings);
            else if (p.type == rib::ParamType::Integer)
                out += str(p.ints);
            else
                out += str(p.floats);
        }
        return out + " }";
    }

    void add(L l, std::string s) {
        calls.push_back(std::move(s));
        lines.push_back(l.line);
        files.push_back(l.file);
    }

    void frameBegin(L l, int a1) override { add(l, std::string("frameBegin") + " " + str(a1)); }
    void frameEnd(L l) override { add(l, "frameEnd"); }
    void worldBegin(L l) override { add(l, "worldBegin"); }
    void worldEnd(L l) override { add(l, "worldEnd"); }
    void attributeBegin(L l) override { add(l, "attributeBegin"); }
    void attributeEnd(L l) override { add(l, "attributeEnd"); }
    void transformBegin(L l) override { add(l, "transformBegin"); }
    void transformEnd(L l) override { add(l, "transformEnd"); }
    void format(L l, int a1, int a2, float a3) override { add(l, std::string("format") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void frameAspectRatio(L l, float a1) override { add(l, std::string("frameAspectRatio") + " " + str(a1)); }
    void screenWindow(L l, float a1, float a2, float a3, float a4) override { add(l, std::string("screenWindow") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void projection(L l, const std::string& a1, const ParamList& a2) override { add(l, std::string("projection") + " " + str(a1) + " " + str(a2)); }
    void clipping(L l, float a1, float a2) override { add(l, std::string("clipping") + " " + str(a1) + " " + str(a2)); }
    void clippingPlane(L l, float a1, float a2, float a3, float a4, float a5,
                       float a6) override {
        add(l, std::string("clippingPlane") + " " + str(a1) + " " + str(a2) + " " +
                   str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6));
    }
    void camera(L l, S a1, const ParamList& a2) override {
        add(l, std::string("camera") + " " + str(a1) + " " + str(a2));
    }
    void pixelSamples(L l, float a1, float a2) override { add(l, std::string("pixelSamples") + " " + str(a1) + " " + str(a2)); }
    void displayChannel(L l, const std::string& a1, const ParamList& a2) override { add(l, std::string("displayChannel") + " " + str(a1) + " " + str(a2)); }
    void display(L l, const std::string& a1, const std::string& a2, const std::string& a3, const ParamList& a4) override { add(l, std::string("display") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void option(L l, const std::string& a1, const ParamList& a2) override { add(l, std::string("option") + " " + str(a1) + " " + str(a2)); }
    void attribute(L l, const std::string& a1, const ParamList& a2) override { add(l, std::string("attribute") + " " + str(a1) + " " + str(a2)); }
    void color(L l, const std::vector<float>& a1) override { add(l, std::string("color") + " " + str(a1)); }
    void opacity(L l, const std::vector<float>& a1) override { add(l, std::string("opacity") + " " + str(a1)); }
    void surface(L l, const std::string& a1, const ParamList& a2) override { add(l, std::string("surface") + " " + str(a1) + " " + str(a2)); }
    void lightSource(L l, const std::string& a1, const std::string& a2, const ParamList& a3) override { add(l, std::string("lightSource") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void illuminate(L l, const std::string& a1, bool a2) override { add(l, std::string("illuminate") + " " + str(a1) + " " + str(a2)); }
    void shadingRate(L l, float a1) override { add(l, std::string("shadingRate") + " " + str(a1)); }
    void sides(L l, int a1) override { add(l, std::string("sides") + " " + str(a1)); }
    void orientation(L l, const std::string& a1) override { add(l, std::string("orientation") + " " + str(a1)); }
    void reverseOrientation(L l) override { add(l, "reverseOrientation"); }
    void identity(L l) override { add(l, "identity"); }
    void transform(L l, const float a1[16]) override { add(l, std::string("transform") + " " + arr(a1, 16)); }
    void concatTransform(L l, const float a1[16]) override { add(l, std::string("concatTransform") + " " + arr(a1, 16)); }
    void translate(L l, float a1, float a2, float a3) override { add(l, std::string("translate") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void rotate(L l, float a1, float a2, float a3, float a4) override { add(l, std::string("rotate") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void scale(L l, float a1, float a2, float a3) override { add(l, std::string("scale") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void polygon(L l, const ParamList& a1) override { add(l, std::string("polygon") + " " + str(a1)); }
    void pointsPolygons(L l, const std::vector<int>& a1, const std::vector<int>& a2, const ParamList& a3) override { add(l, std::string("pointsPolygons") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void sphere(L l, float a1, float a2, float a3, float a4, const ParamList& a5) override { add(l, std::string("sphere") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5)); }
    void declare(L l, const std::string& a1, const std::string& a2) override { add(l, std::string("declare") + " " + str(a1) + " " + str(a2)); }
    void exposure(L l, float a1, float a2) override { add(l, std::string("exposure") + " " + str(a1) + " " + str(a2)); }
    void imager(L l, S a1, P a2) override { add(l, std::string("imager") + " " + str(a1) + " " + str(a2)); }
    void quantize(L l, S a1, int a2, int a3, int a4, float a5) override { add(l, std::string("quantize") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5)); }
    void pixelVariance(L l, float a1) override { add(l, std::string("pixelVariance") + " " + str(a1)); }
    void pixelFilter(L l, S a1, float a2, float a3) override { add(l, std::string("pixelFilter") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void hider(L l, S a1, P a2) override { add(l, std::string("hider") + " " + str(a1) + " " + str(a2)); }
    void colorSamples(L l, Floats a1, Floats a2) override { add(l, std::string("colorSamples") + " " + str(a1) + " " + str(a2)); }
    void relativeDetail(L l, float a1) override { add(l, std::string("relativeDetail") + " " + str(a1)); }
    void cropWindow(L l, float a1, float a2, float a3, float a4) override { add(l, std::string("cropWindow") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void depthOfField(L l, float a1, float a2, float a3) override { add(l, std::string("depthOfField") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void shutter(L l, float a1, float a2) override { add(l, std::string("shutter") + " " + str(a1) + " " + str(a2)); }
    void errorHandler(L l, S a1) override { add(l, std::string("errorHandler") + " " + str(a1)); }
    void matte(L l, bool a1) override { add(l, std::string("matte") + " " + str(a1)); }
    void shadingInterpolation(L l, S a1) override { add(l, std::string("shadingInterpolation") + " " + str(a1)); }
    void textureCoordinates(L l, float a1, float a2, float a3, float a4, float a5, float a6, float a7, float a8) override { add(l, std::string("textureCoordinates") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8)); }
    void bound(L l, const float a1[6]) override { add(l, std::string("bound") + " " + arr(a1, 6)); }
    void detail(L l, const float a1[6]) override { add(l, std::string("detail") + " " + arr(a1, 6)); }
    void detailRange(L l, float a1, float a2, float a3, float a4) override { add(l, std::string("detailRange") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void geometricApproximation(L l, S a1, float a2) override { add(l, std::string("geometricApproximation") + " " + str(a1) + " " + str(a2)); }
    void displacement(L l, S a1, P a2) override { add(l, std::string("displacement") + " " + str(a1) + " " + str(a2)); }
    void atmosphere(L l, S a1, P a2) override { add(l, std::string("atmosphere") + " " + str(a1) + " " + str(a2)); }
    void interior(L l, S a1, P a2) override { add(l, std::string("interior") + " " + str(a1) + " " + str(a2)); }
    void exterior(L l, S a1, P a2) override { add(l, std::string("exterior") + " " + str(a1) + " " + str(a2)); }
    void deformation(L l, S a1, P a2) override { add(l, std::string("deformation") + " " + str(a1) + " " + str(a2)); }
    void areaLightSource(L l, S a1, S a2, P a3) override { add(l, std::string("areaLightSource") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
    void basis(L l, S a1, const float a2[16], int a3, S a4, const float a5[16], int a6) override { add(l, std::string("basis") + " " + str(a1) + " " + arr(a2, 16) + " " + str(a3) + " " + str(a4) + " " + arr(a5, 16) + " " + str(a6)); }
    void trimCurve(L l, Ints a1, Ints a2, Floats a3, Floats a4, Floats a5, Ints a6, Floats a7, Floats a8, Floats a9) override { add(l, std::string("trimCurve") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8) + " " + str(a9)); }
    void perspective(L l, float a1) override { add(l, std::string("perspective") + " " + str(a1)); }
    void skew(L l, float a1, float a2, float a3, float a4, float a5, float a6, float a7) override { add(l, std::string("skew") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7)); }
    void coordinateSystem(L l, S a1) override { add(l, std::string("coordinateSystem") + " " + str(a1)); }
    void scopedCoordinateSystem(L l, S a1) override { add(l, std::string("scopedCoordinateSystem") + " " + str(a1)); }
    void resourceBegin(L l) override { add(l, "resourceBegin"); }
    void resourceEnd(L l) override { add(l, "resourceEnd"); }
    void resource(L l, S a1, S a2, P p) override {
        add(l, std::string("resource") + " " + str(a1) + " " + str(a2) + " " + str(p));
    }
    void coordSysTransform(L l, S a1) override { add(l, std::string("coordSysTransform") + " " + str(a1)); }
    void motionBegin(L l, Floats a1) override { add(l, std::string("motionBegin") + " " + str(a1)); }
    void motionEnd(L l) override { add(l, "motionEnd"); }
    void solidBegin(L l, S a1) override { add(l, std::string("solidBegin") + " " + str(a1)); }
    void solidEnd(L l) override { add(l, "solidEnd"); }
    void objectBegin(L l, S a1) override { add(l, std::string("objectBegin") + " " + str(a1)); }
    void objectEnd(L l) override { add(l, "objectEnd"); }
    void objectInstance(L l, S a1) override { add(l, std::string("objectInstance") + " " + str(a1)); }
    void archiveBegin(L l, S a1, P a2) override { add(l, std::string("archiveBegin") + " " + str(a1) + " " + str(a2)); }
    void archiveEnd(L l) override { add(l, "archiveEnd"); }
    void readArchive(L l, S a1, P a2) override { add(l, std::string("readArchive") + " " + str(a1) + " " + str(a2)); }
    void generalPolygon(L l, Ints a1, P a2) override { add(l, std::string("generalPolygon") + " " + str(a1) + " " + str(a2)); }
    void pointsGeneralPolygons(L l, Ints a1, Ints a2, Ints a3, P a4) override { add(l, std::string("pointsGeneralPolygons") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void patch(L l, S a1, P a2) override { add(l, std::string("patch") + " " + str(a1) + " " + str(a2)); }
    void patchMesh(L l, S a1, int a2, S a3, int a4, S a5, P a6) override { add(l, std::string("patchMesh") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6)); }
    void nuPatch(L l, int a1, int a2, Floats a3, float a4, float a5, int a6, int a7, Floats a8, float a9, float a10, P a11) override { add(l, std::string("nuPatch") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8) + " " + str(a9) + " " + str(a10) + " " + str(a11)); }
    void subdivisionMesh(L l, S a1, Ints a2, Ints a3, Strings a4, Ints a5, Ints a6, Floats a7, P a8) override { add(l, std::string("subdivisionMesh") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8)); }
    void cylinder(L l, float a1, float a2, float a3, float a4, P a5) override { add(l, std::string("cylinder") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5)); }
    void cone(L l, float a1, float a2, float a3, P a4) override { add(l, std::string("cone") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void disk(L l, float a1, float a2, float a3, P a4) override { add(l, std::string("disk") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void torus(L l, float a1, float a2, float a3, float a4, float a5, P a6) override { add(l, std::string("torus") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6)); }
    void paraboloid(L l, float a1, float a2, float a3, float a4, P a5) override { add(l, std::string("paraboloid") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5)); }
    void hyperboloid(L l, const float a1[3], const float a2[3], float a3, P a4) override { add(l, std::string("hyperboloid") + " " + arr(a1, 3) + " " + arr(a2, 3) + " " + str(a3) + " " + str(a4)); }
    void curves(L l, S a1, Ints a2, S a3, P a4) override { add(l, std::string("curves") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4)); }
    void points(L l, P a1) override { add(l, std::string("points") + " " + str(a1)); }
    void blobby(L l, int a1, Ints a2, Floats a3, Strings a4, P a5) override { add(l, std::string("blobby") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5)); }
    void geometry(L l, S a1, P a2) override { add(l, std::string("geometry") + " " + str(a1) + " " + str(a2)); }
    void procedural(L l, S a1, Strings a2, const float a3[6]) override { add(l, std::string("procedural") + " " + str(a1) + " " + str(a2) + " " + arr(a3, 6)); }
    void makeTexture(L l, S a1, S a2, S a3, S a4, S a5, float a6, float a7, P a8) override { add(l, std::string("makeTexture") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8)); }
    void makeBump(L l, S a1, S a2, S a3, S a4, S a5, float a6, float a7, P a8) override { add(l, std::string("makeBump") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7) + " " + str(a8)); }
    void makeLatLongEnvironment(L l, S a1, S a2, S a3, float a4, float a5, P a6) override { add(l, std::string("makeLatLongEnvironment") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6)); }
    void makeCubeFaceEnvironment(L l, Strings a1, S a2, float a3, S a4, float a5, float a6, P a7) override { add(l, std::string("makeCubeFaceEnvironment") + " " + str(a1) + " " + str(a2) + " " + str(a3) + " " + str(a4) + " " + str(a5) + " " + str(a6) + " " + str(a7)); }
    void makeShadow(L l, S a1, S a2, P a3) override { add(l, std::string("makeShadow") + " " + str(a1) + " " + str(a2) + " " + str(a3)); }
};

}  // namespace ribtest
