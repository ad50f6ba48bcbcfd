// types.cpp: RSL coercions and operator typing.
#include "types.h"

namespace rsl {

const char* baseTypeName(BaseType b) {
    switch (b) {
    case BaseType::Error: return "<error>";
    case BaseType::Void: return "void";
    case BaseType::Float: return "float";
    case BaseType::Point: return "point";
    case BaseType::Vector: return "vector";
    case BaseType::Normal: return "normal";
    case BaseType::Color: return "color";
    case BaseType::Matrix: return "matrix";
    case BaseType::String: return "string";
    }
    return "?";
}

BaseType baseTypeFromName(const std::string& s) {
    static const BaseType all[] = {BaseType::Void,   BaseType::Float,  BaseType::Point,
                                   BaseType::Vector, BaseType::Normal, BaseType::Color,
                                   BaseType::Matrix, BaseType::String};
    for (BaseType b : all)
        if (s == baseTypeName(b)) return b;
    return BaseType::Error;
}

char typeCode(BaseType b) {
    switch (b) {
    case BaseType::Void: return 'x';
    case BaseType::Float: return 'f';
    case BaseType::Point: return 'p';
    case BaseType::Vector: return 'v';
    case BaseType::Normal: return 'n';
    case BaseType::Color: return 'c';
    case BaseType::Matrix: return 'm';
    case BaseType::String: return 's';
    default: return '?';
    }
}

BaseType typeFromCode(char c) {
    switch (c) {
    case 'x': return BaseType::Void;
    case 'f': return BaseType::Float;
    case 'p': return BaseType::Point;
    case 'v': return BaseType::Vector;
    case 'n': return BaseType::Normal;
    case 'c': return BaseType::Color;
    case 'm': return BaseType::Matrix;
    case 's': return BaseType::String;
    default: return BaseType::Error;
    }
}

std::string TypeSpec::str() const {
    std::string s = baseTypeName(base);
    if (arraySize > 0) s += "[" + std::to_string(arraySize) + "]";
    if (arraySize < 0) s += "[]";
    return s;
}

int coercionCost(const TypeSpec& from, const TypeSpec& to) {
    if (from.isError() || to.isError()) return 0;  // already reported
    if (from.isArray() || to.isArray()) {
        if (from.base != to.base) return -1;
        if (from.arraySize == to.arraySize || to.arraySize < 0 || from.arraySize < 0)
            return 0;
        return -1;
    }
    if (from.base == to.base) return 0;
    if (from.isPointLike() && to.isPointLike()) return 1;
    if (from.isFloat() && (to.isTriple() || to.isMatrix())) return 2;
    return -1;
}

static TypeSpec pointLikeMix(const TypeSpec& a, const TypeSpec& b) {
    if (a.base == b.base) return a;
    if (a.base == BaseType::Point || b.base == BaseType::Point) return BaseType::Point;
    return BaseType::Vector;
}

TypeSpec binaryResult(const std::string& op, const TypeSpec& a, const TypeSpec& b) {
    if (a.isError() || b.isError()) return TypeSpec();
    if (a.isArray() || b.isArray() || a.isVoid() || b.isVoid()) return TypeSpec();
    if (op == "&&" || op == "||") {
        return a.isFloat() && b.isFloat() ? TypeSpec(BaseType::Float) : TypeSpec();
    }
    if (op == "==" || op == "!=") {
        if (a.base == b.base || (a.isPointLike() && b.isPointLike()) ||
            (a.isFloat() && b.isNumeric()) || (b.isFloat() && a.isNumeric()))
            return BaseType::Float;
        return TypeSpec();
    }
    if (op == "<" || op == ">" || op == "<=" || op == ">=") {
        return a.isFloat() && b.isFloat() ? TypeSpec(BaseType::Float) : TypeSpec();
    }
    if (op == ".") {
        if (a.isPointLike() && b.isPointLike()) return BaseType::Float;
        if (a.isColor() && b.isColor()) return BaseType::Float;
        return TypeSpec();
    }
    if (op == "^") {
        if (a.isPointLike() && b.isPointLike()) return pointLikeMix(a, b);
        return TypeSpec();
    }
    if (a.isString() || b.isString()) return TypeSpec();
    // + - * /
    if (a.isFloat()) return b;
    if (b.isFloat()) return a;
    if (a.isMatrix() || b.isMatrix()) {
        if (a.isMatrix() && b.isMatrix() && op != "+" && op != "-") return a;
        if (a.isMatrix() && b.isMatrix()) return a;
        return TypeSpec();
    }
    if (a.isPointLike() && b.isPointLike()) return pointLikeMix(a, b);
    if (a.isColor() && b.isColor()) return a;
    return TypeSpec();
}

TypeSpec unifyTypes(const TypeSpec& a, const TypeSpec& b) {
    if (a.isError() || b.isError()) return TypeSpec();
    if (a == b) return a;
    if (a.isArray() || b.isArray()) return TypeSpec();
    if (a.isPointLike() && b.isPointLike()) return pointLikeMix(a, b);
    if (a.isFloat() && (b.isTriple() || b.isMatrix())) return b;
    if (b.isFloat() && (a.isTriple() || a.isMatrix())) return a;
    return TypeSpec();
}

}  // namespace rsl
