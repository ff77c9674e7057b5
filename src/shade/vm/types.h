// The Shading Language's types as the compiler and the interpreter share them: a base type
// (float, color, point, vector, normal, matrix, string), an optional fixed array length, and
// a storage class (uniform: one value per grid; varying: one value per point).
#pragma once

#include <cstdint>
#include <string>

namespace streyes::sl {

enum class BaseType : uint8_t { Void, Float, Color, Point, Vector, Normal, Matrix, String };
enum class Detail : uint8_t { Uniform, Varying };

struct SlType {
    BaseType base = BaseType::Void;
    int arrayLen = 0;  // 0: a single value; > 0: a fixed-size array; kResizable: length at run time
    // An array declared without a length (`float a[]`): a parameter sized by its value, a local
    // that resize/push/pop change, a function's formal taking any length. Its length is one
    // value per grid (uniform); the VM keeps its elements apart from the fixed registers.
    static constexpr int kResizable = -1;

    constexpr SlType() = default;
    constexpr SlType(BaseType b, int len = 0) : base(b), arrayLen(len) {}  // NOLINT: implicit on purpose

    bool isArray() const { return arrayLen != 0; }
    bool isResizable() const { return arrayLen == kResizable; }
    SlType element() const { return {base, 0}; }
    bool is(BaseType b) const { return base == b && arrayLen == 0; }
    bool isFloat() const { return is(BaseType::Float); }
    bool isString() const { return base == BaseType::String; }
    bool isMatrix() const { return is(BaseType::Matrix); }
    bool isVoid() const { return base == BaseType::Void; }
    // color, point, vector, normal: three floats
    bool isTriple() const {
        return arrayLen == 0 && (base == BaseType::Color || base == BaseType::Point ||
                                 base == BaseType::Vector || base == BaseType::Normal);
    }
    // point, vector, normal: they convert freely into each other
    bool isPointLike() const {
        return arrayLen == 0 && (base == BaseType::Point || base == BaseType::Vector || base == BaseType::Normal);
    }
    // Floats per point of one element: the interpreter keeps one float array per component.
    int comps() const { return compsOf(base); }
    // Elements of a fixed register (a resizable array's are counted at run time: 1 here).
    int elements() const { return arrayLen > 0 ? arrayLen : 1; }
    static int compsOf(BaseType b) {
        switch (b) {
            case BaseType::Float: return 1;
            case BaseType::Color: case BaseType::Point: case BaseType::Vector: case BaseType::Normal: return 3;
            case BaseType::Matrix: return 16;
            default: return 0;  // strings live apart from the float registers; void has no value
        }
    }
    bool operator==(const SlType& o) const { return base == o.base && arrayLen == o.arrayLen; }
    bool operator!=(const SlType& o) const { return !(*this == o); }
    std::string name() const;  // "float", "color[3]"
};

const char* baseTypeName(BaseType b);
const char* detailName(Detail d);
inline Detail join(Detail a, Detail b) { return a == Detail::Varying || b == Detail::Varying ? Detail::Varying : Detail::Uniform; }

enum class ShaderType : uint8_t { Surface, Displacement, Light, Volume, Imager };
const char* shaderTypeName(ShaderType t);

// The predefined ("global") variables of RI Spec 3.2, section 12.1. Their types and storage
// classes are fixed; which of them a grid provides is up to the caller.
enum class Global : uint8_t {
    P, N, Ng, I, E, Cs, Os, Ci, Oi, s, t, u, v, du, dv, dPdu, dPdv, dPdtime, time, dtime,
    L, Cl, Ol, Ps, alpha, ncomps,
    Ns,  // a light's view of the surface's normal at Ps (PRMan's and Aqsis's)
    Count
};
constexpr int kGlobalCount = int(Global::Count);

struct GlobalInfo {
    const char* name;
    SlType type;
    Detail detail;
    bool writable;  // inputs such as E and time are read-only
};
const GlobalInfo& globalInfo(Global g);
// The global named `name`, or Global::Count.
Global findGlobal(const std::string& name);

}  // namespace streyes::sl
