#include "scene/ri_stream.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>

namespace streyes {

namespace {

thread_local RiStream* current = nullptr;

// Function procedurals by id, while a stream or a generator keeps them.
struct FunctionRegistry {
    std::mutex mutex;
    std::map<std::string, std::weak_ptr<RiFunctionProcedural>> byId;
};
FunctionRegistry& registry() {
    static FunctionRegistry r;
    return r;
}

}  // namespace

RiFunctionProcedural::~RiFunctionProcedural() {
    {
        std::lock_guard<std::mutex> lock(registry().mutex);
        registry().byId.erase(id);
    }
    if (free) free(data);
}

std::shared_ptr<RiFunctionProcedural> findRiFunction(const std::string& id) {
    std::lock_guard<std::mutex> lock(registry().mutex);
    auto it = registry().byId.find(id);
    return it == registry().byId.end() ? nullptr : it->second.lock();
}

std::string RiStream::addFunction(RtPointer data, RtProcSubdivFunc subdivide, RtProcFreeFunc free) {
    static std::atomic<unsigned long long> next{1};
    auto f = std::make_shared<RiFunctionProcedural>();
    f->data = data;
    f->subdivide = subdivide;
    f->free = free;
    f->id = std::to_string(next++);
    {
        std::lock_guard<std::mutex> lock(registry().mutex);
        registry().byId[f->id] = f;
    }
    functions_[f->id] = f;
    return f->id;
}

RiStream* currentRiStream() { return current; }

RibEncoding& pendingRibEncoding() {
    thread_local RibEncoding pending;
    return pending;
}

std::string setRibOutputOption(RibEncoding& encoding, const std::string& token, const char* value) {
    std::string name = token;
    if (name.rfind("string ", 0) == 0) name = name.substr(7);  // an inline declaration
    const std::string v = value ? value : "";
    if (name == "format") {
        if (v != "ascii" && v != "binary") return "Option \"rib\" \"format\" is \"ascii\" or \"binary\", not \"" + v + "\"";
        encoding.binary = v == "binary";
        encoding.float32 = encoding.binary;  // the calls' values are RtFloats: exact as 32-bit floats
        return "";
    }
    if (name == "compression") {
        if (v != "none" && v != "gzip") return "Option \"rib\" \"compression\" is \"none\" or \"gzip\", not \"" + v + "\"";
        encoding.gzip = v == "gzip";
        return "";
    }
    return "Option \"rib\" \"" + name + "\" is not known (\"format\" and \"compression\" are): ignored";
}

RiStreamScope::RiStreamScope(RiStream* stream) : previous_(current) { current = stream; }
RiStreamScope::~RiStreamScope() { current = previous_; }

void RiStream::request(const char* call, const char* request) {
    if (calls_ > 0) text_ += '\n';
    ++calls_;
    call_ = call;
    text_ += request;
}

void RiStream::fail(const std::string& what) {
    if (error_.empty()) error_ = "call " + std::to_string(calls_) + " (" + call_ + "): " + what;
}

void RiStream::number(double v) {
    if (!std::isfinite(v)) {
        fail("a value is not a finite number (" + std::to_string(v) + ")");
        v = 0;
    }
    // 9 significant digits: every float reads back as itself.
    char buf[32];
    std::snprintf(buf, sizeof buf, " %.9g", v);
    text_ += buf;
}

void RiStream::integer(long v) {
    text_ += ' ';
    text_ += std::to_string(v);
}

void RiStream::string(const char* s) {
    if (!s) {
        fail("a string is a null pointer");
        s = "";
    }
    text_ += " \"";
    for (; *s; ++s) {
        if (*s == '"' || *s == '\\') text_ += '\\';
        if (*s == '\n') text_ += "\\n";
        else text_ += *s;
    }
    text_ += '"';
}

void RiStream::floats(const RtFloat* v, size_t n) {
    text_ += " [";
    if (!v && n) fail("an array of values is a null pointer");
    else
        for (size_t i = 0; i < n; ++i) number(v[i]);
    text_ += " ]";
}

void RiStream::integers(const RtInt* v, size_t n) {
    text_ += " [";
    if (!v && n) fail("an array of integers is a null pointer");
    else
        for (size_t i = 0; i < n; ++i) integer(v[i]);
    text_ += " ]";
}

void RiStream::strings(const RtString* v, size_t n) {
    text_ += " [";
    if (!v && n) fail("an array of strings is a null pointer");
    else
        for (size_t i = 0; i < n; ++i) string(v[i]);
    text_ += " ]";
}

void RiStream::params(int n, const RtToken tokens[], const RtPointer values[], const RiClassSizes& sizes) {
    for (int i = 0; i < n; ++i) {
        const char* token = tokens ? tokens[i] : nullptr;
        if (!token) {
            fail("parameter " + std::to_string(i + 1) + " has no name");
            return;
        }
        RibParamDecl decl;
        std::string name = token;
        if (name.find_first_of(" \t") != std::string::npos) {
            const std::string error = parseRibDeclaration(token, true, &decl, &name);
            if (!error.empty()) {
                fail("bad inline declaration \"" + std::string(token) + "\": " + error);
                return;
            }
        } else {
            auto it = declarations_.find(name);
            if (it == declarations_.end()) {
                fail("parameter \"" + name + "\" is not declared: RiDeclare it, or declare it inline (\"uniform float " +
                     name + "\")");
                return;
            }
            decl = it->second;
        }
        int items = 1;
        switch (decl.cls) {
        case ParamClass::Constant: items = 1; break;
        case ParamClass::Uniform: items = sizes.uniform; break;
        case ParamClass::Varying: items = sizes.varying; break;
        case ParamClass::Vertex: items = sizes.vertex; break;
        case ParamClass::FaceVarying: items = sizes.faceVarying; break;
        }
        Param shape;
        shape.type = decl.type;
        shape.arraySize = decl.arraySize;
        const size_t count = size_t(std::max(items, 0)) * size_t(shape.componentsPerItem());
        const void* v = values ? values[i] : nullptr;
        string(token);
        if (decl.type == ParamType::String) strings(static_cast<const RtString*>(v), count);
        else if (decl.type == ParamType::Integer) integers(static_cast<const RtInt*>(v), count);
        else floats(static_cast<const RtFloat*>(v), count);
    }
}

}  // namespace streyes
