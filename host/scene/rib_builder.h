// rib_builder.h: the Ri state machine. It implements rib::Target and turns the requests of
// a RIB stream into Scenes (one per WorldBegin/WorldEnd): it keeps the option state, the
// attribute and transform stacks, binds shaders and lights, and hands geometry to the
// tessellator in world space.
#pragma once
#include <array>
#include <functional>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "quadric_shapes.h"
#include "rib/target.h"
#include "scene.h"
#include "tessellate_blobby.h"
#include "tessellate_curves_points.h"
#include "tessellate_nurbs.h"
#include "tessellate_patches.h"
#include "tessellate_subdiv.h"
#include "tessellate_types.h"

namespace rd {

struct MakeTextureOptions;  // texture/texture_maker.h

// Primitive variables that give shader parameters per-point values
// (rib_builder_point_params.cpp): at most this many per primitive.
constexpr int kMaxPointParams = 8;
bool isStandardPrimvar(const std::string& name);  // P, N, Cs, st ...: not parameters
bool givesOneValue(const rib::Param& p);          // constant, or one value of any class
// The request's variables that give a parameter a value per point (float, color,
// point, vector, normal; not the standard ones), in order, the first kMaxPointParams.
// `withStandard`: then Cs, Os and the texture coordinates (st, or s and t) given per
// point too, at the end: the geometry paths that interpolate point parameters carry
// them to the mesh's colours and st (takeStandardPointValues).
std::vector<const rib::Param*> pointParamsOf(const rib::ParamList* params,
                                             bool withStandard = false);
// Moves the trailing Cs, Os and st values that pointParamsOf(.., true) added to a mesh's
// point parameters into its per-vertex colours (`channels` floats a colour) and st.
void takeStandardPointValues(VertexData& mesh, int channels);
// A SubdivisionMesh's per-point values to refine with it (SubdivInput), its colours and
// texture coordinates among them; false when it has none.
bool subdivPointParamsIn(const rib::ParamList& params, SubdivInput& in);

class RibBuilder : public rib::Target {
public:
    // The most object spaces a world's shaders that read "object" space get an instance
    // each for (objectSpaceOf).
    static constexpr size_t kMaxObjectSpaces = 65536;
    RibBuilder(rib::Diagnostics& diag, const std::string& sourceFile);

    // Scenes completed so far, in WorldEnd order.
    std::vector<Scene>& scenes() { return m_scenes; }
    // Carries out the texture-making requests that came after frame `scene - 1` and
    // before frame `scene` (they may read what that frame writes: a depth map for
    // MakeShadow); the caller renders the frames in order and calls this before each.
    void makeTexturesBefore(size_t scene);

    void frameBegin(L, int) override;
    void frameEnd(L) override;
    void worldBegin(L) override;
    void worldEnd(L) override;
    void attributeBegin(L) override;
    void attribute(L, const std::string& name, const rib::ParamList&) override;
    void visibilityAttribute(L, const rib::ParamList& params);
    void shadeAttribute(L, const rib::ParamList& params);
    void displacementBoundAttribute(L, const rib::ParamList& params);
    void renderAttribute(L, const rib::ParamList& params);
    void traceAttribute(const rib::ParamList& params);
    void attributeEnd(L) override;
    // Resource "attributes": the current attributes saved by name, or restored whole or
    // in part (the transform, or the shading: all but the transform).
    void resourceBegin(L) override;
    void resourceEnd(L) override;
    void resource(L, S name, S type, P params) override;
    void transformBegin(L) override;
    void transformEnd(L) override;

    void format(L, int xres, int yres, float pixelAspect) override;
    void frameAspectRatio(L, float) override;
    void screenWindow(L, float, float, float, float) override;
    void projection(L, const std::string& name, const rib::ParamList&) override;
    void clipping(L, float, float) override;
    void clippingPlane(L, float x, float y, float z, float nx, float ny,
                       float nz) override;
    void camera(L, S name, P params) override;
    void pixelSamples(L, float, float) override;
    void pixelVariance(L, float) override;
    bool runsDynamicLoad() const override { return true; }
    // Level of detail (rib_builder_detail.cpp)
    void relativeDetail(L, float) override;
    void detail(L, const float bound[6]) override;
    void detailRange(L, float minVisible, float lowerTransition, float upperTransition,
                     float maxVisible) override;
    void hider(L, const std::string& type, const rib::ParamList& params) override;
    void pixelFilter(L, const std::string& filter, float xwidth, float ywidth) override;
    void quantize(L, const std::string& type, int one, int min, int max,
                  float dither) override;
    void display(L, const std::string& name, const std::string& type,
                 const std::string& mode, const rib::ParamList&) override;

