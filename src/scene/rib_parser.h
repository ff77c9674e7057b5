// RibParser: reads RIB requests into a Scene, keeping RenderMan's graphics state.
//
// The parser owns the state a RIB stream builds up as it goes: the current transform (which may
// move), the current attributes, the stack of Attribute/Transform/World blocks, declared parameter
// types, light handles and an open MotionBegin block. Keeping that state in an object rather than
// in one function lets a later request (ReadArchive, a procedural) parse a further file or string
// into the same Scene under the state in force where it was called:
//
//     RibParser parser(scene, log);
//     parser.parseFile("scene.rib");   // or parseString(text, "name")
//     parser.finish();                 // WorldEnd seen, every block closed
//
// See docs/SCENE-FORMAT.md for the supported subset. Malformed input throws InputError naming
// file:line; requests outside the subset warn once through the Log and are skipped.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "scene/rib_lexer.h"
#include "streyes/scene.h"

namespace streyes {

// One argument of a request: a number, a string, or a bracketed array of either.
struct RibValue {
    enum class Kind { Number, String, Array };
    Kind kind = Kind::Number;
    std::vector<double> nums;          // Number: one; Array: its numbers
    std::vector<std::string> strings;  // String: one; Array: its strings
    int line = 0;

    bool isString() const { return kind == Kind::String; }
    bool isNumber() const { return kind == Kind::Number; }
    bool isNumericArray() const { return kind == Kind::Array && strings.empty(); }  // [] counts too
    bool isStringArray() const { return kind == Kind::Array && nums.empty(); }      // [] counts too
};

// A request with its arguments as written, before they are interpreted.
struct RibRequest {
    std::string name;
    std::vector<RibValue> args;
    SourceLoc loc;
};

// A parameter's declared storage: "uniform color", "varying float[2]", ...
struct RibParamDecl {
    ParamClass cls = ParamClass::Uniform;
    ParamType type = ParamType::Float;
    int arraySize = 1;
};

// Parse "[class] type[n] name" (an inline declaration) or "[class] type[n]" (Declare's second
// argument, withName = false). Returns an empty string on success, else what is wrong.
std::string parseRibDeclaration(const std::string& text, bool withName, RibParamDecl* decl, std::string* name);

// RIB spellings, for messages: "color", "varying".
const char* paramTypeName(ParamType type);
const char* paramClassName(ParamClass cls);

class RibArgs;

class RibParser {
  public:
    RibParser(Scene& scene, Log& log);

    // Parse a whole RIB file or string into the scene, starting from the current graphics state.
    // parseFile also sets scene.sourceName when it is still empty.
    void parseFile(const std::string& path);
    void parseString(const std::string& text, const std::string& sourceName);

    // Check that the input was a complete scene: a WorldBegin ... WorldEnd block, with every
    // Attribute/Transform/Motion block closed. Call once, after the top-level file.
    void finish();

    // A procedural's output is a fragment: requests inside the world block, starting from the
    // procedural's transform and attributes. beginFragment sets that state; finishFragment checks
    // that every block the fragment opened is closed.
    void beginFragment(const MotionTransform& ctm, const AttributesPtr& attributes);
    void finishFragment();

    // The graphics state where parsing stands, for requests that create geometry themselves.
    const MotionTransform& currentTransform() const { return ctm_; }
    AttributesPtr currentAttributes() const { return attributes_; }
    bool inWorld() const { return worldState_ == WorldState::InWorld; }

    Scene& scene() { return scene_; }

  private:
    // ---- Reading requests
    void parseTokens(RibLexer& lexer);
    RibRequest readRequest(RibLexer& lexer, RibToken nameToken);
    RibValue readArray(RibLexer& lexer, const RibToken& open);
    void dispatch(const RibRequest& request);

    // ---- Parameter lists and declarations
    ParamList readParams(RibArgs& args);
    Param makeParam(RibArgs& args, const RibValue& nameValue, const RibValue& value) const;
    void warnUnusedParams(const ParamList& params, const std::vector<std::string>& known,
                          const std::string& owner);

    // ---- Graphics state
    Attributes& mutableAttributes();  // copy-on-write: primitives keep the state they were given
    void applyTransform(const MotionTransform& requestMatrix, bool replaces, const SourceLoc& loc);

