// writer.h: RibWriter, a Target that writes every call back out as RIB (ASCII, or binary
// encoded), so that reading its output gives the same sequence of calls: parameters
// carry inline declarations ("uniform color Cs"), numbers are written to full float
// precision, named bases and the bare DepthOfField keep their short forms. Read with
// ReadOptions::expandArchives = false to keep ReadArchive/ArchiveBegin as they were.
#pragma once
#include <memory>
#include <ostream>

#include "emitter.h"
#include "target.h"

namespace rib {

class RibWriter : public Target {
public:
    enum class Encoding { Ascii, Binary };
    explicit RibWriter(std::ostream& out, Encoding encoding = Encoding::Ascii);
    ~RibWriter() override;
    // Ends the last line and flushes; also done by the destructor.
    void finish();
    // RiArchiveRecord: "comment" writes "# text", "structure" "##text", "verbatim" the
    // text itself, each on lines of their own (a newline in the text starts another line;
    // a comment's next lines are comments too). Not a Target call: a reader skips
    // comments.
    void record(const std::string& type, const std::string& text);

    void frameBegin(L, int) override;
    void frameEnd(L) override;
    void worldBegin(L) override;
    void worldEnd(L) override;
    void attributeBegin(L) override;
    void attributeEnd(L) override;
    void transformBegin(L) override;
    void transformEnd(L) override;
    void format(L, int, int, float) override;
    void frameAspectRatio(L, float) override;
    void screenWindow(L, float, float, float, float) override;
    void projection(L, const std::string&, const ParamList&) override;
    void clipping(L, float, float) override;
    void clippingPlane(L, float, float, float, float, float, float) override;
    void camera(L, S, P) override;
    void pixelSamples(L, float, float) override;
    void display(L, const std::string&, const std::string&, const std::string&, const ParamList&) override;
    void displayChannel(L, const std::string&, const ParamList&) override;
    void option(L, const std::string&, const ParamList&) override;
    void attribute(L, const std::string&, const ParamList&) override;
    void color(L, const std::vector<float>&) override;
    void opacity(L, const std::vector<float>&) override;
    void surface(L, const std::string&, const ParamList&) override;
    void lightSource(L, const std::string&, const std::string&, const ParamList&) override;
    void illuminate(L, const std::string&, bool) override;
    void shadingRate(L, float) override;
    void sides(L, int) override;
    void orientation(L, const std::string&) override;
    void reverseOrientation(L) override;
    void identity(L) override;
    void transform(L, const float [16]) override;
    void concatTransform(L, const float [16]) override;
    void translate(L, float, float, float) override;
    void rotate(L, float, float, float, float) override;
    void scale(L, float, float, float) override;
    void polygon(L, const ParamList&) override;
    void pointsPolygons(L, const std::vector<int>&, const std::vector<int>&, const ParamList&) override;
    void sphere(L, float, float, float, float, const ParamList&) override;
    void declare(L, const std::string&, const std::string&) override;
    void exposure(L, float, float) override;
    void imager(L, S, P) override;
    void quantize(L, S, int, int, int, float) override;
    void pixelVariance(L, float) override;
    void pixelFilter(L, S, float, float) override;
    void hider(L, S, P) override;
    void colorSamples(L, Floats, Floats) override;
    void relativeDetail(L, float) override;
    void cropWindow(L, float, float, float, float) override;
    void depthOfField(L, float, float, float) override;
    void shutter(L, float, float) override;
    void errorHandler(L, S) override;
    void matte(L, bool) override;
    void shadingInterpolation(L, S) override;
    void geometricRepresentation(L, S) override;
    void textureCoordinates(L, float, float, float, float, float, float, float, float) override;
    void bound(L, const float [6]) override;
    void detail(L, const float [6]) override;
    void detailRange(L, float, float, float, float) override;
    void geometricApproximation(L, S, float) override;
    void displacement(L, S, P) override;
    void atmosphere(L, S, P) override;
    void interior(L, S, P) override;
    void exterior(L, S, P) override;
    void deformation(L, S, P) override;
    void areaLightSource(L, S, S, P) override;
    void basis(L, S, const float [16], int, S, const float [16], int) override;
    void trimCurve(L, Ints, Ints, Floats, Floats, Floats, Ints, Floats, Floats, Floats) override;
    void perspective(L, float) override;
    void skew(L, float, float, float, float, float, float, float) override;
    void coordinateSystem(L, S) override;
    void scopedCoordinateSystem(L, S) override;
    void resourceBegin(L) override;
    void resourceEnd(L) override;
    void resource(L, S, S, P) override;
    void coordSysTransform(L, S) override;
    void motionBegin(L, Floats) override;
    void motionEnd(L) override;
    void solidBegin(L, S) override;
    void solidEnd(L) override;
    void objectBegin(L, S) override;
    void objectEnd(L) override;
    void objectInstance(L, S) override;
    void archiveBegin(L, S, P) override;
    void archiveEnd(L) override;
    void readArchive(L, S, P) override;
    void generalPolygon(L, Ints, P) override;
    void pointsGeneralPolygons(L, Ints, Ints, Ints, P) override;
    void patch(L, S, P) override;
    void patchMesh(L, S, int, S, int, S, P) override;
    void nuPatch(L, int, int, Floats, float, float, int, int, Floats, float, float, P) override;
    void subdivisionMesh(L, S, Ints, Ints, Strings, Ints, Ints, Floats, P) override;
    void cylinder(L, float, float, float, float, P) override;
    void cone(L, float, float, float, P) override;
    void disk(L, float, float, float, P) override;
    void torus(L, float, float, float, float, float, P) override;
    void paraboloid(L, float, float, float, float, P) override;
    void hyperboloid(L, const float [3], const float [3], float, P) override;
    void curves(L, S, Ints, S, P) override;
    void points(L, P) override;
    void blobby(L, int, Ints, Floats, Strings, P) override;
    void geometry(L, S, P) override;
    void procedural(L, S, Strings, const float [6]) override;
    void makeTexture(L, S, S, S, S, S, float, float, P) override;
    void makeBump(L, S, S, S, S, S, float, float, P) override;
    void makeLatLongEnvironment(L, S, S, S, float, float, P) override;
    void makeCubeFaceEnvironment(L, Strings, S, float, S, float, float, P) override;
    void makeShadow(L, S, S, P) override;
private:
    void req(const char* name);
    void params(const ParamList& params);
    void basisArg(const std::string& name, const float m[16]);
    std::unique_ptr<Emitter> m_e;
    int m_indent = 0;
    bool m_finished = false;
};

}  // namespace rib
