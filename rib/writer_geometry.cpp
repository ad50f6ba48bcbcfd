// writer_geometry.cpp: RibWriter's geometry, Basis/TrimCurve and texture-making
// requests (the rest are in writer.cpp). Arguments a1, a2, ... are written in the order
// of the request's signature in requests.def.
#include "writer.h"

namespace rib {

void RibWriter::polygon(L, const ParamList& a1) {
    req("Polygon");
    params(a1);
}

void RibWriter::pointsPolygons(L, const std::vector<int>& a1, const std::vector<int>& a2, const ParamList& a3) {
    req("PointsPolygons");
    m_e->intArray(a1);
    m_e->intArray(a2);
    params(a3);
}

void RibWriter::sphere(L, float a1, float a2, float a3, float a4, const ParamList& a5) {
    req("Sphere");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    params(a5);
}

void RibWriter::basis(L, S a1, const float a2[16], int a3, S a4, const float a5[16], int a6) {
    req("Basis");
    basisArg(a1, a2);
    m_e->integer(a3);
    basisArg(a4, a5);
    m_e->integer(a6);
}

void RibWriter::trimCurve(L, Ints a1, Ints a2, Floats a3, Floats a4, Floats a5, Ints a6, Floats a7, Floats a8, Floats a9) {
    req("TrimCurve");
    m_e->intArray(a1);
    m_e->intArray(a2);
    m_e->floatArray(a3);
    m_e->floatArray(a4);
    m_e->floatArray(a5);
    m_e->intArray(a6);
    m_e->floatArray(a7);
    m_e->floatArray(a8);
    m_e->floatArray(a9);
}

void RibWriter::generalPolygon(L, Ints a1, P a2) {
    req("GeneralPolygon");
    m_e->intArray(a1);
    params(a2);
}

void RibWriter::pointsGeneralPolygons(L, Ints a1, Ints a2, Ints a3, P a4) {
    req("PointsGeneralPolygons");
    m_e->intArray(a1);
    m_e->intArray(a2);
    m_e->intArray(a3);
    params(a4);
}

void RibWriter::patch(L, S a1, P a2) {
    req("Patch");
    m_e->string(a1);
    params(a2);
}

void RibWriter::patchMesh(L, S a1, int a2, S a3, int a4, S a5, P a6) {
    req("PatchMesh");
    m_e->string(a1);
    m_e->integer(a2);
    m_e->string(a3);
    m_e->integer(a4);
    m_e->string(a5);
    params(a6);
}

void RibWriter::nuPatch(L, int a1, int a2, Floats a3, float a4, float a5, int a6, int a7, Floats a8, float a9, float a10, P a11) {
    req("NuPatch");
    m_e->integer(a1);
    m_e->integer(a2);
    m_e->floatArray(a3);
    m_e->number(a4);
    m_e->number(a5);
    m_e->integer(a6);
    m_e->integer(a7);
    m_e->floatArray(a8);
    m_e->number(a9);
    m_e->number(a10);
    params(a11);
}

void RibWriter::subdivisionMesh(L, S a1, Ints a2, Ints a3, Strings a4, Ints a5, Ints a6, Floats a7, P a8) {
    req("SubdivisionMesh");
    m_e->string(a1);
    m_e->intArray(a2);
    m_e->intArray(a3);
    m_e->stringArray(a4);
    m_e->intArray(a5);
    m_e->intArray(a6);
    m_e->floatArray(a7);
    params(a8);
}

void RibWriter::cylinder(L, float a1, float a2, float a3, float a4, P a5) {
    req("Cylinder");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    params(a5);
}

void RibWriter::cone(L, float a1, float a2, float a3, P a4) {
    req("Cone");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    params(a4);
}

void RibWriter::disk(L, float a1, float a2, float a3, P a4) {
    req("Disk");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    params(a4);
}

void RibWriter::torus(L, float a1, float a2, float a3, float a4, float a5, P a6) {
    req("Torus");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    m_e->number(a5);
    params(a6);
}

void RibWriter::paraboloid(L, float a1, float a2, float a3, float a4, P a5) {
    req("Paraboloid");
    m_e->number(a1);
    m_e->number(a2);
    m_e->number(a3);
    m_e->number(a4);
    params(a5);
}

void RibWriter::hyperboloid(L, const float a1[3], const float a2[3], float a3, P a4) {
    req("Hyperboloid");
    for (int i = 0; i < 3; ++i) m_e->number(a1[i]);
    for (int i = 0; i < 3; ++i) m_e->number(a2[i]);
    m_e->number(a3);
    params(a4);
}

void RibWriter::curves(L, S a1, Ints a2, S a3, P a4) {
    req("Curves");
    m_e->string(a1);
    m_e->intArray(a2);
    m_e->string(a3);
    params(a4);
}

void RibWriter::points(L, P a1) {
    req("Points");
    params(a1);
}

void RibWriter::blobby(L, int a1, Ints a2, Floats a3, Strings a4, P a5) {
    req("Blobby");
    m_e->integer(a1);
    m_e->intArray(a2);
    m_e->floatArray(a3);
    m_e->stringArray(a4);
    params(a5);
}

void RibWriter::geometry(L, S a1, P a2) {
    req("Geometry");
    m_e->string(a1);
    params(a2);
}

void RibWriter::procedural(L, S a1, Strings a2, const float a3[6]) {
    req("Procedural");
    m_e->string(a1);
    m_e->stringArray(a2);
    m_e->floatArray(std::vector<float>(a3, a3 + 6));
}

void RibWriter::makeTexture(L, S a1, S a2, S a3, S a4, S a5, float a6, float a7, P a8) {
    req("MakeTexture");
    m_e->string(a1);
    m_e->string(a2);
    m_e->string(a3);
    m_e->string(a4);
    m_e->string(a5);
    m_e->number(a6);
    m_e->number(a7);
    params(a8);
}

void RibWriter::makeBump(L, S a1, S a2, S a3, S a4, S a5, float a6, float a7, P a8) {
    req("MakeBump");
    m_e->string(a1);
    m_e->string(a2);
    m_e->string(a3);
    m_e->string(a4);
    m_e->string(a5);
    m_e->number(a6);
    m_e->number(a7);
    params(a8);
}

void RibWriter::makeLatLongEnvironment(L, S a1, S a2, S a3, float a4, float a5, P a6) {
    req("MakeLatLongEnvironment");
    m_e->string(a1);
    m_e->string(a2);
    m_e->string(a3);
    m_e->number(a4);
    m_e->number(a5);
    params(a6);
}

void RibWriter::makeCubeFaceEnvironment(L, Strings a1, S a2, float a3, S a4, float a5, float a6, P a7) {
    req("MakeCubeFaceEnvironment");
    for (size_t i = 0; i < 6; ++i) m_e->string(i < a1.size() ? a1[i] : std::string());
    m_e->string(a2);
    m_e->number(a3);
    m_e->string(a4);
    m_e->number(a5);
    m_e->number(a6);
    params(a7);
}

void RibWriter::makeShadow(L, S a1, S a2, P a3) {
    req("MakeShadow");
    m_e->string(a1);
    m_e->string(a2);
    params(a3);
}

}  // namespace rib
