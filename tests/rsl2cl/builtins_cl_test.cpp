// builtins_cl_test.cpp: the RSL builtin library (rsl_stdlib.clh) through the whole
// compiler on the device, over a grid, against independent host implementations;
// noise by its properties (range, continuity, periodicity, determinism, variants).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "testshade.h"

namespace {

using V3 = std::array<double, 3>;
using Ref = std::function<V3(double x, double y, double s, double t)>;

struct Case {
    const char* rsl;  // statements setting Ci, with x = 2s - 1, y = 2t - 1 in scope
    Ref ref;
    double tol;
};

double dotd(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 normd(V3 a) {
    double l = std::sqrt(dotd(a, a));
    return {a[0] / l, a[1] / l, a[2] / l};
}
double smooth(double a, double b, double x) {
    if (x < a) return 0;
    if (x >= b) return 1;
    double u = (x - a) / (b - a);
    return u * u * (3 - 2 * u);
}
double catmull(double t, std::vector<double> k) {
    int nseg = int(k.size()) - 3;
    double xx = t * nseg;
    int i = std::min(int(xx), nseg - 1);
    double f = xx - i, p0 = k[i], p1 = k[i + 1], p2 = k[i + 2], p3 = k[i + 3];
    return 0.5 * (2 * p1 + (-p0 + p2) * f + (2 * p0 - 5 * p1 + 4 * p2 - p3) * f * f +
                  (-p0 + 3 * p1 - 3 * p2 + p3) * f * f * f);
}
V3 rgb2hsv(V3 c) {
    double mx = std::max({c[0], c[1], c[2]}), mn = std::min({c[0], c[1], c[2]}), d = mx - mn, h = 0;
    if (d > 0) {
        if (mx == c[0]) h = std::fmod((c[1] - c[2]) / d + 6, 6);
        else if (mx == c[1]) h = (c[2] - c[0]) / d + 2;
        else h = (c[0] - c[1]) / d + 4;
    }
    return {h / 6, mx > 0 ? d / mx : 0, mx};
}
V3 hsv2rgb(V3 c) {  // via the chroma formulation
    double C = c[2] * c[1], h = c[0] * 6, X = C * (1 - std::fabs(std::fmod(h, 2) - 1)), m = c[2] - C;
    V3 r = h < 1 ? V3{C, X, 0} : h < 2 ? V3{X, C, 0} : h < 3 ? V3{0, C, X}
         : h < 4 ? V3{0, X, C} : h < 5 ? V3{X, 0, C} : V3{C, 0, X};
    return {r[0] + m, r[1] + m, r[2] + m};
}

const double kPi = 3.14159265358979;

std::vector<Case> cases() {
    return {
        {"Ci = color(sin(x * 3), cos(x * 3), tan(x));",
         [](double x, double, double, double) { return V3{sin(x * 3), cos(x * 3), tan(x)}; }, 1e-5},
        {"Ci = color(asin(x * .9), acos(y * .9), atan(x * 3));",
         [](double x, double y, double, double) { return V3{asin(x * .9), acos(y * .9), atan(x * 3)}; }, 1e-5},
        {"Ci = color(atan(y, x), pow(s + 0.1, 2.5), exp(x));",
         [](double x, double y, double s, double) { return V3{atan2(y, x), pow(s + .1, 2.5), exp(x)}; }, 1e-5},
        // rsl_pow: a positive base through exp2/log2 (a specular exponent of 100; the
        // float base's own rounding, 6e-8, grows 100-fold, hence 2e-5), a negative base
        // with an integer exponent, a zero base and a unit one keep pow's rules
        {"Ci = color(pow(0.9 + 0.1 * s, 100), pow(-1.5 - s, 3), pow(s * 0, 2) + pow(1, 1e30));",
         [](double, double, double s, double) {
             return V3{pow(.9 + .1 * s, 100), pow(-1.5 - s, 3), 1.0};
         }, 2e-5},
        {"Ci = color(sqrt(s), inversesqrt(s + 0.5), log(s + 0.1));",
         [](double, double, double s, double) { return V3{sqrt(s), 1 / sqrt(s + .5), log(s + .1)}; }, 1e-5},
        {"Ci = color(log(s + 0.1, 2), mod(x * 7, 1.3), abs(x));",
         [](double x, double, double s, double) {
             return V3{log2(s + .1), x * 7 - 1.3 * floor(x * 7 / 1.3), fabs(x)};
         }, 1e-4},
        {"Ci = color(sign(x), floor(x * 3), ceil(x * 3));",
         [](double x, double, double, double) { return V3{double((x > 0) - (x < 0)), floor(x * 3), ceil(x * 3)}; }, 0},
        {"Ci = color(round(x * 3 + 0.1), radians(x * 90), degrees(x));",
         [](double x, double, double, double) { return V3{round(x * 3 + .1), x * 90 * kPi / 180, x * 180 / kPi}; }, 1e-5},
        {"Ci = color(min(x, y), max(x, y, 0.25), clamp(x, -0.5, 0.5));",
         [](double x, double y, double, double) {
             return V3{std::min(x, y), std::max({x, y, .25}), std::min(std::max(x, -.5), .5)};
         }, 0},
        {"Ci = color(mix(x, y, s), step(0.2, x), smoothstep(-0.5, 0.5, y));",
         [](double x, double y, double s, double) {
             return V3{x * (1 - s) + y * s, x < .2 ? 0. : 1., smooth(-.5, .5, y)};
         }, 1e-5},
        {"Ci = clamp(color(x, y, x * y), color(-0.2, -0.1, 0), color(0.5, 0.6, 0.2)) + "
         "max(color(x, 0, 0), color(y, 0, 0));",
         [](double x, double y, double, double) {
             return V3{std::min(std::max(x, -.2), .5) + std::max(x, y), std::min(std::max(y, -.1), .6),
                       std::min(std::max(x * y, 0.), .2)};
         }, 1e-6},
        {"Ci = mix(color(1, 0, 0), color(0, 1, s), t);",
         [](double, double, double s, double t) { return V3{1 - t, t, s * t}; }, 1e-6},
        {"Ci = color(spline(s, 0, 1, 3, 2, 5, 4), spline(\"linear\", s, 0, 1, 3, 2), 0);",
         [](double, double, double s, double) {
             double xx = s * 3;
             int i = std::min(int(xx), 2);
             std::vector<double> k = {0, 1, 3, 2};
             return V3{catmull(s, {0, 1, 3, 2, 5, 4}), k[i] * (1 - (xx - i)) + k[i + 1] * (xx - i), 0};
         }, 1e-5},
        {"Ci = spline(s, color(0), color(1, 0, 0), color(0, 1, 0), color(0, 0, 1), color(1));",
         [](double, double, double s, double) {
             return V3{catmull(s, {0, 1, 0, 0, 1}), catmull(s, {0, 0, 1, 0, 1}), catmull(s, {0, 0, 0, 1, 1})};
         }, 1e-5},
        {"vector a = vector(x, y, 0.5);\n"
         "Ci = color(length(a), distance(point(x, y, 0), point(1, 2, 3)), xcomp(normalize(a)));",
         [](double x, double y, double, double) {
             return V3{sqrt(x * x + y * y + .25), sqrt((x - 1) * (x - 1) + (y - 2) * (y - 2) + 9),
                       x / sqrt(x * x + y * y + .25)};
         }, 1e-5},
        {"Ci = color(reflect(normalize(vector(x, y, -1)), normal(0, 0, 1)));",
         [](double x, double y, double, double) {
             V3 i = normd({x, y, -1});
             return V3{i[0], i[1], -i[2]};
         }, 1e-5},
        {"Ci = color(refract(normalize(vector(x, y, -1)), normal(0, 0, 1), 0.7));",
         [](double x, double y, double, double) {
             V3 i = normd({x, y, -1});
             double c = -i[2], k = 1 - .49 * (1 - c * c);  // Snell: tangential part scales by eta
             return V3{.7 * i[0], .7 * i[1], -sqrt(k)};
         }, 1e-5},
        {"Ci = color(faceforward(normal(x, y, 1), vector(0, 0, 1))) + "
         "color(faceforward(normal(1, 0, 0), vector(x, 0, 0), vector(1, 0, 0)));",
         [](double x, double y, double, double) {
             double f = x < 0 ? 1 : -1;
             return V3{-x + f, -y, -1};
         }, 1e-6},
        {"float kr, kt; vector R, T;\n"
         "fresnel(normalize(vector(x, y, -1)), normal(0, 0, 1), 1 / 1.5, kr, kt, R, T);\n"
         "Ci = color(kr, kt, zcomp(T) + xcomp(R));",
         [](double x, double y, double, double) {
             V3 i = normd({x, y, -1});
             double ci = -i[2], st = sqrt(1 - ci * ci) / 1.5, ct = sqrt(1 - st * st);
             double n1 = 1, n2 = 1.5;  // Fresnel equations with Snell's law
             double rs = (n1 * ci - n2 * ct) / (n1 * ci + n2 * ct), rp = (n2 * ci - n1 * ct) / (n2 * ci + n1 * ct);
             double kr = .5 * (rs * rs + rp * rp);
             return V3{kr, 1 - kr, -ct + i[0]};
         }, 1e-5},
        {"vector a = vector(x, y, 1), b = vector(1, s, t);\n"
         "Ci = color(a . b, zcomp(a ^ b), xcomp(a ^ b));",
         [](double x, double y, double s, double t) { return V3{x + y * s + t, x * s - y, y * t - s}; }, 1e-5},
        {"point q = rotate(point(x, y, 0), 0.5, point(0, 0, 0), point(0, 0, 1));\n"
         "Ci = color(ptlined(point(0, 0, 0), point(1, 0, 0), point(x, y, 0)), xcomp(q), ycomp(q));",
         [](double x, double y, double, double) {
             double d = x < 0 ? sqrt(x * x + y * y) : x > 1 ? sqrt((x - 1) * (x - 1) + y * y) : fabs(y);
             return V3{d, x * cos(.5) - y * sin(.5), x * sin(.5) + y * cos(.5)};
         }, 1e-5},
        {"color c = color(x, y, s); setcomp(c, 1, 7);\n"
         "Ci = color(comp(c, 0), comp(c, 1), comp(c, 2));",
         [](double x, double, double s, double) { return V3{x, 7, s}; }, 0},
        {"Ci = ctransform(\"hsv\", color(s, t, 0.5));",
         [](double, double, double s, double t) { return rgb2hsv({s, t, .5}); }, 1e-5},
        {"Ci = ctransform(\"hsv\", \"rgb\", color(s * 0.99, 0.8, 0.6)) - color \"hsv\" (s * 0.99, t, 1);",
         [](double, double, double s, double t) {
             V3 a = hsv2rgb({s * .99, .8, .6}), b = hsv2rgb({s * .99, t, 1});
             return V3{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
         }, 1e-5},
        {"Ci = ctransform(\"hsl\", \"rgb\", ctransform(\"hsl\", color(s, t, 0.3))) + "
         "ctransform(\"xyz\", \"rgb\", ctransform(\"xyz\", color(t, 0.2, s)));",
         [](double, double, double s, double t) { return V3{s + t, t + .2, .3 + s}; }, 1e-4},
        {"Ci = ctransform(\"xyY\", \"rgb\", ctransform(\"xyY\", color(s, t, 0.3))) + "
         "color \"xyY\" (0.3127, 0.3290, 1);",  // and D65's white point at Y = 1
         [](double, double, double s, double t) { return V3{s + 1, t + 1, 1.3}; }, 2e-3},
        {"Ci = ctransform(\"xyz\", color(s, t, 0.3));",
         [](double, double, double s, double t) {  // Rec. 709 / sRGB primaries, D65
             return V3{.412453 * s + .357580 * t + .180423 * .3, .212671 * s + .715160 * t + .072169 * .3,
                       .019334 * s + .119193 * t + .950227 * .3};
         }, 1e-5},
        {"Ci = color(transform(\"shader\", point(x, y, 0))) + "
         "color(vtransform(\"shader\", \"current\", vector(x, y, 1)));",
         [](double x, double y, double, double) { return V3{x - 1 + x, y - 2 + y, -3 + 1}; }, 1e-5},
        {"Ci = color(transform(\"shader\", \"current\", point(x, y, 0))) + "
         "color(ntransform(\"shader\", normal(x, y, 1))) + color(point \"shader\" (1, 1, 1));",
         [](double x, double y, double, double) { return V3{x + 1 + x + 2, y + 2 + y + 3, 3 + 1 + 4}; }, 1e-5},
        {"matrix m = (1, 0, 0, 0,  0, 2, 0, 0,  0, 0, 3, 0,  1, 1, 1, 1);\n"
         "Ci = color(transform(m, point(x, y, 1))) + color(determinant(m), comp(m, 3, 0), 0) * 10;",
         [](double x, double y, double, double) { return V3{x + 1 + 60, 2 * y + 1 + 10, 4}; }, 1e-5},
        {"matrix m = translate(matrix 1, vector(1, 2, 3));\n"
         "matrix n = scale(matrix 1, point(2, 2, 2)) * m;\n"
         "Ci = color(transform(m, point(x, y, 0))) + color(transform(n / m, point(1, 1, 1)));",
         [](double x, double y, double, double) { return V3{x + 1 + 2, y + 2 + 2, 3 + 2}; }, 1e-5},
        {"float f = 0;\n"
         "Ci = color(Du(s) + Dv(t) + area(P), surface(\"foo\", f), match(\"ab\", \"xabx\")) + "
         "color(concat(\"a\", \"b\") == \"ab\", 0, 0);",
         [](double, double, double, double) { return V3{1, 0, 1}; }, 0},
    };
}

std::string caseShader(const std::vector<Case>& cs) {
    std::string src = "surface bt(float which = 0;)\n{\n  float x = s * 2 - 1, y = t * 2 - 1;\n";
    for (size_t i = 0; i < cs.size(); ++i)
        src += std::string(i ? "  else " : "  ") + "if (which == " + std::to_string(i) + ") {\n" +
               cs[i].rsl + "\n  }\n";
    return src + "}\n";
}

TEST(Builtins, AgainstHostImplementations) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    std::vector<Case> cs = cases();
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(caseShader(cs), "bt.sl", &err)) << err;
    ts::Scene sc;
    sc.shaderOffset[0] = 1, sc.shaderOffset[1] = 2, sc.shaderOffset[2] = 3;
    std::string log;
    ASSERT_TRUE(sh.buildOnDevice(sc, &log)) << log;
    auto pts = ts::grid(8);
    for (size_t i = 0; i < cs.size(); ++i) {
        sh.setParam("which", {float(i)});
        auto out = sh.run(pts, sc);
        ASSERT_EQ(out.size(), pts.size());
        for (size_t k = 0; k < pts.size(); ++k) {
            double s = pts[k].s, t = pts[k].t;
            V3 want = cs[i].ref(2 * s - 1, 2 * t - 1, s, t);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(out[k].Ci[c], want[c], cs[i].tol * std::max(1.0, std::fabs(want[c])) + 1e-6)
                    << "case " << i << ": " << cs[i].rsl << "\n at s=" << s << " t=" << t << " channel " << c;
        }
    }
}

// pow of a positive base (rsl_pow: exp2(y log2 x), not OpenCL's pow) against pow in
// double, over bases from 1e-6 to 1e6 and around 1 and exponents to 400: the relative
// error stays within (4 + 2 |y log2 x|) float ulps (the product's rounding alone is
// |y log2 x| ulps). Powers below 2^-126 come out as at most that (rsl_pow: 0).
TEST(Builtins, PowOfAPositiveBaseIsWithinUlpsOfPow) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource("surface p() { Ci = color(pow(s, t), pow(u, v), 0); }", "p.sl", &err))
        << err;
    ts::Scene sc;
    std::string log;
    ASSERT_TRUE(sh.buildOnDevice(sc, &log)) << log;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    std::vector<ts::Point> pts(4096);
    for (size_t k = 0; k < pts.size(); ++k) {
        const double around1 = 1 + (U(rng) - 0.5) * std::pow(10.0, -7 * U(rng));
        pts[k].s = float(std::pow(10.0, 12 * U(rng) - 6));
        pts[k].t = float(k % 8 == 0 ? std::round(40 * U(rng) - 20) : 440 * U(rng) - 40);
        pts[k].u = float(k % 2 ? around1 : 0.5 + U(rng));
        pts[k].v = float(k % 3 ? 1 / (0.05 + U(rng)) : -1000 * U(rng));
    }
    const std::vector<ts::Out> out = sh.run(pts, sc);
    ASSERT_EQ(out.size(), pts.size());
    const double ulp = std::ldexp(1.0, -24);
    size_t checked = 0;
    double worst = 0;
    for (size_t k = 0; k < pts.size(); ++k)
        for (int c = 0; c < 2; ++c) {
            const double x = c ? pts[k].u : pts[k].s, y = c ? pts[k].v : pts[k].t;
            const double want = std::pow(x, y), got = out[k].Ci[c];
            if (x == 1 || !(want < 3e38)) continue;
            if (want < std::ldexp(1.0, -126)) {
                EXPECT_GE(got, 0.0);
                EXPECT_LE(got, std::ldexp(1.0, -126)) << "pow(" << x << ", " << y << ")";
                continue;
            }
            const double err = std::fabs(got - want) / want / ulp,
                         bound = 4 + 2 * std::fabs(y * std::log2(x));
            EXPECT_LE(err, bound) << "pow(" << x << ", " << y << "): " << got << " against " << want;
            worst = std::max(worst, err / bound);
            ++checked;
        }
    EXPECT_GT(checked, pts.size());  // both columns mostly in range
    std::printf("pow: %zu values, worst error %.2f of the bound\n", checked, worst);
}