    void option(L, const std::string& name, const rib::ParamList&) override;
    void displayChannel(L, const std::string& channel, const rib::ParamList&) override;
    void cropWindow(L, float, float, float, float) override;
    void depthOfField(L, float fstop, float focalLength, float focalDistance) override;
    void matte(L, bool) override;
    void geometricRepresentation(L, S) override;
    void procedural(L, const std::string& name, const std::vector<std::string>& args,
                    const float bound[6]) override;
    void color(L, const std::vector<float>&) override;
    void opacity(L, const std::vector<float>&) override;
    void surface(L, const std::string& name, const rib::ParamList&) override;
    void lightSource(L, const std::string& name, const std::string& handle,
                     const rib::ParamList&) override;
    void illuminate(L, const std::string& handle, bool on) override;
    void areaLightSource(L, S name, S handle, P params) override;
    void atmosphere(L, S name, P params) override;
    void interior(L, S name, P params) override;
    void exterior(L, S name, P params) override;
    void deformation(L, S name, P params) override;
    void displacement(L, S name, P params) override;
    // Texture making, when read (rib_builder_textures.cpp)
    void makeTexture(L, S picture, S texture, S swrap, S twrap, S filter, float swidth,
                     float twidth, P) override;
    void makeBump(L, S picture, S texture, S swrap, S twrap, S filter, float swidth,
                  float twidth, P) override;
    void makeLatLongEnvironment(L, S picture, S texture, S filter, float swidth, float twidth,
                                P) override;
    void makeCubeFaceEnvironment(L, Strings faces, S texture, float fov, S filter, float swidth,
                                 float twidth, P) override;
    void makeShadow(L, S picture, S texture, P) override;
    bool deferProcedural(L, S name, Strings args, const float bound[6], S file) override;
    // The DelayedReadArchive calls (Scene::DeferredProcedural::key) to load when read;
    // the others wait, as boxes, until a ray reaches them.
    void setLoadedProcedurals(std::set<std::string> keys) { m_loadProcedurals = std::move(keys); }
    // Off: every DelayedReadArchive is read at once (its RIB cannot be read again: the
    // standard input, the Ri API's calls).
    void setDeferProcedurals(bool on) { m_deferProcedurals = on; }
    void imager(L, S name, P params) override;
    void sides(L, int n) override;
    void shadingRate(L, float size) override;
    void skew(L, float angleDeg, float dx1, float dy1, float dz1, float dx2, float dy2,
              float dz2) override;
    void perspective(L, float fovDeg) override;
    void exposure(L, float gain, float gamma) override;
    void colorSamples(L, Floats nRGB, Floats RGBn) override;
    // ColorSamples n <= 3: kept as n channels (scene.h ColorSamples); more: made RGB as read
    bool wantsRgbColors() const override { return true; }
    // Colours keep up to 15 channels, primitive variables too (per-point parameters
    // in pieces of three: VertexData::PointParam)
    int keptColorSamples() const override { return ColorSamples::kMaxChannels; }
    void primitiveVariables(const rib::ParamList* params) override { m_primVars = params; }
    void textureCoordinates(L, float s1, float t1, float s2, float t2, float s3, float t3,
                            float s4, float t4) override;
    void orientation(L, const std::string& o) override;
    void reverseOrientation(L) override;
    // Whether normals computed from world-space vertices must be reversed to be RI's:
    // the primitive inside out, or its transform a mirror (the cross product flips).
    bool flipWorldNormals() const;
    void coordinateSystem(L, S name) override;
    void scopedCoordinateSystem(L, S name) override;
    void coordSysTransform(L, S name) override;
    bool transformPoints(S from, S to, float* xyz, int n) override;

