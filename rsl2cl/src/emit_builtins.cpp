// emit_builtins.cpp: OpenCL C for calls of RSL builtins (runtime/rsl_stdlib.clh).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "emit_internal.h"

namespace rsl {

std::string Emitter::spaceArg(const Expr& e) {
    if (e.kind == ExprKind::String) {
        return spaceOfName(e.text);
    }
    m_out.usesObjectSpace = m_out.usesSpaceTable = true;  // (it may name either)
    return "rsl_space_from_id(" + expr(e) + ")";
}

// A coordinate system's RSL_SPACE_* value, or a named one's -(string id) (rsl_abi.h,
// SPACES), noting what the renderer must provide.
std::string Emitter::spaceOfName(const std::string& name) {
    const int sp = spaceIdOf(name);
    m_out.usesObjectSpace |= sp == kObjectSpaceId;
    m_out.usesSpaceTable |= sp < 0 || sp >= kScreenSpaceId;
    if (sp >= 0) return std::to_string(sp);
    if (std::find(m_out.namedSpaces.begin(), m_out.namedSpaces.end(), name) ==
        m_out.namedSpaces.end())
        m_out.namedSpaces.push_back(name);
    return "(-" + std::to_string(stringId(name)) + ")";
}

std::string Emitter::colorSpaceArg(const Expr& e) {
    if (e.kind == ExprKind::String) {
        int c = colorIdOf(e.text);
        if (c < 0) {
            error(e.loc, "unknown colour space \"" + e.text + "\"");
            return "RSL_COLOR_RGB";
        }
        return std::to_string(c);
    }
    return "rsl_color_from_id(" + expr(e) + ")";
}

// lightsource() in an illuminance loop, attribute(), option(), rayinfo(), surface(),
// displacement(), atmosphere(), incident() and opposite() ask the renderer (rsl_abi.h,
// MESSAGE PASSING); rendererinfo() is answered here ("renderer", "version",
// "versionstring").
std::string Emitter::message(const Expr& e) {
    const std::string& n = e.text;
    std::string svc;
    // rendererinfo's answers: a string's id, or the version's four numbers
    std::vector<std::string> known;
    if (n == "rendererinfo" && e.args.size() == 2 &&
        e.args[0]->kind == ExprKind::String) {
        const std::string& what = e.args[0]->text;
        const TypeSpec& t = e.args[1]->type;
        if (t.isString() && !t.isArray() &&
            (what == "renderer" || what == "versionstring"))
            known = {
                stringLiteral(what == "renderer" ? "RayDrive" : RSL2CL_RENDERER_VERSION)};
        else if (what == "version" && t.isArray() && t.arraySize == 4 &&
                 t.element().base == BaseType::Float) {
            // (the project's major, minor and patch numbers, CMakeLists.txt, then 0)
            std::istringstream numbers(RSL2CL_RENDERER_VERSION_NUMBERS);
            for (std::string v; std::getline(numbers, v, ',');) known.push_back(v);
            known.push_back("0.0f");
        }
        if (known.empty()) return "0.0f";
        svc = "rendererinfo";
    }
    if (n == "lightsource" && !m_func && !m_lightVars.empty())
        svc = "rsl_lightsource_param(g, " + m_lightVars.back() + ", ";
    else if (n == "attribute")
        svc = "rsl_attribute(g, ";
    else if (n == "rayinfo")
        svc = "rsl_rayinfo(g, ";
    else if (n == "surface")
        svc = "rsl_shader_param(g, 0, ";
    else if (n == "displacement")
        svc = "rsl_shader_param(g, 1, ";
    else if (n == "atmosphere")
        svc = "rsl_shader_param(g, 2, ";
    else if (n == "incident")
        svc = "rsl_shader_param(g, 5, ";
    else if (n == "opposite")
        svc = "rsl_shader_param(g, 6, ";
    else if (n == "option") {  // (the service reads the scene through the spaces)
        svc = "rsl_option(sp, ";
        m_usesSpaces = true;
    }
    if (svc.empty() || e.args.size() != 2) return "0.0f";
    const Expr& var = *e.args[1];
    const TypeSpec& t = var.type;
    int count = t.isArray() ? t.arraySize : 1;
    TypeSpec el = t.element();
    if (count <= 0 || (t.isArray() && el.isMatrix())) {
        error(e.loc, n + "() into an unsized array or a matrix array is not supported");
        return "0.0f";
    }
    int slots = this->slots(t.base) * count;
    std::string buf = "_msg" + std::to_string(m_tmp++);
    m_pre.push_back("float " + buf + "[" + std::to_string(slots) + "];");
    std::string found = svc + exprAs(*e.args[0], BaseType::String) + ", " + buf + ", " +
                        std::to_string(slots) + ")";
    if (!known.empty()) {
        for (size_t i = 0; i < known.size(); ++i)
            m_pre.push_back(buf + "[" + std::to_string(i) + "] = " + known[i] + ";");
        found = "1";
    }
    std::string kc = el.isMatrix()   ? "m"
                     : el.isColor()  ? "c"
                     : el.isTriple() ? "v"
                     : el.isString() ? "s"
                                     : "f";
    if (t.isArray()) {
        kc[0] = char(kc[0] - 'a' + 'A');
        return "rsl_msg_" + kc + "(" + found + ", " + buf + ", " + lvalue(var) + ", " +
               std::to_string(count) + ")";
    }
    return "rsl_msg_" + kc + "(" + found + ", " + buf + ", &" + lvalue(var) + ")";
}

// texture(), environment(), shadow() and bump() through the renderer's texture service
// (rsl_abi.h, TEXTURES): the positional arguments, then "name", value pairs: blur,
// width (swidth, twidth: their larger), fill, bias, samples.
std::string Emitter::textureCall(const Expr& e, bool vret) {
    const std::string& n = e.text;
    m_out.usesTexture = true;
    m_out.usesDerivatives = true;  // filter widths come from the footprint
    size_t pairs = 1;
    while (pairs < e.args.size() && !e.args[pairs]->type.isString()) ++pairs;
    std::map<std::string, std::string> opt = {{"blur", "0.0f"}, {"width", "1.0f"},
                                              {"fill", "0.0f"}, {"bias", "-1.0f"},
                                              {"samples", "16.0f"}};
    std::string sw, tw;
    for (size_t i = pairs; i + 1 < e.args.size(); i += 2) {
        const Expr& key = *e.args[i];
        std::string v = exprAs(*e.args[i + 1], BaseType::Float);
        if (key.kind != ExprKind::String) {
            m_diag.warning(key.loc, n + "(): a parameter name must be a string literal; ignored");
            continue;
        }
        if (key.text == "swidth") sw = v;
        else if (key.text == "twidth") tw = v;
        else if (opt.count(key.text)) opt[key.text] = v;
        else if (key.text != "filter")
            m_diag.warning(key.loc, n + "(): parameter \"" + key.text + "\" is not supported; ignored");
    }
    if (!sw.empty() || !tw.empty())
        opt["width"] = "fmax(" + (sw.empty() ? opt["width"] : sw) + ", " + (tw.empty() ? opt["width"] : tw) + ")";
    std::string id = exprAs(*e.args[0], BaseType::String);
    std::string ch = e.channel ? "(int)(" + exprAs(*e.channel, BaseType::Float) + ")" : "0";
    auto F = [&](size_t i) { return exprAs(*e.args[i], BaseType::Float); };
    auto V = [&](size_t i) { return exprAs(*e.args[i], BaseType::Vector); };
    std::string call;
    if (n == "texture") {
        if (pairs == 1)
            call = "rsl_tex2d(g, ev, " + id + ", " + ch + ", g->s, g->t, ";
        else if (pairs == 3)
            call = "rsl_tex2d(g, ev, " + id + ", " + ch + ", " + F(1) + ", " + F(2) + ", ";
        else {
            call = "rsl_tex2d_quad(ev, " + id + ", " + ch;
            for (size_t i = 1; i < 9; ++i) call += ", " + F(i);
            call += ", ";
        }
        call += opt["width"] + ", " + opt["blur"] + ", " + opt["fill"] + ")";
    } else if (n == "environment") {
        // the four-direction form: their mean, the spread between them as the footprint
        std::string R = pairs == 2 ? V(1) : "(0.25f * (" + V(1) + " + " + V(2) + " + " + V(3) + " + " + V(4) + "))";
        call = "rsl_environment_map(ev, " + id + ", " + ch + ", " + R + ", " + opt["width"] + ", " +
               opt["blur"] + ", " + opt["fill"] + ")";
    } else if (n == "shadow") {
        std::string P = pairs == 2 ? exprAs(*e.args[1], BaseType::Point)
                                   : "(0.25f * (" + exprAs(*e.args[1], BaseType::Point) + " + " +
                                         exprAs(*e.args[2], BaseType::Point) + " + " +
                                         exprAs(*e.args[3], BaseType::Point) + " + " +
                                         exprAs(*e.args[4], BaseType::Point) + "))";
        call = "rsl_shadow_map(ev, " + id + ", " + ch + ", " + P + ", " + opt["width"] + ", " +
               opt["blur"] + ", " + opt["bias"] + ", " + opt["samples"] + ")";
        // "raytrace" (and "") in a light: the renderer's own shadow ray does the work
        if (m_sh.kind == ShaderKind::Light)
            call = "((" + id + ") == " + std::to_string(stringId("raytrace")) + " || (" + id +
                   ") == 0 ? (float4)(0.0f) : " + call + ")";
        else if (e.args[0]->kind == ExprKind::String && e.args[0]->text == "raytrace")
            m_diag.warning(e.loc, "shadow(\"raytrace\") in a surface shader is not traced: it "
                                  "gives 0 (unoccluded); the renderer traces light shadows itself");
        if (e.args[0]->kind == ExprKind::String && e.args[0]->text == "raytrace")
            call = "(float4)(0.0f)";
    } else {  // bump(name, N, dPdu, dPdv[, s, t | 8 coordinates])
        std::string s = pairs >= 6 ? F(4) : "g->s", t = pairs >= 6 ? F(5) : "g->t";
        return "rsl_bump_map(g, ev, " + id + ", " + ch + ", " + exprAs(*e.args[1], BaseType::Normal) +
               ", " + V(2) + ", " + V(3) + ", " + s + ", " + t + ", " + opt["width"] + ", " +
               opt["blur"] + ")";
    }
    if (!vret) return "(" + call + ").x";
    // a texture's or environment's texels are RGB; a shadow's fraction is the same in
    // every channel
    if (n == "shadow") return "rsl_f2c((" + call + ").x)";
    return rgbIn("rsl_w0(" + call + ")");
}

// textureinfo(name, "resolution" | "channels" | "type", var)
std::string Emitter::textureInfo(const Expr& e) {
    m_out.usesTexture = true;  // its map names are the renderer's to find
    const Expr& what = *e.args[1];
    const Expr& var = *e.args[2];
    int code = -1, slots = 0;
    if (what.kind == ExprKind::String) {
        if (what.text == "resolution") code = 0, slots = 2;
        else if (what.text == "channels") code = 1, slots = 1;
        else if (what.text == "type") code = 2, slots = 1;
    }
    int varSlots =
        this->slots(var.type.base) * (var.type.isArray() ? var.type.arraySize : 1);
    if (code < 0 || varSlots != slots) return "0.0f";
    std::string buf = "_tinfo" + std::to_string(m_tmp++);
    m_pre.push_back("float " + buf + "[" + std::to_string(slots) + "];");
    std::string found = "rsl_textureinfo(" + exprAs(*e.args[0], BaseType::String) + ", " +
                        std::to_string(code) + ", " + buf + ", " + std::to_string(slots) + ")";
    if (var.type.isArray())
        return "rsl_msg_F(" + found + ", " + buf + ", " + lvalue(var) + ", " + std::to_string(slots) + ")";
    return "rsl_msg_" + std::string(var.type.isString() ? "s" : "f") + "(" + found + ", " + buf +
           ", &" + lvalue(var) + ")";
}

std::string Emitter::arg(const BuiltinCall& c, size_t i) {
    const BuiltinSig& sig = c.sig;
    const TypeSpec t = i < sig.args.size()
                           ? (sig.args[i].anyType ? c.e.args[i]->type : sig.args[i].type)
                       : sig.repeatLast && !sig.args.empty() ? sig.args.back().type
                                                             : c.e.args[i]->type;
    return exprAs(*c.e.args[i], t);
}

std::string Emitter::intArg(const BuiltinCall& c, size_t i) {
    return "(int)(" + arg(c, i) + ")";
}

std::string Emitter::callOf(const BuiltinCall& c, const std::string& fn, size_t from,
                            size_t to) {
    std::string s = fn + "(";
    for (size_t i = from; i < c.count && i < to; ++i)
        s += (i > from ? ", " : "") + arg(c, i);
    return s + ")";
}

// Arithmetic, interpolation, derivatives, noise and random numbers; empty when `c` is
// none of them.
std::string Emitter::mathBuiltin(const BuiltinCall& c) {
    const Expr& e = c.e;
    const std::string& n = e.text;
    static const std::set<std::string> direct = {"sin", "asin", "cos", "acos", "tan", "exp",
                                                 "sqrt", "floor", "ceil", "round"};
    if (direct.count(n)) return callOf(c, n);
    if (n == "pow") return callOf(c, "rsl_pow");
    if (n == "abs") return callOf(c, "fabs");
    if (n == "inversesqrt") return callOf(c, "rsqrt");
    if (n == "radians" || n == "degrees" || n == "mod" || n == "sign" || n == "step" ||
        n == "smoothstep")
        return callOf(c, "rsl_" + n);
    if (n == "atan") return callOf(c, c.count == 2 ? "atan2" : "atan");
    if (n == "log") return callOf(c, c.count == 2 ? "rsl_log2b" : "log");
    if (n == "min" || n == "max") {
        std::string s = arg(c, 0);
        for (size_t i = 1; i < c.count; ++i)
            s = "rsl_" + n + c.vf + "(" + s + ", " + arg(c, i) + ")";
        return s;
    }
    if (n == "clamp" || n == "mix") return callOf(c, "rsl_" + n + c.vf);
    if (n == "filterstep") {
        // filterstep(edge, s1[, s2][, "width", w]): the optional pairs start at the
        // first string argument
        m_out.usesDerivatives = true;
        size_t pairs = 2;
        while (pairs < c.count && !e.args[pairs]->type.isString()) ++pairs;
        std::string s2 = pairs > 2 ? exprAs(*e.args[2], BaseType::Float) : "NAN";
        std::string width = "1.0f";
        for (size_t i = pairs; i + 1 < c.count; i += 2) {
            const Expr& name = *e.args[i];
            if (name.kind == ExprKind::String && name.text == "width")
                width = exprAs(*e.args[i + 1], BaseType::Float);
            else
                m_diag.warning(name.loc, "filterstep: only the \"width\" parameter is "
                                         "honoured (the filter is a box)");
        }
        return "rsl_filterstep(g, ev, " + exprAs(*e.args[0], BaseType::Float) + ", " +
               exprAs(*e.args[1], BaseType::Float) + ", " + s2 + ", " + width + ")";
    }
    if (n == "spline") {
        size_t k = 0;
        std::string basis = "0";
        if (e.args[0]->type.isString()) {
            k = 1;
            const Expr& b = *e.args[0];
            if (b.kind == ExprKind::String && b.text == "linear") basis = "1";
            else if (b.kind != ExprKind::String || b.text != "catmull-rom")
                m_diag.warning(b.loc, "spline basis other than \"catmull-rom\" and \"linear\" "
                                      "is evaluated as catmull-rom");
        }
        std::string t = exprAs(*e.args[k], BaseType::Float);  // the def types t loosely
        std::string fn = "rsl_spline" + c.vf + "(" + basis + ", " + t + ", ";
        if (c.count == k + 2 && e.args[k + 1]->type.isArray())
            return fn + expr(*e.args[k + 1]) + ", " + std::to_string(e.args[k + 1]->type.arraySize) + ")";
        // the knots go into a temporary array declared before the statement
        std::string tmp = "_knots" + std::to_string(m_tmp++);
        std::string lst = std::string(clType(c.ret)) + " " + tmp + "[] = {";
        for (size_t i = k + 1; i < c.count; ++i)
            lst += (i > k + 1 ? ", " : "") + arg(c, i);
        m_pre.push_back(lst + "};");
        return fn + tmp + ", " + std::to_string(c.count - k - 1) + ")";
    }
    // finite differences over the point's neighbours (rsl_abi.h, DERIVATIVES)
    if (n == "Du" || n == "Dv" || n == "Deriv") {
        m_out.usesDerivatives = true;
        std::string s = "rsl_" + n + c.vf + "(g, ev, " + arg(c, 0);
        return s + (n == "Deriv" ? ", " + arg(c, 1) : std::string()) + ")";
    }
    if (n == "area" || n == "calculatenormal") {
        m_out.usesDerivatives = true;
        return "rsl_" + n + "(g, ev, " + arg(c, 0) + ")";
    }
    if (n == "random") m_out.usesRandom = true;
    // (a point takes three sites, a colour max(3, n): rsl_abi.h RANDOM)
    if (n == "random") {
        const int site = m_randomSite;
        m_randomSite += c.vf == "_f" ? 1 : c.vf == "_c" ? m_colorSlots : 3;
        return "rsl_random" + c.vf + "(g, " + std::to_string(site) + ")";
    }
    if (n == "noise" || n == "pnoise" || n == "cellnoise") {
        std::string dims =
            n == "pnoise" ? c.codes.substr(0, c.codes.size() / 2) : c.codes;
        int d = dims == "f" ? 1 : dims == "ff" ? 2 : (dims == "p" || dims == "v") ? 3 : 4;
        return callOf(c, "rsl_" + n + std::to_string(d) + c.vf);
    }
    return {};
}

// Points, vectors, normals and their spaces; empty when `c` is none of them.
std::string Emitter::geometryBuiltin(const BuiltinCall& c) {
    const Expr& e = c.e;
    const std::string& n = e.text;
    if (n == "xcomp") return "(" + arg(c, 0) + ").x";
    if (n == "ycomp") return "(" + arg(c, 0) + ").y";
    if (n == "zcomp") return "(" + arg(c, 0) + ").z";
    if (n == "setxcomp" || n == "setycomp" || n == "setzcomp")
        return "(" + lvalue(*e.args[0]) + "." + n.substr(3, 1) + " = " + arg(c, 1) + ")";
    if (n == "length" || n == "normalize" || n == "distance" || n == "ptlined" ||
        n == "reflect" || n == "refract" || n == "determinant" ||
        n == "translate" || n == "scale")
        return callOf(c, "rsl_" + n);
    // BMRT's and PRMan's: the ray's depth, and whether a shadow ray runs the shader
    // (never: shadows take the surface's constant Os, rsl_abi.h TRACE)
    if (n == "raylevel") return "((float)(g->ray_depth & ~RSL_SHADOW_RAY))";
    if (n == "isshadowray") return "((float)(g->ray_depth >> 31))";
    if (n == "arraylength") {
        const TypeSpec& t = e.args[0]->type;
        return clNumber(t.isArray() ? t.arraySize : -1);
    }
    if (n == "depth") {  // (camera space and clipping come through the spaces)
        m_usesSpaces = true;
        return "rsl_depth(sp, " + arg(c, 0) + ")";
    }
    if (n == "specularbrdf") return "rsl_f2c(" + callOf(c, "rsl_" + n) + ")";
    if (n == "rotate") return callOf(c, c.ret.isMatrix() ? "rsl_mrotate" : "rsl_rotate");
    if (n == "faceforward")
        return "rsl_faceforward(" + arg(c, 0) + ", " + arg(c, 1) + ", " +
               (c.count > 2 ? arg(c, 2) : "g->Ng") + ")";
    if (n == "fresnel") {
        std::string s = std::string(c.count > 5 ? "rsl_fresnel(" : "rsl_fresnel5(") +
                        arg(c, 0) + ", " + arg(c, 1) + ", " + arg(c, 2);
        for (size_t i = 3; i < c.count; ++i) s += ", &" + lvalue(*e.args[i]);
        return s + ")";
    }
    if (n == "transform" || n == "vtransform" || n == "ntransform") {
        char kc = n[0] == 't' ? 'p' : n[0];
        std::string fn = std::string("rsl_transform_") + kc;
        std::string xf = kc == 'p' ? "rsl_xpoint" : kc == 'v' ? "rsl_xvector" : "rsl_xnormal";
        m_usesSpaces = true;
        if (c.codes.size() == 2 && c.codes[0] == 's')
            return fn + "(sp, RSL_SPACE_CURRENT, " + spaceArg(*e.args[0]) + ", " +
                   arg(c, 1) + ")";
        if (c.codes.size() == 3 && c.codes[0] == 's' && c.codes[1] == 's')
            return fn + "(sp, " + spaceArg(*e.args[0]) + ", " + spaceArg(*e.args[1]) +
                   ", " + arg(c, 2) + ")";
        if (c.codes.size() == 2 && c.codes[0] == 'm')
            return xf + "(" + arg(c, 0) + ", " + arg(c, 1) + ")";
        if (c.codes.size() == 3 && c.codes[0] == 's' && c.codes[1] == 'm')
            return xf + "(" + arg(c, 1) + ", " + fn + "(sp, " + spaceArg(*e.args[0]) +
                   ", RSL_SPACE_CURRENT, " + arg(c, 2) + "))";
    }
    return {};
}

// Colour and matrix components, colour spaces, strings; empty when `c` is none of them.
std::string Emitter::componentOrStringBuiltin(const BuiltinCall& c) {
    const Expr& e = c.e;
    const std::string& n = e.text;
    if (n == "comp") {
        if (c.codes == "mff")
            return "rsl_mget(" + arg(c, 0) + ", " + intArg(c, 1) + ", " + intArg(c, 2) +
                   ")";
        return "rsl_comp(" + arg(c, 0) + ", " + intArg(c, 1) + ")";
    }
    if (n == "setcomp") {
        if (c.codes == "mfff")
            return "rsl_mset(&" + lvalue(*e.args[0]) + ", " + intArg(c, 1) + ", " +
                   intArg(c, 2) + ", " + arg(c, 3) + ")";
        return "rsl_setcomp(&" + lvalue(*e.args[0]) + ", " + intArg(c, 1) + ", " +
               arg(c, 2) + ")";
    }
    if (n == "ctransform") {
        const std::string fn = ctransformFn();
        if (c.count == 2)
            return fn + "RSL_COLOR_RGB, " + colorSpaceArg(*e.args[0]) + ", " + arg(c, 1) +
                   ")";
        return fn + colorSpaceArg(*e.args[0]) + ", " + colorSpaceArg(*e.args[1]) + ", " +
               arg(c, 2) + ")";
    }
    // ---- strings (uniform, minimal) ----
    if (n == "concat" || n == "format") {
        std::string all;
        bool literal = true;
        for (size_t i = 0; i < (n == "format" ? size_t(1) : c.count); ++i) {
            literal = literal && e.args[i]->kind == ExprKind::String;
            all += e.args[i]->text;
        }
        if (literal && (n == "concat" || c.count == 1)) return stringLiteral(all);
        m_diag.warning(e.loc, n + "() of non-literal strings returns its first argument");
        return arg(c, 0);
    }
    if (n == "match") {
        if (e.args[0]->kind == ExprKind::String && e.args[1]->kind == ExprKind::String)
            return e.args[1]->text.find(e.args[0]->text) != std::string::npos ? "1.0f" : "0.0f";
        return "0.0f";
    }
    if (n == "printf") return "((void)0)";
    return {};
}

// Lighting, rays, textures and messages; empty when `c` is none of them.
std::string Emitter::shadingBuiltin(const BuiltinCall& c) {
    const Expr& e = c.e;
    const std::string& n = e.text;
    if (n == "ambient") {
        m_out.usesLighting = true;
        return "rsl_cw0(rsl_ambient(g))";
    }
    if (n == "diffuse" || n == "specular" || n == "phong") {
        m_out.usesLighting = true;
        std::string s = "rsl_" + n + "(g, ev";
        for (size_t i = 0; i < c.count; ++i) s += ", " + arg(c, i);
        return s + ")";
    }
    if (n == "trace") {
        traceSite(e);
        return "rsl_trace(ev, " + arg(c, 0) + ", " + arg(c, 1) + ")";
    }
    if (n == "transmission") {
        // In a light shader it is 1: RayDrive traces a shadow ray for every light (but
        // those whose shadows a map gives), which asks the same. In a surface, a
        // visibility ray from the first point to the second.
        if (m_sh.kind != ShaderKind::Surface) return "rsl_f2c(1.0f)";
        traceSite(e);
        m_out.usesVisibility = true;
        return "rsl_transmission(ev, " + arg(c, 0) + ", " + arg(c, 1) + ")";
    }
    if (n == "occlusion" || n == "indirectdiffuse") return hemisphereCall(e);
    if (n.rfind("__gather_", 0) == 0) return gatherCall(e);
    if (n == "texture" || n == "environment" || n == "shadow" || n == "bump")
        return textureCall(e, c.ret.isTriple());
    if (n == "textureinfo") return textureInfo(e);
    if (e.builtin->flags & BF_MESSAGE) return message(e);
    return {};
}

std::string Emitter::builtin(const Expr& e) {
    if (!e.sig) {
        error(e.loc, "unresolved builtin '" + e.text + "'");
        return "0";
    }
    BuiltinCall c{e, *e.sig, e.sig->ret, "", "", e.args.size()};
    c.vf = c.ret.isColor() ? "_c" : c.ret.isTriple() ? "_v" : "_f";
    // argument codes only (after the return code, without & markers)
    for (size_t i = 1; i < c.sig.code.size(); ++i)
        if (c.sig.code[i] != '&') c.codes += c.sig.code[i];
    for (auto family : {&Emitter::mathBuiltin, &Emitter::geometryBuiltin,
                        &Emitter::componentOrStringBuiltin, &Emitter::shadingBuiltin})
        if (std::string code = (this->*family)(c); !code.empty()) return code;
    error(e.loc, "builtin '" + e.text + "' is not supported by the code generator yet");
    return clZero(c.ret);
}

}  // namespace rsl