// ---- noise ---------------------------------------------------------------------------------
const char* kNoise =
    "surface nz(float which = 0;)\n{\n"
    "  float x = s * 2 - 1, y = t * 2 - 1;\n  point Q = P * 3;\n"
    "  point F = point(floor(xcomp(Q)), floor(ycomp(Q)), floor(zcomp(Q)));\n"
    "  if (which == 0) Ci = color(noise(x * 5), noise(x * 5, y * 5), noise(Q));\n"
    "  else if (which == 1) Ci = color(noise(Q, s * 2), pnoise(x * 5, 4), pnoise(Q, point(4, 4, 4)));\n"
    "  else if (which == 2) Ci = noise(Q);\n"
    "  else if (which == 3) Ci = color(cellnoise(x * 5), cellnoise(Q), cellnoise(Q, s * 3));\n"
    "  else if (which == 4) Ci = color(noise(x * 5) - noise(x * 5 + 1e-3),\n"
    "                                 noise(Q) - noise(Q + vector(1e-3, 1e-3, 0)),\n"
    "                                 noise(Q, s) - noise(Q, s + 1e-3));\n"
    "  else if (which == 5) Ci = color(pnoise(x * 5, 4) - pnoise(x * 5 + 4, 4),\n"
    "                                 pnoise(x * 5, y * 5, 3, 5) - pnoise(x * 5 + 3, y * 5 - 5, 3, 5),\n"
    "                                 pnoise(Q, point(2, 2, 2)) - pnoise(Q + vector(2, -4, 0), point(2, 2, 2)));\n"
    "  else if (which == 6) Ci = color(cellnoise(floor(x * 5) + 0.2) - cellnoise(floor(x * 5) + 0.7),\n"
    "                                 cellnoise(F + vector(0.1)) - cellnoise(F + vector(0.9)),\n"
    "                                 0);\n"
    "  else if (which == 7) Ci = noise(Q) - color(float noise(Q));\n"
    "}\n";

