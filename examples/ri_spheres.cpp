// ri_spheres.cpp: a scene given through the Ri API (host/ri/ri.h) instead of a RIB file:
// three plastic spheres on a checkered floor under a spot light, rendered at once.
// Build: part of the project (target ri_spheres). Run: build/bin/ri_spheres [out.exr]
// (default ri_spheres.exr); `build/bin/ri_spheres out.rib` writes the calls as RIB.
#include <cstring>
#include <string>

#include "ri.h"

int main(int argc, char** argv) {
    const std::string out = argc > 1 ? argv[1] : "ri_spheres.exr";
    const bool rib = out.size() > 4 && out.compare(out.size() - 4, 4, ".rib") == 0;
    RiBegin(rib ? out.c_str() : RI_NULL);
    if (!rib) RiDisplay(out.c_str(), RI_FILE, RI_RGBA, RI_NULL);
    RiFormat(320, 240, 1);
    RiPixelSamples(4, 4);
    RtFloat fov = 40;
    RiProjection(RI_PERSPECTIVE, RI_FOV, &fov, RI_NULL);
    RiTranslate(0, -0.5f, 6);
    RiRotate(-20, 1, 0, 0);
    RiWorldBegin();
    RtFloat ambient = 0.08f;
    RiLightSource(RI_AMBIENTLIGHT, RI_INTENSITY, &ambient, RI_NULL);
    RtPoint from = {3, 6, -4}, to = {0, 0, 0};
    RtFloat intensity = 60, cone = 0.6f;
    RiLightSource(RI_SPOTLIGHT, RI_FROM, from, RI_TO, to, RI_INTENSITY, &intensity,
                  RI_CONEANGLE, &cone, RI_NULL);

    const RtColor colours[3] = {
        {0.9f, 0.2f, 0.15f}, {0.2f, 0.8f, 0.3f}, {0.2f, 0.35f, 0.9f}};
    for (int i = 0; i < 3; ++i) {
        RiAttributeBegin();
        RiColor(const_cast<RtFloat*>(colours[i]));
        RtFloat ks = 0.6f, roughness = 0.08f;
        RiSurface(RI_PLASTIC, RI_KS, &ks, RI_ROUGHNESS, &roughness, RI_NULL);
        RiTranslate(-1.6f + 1.6f * float(i), 0.6f, 0);
        RiSphere(0.6f, -0.6f, 0.6f, 360, RI_NULL);
        RiAttributeEnd();
    }

    // The floor: 8x8 squares, one mesh, a colour per square (uniform Cs).
    RtInt nverts[64], verts[256];
    RtPoint P[81];
    RtColor Cs[64];
    for (int y = 0; y <= 8; ++y)
        for (int x = 0; x <= 8; ++x) {
            P[y * 9 + x][0] = -4 + float(x);
            P[y * 9 + x][1] = 0;
            P[y * 9 + x][2] = -4 + float(y);
        }
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const int f = y * 8 + x;
            nverts[f] = 4;
            verts[4 * f] = y * 9 + x, verts[4 * f + 1] = y * 9 + x + 1;
            verts[4 * f + 2] = (y + 1) * 9 + x + 1, verts[4 * f + 3] = (y + 1) * 9 + x;
            const float v = (x + y) % 2 ? 0.85f : 0.25f;
            Cs[f][0] = Cs[f][1] = Cs[f][2] = v;
        }
    RiAttributeBegin();
    RiSurface(RI_MATTE, RI_NULL);
    RiPointsPolygons(64, nverts, verts, RI_P, P, "uniform color Cs", Cs, RI_NULL);
    RiAttributeEnd();
    RiWorldEnd();
    RiEnd();
    return RiLastError == RIE_NOERROR ? 0 : 1;
}
