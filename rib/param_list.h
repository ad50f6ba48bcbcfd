// param_list.h: typed RenderMan parameter lists ("Kd" 0.5, "point P" [...]) as the reader
// hands them to a Target. Types come from inline declarations, Declare, or the standard
// predefined names (P, N, Cs, Os, s, t, ...).
#pragma once
#include <string>
#include <vector>

namespace rib {

enum class ParamType { Float, Integer, String, Point, Vector, Normal, Color, HPoint, Matrix };
enum class StorageClass { Constant, Uniform, Varying, Vertex, FaceVarying };

struct Param {
    std::string name; // without its inline declaration
    ParamType type = ParamType::Float;
    StorageClass storage = StorageClass::Uniform;
    int arraySize = 1;               // the [n] of "float[4] x"
    std::vector<float> floats;       // Float, Point, Vector, Normal, Color, HPoint, Matrix
    std::vector<int> ints;           // Integer
    std::vector<std::string> strings; // String
    int colorComponents = 3;          // a color's floats (ColorSamples)
    // Floats per element: 3 for point/vector/normal, colorComponents for color, 4 for
    // hpoint, 16 for matrix.
    int components() const;
};

// How many values each storage class of a primitive's variables has (RI 3.2 section 5);
// constant ones have one.
struct ClassCounts {
    long long uniform = 1, varying = 1, vertex = 1, faceVarying = 1;
    long long of(StorageClass storage) const {
        return storage == StorageClass::Constant  ? 1
               : storage == StorageClass::Uniform ? uniform
               : storage == StorageClass::Varying ? varying
               : storage == StorageClass::Vertex  ? vertex
                                                  : faceVarying;
    }
};

// Spec spellings ("point", "varying"), for messages and for RIB writers.
const char* paramTypeName(ParamType type);
const char* storageClassName(StorageClass storage);

class ParamList {
public:
    std::vector<Param> params;

    const Param* find(const std::string& name) const;
    float getFloat(const std::string& name, float def) const;
    int getInt(const std::string& name, int def) const;
    std::string getString(const std::string& name, const std::string& def) const;
    // Three floats (point, vector, normal, color); `def` is returned when absent.
    void get3(const std::string& name, float out[3], const float def[3]) const;
};

} // namespace rib