TEST(Builtins, NoiseProperties) {
    if (!ts::deviceAvailable()) GTEST_SKIP() << "no OpenCL device";
    ts::Shade sh;
    std::string err;
    ASSERT_TRUE(sh.compileSource(kNoise, "nz.sl", &err)) << err;
    ts::Scene sc;
    auto pts = ts::grid(24);
    auto runCase = [&](int w) {
        sh.setParam("which", {float(w)});
        return sh.run(pts, sc);
    };
    // range [0, 1], mean near 0.5, not constant
    for (int w : {0, 1, 2, 3}) {
        auto out = runCase(w);
        ASSERT_EQ(out.size(), pts.size());
        for (int c = 0; c < 3; ++c) {
            double sum = 0, sum2 = 0;
            for (const auto& o : out) {
                EXPECT_GE(o.Ci[c], 0.0f) << "case " << w;
                EXPECT_LE(o.Ci[c], 1.0f) << "case " << w;
                sum += o.Ci[c];
                sum2 += double(o.Ci[c]) * o.Ci[c];
            }
            double mean = sum / out.size(), var = sum2 / out.size() - mean * mean;
            EXPECT_NEAR(mean, 0.5, 0.15) << "case " << w << " channel " << c;
            EXPECT_GT(std::sqrt(var), 0.04) << "case " << w << " channel " << c;
        }
        // determinism
        auto again = runCase(w);
        for (size_t k = 0; k < out.size(); ++k)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(out[k].Ci[c], again[k].Ci[c]);
    }
    // continuity: a step of 1e-3 changes noise by little
    for (const auto& o : runCase(4))
        for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(o.Ci[c]), 0.02f);
    // periodicity of pnoise
    for (const auto& o : runCase(5))
        for (int c = 0; c < 3; ++c) EXPECT_LT(std::fabs(o.Ci[c]), 1e-4f);
    // cellnoise is constant over a cell
    for (const auto& o : runCase(6))
        for (int c = 0; c < 3; ++c) EXPECT_EQ(o.Ci[c], 0.0f);
    // the colour variant differs from the float one (and its channels from each other)
    int differ = 0, chan = 0;
    auto out7 = runCase(7), out2 = runCase(2);
    for (size_t k = 0; k < out7.size(); ++k) {
        differ += std::fabs(out7[k].Ci[0]) > 1e-3f;
        chan += std::fabs(out2[k].Ci[0] - out2[k].Ci[1]) > 1e-3f;
    }
    EXPECT_GT(differ, int(out7.size()) * 3 / 4);
    EXPECT_GT(chan, int(out2.size()) * 3 / 4);
}

}  // namespace
