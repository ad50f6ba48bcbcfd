// hoist.h: uniform work done once per shader instance (DESIGN.md section 4, PixelFlow).
// A top-level declaration of a uniform variable whose initialiser depends only on the
// shader's parameters (and on variables hoisted before it), calls only pure builtins,
// and which nothing assigns again, is computed once per instance by the shader's
// prepare function (rsl_prep_<kind>_<name>) into slots after its parameter block; the
// shader reads the slot instead of computing it again at every shading point.
#pragma once
#include <map>
#include <vector>

#include "ast.h"

namespace rsl {

struct HoistPlan {
    std::vector<const VarDecl*> decls;       // in program order
    std::map<const VarDecl*, int> slot;      // float offset within the prepared slots
    // illuminate and illuminance statements of the body whose cone angle is uniform work
    // (it depends on parameters, not a constant): the slot of its cosine (rsl_cone_cos)
    std::vector<const Stmt*> cones;
    std::map<const Stmt*, int> coneSlot;
    int floats = 0;
};

// The angle of a cone statement (illuminate P, axis, angle; illuminance [category,] P,
// axis, angle), or null without one.
const Expr* coneAngle(const Stmt& s);

// `computedDefault[i]` is true for parameter i whose default is not a constant (it is
// computed per shading point, so nothing that reads it can be hoisted).
// colorSlots: the slots a colour takes (max(3, colour channels)).
HoistPlan planHoisting(const ShaderDecl& shader, const std::vector<bool>& computedDefault,
                       int colorSlots = 3);

}  // namespace rsl