    // ---- Request handlers, by group
    void version(RibArgs& args);
    void declare(RibArgs& args);
    void unsupported(RibArgs& args);
    void frameBeginEnd(RibArgs& args);
    void skippedBlockBegin(RibArgs& args);
    // Options
    void format(RibArgs& args);
    void projection(RibArgs& args);
    void screenWindow(RibArgs& args);
    void frameAspectRatio(RibArgs& args);
    void clipping(RibArgs& args);
    void shutter(RibArgs& args);
    void pixelSamples(RibArgs& args);
    void pixelFilter(RibArgs& args);
    void display(RibArgs& args);
    void option(RibArgs& args);
    // Blocks
    void worldBegin(RibArgs& args);
    void worldEnd(RibArgs& args);
    void attributeBegin(RibArgs& args);
    void attributeEnd(RibArgs& args);
    void transformBegin(RibArgs& args);
    void transformEnd(RibArgs& args);
    void motionBegin(RibArgs& args);
    void motionEnd(RibArgs& args);
    // Transforms
    void transformRequest(RibArgs& args);
    Matrix4 readTransformMatrix(RibArgs& args, bool* replaces);
    // Attributes
    void color(RibArgs& args);
    void opacity(RibArgs& args);
    void surface(RibArgs& args);
    void shadingRate(RibArgs& args);
    void attribute(RibArgs& args);
    void lightSource(RibArgs& args);
    void illuminate(RibArgs& args);
    // Geometry
    struct PatchKey;
    void patchOrPolygon(RibArgs& args);
    bool readPatchKey(RibArgs& args, PatchKey* key);
    void addPatch(const std::vector<double>& times, const std::vector<PatchKey>& keys, const SourceLoc& loc);
    void unsupportedGeometry(RibArgs& args);
    // Curved and polygon-mesh geometry (PatchMesh, Patch "bicubic", SubdivisionMesh, quadrics,
    // polygons beyond four vertices): one request, or one per motion key.
    void basis(RibArgs& args);
    void curvedGeometry(RibArgs& args);
    void geometry(const std::vector<double>& times, const std::vector<RibRequest>& requests, const char* usage);
    bool readPatchMeshKey(RibArgs& args, PatchMeshDesc* out);
    bool readSubdivisionKey(RibArgs& args, SubdivisionMeshDesc* out);
    bool readQuadricKey(RibArgs& args, QuadricDesc* out);
    bool readPolygonsKey(RibArgs& args, std::vector<Vec3d>* points,
                         std::vector<std::vector<std::vector<int>>>* polygons, ColorPrimvar* Cs);
    void procedural(RibArgs& args);
    void readArchive(RibArgs& args);
    std::string resolveArchive(const std::string& name, const SourceLoc& loc) const;

    // ---- State
    enum class WorldState { BeforeWorld, InWorld, AfterWorld };
    enum class BlockKind { World, Attribute, Transform };
    struct Block {
        BlockKind kind;
        SourceLoc begin;
        std::shared_ptr<Attributes> attributes;  // saved by World and Attribute blocks
        MotionTransform ctm;
    };
    struct MotionBlock {
        std::vector<double> times;
        SourceLoc begin;
        std::vector<RibRequest> requests;  // held until MotionEnd, all the same request
        const char* usage = "";            // how that request is written, for messages
    };
    // ObjectBegin/ObjectEnd and ArchiveBegin/ArchiveEnd: contents skipped until the matching end.
    struct SkippedBlock {
        std::string beginName, endName;
        SourceLoc begin;
        int depth = 1;
    };

    Scene& scene_;
    Log& log_;
    std::shared_ptr<Attributes> attributes_;
    MotionTransform ctm_;
    std::vector<Block> blocks_;
    WorldState worldState_ = WorldState::BeforeWorld;
    SourceLoc worldBegin_;
    std::optional<MotionBlock> motion_;
    std::optional<SkippedBlock> skipping_;
    std::map<std::string, RibParamDecl> declarations_;
    std::map<std::string, int> lightHandles_;    // handle -> index in scene_.lights
    std::set<std::string> skippedLightHandles_;  // handles of lights of unsupported types
    SourceLoc lastLoc_;                          // last line read, for "missing ..." at the end
    int nesting_ = 0;                            // parseFile/parseString calls in progress
    bool fragment_ = false;                      // parsing a procedural's output
};

}  // namespace streyes
