// rib_builder_transforms.cpp: the transform requests, TransformBegin/End, Shutter and
// MotionBegin/End. A MotionBegin around transforms makes the current placement move:
// linearly from its first key to its last between their times (motion blur of whatever
// is declared under it, quadrics exactly); around a mesh's keys it makes the mesh
// deform. Keys between the first and the last are not used yet.
#include <glm/gtc/matrix_transform.hpp>

#include "rib_builder.h"
#include "rib_builder_util.h"

namespace rd {

void RibBuilder::applyTransform(const glm::mat4& m, bool replace) {
    Attributes& a = m_attrStack.back();
    if (m_motion.active) {
        glm::mat4 key = replace ? m : m_motion.before.ctm * m;
        if (m_motion.count++ == 0) m_motion.firstKey = key;
        a.ctm = key;  // the last key so far; MotionEnd makes the pair
        return;
    }
    a.ctm = replace ? m : a.ctm * m;
    if (a.moving) a.ctmEnd = replace ? m : a.ctmEnd * m;
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
    const float t0 = block.times.empty() ? 0.0f : block.times.front();
    const float t1 = block.times.empty() ? 0.0f : block.times.back();
    Attributes& a = m_attrStack.back();
    if (block.count >= 2) {
        if (block.before.moving)
            m_diag.warning(loc, "MotionBegin inside a moving transform: the outer motion is "
                                "replaced");
        a.ctmEnd = a.ctm;
        a.ctm = block.firstKey;
        a.moving = t1 > t0;
        a.t0 = t0;
        a.t1 = t1;
    }
    if (block.meshKeys.size() == 1) addMesh(loc, block.meshKeys.front());
    if (block.meshKeys.size() >= 2)
        addMovingMesh(loc, block.meshKeys.front(), block.meshKeys.back(), t0, t1);
}

void RibBuilder::transformBegin(L) { m_xformStack.push_back(m_attrStack.back()); }
void RibBuilder::transformEnd(L) {
    if (m_xformStack.empty()) return;
    static_cast<Placement&>(m_attrStack.back()) = m_xformStack.back();
    m_xformStack.pop_back();
}

void RibBuilder::coordinateSystem(L, S name) { m_coordSystems[name] = m_attrStack.back().ctm; }

// Makes a named coordinate system current: one CoordinateSystem named, or "world"
// (identity inside the world), "camera" (camera to world); "object" and "shader" leave
// the current transform as it is.
void RibBuilder::coordSysTransform(L loc, S name) {
    if (auto it = m_coordSystems.find(name); it != m_coordSystems.end())
        return applyTransform(it->second, true);
    if (name == "world") return applyTransform(glm::mat4(1.0f), true);
    if (name == "camera") {
        const glm::mat4 worldToCamera =
            m_inWorld ? m_world.camera.worldToCamera : glm::mat4(1.0f);
        return applyTransform(glm::inverse(worldToCamera), true);
    }
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

}  // namespace rd