    void shutter(L, float open, float close) override;
    void motionBegin(L, Floats times) override;
    void motionEnd(L) override;
    void identity(L) override;
    void transform(L, const float m[16]) override;
    void concatTransform(L, const float m[16]) override;
    void translate(L, float, float, float) override;
    void rotate(L, float, float, float, float) override;
    void scale(L, float, float, float) override;

    void objectBegin(L, const std::string& handle) override;
    void objectEnd(L) override;
    void objectInstance(L, const std::string& handle) override;
    void polygon(L, const rib::ParamList&) override;
    void pointsPolygons(L, const std::vector<int>& nverts, const std::vector<int>& verts,
                        const rib::ParamList&) override;
    void sphere(L, float radius, float zmin, float zmax, float thetamax,
                const rib::ParamList&) override;
    // The other surfaces (rib_builder_geometry.cpp), tessellated for their size on screen.
    void cylinder(L, float radius, float zmin, float zmax, float thetamax, P) override;
    void cone(L, float height, float radius, float thetamax, P) override;
    void disk(L, float height, float radius, float thetamax, P) override;
    void torus(L, float majorRadius, float minorRadius, float phiMin, float phiMax,
               float thetamax, P) override;
    void paraboloid(L, float rmax, float zmin, float zmax, float thetamax, P) override;
    void hyperboloid(L, const float point1[3], const float point2[3], float thetamax,
                     P) override;
    void generalPolygon(L, Ints nverts, P) override;
    void pointsGeneralPolygons(L, Ints nloops, Ints nverts, Ints verts, P) override;
    void basis(L, S, const float ubasis[16], int ustep, S, const float vbasis[16],
               int vstep) override;
    void patch(L, S type, P) override;
    void patchMesh(L, S type, int nu, S uwrap, int nv, S vwrap, P) override;
    void geometry(L, S type, P) override;  // "teapot"
    void trimCurve(L, Ints ncurves, Ints order, Floats knot, Floats min, Floats max, Ints n,
                   Floats u, Floats v, Floats w) override;
    void nuPatch(L, int nu, int uorder, Floats uknot, float umin, float umax, int nv,
                 int vorder, Floats vknot, float vmin, float vmax, P) override;
    void subdivisionMesh(L, S scheme, Ints nverts, Ints verts, Strings tags, Ints nargs,
                         Ints intargs, Floats floatargs, P) override;
    void curves(L, S type, Ints nvertices, S wrap, P) override;
    void blobby(L, int nleaf, const std::vector<int>& code,
                const std::vector<float>& floats, const std::vector<std::string>& strings,
                const rib::ParamList&) override;
    void points(L, P) override;
    // CSG (rib_builder_solids.cpp)
    void solidBegin(L, S op) override;
    void solidEnd(L) override;

    // Quadrics are tessellated instead of intersected exactly (for comparisons).
    // (The command line's choice wins over Option "render" "exactquadrics".)
    void setTessellateQuadrics(bool on) { m_forceTessellate = on; }
    // The pixel filter until the RIB gives one (RI's default: gaussian 2 2).
    void setPixelFilter(const std::string& name, float xwidth, float ywidth) {
        m_options.camera.pixelFilter = name;
        m_options.camera.filterWidth[0] = xwidth,
        m_options.camera.filterWidth[1] = ywidth;
    }

private:
    template <typename F>
    void makeTextureFile(L loc, const char* request, const std::string& output, F&& make);
    // MakeTexture and MakeBump: a 2D texture of a picture (rib_builder_textures.cpp)
    void make2dTexture(L loc, const char* request, S picture, S texture,
                       const MakeTextureOptions& o);

