// light_services.h: the scene's light instances in the params buffer, and the services
// the generated code calls to run them (rsl_abi.h, LIGHTS). Each light shader is called
// from one place, its instances told apart by where their data lies (tables of offsets:
// the layout, not the values), so a light edited between renders changes data, not the
// program, which would cost a build and every kernel's first compile again (2.85 s for
// SPD teapot).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace rsl {
struct EmittedShader;
}

namespace rd {

// Per bound light instance (a LightSource call whose shader compiled): its shader's index
// in `shaders`, the offsets of its parameter block and of its place (P, N: 8 floats) in
// the params buffer, and an area light's triangles (their start and count; 0 of them: a
// point light's place).
struct BoundLights {
    std::vector<int> shaderOf;
    std::vector<size_t> block, place, areaAt, areaCount;
    std::vector<const rsl::EmittedShader*> shaders;  // each light shader, once
    std::vector<bool> ambient;      // an ambient light: no direction, no shadow ray
    std::vector<bool> mapShadowed;  // its "shadowname" names a map: no traced shadow ray
    uint32_t count() const { return uint32_t(shaderOf.size()); }
};

// Appends the first `count` of an area light's triangles to `params` at a float4
// boundary (data too: a camera move shifts them, eye-relative), each corner a float4, the
// first one's w the share of the area up to and with that triangle (rd_area_point picks
// by it); returns their start.
size_t appendAreaTriangles(const std::vector<std::array<glm::vec3, 3>>& triangles,
                           size_t count, std::vector<float>& params);

// rsl_light_count, rsl_lightsource_param, rd_run_light, rd_light_traces_shadows,
// rd_light_is_ambient, the light cache (rd_light_at, rd_fill_light_cache), rsl_light
// and rsl_ambient, OpenCL C.
std::string lightServices(const BoundLights& lights);

}  // namespace rd
