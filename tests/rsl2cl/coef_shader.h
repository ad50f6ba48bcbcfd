// coef_shader.h: a surface that takes every light-coefficient path of the code generator
// (rsl2cl emit_coefs.cpp): an illumination model in a function with two returns, an
// illuminance loop, impure operands (area, random, a texture), ?:, mix, compound
// assignments, and a trace() besides. Mutated by fuzz_test.cpp and light_coefs_test.cpp.
#pragma once

namespace rsltest {

inline const char* coefShader() {
    return "surface f(float Kd = .5, Ks = .5; color sc = 1;) {\n"
           "  color m(normal Nf; vector V; float r; color sc) {\n"
           "    color C = 0;\n"
           "    illuminance(P, Nf, PI / 2) { C += Cl * (normalize(L) . Nf) * r; C -= Cl / 8; }\n"
           "    if (r > 1) return C * random();\n"
           "    return C + sc * specular(Nf, V, r) / 2;\n"
           "  }\n"
           "  normal Nf = faceforward(normalize(N), I);\n"
           "  color c = area(P) * diffuse(Nf), d = u > .5 ? c : -c;\n"
           "  c *= 1 + random();\n"
           "  d = mix(c, d, v) + color texture(\"t.tx\", \"fill\", 0.5) * m(Nf, -I, Ks, sc);\n"
           "  Oi = Os;\n"
           "  Ci = Os * (Cs * Kd * (c + d) + trace(P, Nf));\n"
           "}\n";
}

}  // namespace rsltest