    // The current transform, with its motion: between the shutter times t0 and t1 the
    // object-to-world map moves from ctm to ctmEnd through the keys between (MotionBegin
    // around transforms), linearly from key to key.
    struct Placement {
        glm::mat4 ctm{1.0f};  // object to world (camera before WorldBegin)
        glm::mat4 ctmEnd{1.0f};
        bool moving = false;
        float t0 = 0, t1 = 0;
        std::vector<std::pair<float, glm::mat4>> between;  // (time, map), ascending
    };
    // The map of a moving placement at `time` (the keys' components interpolated, as the
    // device does for a quadric), or its ctm when it does not move.
    static glm::mat4 ctmAt(const Placement& p, float time);
    struct Attributes : Placement {
        // ScopedCoordinateSystem names given in this attribute block or those around it
        std::vector<std::pair<std::string, glm::mat4>> scopedSystems;
        // in the scene's channels (ColorSamples::slots() of them)
        float color[ColorSamples::kMaxChannels] = {1, 1, 1, 1, 1, 1, 1, 1,
                                                   1, 1, 1, 1, 1, 1, 1};
        float opacity[ColorSamples::kMaxChannels] = {1, 1, 1, 1, 1, 1, 1, 1,
                                                     1, 1, 1, 1, 1, 1, 1};
        MessageValues messages;  // what attribute() finds (Attribute values given)
        float detail = -1.0f;    // Detail: its bound's raster area (-1: none given)
        bool lodHidden = false;  // DetailRange leaves geometry out at this detail
        ShaderRef surface;    // the current Surface call
        uint64_t surfaceKey = 0;  // which Surface call it was (0: the default surface)
        bool matte = false;
        uint32_t visibility = 0;  // RT_MATERIAL_NO_CAMERA, RT_MATERIAL_NO_TRACE, ...
        // "shade" "transmissionhitmode" "shader": transmission 1 or "Os" is the shader's
        bool shadowHitShader = false;
        uint32_t lightsOff = 0;  // bit l: light l turned off (Illuminate handle 0)
        // Orientation relative to the current coordinate system's handedness: true when
        // primitives are inside out (their normals flipped); Sides 1 or 2.
        bool insideOut = false;
        int sides = 2;
        // TextureCoordinates: s and t at the parametric corners (u, v) = 00, 10, 01, 11
        float texS[4] = {0, 1, 0, 1}, texT[4] = {0, 0, 1, 1};
        ShaderRef atmosphere;    // the current Atmosphere call (name empty: none)
        uint64_t atmosphereKey = 0;
        ShaderRef interior;  // the current Interior call (name empty: none)
        uint64_t interiorKey = 0;
        ShaderRef exterior;  // the current Exterior call (name empty: none)
        uint64_t exteriorKey = 0;
        ShaderRef displacement;  // the current Displacement call (name empty: none)
        int areaLight = -1;      // AreaLightSource in this block: the geometry emits
        uint64_t displacementKey = 0;
        // True displacement (the surface diced and moved, host/scene/dice_displaced.h):
        // Attribute "render" "truedisplacement" (BMRT; -1 not given), else a nonzero
        // Attribute "displacementbound" "sphere" (PRMan); ShadingRate sets the dicing.
        int trueDisplacement = -1;
        // Attribute "trace" "maxspeculardepth" (-1: the default)
        int maxSpecularDepth = -1;
        float displacementBound = 0.0f;
        float shadingRate = 1.0f;
        bool displacesTruly() const {
            return displacementKey != 0 &&
                   (trueDisplacement > 0 ||
                    (trueDisplacement < 0 && displacementBound > 0.0f));
        }
        CubicBasis ubasis = bezierBasis(), vbasis = bezierBasis();
        std::shared_ptr<const TrimCurves> trim;  // TrimCurve applies to later NuPatches
    };
    enum class Block { Frame, World, Attribute, Transform };

