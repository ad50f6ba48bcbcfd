/* layout_probe.cl: writes the device's sizeof and offsetof of every shared struct, in the
 * order of layout_fields.h, so tests/layout_test.cpp can compare them with the host's. */
#include "all_types.h"

__kernel void layout_probe(__global uint* out) {
    if (get_global_id(0) != 0) return;
    uint i = 0;
#define RT_STRUCT(T) out[i++] = (uint)sizeof(T);
#define RT_FIELD(T, f) out[i++] = (uint)__builtin_offsetof(T, f);
#include "layout_fields.h"
#undef RT_STRUCT
#undef RT_FIELD
}
