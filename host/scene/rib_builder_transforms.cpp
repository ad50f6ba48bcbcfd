// rib_builder_transforms.cpp: the transform requests, TransformBegin/End, Shutter and
// MotionBegin/End. A MotionBegin around transforms makes the current placement move
// through its keys at their times, linearly from key to key (motion blur of whatever is
// declared under it, quadrics exactly); around a mesh's keys it makes the mesh deform.
#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "rib_builder.h"
#include "rib_builder_util.h"

namespace rd {

void RibBuilder::applyTransform(const glm::mat4& m, bool replace) {
    Attributes& a = m_attrStack.back();
    if (m_motion.active) {
        glm::mat4 key = replace ? m : m_motion.before.ctm * m;
        m_motion.keys.push_back(key);
        a.ctm = key;  // the last key so far; MotionEnd makes the motion
        return;
    }
    a.ctm = replace ? m : a.ctm * m;
    if (a.moving) {
        a.ctmEnd = replace ? m : a.ctmEnd * m;
        for (auto& key : a.between) key.second = replace ? m : key.second * m;
    }
}

std::pair<int, int> RibBuilder::keySegments(int nu, int nv) {
    if (!m_motion.active) return {nu, nv};
    if (m_motion.meshKeys.empty()) m_motion.segments = {nu, nv};
    return m_motion.segments;
}

glm::mat4 RibBuilder::ctmAt(const Placement& p, float time) {
    if (!p.moving) return p.ctm;
    float ta = p.t0, tb = p.t1;
    const glm::mat4 *ka = &p.ctm, *kb = &p.ctmEnd;
    for (const auto& [t, key] : p.between) {  // (as cl/lib/motion.clh picks them)
        if (!(time >= t)) {
            kb = &key, tb = t;
            break;
        }
        ka = &key, ta = t;
    }
    const float s = tb > ta ? std::clamp((time - ta) / (tb - ta), 0.0f, 1.0f) : 0.0f;
    return (1.0f - s) * *ka + s * *kb;
}

void RibBuilder::shutter(L loc, float open, float close) {
    if (!(open <= close) || !std::isfinite(open) || !std::isfinite(close)) {
        m_diag.error(loc, "Shutter needs finite open <= close");
        return;
    }
    m_options.camera.shutter[0] = open;
    m_options.camera.shutter[1] = close;
}

void RibBuilder::motionBegin(L, Floats times) {
    m_motion = MotionBlock();
    m_motion.active = true;
    m_motion.times = times;
    m_motion.before = m_attrStack.back();
}

void RibBuilder::motionEnd(L loc) {
    if (!m_motion.active) return;
    MotionBlock block = std::move(m_motion);
    m_motion = MotionBlock();
    Attributes& a = m_attrStack.back();
    // (the reader reports a count of keys other than the times'; the shorter is used)
    const size_t keys = std::min(block.keys.size(), block.times.size());
    if (keys >= 2) {
        if (block.before.moving)
            m_diag.warning(loc, "MotionBegin inside a moving transform: the outer motion is "
                                "replaced");
        a.ctm = block.keys.front();
        a.ctmEnd = block.keys[keys - 1];
        a.t0 = block.times.front();
        a.t1 = block.times[keys - 1];
        a.moving = a.t1 > a.t0;
        a.between.clear();
        for (size_t k = 1; k + 1 < keys; ++k)
            a.between.push_back({block.times[k], block.keys[k]});
    }
    const size_t meshKeys = std::min(block.meshKeys.size(), block.times.size());
    if (meshKeys == 1) addMesh(loc, block.meshKeys.front());
    if (meshKeys >= 2) {
        block.meshKeys.resize(meshKeys);
        block.times.resize(meshKeys);
        addMovingMesh(loc, block.meshKeys, block.times);
    }
}

void RibBuilder::transformBegin(L) { m_xformStack.push_back(m_attrStack.back()); }
void RibBuilder::transformEnd(L) {
    if (m_xformStack.empty()) return;
    static_cast<Placement&>(m_attrStack.back()) = m_xformStack.back();
    m_xformStack.pop_back();
}

// ClippingPlane (RI 3.2): the plane in the current space; camera space before the world
// (WorldBegin takes it to the world), world space inside it.
std::array<glm::vec3, 2> transformPlane(const glm::mat4& m,
                                        const std::array<glm::vec3, 2>& p) {
    return {glm::vec3(m * glm::vec4(p[0], 1.0f)),
            glm::normalize(glm::transpose(glm::inverse(glm::mat3(m))) * p[1])};
}
void RibBuilder::clippingPlane(L loc, float x, float y, float z, float nx, float ny,
                               float nz) {
    const glm::vec3 p(x, y, z), n(nx, ny, nz);
    if (!finite3(p) || !finite3(n) || !(glm::dot(n, n) > 0.0f))
        return m_diag.error(loc,
                            "ClippingPlane needs a finite point and a nonzero normal");
    const std::array<glm::vec3, 2> plane = transformPlane(m_attrStack.back().ctm, {p, n});
    if (!finite3(plane[0]) || !finite3(plane[1]))
        return m_diag.error(loc, "ClippingPlane: the current transform is singular");
    auto& planes = (m_inWorld ? m_world : m_options).clipPlanes;
    if (planes.size() == kMaxClipPlanes)
        m_diag.warning(loc, "more than " + std::to_string(kMaxClipPlanes) +
                                " ClippingPlane requests; the later ones are not used");
    planes.push_back(plane);
}

// Camera "name" (PRMan): the camera as it stands is a coordinate system of that name.
void RibBuilder::camera(L, S name, P) {
    m_coordSystems[name] = glm::inverse(m_attrStack.back().ctm);
}

void RibBuilder::coordinateSystem(L, S name) { m_coordSystems[name] = m_attrStack.back().ctm; }

// (kept in the attributes: the attribute block's end forgets it; shaders that name it
// get its last placement, m_lastScopedSystems)
void RibBuilder::scopedCoordinateSystem(L, S name) {
    Attributes& a = m_attrStack.back();
    a.scopedSystems.push_back({name, a.ctm});
    m_lastScopedSystems[name] = a.ctm;
}

// A named coordinate system's transform to world: one ScopedCoordinateSystem named in the
// attribute blocks around (the latest first), or CoordinateSystem, or "world" (identity
// inside the world), "camera" (camera to world). Not "object" or "shader", whose meaning
// the caller decides.
std::optional<glm::mat4> RibBuilder::namedSpace(const std::string& name) const {
    const auto& scoped = m_attrStack.back().scopedSystems;
    for (auto it = scoped.rbegin(); it != scoped.rend(); ++it)
        if (it->first == name) return it->second;
    if (auto it = m_coordSystems.find(name); it != m_coordSystems.end())
        return it->second;
    if (name == "world") return glm::mat4(1.0f);
    if (name == "camera")
        return glm::inverse(m_inWorld ? m_world.camera.worldToCamera : glm::mat4(1.0f));
    return std::nullopt;
}

// Makes a named coordinate system current (namedSpace); "object" and "shader" leave the
// current transform as it is.
void RibBuilder::coordSysTransform(L loc, S name) {
    if (const auto m = namedSpace(name)) return applyTransform(*m, true);
    if (name == "object" || name == "shader") return;
    m_diag.error(loc, "CoordSysTransform: no coordinate system named \"" + name + "\"");
}

// Orientation and Sides (RI 3.2 section 4.2): the current orientation follows the
// coordinate system's handedness through every transform, so what is kept is whether it
// differs from it (inside out). "lh"/"rh" compare with the handedness of object to camera
// space, left-handed when its determinant is positive (camera space is left-handed).
void RibBuilder::sides(L loc, int n) {
    if (n != 1 && n != 2) return m_diag.error(loc, "Sides must be 1 or 2");
    m_attrStack.back().sides = n;
}
// ShadingRate: the area in pixels of a micropolygon; here it sets how finely truly
// displaced surfaces are diced (an edge of sqrt(size) pixels).
void RibBuilder::shadingRate(L loc, float size) {
    if (!(size > 0.0f) || !std::isfinite(size))
        return m_diag.error(loc, "ShadingRate must be a positive number");
    m_attrStack.back().shadingRate = size;
}
void RibBuilder::orientation(L loc, const std::string& o) {
    Attributes& a = m_attrStack.back();
    const glm::mat4 toCamera = m_inWorld ? m_world.camera.worldToCamera * a.ctm : a.ctm;
    const bool leftHanded = glm::determinant(glm::mat3(toCamera)) > 0.0f;
    if (o == "outside") a.insideOut = false;
    else if (o == "inside") a.insideOut = true;
    else if (o == "lh") a.insideOut = !leftHanded;
    else if (o == "rh") a.insideOut = leftHanded;
    else m_diag.error(loc, "Orientation must be outside, inside, lh or rh, not \"" + o + "\"");
}
void RibBuilder::reverseOrientation(L) { m_attrStack.back().insideOut ^= true; }

bool RibBuilder::flipWorldNormals() const {
    const Attributes& a = m_attrStack.back();
    return a.insideOut != (glm::determinant(glm::mat3(a.ctm)) < 0.0f);
}

// Skew (RI 3.2): shears along the second axis so that the first axis turns by `angle`
// toward it: P' = P + s (P . d1perp) d2, with d1perp the part of d1 across d2. An angle
// that would take d1 past d2 is an error.
void RibBuilder::skew(L loc, float angleDeg, float dx1, float dy1, float dz1, float dx2,
                      float dy2, float dz2) {
    glm::dvec3 d1(dx1, dy1, dz1), d2(dx2, dy2, dz2);
    if (!(glm::length(d1) > 0) || !(glm::length(d2) > 0))
        return m_diag.error(loc, "Skew axes must not be zero");
    d1 = glm::normalize(d1), d2 = glm::normalize(d2);
    glm::dvec3 across = d1 - glm::dot(d1, d2) * d2;  // d1's part perpendicular to d2
    const double perp = glm::length(across), par = glm::dot(d1, d2);
    if (!(perp > 1e-9)) return m_diag.error(loc, "Skew axes must not be parallel");
    const double from = std::atan2(perp, par), to = from - glm::radians(double(angleDeg));
    if (!(to > 1e-9 && to < M_PI - 1e-9))
        return m_diag.error(loc, "Skew angle turns the first axis past the second");
    const double s = (perp / std::tan(to) - par) / perp;
    const glm::dvec3 n = across / perp;
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c)      // column c: the image of axis c
        for (int r = 0; r < 3; ++r)  // row r
            m[c][r] += s * d2[r] * n[c];
    applyTransform(glm::mat4(m), false);
}

