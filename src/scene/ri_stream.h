// The RIB stream behind the RI C API (include/ri.h): each Ri call appends the request it stands
// for, as RIB text, to the stream current on the calling thread; the RIB reader reads it. So a
// scene built through calls is the scene its RIB gives, with every check the reader makes.
//
// A procedural's expansion makes a stream current on its thread while the plug-in's Subdivide
// runs (thread_local: expansions on other threads have their own); RiBegin makes one current for
// a session. A bad call (a NaN, an undeclared parameter) is not thrown through the caller's C
// frames: the stream keeps the first one, which its owner reports.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ri.h"
#include "scene/rib_params.h"
#include "scene/rib_writer.h"

namespace streyes {

// RiProcedural with a subdivide function of the program's own: the RIB cannot name a function,
// so the stream writes Procedural "RiFunction" ["id"] [bound] and keeps the function here, under
// that id. freefunc(data) runs when the last owner lets go.
struct RiFunctionProcedural {
    RtPointer data = nullptr;
    RtProcSubdivFunc subdivide = nullptr;
    RtProcFreeFunc free = nullptr;
    std::string id;
    RiFunctionProcedural() = default;
    RiFunctionProcedural(const RiFunctionProcedural&) = delete;
    RiFunctionProcedural& operator=(const RiFunctionProcedural&) = delete;
    ~RiFunctionProcedural();
};
constexpr const char* kRiFunctionKind = "RiFunction";

// How many values a parameter of each class has on the primitive being written (RISpec 3.2 §5).
struct RiClassSizes {
    int uniform = 1, varying = 1, vertex = 1, faceVarying = 1;
};

class RiStream {
  public:
    explicit RiStream(std::string name) : name_(std::move(name)) {}
    RiStream(const RiStream&) = delete;
    RiStream& operator=(const RiStream&) = delete;

    const std::string& name() const { return name_; }
    const std::string& text() const { return text_; }
    int calls() const { return calls_; }

    // Starts the next request line: `request` is its RIB name; `call` ("RiSphere") names it in
    // messages. Each call is one line, so a reader's "line n" is the n-th call.
    void request(const char* call, const char* request);
    void number(double v);         // a float argument; a NaN or infinity is a bad call
    void integer(long v);
    void string(const char* s);    // quoted; a null pointer is a bad call
    void floats(const RtFloat* v, size_t n);  // [v ...]
    void integers(const RtInt* v, size_t n);
    void strings(const RtString* v, size_t n);
    void raw(const char* text) { text_ += text; }
    // The parameter list: n tokens, each a declared name or an inline declaration, with its
    // values (as many as the declaration and `sizes` say).
    void params(int n, const RtToken tokens[], const RtPointer values[], const RiClassSizes& sizes);

    // Records a bad call (the first is kept): "call 12 (RiSphere): ...".
    void fail(const std::string& what);
    const std::string& error() const { return error_; }

    // RiDeclare: the stream's declarations (RenderMan's predeclared names, then RiDeclare's).
    std::map<std::string, RibParamDecl>& declarations() { return declarations_; }
    int uStep = 3, vStep = 3;  // RiBasis's steps: PatchMesh's varying counts depend on them
    std::vector<std::pair<int, int>> savedSteps;  // by RiAttributeBegin, as the reader saves the Basis
    int nextLight = 1;          // RiLightSource handles, numbered as RIB 3.2 does
    // How RiEnd writes the session's file: Option "rib" "format" and "compression" (RiOption).
    RibEncoding encoding;

    // Function procedurals written to this stream, by id; also findable with findRiFunction while
    // the stream keeps them.
    std::string addFunction(RtPointer data, RtProcSubdivFunc subdivide, RtProcFreeFunc free);
    std::map<std::string, std::shared_ptr<RiFunctionProcedural>>& functions() { return functions_; }

  private:
    std::string name_, text_, call_, error_;
    int calls_ = 0;
    std::map<std::string, RibParamDecl> declarations_ = predeclaredParams();
    std::map<std::string, std::shared_ptr<RiFunctionProcedural>> functions_;
};

// The stream Ri calls on this thread write to; nullptr when none (the call is reported on
// standard error and ignored).
RiStream* currentRiStream();

// Option "rib" given before RiBegin, as PRMan has it: the encoding the next session on this thread
// writes its file in (RiBegin takes it).
RibEncoding& pendingRibEncoding();

// RiOption("rib", ...): "format" "ascii" | "binary" (binary reals are 32-bit floats, what the
// calls gave), "compression" "none" | "gzip". Returns what was wrong with a token or value ("" if
// nothing); what it does not know is left alone.
std::string setRibOutputOption(RibEncoding& encoding, const std::string& token, const char* value);
// Makes `stream` current on this thread until the scope ends (the previous one again after).
class RiStreamScope {
  public:
    explicit RiStreamScope(RiStream* stream);
    ~RiStreamScope();
    RiStreamScope(const RiStreamScope&) = delete;
    RiStreamScope& operator=(const RiStreamScope&) = delete;

  private:
    RiStream* previous_;
};

// The function procedural a stream wrote under `id`, while some stream or generator keeps it;
// nullptr otherwise (a RIB file naming "RiFunction" itself finds none).
std::shared_ptr<RiFunctionProcedural> findRiFunction(const std::string& id);

// Links every Ri function into a program that links streyes statically: plug-ins find them in
// the program when it exports them (-rdynamic or --export-dynamic-symbol=Ri*). Returns how many.
int riApiFunctionCount();

}  // namespace streyes
