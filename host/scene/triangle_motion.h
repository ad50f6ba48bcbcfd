// triangle_motion.h: a moving triangle's motion keys as the Scene holds them (its first
// key in Scene::triangles, its last in trianglesEnd, the keys between in quadricMotion,
// a RT_Q_MOVING_TRIANGLE record over them all: cl/lib/motion.clh reads them), written by
// the RIB builder and read and rewritten by true displacement, which dices and moves
// them.
#pragma once
#include <vector>

#include "host/scene/scene.h"

namespace rd {

// Makes the scene's last triangle (its first key) move through `keys` (the second key
// on) at `times` (every key's, the first included), and adds its motion record.
void addTriangleMotion(Scene& s, const std::vector<Triangle>& keys,
                       const std::vector<float>& times);

// A moving triangle's keys from the second on (the w components are the scene's own
// bookkeeping) and their times, the first key's included.
struct TriangleKeys {
    std::vector<Triangle> keys;
    std::vector<float> times;
};
TriangleKeys triangleKeys(const Scene& s, size_t triangle);

// Moves triangle `triangle`'s keys from the second on to `keys`' places (as many as
// triangleKeys gave), keeping the scene's bookkeeping in their w components.
void setTriangleKeys(Scene& s, size_t triangle, const std::vector<Triangle>& keys);

// The box over every key of a moving triangle.
Aabb triangleMotionBounds(const Scene& s, size_t triangle);

}  // namespace rd
