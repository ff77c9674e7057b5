// A compiled shader: registers, instructions and parameters. The compiler (shade/sl) makes it;
// the interpreter (ShadingVM) runs it. Immutable once made, so one program is shared by every
// thread; all run-time state lives in the VM.
//
// An instruction is a function over the whole grid (one call per instruction per grid, never
// per point) plus up to six operands: register numbers, immediates, jump targets, or a span of
// `extra` for functions with many arguments.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "shade/vm/types.h"
#include "streyes/error.h"

namespace streyes::sl {

struct Exec;
struct Instr;
using OpFn = void (*)(Exec&, const Instr&);

struct Instr {
    OpFn fn = nullptr;
    int32_t a[6] = {-1, -1, -1, -1, -1, -1};
    int32_t loc = -1;      // index into ShaderProgram::locs, for run-time messages
    bool varying = false;  // works on n points (else on one): statistics only
};

// A register holds one variable or temporary: one float array per component and element,
// n floats long when varying, 1 when uniform. Strings are uniform and live in string slots.
struct Register {
    SlType type;
    Detail detail = Detail::Uniform;
    int global = -1;    // the predefined variable it holds (Global), or -1
    int param = -1;     // the shader parameter it holds, or -1
    int constant = -1;  // a constant: first index into constFloats (or constStrings), or -1
    std::string name;   // variable name; "" for temporaries
    // Assigned by finish(): uniform registers' float offset in the uniform area; varying
    // registers' first lane array; string registers' first string slot; resizable arrays'
    // (string ones too) index among the frame's resizable stores (frame.h).
    int slot = 0;
    int floats() const { return type.comps() * type.elements(); }
    bool resizable() const { return type.isResizable(); }
    bool varying() const { return detail == Detail::Varying; }
};

struct ParamInfo {
    std::string name;
    SlType type;
    Detail detail = Detail::Uniform;
    bool output = false;
    int reg = -1;
    int initBegin = 0, initEnd = 0;  // the instructions computing the default value
    // The default as a value, computed with every space the identity ("point "shader" (0,0,0)"
    // gives 0 0 0): what sloinfo prints. Floats: comps x elements, element-major.
    std::vector<float> defaultFloats;
    std::vector<std::string> defaultStrings;
    std::string defaultText;  // the default expression as written
    SourceLoc loc;
};

// What a shader's results (a surface's Ci and Oi, a displacement's P and N, a light's Cl and
// Ol, every output parameter) read of the view, under a rigid camera: the compiler's analysis
// (shade/sl/view_use.h). None: nothing; FacingOnly: only through which side faces the eye (the
// sign of N.I or Ng.I); Reads: otherwise, or not proven. Ordered: the larger, the more it reads.
enum class ViewUse : uint8_t { None, FacingOnly, Reads };

struct ShaderProgram {
    uint64_t id = 0;  // unique per compilation: a VM's registers for it are found by id
    ShaderType type = ShaderType::Surface;
    std::string name;
    std::string path;  // file it came from ("" for a string)
    std::vector<std::string> sources;   // every file read: path, then what it #included
    // The compiler's warnings (#warning, a macro defined twice), each at its place.
    struct Warning {
        SourceLoc loc;
        std::string what;
        std::string str() const { return loc.str() + ": warning: " + what; }
    };
    std::vector<Warning> warnings;
    std::vector<ParamInfo> params;
    std::vector<Register> regs;
    std::vector<Instr> code;
    int bodyBegin = 0;               // code before this computes parameter defaults
    std::vector<int32_t> extra;      // operand lists of instructions with many operands
    std::vector<float> constFloats;
    std::vector<std::string> constStrings;
    std::vector<SourceLoc> locs;
    int globalReg[kGlobalCount];     // the register of each predefined variable used, or -1
    bool illuminates = false;        // a light with illuminate or solar (else: an ambient light)
    bool usesLights = false;         // calls illuminance, ambient, diffuse, specular, phong
    int maxMaskDepth = 0;            // deepest nesting of varying control flow
    ViewUse viewUse = ViewUse::Reads;  // what its results read of the view (view_use.h)
    std::string viewUseWhy;          // where it first reads it ("file:line:col: what"), for messages
    // Filled by finish():
    int uniformFloats = 0;           // size of the uniform area
    int varyingArrays = 0;           // number of n-float arrays
    int stringSlots = 0;
    int resizableArrays = 0;         // resizable (unsized) float-based arrays: a store each

    ShaderProgram() { for (int& r : globalReg) r = -1; }
    const ParamInfo* findParam(const std::string& n) const;
    int paramIndex(const std::string& n) const;
    void finish();                   // assigns register slots and a fresh id
    std::string dump() const;        // instruction listing, for tests and debugging
};

using ProgramPtr = std::shared_ptr<const ShaderProgram>;

// The name of an instruction's function, for dumps ("" when unknown).
const char* opName(OpFn fn);

}  // namespace streyes::sl