void RibBuilder::exposure(L loc, float gain, float gamma) {
    if (!(gain >= 0) || !(gamma > 0) || !std::isfinite(gain) || !std::isfinite(gamma))
        return m_diag.error(loc, "Exposure needs gain >= 0 and gamma > 0");
    m_options.camera.exposure[0] = gain;
    m_options.camera.exposure[1] = gamma;
}

// Perspective makes the current transform projective. As the projection (after
// Projection "null", or first in the camera's transforms before WorldBegin) it is the
// perspective camera of that field of view; anywhere else placements here cannot be
// projective and it is ignored with a warning.
void RibBuilder::perspective(L loc, float fov) {
    const bool identity = m_attrStack.back().ctm == glm::mat4(1.0f);
    if (!m_inWorld && !m_defining && (m_projectionNull || identity)) {
        if (!(fov > 0.0f && fov < 180.0f))
            return m_diag.error(loc, "Perspective fov must be in (0, 180) degrees");
        m_options.camera.perspective = true;
        m_options.camera.fovDeg = fov;
        m_projectionNull = false;
        m_attrStack.back().ctm = glm::mat4(1.0f);  // camera space starts after it
        return;
    }
    m_diag.warning(loc, "Perspective inside the world or after camera transforms (a "
                        "projective transform) is not supported; ignored");
}

