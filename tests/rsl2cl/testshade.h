// testshade.h: runs shaders compiled by rsl2cl on the OpenCL device (PoCL) over a set
// of shading points, with fake lights and a chosen evaluation mode (rsl_abi.h).
#pragma once
#include <string>
#include <vector>

#include "emit_cl.h"

namespace ts {

struct Light {
    float L[3];   // surface-side L: toward the light
    float Cl[3];  // unshadowed colour
};

// A value the fake renderer services answer with (rsl_abi.h, MESSAGE PASSING).
struct Message {
    int light = -1;             // rsl_lightsource_param: the light index; else unused
    std::string name;
    std::vector<float> values;  // answered only when the caller asks for this many
};

struct Scene {
    std::vector<Light> lights;
    float ambient[3] = {0, 0, 0};
    // Written after the parameter block (EmittedShader::spaceOffset): "shader" and
    // "object" to current, row-major, RSL row-vector convention. shaderOffset, when
    // not zero, is added to shaderMatrix's translation row (world translated by it).
    float shaderMatrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    float objectMatrix[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    float shaderOffset[3] = {0, 0, 0};
    float cameraOffset[3] = {0, 0, 0};  // rsl_space_matrix(RSL_SPACE_CAMERA): translation
    std::vector<Message> lightParams, attributes, options;
};

struct Point {
    float P[3] = {0, 0, 0}, N[3] = {0, 0, 1}, Ng[3] = {0, 0, 1}, I[3] = {0, 0, -1};
    float E[3] = {0, 0, 0}, Cs[3] = {1, 1, 1}, Os[3] = {1, 1, 1};
    float Ps[3] = {0, 0, 0};
    float s = 0, t = 0, u = 0, v = 0;
};

struct Out {
    float Ci[3], Oi[3], L[3], Cl[3];
    int traceCount = 0;
    float org[8][3], dir[8][3];
    float outputs[32];  // RslEval::outputs after the evaluation
    float CiLight[8][3];  // kCoefficients: RslEval::Ci_light of the first 8 lights
};

// run()'s modeLight for the base evaluation with light coefficients (rsl_abi.h).
constexpr int kCoefficients = -2;

// n x n points: s, t, u, v in [0, 1]; P = (4s - 2, 4t - 2, 0); E = (0, 0, 5);
// Ps = P + (0, 0, 1) (for light shaders).
std::vector<Point> grid(int n);

class Shade {
public:
    // Compiles RSL (front end + code generator). False with diagnostics in *err.
    bool compileSource(const std::string& rsl, const std::string& name, std::string* err);
    bool compileFile(const std::string& path, std::string* err);
    // Builds the generated OpenCL C with the runtime on the device; false + log.
    bool buildOnDevice(const Scene& scene, std::string* log);
    void setParam(const std::string& name, const std::vector<float>& values);
    // Runs in a mode (light l / trace i; -1 -1 = base; kCoefficients: base, with the
    // light coefficients). Builds for `scene` if needed.
    std::vector<Out> run(const std::vector<Point>& pts, const Scene& scene, int modeLight = -1,
                         int modeTrace = -1);

    // More than 3: colours have this many channels (RSL_COLOR_LANES 8 or 16), each of
    // RGB's repeated (channel i is RGB's i % 3): every RGB value goes in and comes out
    // the same. Set before compiling.
    int colorChannels = 3;
    rsl::EmittedShader shader;
    std::vector<float> params;
    std::string diagnostics;

private:
    std::string m_builtFor;
    void* m_program = nullptr;
};

bool deviceAvailable();

}  // namespace ts
