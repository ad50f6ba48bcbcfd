// scene.h: the scene as the host holds it after the RIB is read: world-space triangles with
// their attributes, shader instances, lights, camera and the output options. The device
// arrays are built from it (render/scene_upload), the BVH over its triangles.
#pragma once
#include <array>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cl/include/quadric.h"
#include "cl/include/scene_types.h"
#include "host/bvh/aabb.h"
#include "host/scene/color_samples.h"
#include "rib/diagnostics.h"
#include "rib/param_list.h"

namespace rd {

struct DisplaySpec {
    std::string name;          // file name ("" = <scene>.exr)
    std::string type = "file"; // "file", "openexr", "framebuffer", ...
    std::string mode = "rgba"; // "rgb", "rgba"
    rib::SourceLoc loc;
};

// Quantize "rgba" one min max ditheramplitude: how a picture that is not OpenEXR (a
// TIFF, PNG, ...) stores its colour: round(one * value + dither * r) clamped to
// [min, max], r uniform in [-1, 1); one 0 stores floats. (OpenEXR keeps the floats.)
struct QuantizeSpec {
    int one = 255, min = 0, max = 255;
    float dither = 0.5f;
};

// A secondary display (Display "+name" ...): a file of its own with the AOVs its mode
// names ("diffuse", "color diffuse,float mask"; "rgba" or "rgb": the image's colour too).
struct AovDisplay {
    std::string name;
    std::vector<std::string> aovs;
    std::string colour;  // "", "rgb" or "rgba"
    rib::SourceLoc loc;
};

struct CameraSpec {
    int width = 640, height = 480; // Format (RI default)
    float pixelAspect = 1.0f;
    float frameAspect = 0.0f;       // 0: from Format
    bool screenWindowSet = false;
    float screen[4] = {-1, 1, -1, 1};
    bool perspective = false;       // RI default projection is orthographic
    float fovDeg = 90.0f;
    float clipNear = 1e-10f, clipFar = 1e30f;
    float pixelSamples[2] = {2, 2}; // RI default PixelSamples 2 2
    std::string pixelFilter = "gaussian";  // PixelFilter (RI default gaussian 2 2)
    float filterWidth[2] = {2, 2};
    glm::mat4 worldToCamera{1.0f};  // column-vector convention (glm)
    // A moving camera: worldToCamera holds at motionTimes[0], this at motionTimes[1].
    bool moving = false;
    glm::mat4 worldToCameraEnd{1.0f};
    float motionTimes[2] = {0, 0};
    std::vector<std::pair<float, glm::mat4>>
        worldToCameraBetween;                             // keys between: (time, map)
    float fstop = 0, focalLength = 0, focalDistance = 0;  // DepthOfField; fstop 0 = pinhole
    float shutter[2] = {0, 0};      // Shutter open, close
    float exposure[2] = {1, 1};     // Exposure gain, gamma
    float crop[4] = {0, 1, 0, 1};   // CropWindow xmin xmax ymin ymax (NDC)
    // The pixels the crop window covers: [x0, x1) x [y0, y1).
    void cropPixels(int& x0, int& x1, int& y0, int& y1) const;
};

// The most ClippingPlane requests a render honours (the rest are a warning).
constexpr size_t kMaxClipPlanes = 8;

// A Surface or LightSource as the RIB gave it: the shader's name, its parameter list and
// the transform current when it was declared ("shader" space to world).
struct ShaderRef {
    std::string name;
    rib::ParamList params;
    glm::mat4 shaderToWorld{1.0f};
    rib::SourceLoc loc;
    // Parameters its primitives give per point (RI varying, vertex, facevarying, or
    // uniform on several faces), in the order of their values (Scene::pointParamValues):
    // name, and floats per value (1 float, 3 point/vector/normal, a colour's channels),
    // each taking pointParamEntries(floats) values a point
    std::vector<std::pair<std::string, int>> pointParams = {};
    // "object" space to world: the primitives' own, for a shader that reads "object"
    // space (an instance per object space); none: the shader's space stands for it.
    std::optional<glm::mat4> objectToWorld = std::nullopt;
};

// The float4 values a per-point parameter of `floats` floats takes: three floats each
// (a colour of n > 3 channels in pieces, rsl_abi.h PER-POINT PARAMETERS).
inline int pointParamEntries(int floats) { return (floats + 2) / 3; }

// Option "render" ...: budgets and adaptive sampling (the command line overrides).
struct RenderOptionsSpec {
    float time = 0;          // "float time": seconds, 0 = none
    float error = 0;         // "float error": relative film error target, 0 = none
    int firstPassBlock = 2;  // "int firstpassblock": first pass at 1 ray per N x N pixels
    // "float pixelerror" or PixelVariance: per-pixel relative error to refine to
    float pixelError = 0.01f;
    // Hider "raytrace" "int minsamples"/"maxsamples": each pixel's (0: PixelSamples')
    int minSamples = 0, maxSamples = 0;
    float relativeDetail = 1.0f;  // RelativeDetail: scales every Detail's raster area
    bool exactQuadrics = true; // "int exactquadrics": 0 tessellates quadrics into triangles
    int textureMemoryKB = 0;   // Option "limits" "texturememory": the device tile cache (0: auto)
    // Option "limits" "dicedtriangles": true displacement's most diced triangles (0: 4M,
    // dice_displaced.h kMaxDicedTriangles)
    int dicedTriangles = 0;
    int treeletBytes = 0;      // Option "limits" "treeletbytes": treelet budget (0: resident BVH)
    int sceneMemoryKB = 0;     // Option "limits" "scenememory": device BVH bytes (0: all)
    int seed = 0;              // "int seed": which random numbers (0 is the default set)
    bool sobol = true;         // "string sampler": "sobol" (default) or "independent"
};

// A value attribute() or option() gives shaders (rsl_abi.h, MESSAGE PASSING): an
// Attribute or Option parameter as "category:name" (Attribute "user" "float k" [1] is
// "user:k"), its floats: integers as floats, strings as their ids (rsl::stringId), an
// attribute's points, vectors and normals in the renderer's current (eye-relative world)
// space. A set is sorted by name.
struct MessageValue {
    std::string name;
    std::vector<float> values;
    bool operator<(const MessageValue& o) const {
        return name != o.name ? name < o.name : values < o.values;
    }
    bool operator==(const MessageValue& o) const {
        return name == o.name && values == o.values;
    }
};
using MessageValues = std::vector<MessageValue>;

struct Scene {
    std::string sourceFile;
    ColorSamples colors;
    std::vector<Triangle> triangles;
    std::vector<TriangleAttr> attrs;
    std::vector<rt_float4> normals; // 3 per triangle with has_normals, else unused entries
    // Per-vertex primitive variables, 3 per triangle, filled only when some geometry
    // gives them (RT_PRIMVAR_* in TriangleAttr says which triangles do): (s, t, 0, 0),
    // Cs, Os (a colour with more than three channels takes colors.lanes() / 4 float4s).
    std::vector<rt_float4> vertexSt, vertexCs, vertexOs;
    // With more than three colour channels (ColorSamples n > 3): each material's Cs then
    // Os in the n channels, 2 n floats a material (Material::cs and os hold their RGB);
    // else empty.
    std::vector<float> materialChannels;
    // Shader parameters given per point (ShaderRef::pointParams, K values): by triangle,
    // the first of its 3 x K values (corner-major) in pointParamValues, or
    // RT_NO_POINT_PARAMS; empty when no triangle has any. Quadrics: Quadric.point_params,
    // 4 x K (the (u, v) corners 00, 10, 01, 11). Points, vectors, normals in world space.
    std::vector<uint32_t> triangleParams;
    std::vector<rt_float4> pointParamValues;
    int maxPointParams = 0;  // the largest K of a surface in use (0: none)
    // Exact quadrics and CSG solids (cl/include/quadric.h), hit as RT_OBJECT_BIT | index,
    // with their world bounds; csg holds the solids' member lists and programs.
    std::vector<Quadric> quadrics;
    std::vector<Aabb> quadricBounds;
    std::vector<uint32_t> csg;
    // 8 colours per quadric that has them (Quadric.primvars), in float4s as vertexCs
    std::vector<rt_float4> quadricPrimvars;
    // Motion blur: moving quadrics' last keys (4 per one, Quadric.motion) and moving
    // triangles' last keys (by triangle index; empty without moving triangles).
    std::vector<rt_float4> quadricMotion;
    std::vector<Triangle> trianglesEnd;
    // Instanced objects: each prototype's triangles (RT_QF_PROTOTYPE, in object space)
    // and their box; instances are RT_Q_INSTANCE records whose first_member indexes this.
    struct Prototype {
        uint32_t firstTriangle = 0, triangleCount = 0;
        glm::vec3 lo{0.0f}, hi{0.0f};
    };
    std::vector<Prototype> prototypes;
    // Materials: Material::shader indexes surfaceRefs until the shader set compiles them.
    std::vector<Material> materials;
    // attribute(): the distinct sets of attribute values (set 0: none) and each
    // material's set, by material index
    std::vector<MessageValues> attributeSets{MessageValues{}};
    std::vector<uint32_t> materialAttributes;
    // By material: a truly displaced surface's micropolygon edge in pixels (sqrt of its
    // ShadingRate), 0 for every other (RT_MATERIAL_TRUE_DISPLACEMENT)
    std::vector<float> materialDicing;
    // By material: Attribute "trace" "maxspeculardepth", the trace() depth past which
    // its shader's rays are not sent (maxSpecularDepth: the deepest of them)
    std::vector<int> materialSpecularDepth;
    MessageValues optionValues;          // option(): every Option's values
    std::vector<ShaderRef> surfaceRefs;  // one per distinct Surface call in use
    // DelayedReadArchive calls not loaded yet (RT_Q_PROCEDURAL boxes); key: where the
    // call is and what it reads, the same from one reading of the RIB to the next
    struct DeferredProcedural {
        std::string key, file;
        rib::SourceLoc loc;
    };
    std::vector<DeferredProcedural> procedurals;
    std::vector<ShaderRef> lights;       // every LightSource, in order
    // AreaLightSource: the triangles of the geometry that followed it in its attribute
    // block (world, eye-relative, facing where they emit), by index into lights
    std::map<uint32_t, std::vector<std::array<glm::vec3, 3>>> areaLightTriangles;
    std::vector<ShaderRef> atmospheres;  // one per distinct Atmosphere call in use
    std::vector<ShaderRef> interiors;    // one per distinct Interior call in use
    std::vector<ShaderRef> exteriors;    // one per distinct Exterior call in use
    // By material: 1 + its Exterior's index in exteriors, 0 for none (no flag bits left)
    std::vector<uint32_t> materialExterior;
    // ClippingPlane: (a point, its normal) each; what lies on the normal's side is not
    // seen by camera rays. Camera space outside the world, world space inside (device
    // space after WorldEnd).
    std::vector<std::array<glm::vec3, 2>> clipPlanes;
    std::vector<ShaderRef> displacements;  // one per distinct Displacement call in use
    // The coordinate systems CoordinateSystem and Camera named, to world (device space
    // after WorldEnd), for shaders that name them
    std::map<std::string, glm::mat4> coordinateSystems;
    ShaderRef imager;                    // the Imager option (name empty: none)
    std::vector<std::string> shaderSearchPath;  // Option "searchpath" "shader", split
    std::vector<std::string> textureSearchPath; // Option "searchpath" "texture", split
    int maxSpecularDepth = 2;  // Attribute "trace" "maxspeculardepth" (the largest given)
    // Attribute "trace" "maxdiffusedepth" (the largest given; -1: none, the diffuse rays
    // of indirectdiffuse() bounded by maxspeculardepth alone); 0 and 1 are kept exactly
    int maxDiffuseDepth = -1;
    // Attribute/Option "trace" "maxtransparentdepth": surfaces of Opacity < 1 a ray goes
    // through; rays cut there are counted (--stats) and reported, never silently lost.
    int maxTransparentDepth = 256;
    int rouletteDepth = 0;  // Option/Attribute "trace" "roulettedepth": 0 = no roulette
    // Where the device's origin is in RIB world space: triangles, camera, lights and
    // shader spaces are stored relative to it (the eye), for precision far from the origin.
    glm::dvec3 worldOrigin{0.0};
    CameraSpec camera;
    DisplaySpec display;
    QuantizeSpec quantize;
    std::vector<std::string> aovs;  // the image's AOVs (DisplayChannel, the Display's mode)
    std::vector<AovDisplay> aovDisplays;  // Display "+name": files of AOVs
    // AOV types declared (DisplayChannel "color diffuse", or in a display's mode): float,
    // color, point, vector or normal; an AOV not declared takes its shader output's type
    std::map<std::string, std::string> aovTypes;
    // Every AOV some image of the scene holds: aovs, then the secondary displays'.
    std::vector<std::string> aovNames() const;
    RenderOptionsSpec render;
    bool anySmoothNormals = false;
    bool anyMatte = false;
    uint32_t primvarsUsed = 0;  // RT_PRIMVAR_* bits some triangle carries

    // The device camera: screen window, fov scale and camera-to-world matrix.
    Camera deviceCamera() const;
};

}  // namespace rd