// ColorSamples n <= 15: the reader hands colours over as their n values
// (keptColorSamples; under three padded to three) and the renderer shades, traces and
// sums samples in those channels, converting each sample to RGB for the film; primitive
// variables too (Cs, Os, and per-point shader parameters). More than 15:
// the reader converts every colour to RGB through nRGB as it reads it, and the renderer
// stays RGB.
void RibBuilder::colorSamples(L loc, Floats nRGB, Floats RGBn) {
    if (m_inWorld)
        m_diag.warning(loc, "ColorSamples is an option: inside the world block it applies to "
                            "the whole image, colours given before it included");
    for (Scene* s : {&m_options, &m_world})
        if (!s->colors.set(nRGB, RGBn)) s->colors = ColorSamples{};
    if (nRGB.size() > 3 * size_t(ColorSamples::kMaxChannels))
        m_diag.warning(
            loc, "ColorSamples " + std::to_string(nRGB.size() / 3) + ": more than " +
                     std::to_string(ColorSamples::kMaxChannels) +
                     " channels are converted to RGB as they are read (colours "
                     "then multiply in RGB)");
}

void RibBuilder::textureCoordinates(L, float s1, float t1, float s2, float t2, float s3,
                                    float t3, float s4, float t4) {
    Attributes& a = m_attrStack.back();
    const float s[4] = {s1, s2, s3, s4}, t[4] = {t1, t2, t3, t4};
    std::copy(s, s + 4, a.texS);
    std::copy(t, t + 4, a.texT);
}