    uint32_t currentMaterial();
    void setShadowMode(uint32_t mode);
    void keepCall(L loc, S name, P params, ShaderRef& call, uint64_t& key);
    // Attribute and Option values for attribute() and option()
    // (rib_builder_messages.cpp): params of `category` into `into` as "category:name",
    // replacing those of the same name; `ctm` (attributes) moves points, vectors and
    // normals to current space.
    void setMessageValues(L, const std::string& category, const rib::ParamList& params,
                          MessageValues& into, const glm::mat4* ctm);
    // The index of an attribute set in m_world.attributeSets, added when new.
    uint32_t attributeSetIndex(const MessageValues& set);
    // "trace" "maxtransparentdepth" of an Attribute or Option.
    void traceDepthOption(const rib::ParamList& params);
    void addAov(const std::string& name);
    // A display mode's entries ("rgba", "color diffuse,mask"): their names, their
    // declared types noted in aovTypes.
    std::vector<std::string> aovModeEntries(L, const std::string& mode);
    bool inWorld(L, const char* request);
    // inWorld, and the current DetailRange shows geometry at the current Detail
    bool shown(L, const char* request);
    // Adds an object-space mesh (placed by the current transform) with its primitive
    // variables; degenerate and non-finite triangles are counted and left out.
    void addMesh(L, const VertexData& mesh);
    // Per-vertex "N" of a polygon mesh with np points.
    void readVertexNormals(const rib::ParamList& params, size_t np, VertexData& mesh);
    // Per-point shader parameters (rib_builder_point_params.cpp): of a polygon mesh, with
    // its Cs, Os and st whatever their class (split into one vertex per face-vertex when
    // some are facevarying or uniform; mesh.tris are then remade from nverts/verts), of a
    // diced quadric (bilinear in the
    // corner values at each vertex's (u, v) in mesh.st), and of an exact quadric (4
    // corner values appended to Scene::pointParamValues; returns the first or
    // RT_NO_POINT_PARAMS).
    void readPointParams(const rib::ParamList& params, const std::vector<int>& nverts,
                         const std::vector<int>& verts, VertexData& mesh);
    void cornerPointParams(const rib::ParamList& params, VertexData& mesh,
                           bool withStandard = false);
    // SubdivisionMesh: vertex values go to the limit, varying ones are refined
    // linearly, facevarying ones linearly within each face (`refined`:
    // tessellateSubdivisionMesh's values for subdivPointParamsIn's input), uniform ones
    // per base face (faceIndex).
    void subdivPointParams(const rib::ParamList& params,
                           const std::vector<std::vector<glm::vec3>>& refined,
                           const std::vector<int>& faceIndex, VertexData& mesh);
    // Curves: varying (and facevarying) values along each curve's segments, vertex
    // values through the cubic basis like P, uniform ones per curve (faceIndex).
    void curvesPointParams(const rib::ParamList& params, const CurvesInput& in,
                           const std::vector<glm::vec2>& uv, const std::vector<int>& faceIndex,
                           VertexData& mesh);
    // A Blobby's per-leaf values blended at its vertices (BlobbyLeafWeights).
    void blobbyPointParams(const rib::ParamList& params, const BlobbyLeafWeights& weights,
                           VertexData& mesh);
    // Points: each disc (faceIndex: its point) has its point's value all over.
    void pointsPointParams(const rib::ParamList& params, const std::vector<int>& faceIndex,
                           VertexData& mesh);
    // General polygons (their tessellation's vertices are the points of P; faceIndex
    // names each triangle's polygon): split into one vertex per triangle corner when
    // some are facevarying or uniform.
    void generalPolygonPointParams(const rib::ParamList& params, const std::vector<int>& nloops,
                                   const std::vector<int>& nverts, const std::vector<int>& verts,
                                   const std::vector<int>& faceIndex, VertexData& mesh);
    // Patch and PatchMesh: varying (facevarying, bilinear vertex) values on the grid of
    // sub-patch corners, bilinear at each vertex's global (u, v) (`uv`, the dicer's st);
    // uniform ones per sub-patch (faceIndex); a single bicubic Patch's 16 vertex values
    // through its basis. Vertex values of a bicubic PatchMesh are not carried.
    // NuPatch the same over its knot spans (orders and knots given; vertex values, which
    // follow the NURBS basis, are not carried).
    struct PatchGrid {
        bool bicubic = false, uperiodic = false, vperiodic = false;
        int nupatches = 1, nvpatches = 1;
        CubicBasis ubasis = bezierBasis(), vbasis = bezierBasis();
        int uorder = 0, vorder = 0;  // a NuPatch's: sub-patches are its knot spans
        std::vector<float> uknot, vknot;
        int nu = 0, nv = 0;  // control points (vertex values): bicubic mesh, NuPatch
        std::vector<float> weights;  // a rational NuPatch's: w of each control point
    };
    void patchPointParams(const rib::ParamList& params, const PatchGrid& grid,
                          const std::vector<glm::vec2>& uv, const std::vector<int>& faceIndex,
                          VertexData& mesh);
    uint32_t quadricPointParams(const rib::ParamList& params, const glm::mat4& ctm);
    // A per-point variable's values moved by ctm as its kind moves (points eye-relative
    // in world space, unless `eyeRelative` is false).
    std::vector<glm::vec3> pointParamToWorld(const glm::mat4& ctm,
                                             const VertexData::PointParam& p,
                                             bool eyeRelative = true) const;
    // Scene::triangleParams gets placeholders up to the triangles so far.
    void startTrianglePointParams();
    // While a primitive that carries per-point parameters picks its material: their
    // names and floats per value, in the order of its values (ShaderRef::pointParams).
    std::vector<std::pair<std::string, int>> m_carriedPointParams;
    // Pixels per world unit at distance `depth` in front of the camera.
    float pixelsPerUnit(float depth) const;
    // Screen size in pixels of an object-space sphere (centre, radius), for dicing rates.
    float screenRadius(const glm::vec3& centre, float radius) const;
    // Screen size of the bounding sphere of object-space points.
    float screenRadius(const std::vector<glm::vec3>& points) const;
    // Adds a tessellated surface, or reports why the tessellator refused it.
    // `perPoint`, when given, adds the per-point shader parameters to the mesh.
    void addSurface(L, const char* what, bool ok, const SurfaceMesh& m, const std::string& err,
                    const std::function<void(VertexData&)>& perPoint = nullptr);
    // Adds an exact quadric placed by the current transform (or keeps it in the object
    // being defined, or in the solid being built); "st"/"s"/"t" give corner values.
    // `placement` maps it into the space the current transform places (an object
    // definition's space for instances).
    void addQuadric(L, const char* what, QuadricShape shape, const rib::ParamList& params,
                    const glm::mat4& placement = glm::mat4(1.0f));
    void quadricTextureCoordinates(Quadric& q, const rib::ParamList& params,
                                   const glm::mat4& placement) const;
    void quadricMaterial(Quadric& q, const rib::ParamList& params,
                         const glm::mat4& placement);
    // The eye-relative world placement of `placement` under `ctm`.
    glm::mat4 eyeRelative(const glm::mat4& ctm, const glm::mat4& placement) const;
    // Appends an object record (quadric or instance) already placed at the current
    // transform, with the motion of the current placement and its world bounds from its
    // object-space box [lo, hi].
    void addObjectRecord(L, const char* what, Quadric q, glm::vec3 lo, glm::vec3 hi,
                         const glm::mat4& placement);
    // CSG: the primitive solid the next surface belongs to (one is opened implicitly for
    // a surface given directly under an operation), or -1 outside SolidBegin.
    int solidLeafForSurface(L);
    // Quadrics stay exact inside SolidBegin whatever the option: a diced one is not a
    // closed solid (its seams and poles do not meet exactly).
    // (Inside MotionBegin a quadric's keys give its parameters' motion: they are diced,
    // alike, into the keys of a deforming mesh; but a solid's members stay exact.)
    bool exactQuadrics() const {
        if (!m_solidStack.empty()) return true;
        if (m_motion.active) return false;
        if (m_attrStack.back().areaLight >= 0) return false;  // its triangles are sampled
        if (m_attrStack.back().displacesTruly()) return false;  // diced, then displaced
        return !m_forceTessellate && (m_inWorld ? m_world : m_options).render.exactQuadrics;
    }
    void finishSolid(int root);
    struct SolidProgram;
    Aabb writeSolid(int i, bool negative, int depth, SolidProgram& p);
    Aabb solidMemberBounds(uint32_t prim) const;
    bool solidsClosed(const Aabb& bounds);

