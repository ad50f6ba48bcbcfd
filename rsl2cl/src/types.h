// types.h: RSL types (float, point, vector, normal, color, matrix, string, arrays) and
// the coercion and operator rules of the type checker.
#pragma once
#include <string>

namespace rsl {

enum class BaseType { Error, Void, Float, Point, Vector, Normal, Color, Matrix, String };

struct TypeSpec {
    BaseType base = BaseType::Error;
    int arraySize = 0;  // 0: not an array; > 0: fixed length; -1: unsized (parameters)

    TypeSpec() = default;
    TypeSpec(BaseType b, int n = 0) : base(b), arraySize(n) {}
    bool isError() const { return base == BaseType::Error; }
    bool isArray() const { return arraySize != 0; }
    bool isScalar(BaseType b) const { return base == b && !isArray(); }
    bool isFloat() const { return isScalar(BaseType::Float); }
    bool isString() const { return isScalar(BaseType::String); }
    bool isMatrix() const { return isScalar(BaseType::Matrix); }
    bool isColor() const { return isScalar(BaseType::Color); }
    bool isVoid() const { return base == BaseType::Void; }
    // point, vector or normal (not an array)
    bool isPointLike() const {
        return !isArray() && (base == BaseType::Point || base == BaseType::Vector ||
                              base == BaseType::Normal);
    }
    bool isTriple() const { return isPointLike() || isColor(); }
    bool isNumeric() const { return isFloat() || isTriple() || isMatrix(); }
    TypeSpec element() const { return TypeSpec(base); }
    bool operator==(const TypeSpec& o) const {
        return base == o.base && arraySize == o.arraySize;
    }
    bool operator!=(const TypeSpec& o) const { return !(*this == o); }
    std::string str() const;  // "float", "color[3]", "point[]"
};

const char* baseTypeName(BaseType b);
// Parses a type keyword ("float" ... "void"); returns Error when s is none.
BaseType baseTypeFromName(const std::string& s);
// Signature code letter of STYLE.md section 3: f p v n c m s x (void).
char typeCode(BaseType b);
BaseType typeFromCode(char c);

// Cost of converting a value of type `from` where `to` is wanted: 0 exact,
// 1 among point/vector/normal, 2 float to a triple or matrix, -1 not allowed.
int coercionCost(const TypeSpec& from, const TypeSpec& to);
inline bool assignable(const TypeSpec& from, const TypeSpec& to) {
    return coercionCost(from, to) >= 0;
}
// Result of a binary operator (+ - * / . ^ == != < > <= >= && ||) or Error.
TypeSpec binaryResult(const std::string& op, const TypeSpec& a, const TypeSpec& b);
// Common type of the two branches of ?: (or Error).
TypeSpec unifyTypes(const TypeSpec& a, const TypeSpec& b);

}  // namespace rsl