void RibBuilder::identity(L) {
    // Inside the world, identity means world space; outside, camera space.
    applyTransform(glm::mat4(1.0f), true);
}
void RibBuilder::transform(L, const float m[16]) { applyTransform(ribMatrix(m), true); }
void RibBuilder::concatTransform(L, const float m[16]) { applyTransform(ribMatrix(m), false); }
void RibBuilder::translate(L, float x, float y, float z) {
    applyTransform(glm::translate(glm::mat4(1.0f), {x, y, z}), false);
}
void RibBuilder::rotate(L loc, float a, float x, float y, float z) {
    glm::vec3 axis(x, y, z);
    if (!(glm::length(axis) > 0.0f)) {
        m_diag.error(loc, "Rotate axis must not be zero");
        return;
    }
    applyTransform(glm::rotate(glm::mat4(1.0f), glm::radians(a), glm::normalize(axis)), false);
}
void RibBuilder::scale(L, float x, float y, float z) {
    applyTransform(glm::scale(glm::mat4(1.0f), {x, y, z}), false);
}

// RiTransformPoints, inside a world block: "object", "current" and "shader" (the current
// transform), "world", "camera", "screen", "NDC", "raster" (RI 3.2 section 4.1: screen is
// the projection of camera space, its z the camera depth, so a point can leave these
// spaces as well as enter them) and the names CoordinateSystem and
// ScopedCoordinateSystem gave. False for any other space, or outside a world.
bool RibBuilder::transformPoints(S from, S to, float* xyz, int n) {
    if (!m_inWorld) return false;
    const Camera dc = m_world.deviceCamera();
    const glm::mat4& worldToCamera = m_world.camera.worldToCamera;
    // object to world of an affine space (namedSpace, or the current transform); none for
    // a projected or unknown one
    auto affine = [&](const std::string& s) -> std::optional<glm::mat4> {
        if (s == "object" || s == "current" || s == "shader")
            return m_attrStack.back().ctm;
        return namedSpace(s);
    };
    const float l = dc.screen[0], r = dc.screen[1], b = dc.screen[2], t = dc.screen[3];
    const float tanHalf = dc.perspective ? dc.tan_half_fov : 1.0f;
    // camera -> screen -> NDC -> raster, and back: `steps` of them from camera space
    auto project = [&](glm::vec3 p, int steps) {
        if (steps >= 1 && dc.perspective)
            p = {p.x / (p.z * tanHalf), p.y / (p.z * tanHalf), p.z};
        if (steps >= 2) p = {(p.x - l) / (r - l), (t - p.y) / (t - b), p.z};
        if (steps >= 3) p = {p.x * float(dc.width), p.y * float(dc.height), p.z};
        return p;
    };
    auto unproject = [&](glm::vec3 p, int steps) {
        if (steps >= 3) p = {p.x / float(dc.width), p.y / float(dc.height), p.z};
        if (steps >= 2) p = {l + p.x * (r - l), t - p.y * (t - b), p.z};
        if (steps >= 1 && dc.perspective)
            p = {p.x * p.z * tanHalf, p.y * p.z * tanHalf, p.z};
        return p;
    };
    auto projected = [](const std::string& s) {
        return s == "screen" ? 1 : s == "NDC" ? 2 : s == "raster" ? 3 : 0;
    };
    // from `from` (camera space when projected) to world, and from world to `to`
    const int pf = projected(from), pt = projected(to);
    const std::optional<glm::mat4> fromSpace =
        pf ? glm::inverse(worldToCamera) : affine(from);
    const std::optional<glm::mat4> toSpace =
        pt ? glm::inverse(worldToCamera) : affine(to);
    if (!fromSpace || !toSpace) return false;
    const glm::mat4 m = glm::inverse(*toSpace) * *fromSpace;
    for (int i = 0; i < n; ++i) {
        glm::vec3 p(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
        if (pf) p = unproject(p, pf);
        p = glm::vec3(m * glm::vec4(p, 1.0f));
        if (pt) p = project(p, pt);
        xyz[3 * i] = p.x, xyz[3 * i + 1] = p.y, xyz[3 * i + 2] = p.z;
    }
    return true;
}

}  // namespace rd