    rib::Diagnostics& m_diag;
    std::set<std::string> m_loadProcedurals;  // DelayedReadArchive keys read at once
    bool m_deferProcedurals = true;
    // The geometry request being read: its constant primitive variables that are not the
    // standard ones override the surface shader's parameters of the same names
    const rib::ParamList* m_primVars = nullptr;
    std::map<std::pair<uint64_t, std::string>, uint32_t> m_surfaceVariants;
    std::set<std::string> m_varyingPrimvarWarned;
    uint32_t surfaceFor(const Attributes& a);  // the surface reference of this primitive
    bool m_projectionNull = false;  // Projection "null": a Perspective defines it
    Scene m_options;               // option state; copied into each new world
    std::vector<Scene> m_frameOptions;  // the options at each open FrameBegin
    Scene m_world;                 // the world being built
    bool m_inWorld = false;
    bool m_forceTessellate = false;
    std::vector<Attributes> m_attrStack;
    // Resource saves by name, one map per ResourceBegin block open
    std::vector<std::map<std::string, Attributes>> m_resources{1};
    std::vector<Placement> m_xformStack;
    // MotionBegin/End being read (rib_builder_transforms.cpp): its times, how many of
    // its requests came, the placement before it and the transform keys so far; meshes
    // given as keys (deformation) wait for the last one.
    struct MotionBlock {
        bool active = false;
        std::vector<float> times;
        int count = 0;
        Placement before;
        std::vector<glm::mat4> keys;  // the transform at each key
        std::vector<VertexData> meshKeys;
        std::pair<int, int> segments{0,
                                     0};  // a diced quadric's first key's (u, v) counts
    } m_motion;
    // Applies a transform request: concatenated (or replacing the ctm) on both ends of a
    // moving placement, or as the next key inside MotionBegin.
    void applyTransform(const glm::mat4& m, bool replace);
    // The (u, v) segment counts to dice a quadric with: its own, or inside MotionBegin
    // those of its first key, so that every key has the same topology.
    std::pair<int, int> keySegments(int nu, int nv);
    // Adds a mesh whose points move through `keys` (object space, same topology) at
    // `times`, placed by the current transform (and its motion): one key, the
    // transform's keys; more, a deformation (the transform taken at their times).
    void addMovingMesh(L, const std::vector<VertexData>& keys,
                       const std::vector<float>& times);
    // Object-space points placed by `ctm` in the eye-relative world (in double).
    std::vector<glm::vec3> worldPoints(const glm::mat4& ctm, const std::vector<glm::vec3>& p) const;
    // A moving mesh's world points at its keys after the first (the last one last) and
    // the times of all its keys, the first one's first.
    struct MeshMotion {
        std::vector<std::vector<glm::vec3>> keys;
        std::vector<float> times;
        // A deformation whose keys each give N: the vertex normals of the keys after the
        // first, in world space (the first key's are the mesh's own); else empty.
        std::vector<std::vector<glm::vec3>> normals;
    };
    // Appends a mesh's triangles at world points wp (its first key, when `motion` makes
    // them move), reporting degenerate ones once per request.
    void appendTriangles(L, const VertexData& mesh, const std::vector<glm::vec3>& wp,
                         const MeshMotion* motion, uint32_t extraFlags = 0);
    // What a mesh request's triangles share (appendTriangles' set-up)
    struct MeshSetUp;
    MeshSetUp meshSetUp(L, const VertexData& mesh, uint32_t extraFlags);
    // One kept triangle of the mesh (its corners' indices); false where its vertex
    // normals were bad and left zero (the device then shades it with Ng)
    bool appendTriangle(L, const MeshSetUp& m, const VertexData& mesh,
                        const std::vector<glm::vec3>& wp, const MeshMotion* motion,
                        const std::array<int, 3>& corners);
    bool appendCorners(const MeshSetUp& m, const VertexData& mesh,
                       const std::array<int, 3>& corners);
    void addKeyNormals(const MeshMotion& motion, const std::array<int, 3>& corners);
    std::vector<Scene> m_scenes;
    // Make* requests read after a frame was built: run before the next frame renders
    std::vector<std::pair<size_t, std::function<void()>>> m_deferredMakes;
    std::unordered_map<std::string, uint32_t> m_materialKeys;
    std::map<MessageValues, uint32_t> m_attributeSetIndex;
    // A volume or displacement call's index in its list, by (its call's number, its
    // object space: objectSpaceOf)
    using CallIndex = std::map<std::pair<uint64_t, uint32_t>, size_t>;
    CallIndex m_atmosphereKeys, m_interiorKeys, m_exteriorKeys, m_displacementKeys;
    size_t callIndex(uint64_t key, const ShaderRef& call, CallIndex& index,
                     std::vector<ShaderRef>& calls, size_t limit, const char* request);
    // 0 when the call's shader does not read "object" space (shaderReadsObjectSpace,
    // asked once a world), else 1 + the index of the current transform among the object
    // spaces the world's primitives gave such shaders (at most kMaxObjectSpaces; past
    // them 0, with a warning).
    uint32_t objectSpaceOf(const ShaderRef& call);
    std::map<std::string, bool> m_readsObjectSpace;
    std::map<std::string, uint32_t> m_objectSpaces;  // by the transform's bytes
    uint64_t m_surfaceCalls = 0;
    int m_degenerate = 0;
    glm::dvec3 m_origin{0.0};  // the eye in world space: the device's world origin
    std::set<std::pair<std::string, int>> m_warnedAt;  // requests already reported
    // Object definitions (ObjectBegin/End): tessellated pieces and exact quadrics in the
    // object's space (a quadric's matrices map it into the object's space).
    struct ObjectDef {
        std::vector<VertexData> meshes;  // in the object's space, per-point values too
        std::vector<QuadricShape> quadrics;
        std::vector<rib::ParamList> quadricParams;  // each quadric's primitive variables
        // Each quadric's request again, with its place in the object's space: a truly
        // displaced instance makes it once more where it stands, to be diced (exact
        // quadrics are not displaced)
        std::vector<std::pair<glm::mat4, std::function<void()>>> quadricCalls;
    };
    // Inside ObjectBegin, keeps a quadric request that makes an exact quadric for the
    // instances that dice it (ObjectDef::quadricCalls).
    void keepQuadricCall(std::function<void()> call);
    std::map<std::string, ObjectDef> m_objects;
    std::map<std::string, uint32_t> m_prototypes;  // per world: handle -> Scene::prototypes
    std::map<std::string, uint32_t> m_lightHandles;  // per world: handle -> light index
    std::map<std::string, uint32_t> m_optionLightHandles;  // ... of lights before WorldBegin
    // a named coordinate system's transform to world (rib_builder_transforms.cpp)
    std::optional<glm::mat4> namedSpace(const std::string& name) const;
    std::map<std::string, glm::mat4> m_coordSystems; // CoordinateSystem name -> object to world
    // ScopedCoordinateSystem name -> its last placement (for shaders that name it)
    std::map<std::string, glm::mat4> m_lastScopedSystems;
    // ObjectInstance without copies: the object's meshes become a prototype (once per
    // world, in object space), each instance a record placing it; `pointParams` are the
    // per-point values all its meshes give (sharedPointParams).
    void addInstance(L, const std::string& handle, const ObjectDef& def,
                     const std::vector<std::pair<std::string, int>>& pointParams);
    // The per-point shader parameters (names, floats a value) that all of an object's
    // meshes give, or none; nullopt when its instances cannot share one prototype: its
    // meshes give different ones, or points, vectors or normals, which each instance
    // places in its own space (those instances are copies, as inside a solid).
    static std::optional<std::vector<std::pair<std::string, int>>> sharedPointParams(
        const ObjectDef& def);

    ObjectDef* m_defining = nullptr;
    // SolidBegin/End blocks being built: a tree of nodes; primitive leaves list the
    // members (triangle indices or RT_OBJECT_BIT | quadric index) with what they were.
    struct SolidNode {
        std::string op;
        rib::SourceLoc loc;
        std::vector<int> children;
        std::vector<uint32_t> members;
        std::vector<std::string> memberWhat;  // "Cylinder at file:line"
    };
    std::vector<SolidNode> m_solidNodes;
    // Per node (children follow their parents), whether it holds no surface at all.
    static std::vector<char> emptySolidNodes(const std::vector<SolidNode>& nodes);
    std::string whyNotClosed(const SolidNode& n, float tol) const;
    std::vector<int> m_solidStack;
    glm::mat4 m_definingCtm{1.0f};
};

}  // namespace rd
