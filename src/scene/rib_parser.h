// RibParser: reads RIB requests into a Scene, keeping RenderMan's graphics state.
//
// The parser owns the state a RIB stream builds up as it goes (RibState). Keeping that state in an
// object rather than in one function lets a later request (ReadArchive, a procedural) parse a
// further file or string into the same Scene under the state in force where it was called:
//
//     RibParser parser(scene, log);
//     parser.parseFile("scene.rib");   // or parseString(text, "name")
//     parser.finish();                 // WorldEnd seen, every block closed
//
// The requests themselves are handled by the files of their groups, through the request table
// (rib_requests.h); every handler reads and changes this one parser's state.
//
// See docs/SCENE-FORMAT.md for the supported subset. Malformed input throws InputError naming
// file:line; requests outside the subset warn once through the Log and are skipped.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "scene/rib_args.h"
#include "scene/rib_lexer.h"
#include "scene/rib_params.h"
#include "scene/search_path.h"
#include "streyes/rib.h"
#include "streyes/scene.h"

namespace streyes {

// The graphics state where reading stands: what requests build up and later requests read.
struct RibState {
    enum class World { Before, Inside, After };
    enum class BlockKind { World, Attribute, Transform, Solid };
    struct Block {
        BlockKind kind;
        SourceLoc begin;
        std::shared_ptr<Attributes> attributes;  // saved by World, Attribute and Solid blocks
        MotionTransform ctm;
        int outerSolid = -1;  // Solid blocks: openSolid before it (restored at SolidEnd)
        // ScopedCoordinateSystem names given in the block, with what each meant before (none: it
        // was not defined): restored at its end (endScopedCoordinateSystems).
        std::vector<std::pair<std::string, std::optional<MotionTransform>>> scopedSpaces = {};
    };
    struct MotionBlock {
        std::vector<double> times;
        SourceLoc begin;
        std::vector<RibRequest> requests;  // held until MotionEnd, all the same request
        const char* usage = "";            // how that request is written, for messages
    };
    // ArchiveBegin/ArchiveEnd: contents skipped until the matching end.
    struct SkippedBlock {
        std::string beginName, endName;
        SourceLoc begin;
        int depth = 1;
    };
    // The attribute requests given inside an object's definition that led to each attribute state
    // its primitives hold (in order, those of closed AttributeBegin blocks left out): replayed
    // over the attributes in force at each ObjectInstance (rib_objects.cpp).
    using AttributeEdits = std::vector<std::pair<AttributesPtr, std::vector<RibRequest>>>;
    // ObjectBegin ... ObjectEnd: primitives go to the object, not the scene (rib_objects.cpp).
    struct ObjectDefinition {
        std::string handle;
        SourceLoc begin;
        std::shared_ptr<Scene> object;
        MotionTransform ctm;                     // restored at ObjectEnd
        std::shared_ptr<Attributes> attributes;  // restored at ObjectEnd
        size_t blocks = 0;                       // open blocks at ObjectBegin
        AttributeEdits edits;
    };
    static const char* beginName(BlockKind kind);  // "AttributeBegin"
    static const char* endName(BlockKind kind);    // "AttributeEnd"

    // Shared with the primitives made under them: change them through mutableAttributes().
    std::shared_ptr<Attributes> attributes = std::make_shared<Attributes>();
    MotionTransform ctm;  // object to world; before WorldBegin, world to camera
    // CoordinateSystem and ScopedCoordinateSystem: the CTM where each name was given, as object to
    // world (one given before WorldBegin is made so at WorldBegin; until then it is camera-relative
    // and listed in cameraSpaces).
    std::map<std::string, MotionTransform> coordinateSystems;
    std::set<std::string> cameraSpaces;
    void endScopedCoordinateSystems(Block& block);  // at the end of a block: its scoped names undone
    std::vector<Block> blocks;  // open World/Attribute/Transform blocks, innermost last
    World world = World::Before;
    SourceLoc worldBegin;
    // The innermost open SolidBegin's node in Scene::solids (rib_solids.cpp), -1 outside solids,
    // kNoSolidNode in a solid block that makes no node (inside ObjectBegin or a procedural's output).
    static constexpr int kNoSolidNode = -2;
    int openSolid = -1;
    std::optional<MotionBlock> motion;
    std::optional<SkippedBlock> skipping;
    std::optional<ObjectDefinition> defining;                          // the open ObjectBegin
    std::map<std::string, std::shared_ptr<const Scene>> objects;      // handle -> defined object
    std::map<std::string, AttributeEdits> objectEdits;                 // handle -> its definition's edits
    // An object's attribute states as instanced under one attribute state (ProceduralDesc::
    // objectAttributes), made once for every instance under it.
    std::map<std::pair<std::string, const Attributes*>, std::pair<AttributesPtr, std::vector<std::pair<AttributesPtr, AttributesPtr>>>>
        instanceAttributes;
    std::map<std::string, RibParamDecl> declarations = predeclaredParams();
    std::vector<int> cameraLights;              // lights declared before WorldBegin (camera-relative)
    std::map<std::string, int> lightHandles;    // handle -> index in Scene::lights
    std::set<std::string> skippedLightHandles;  // handles of lights of unsupported types
    bool fragment = false;                      // reading a procedural's output
    // Option "searchpath" "procedural" | "archive": where plug-ins and archives named without a
    // folder are looked up (scene/search_path.h).
    std::string proceduralPath = kDefaultSearchPath, archivePath = kDefaultSearchPath;

    // Copy-on-write: primitives keep the attributes they were made with (rib_attributes.cpp).
    Attributes& mutableAttributes();
    // A transform request: it replaces the CTM, or applies to points before it (rib_transforms.cpp).
    void applyTransform(const MotionTransform& request, bool replaces, const SourceLoc& loc);
};

class RibParser {
  public:
    RibParser(Scene& scene, Log& log) : scene_(scene), log_(log) {}
    RibParser(const RibParser&) = delete;
    RibParser& operator=(const RibParser&) = delete;

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

    // How large on screen what is read will be (streyes/rib.h): a Blobby's cells follow it.
    void setReadDetail(const ReadDetail& detail) { detail_ = detail; }
    const ReadDetail& readDetail() const { return detail_; }

    // The graphics state where parsing stands, for requests that create geometry themselves.
    const MotionTransform& currentTransform() const { return state_.ctm; }
    AttributesPtr currentAttributes() const { return state_.attributes; }
    bool inWorld() const { return state_.world == RibState::World::Inside; }

    // Frame sequences: with a handler set, each FrameBegin n ... FrameEnd block is read as a
    // complete scene of its own (options, camera, world), starting from the state before the block,
    // and handed over at FrameEnd; the state returns to what it was at FrameBegin. Without one,
    // FrameBegin and FrameEnd are skipped with a warning (one scene per file).
    using FrameHandler = std::function<void(Scene&&)>;
    void setFrameHandler(FrameHandler handler) { frameHandler_ = std::move(handler); }
    bool readsFrames() const { return bool(frameHandler_); }
    void beginFrame(int number, const SourceLoc& loc);  // rib_blocks.cpp's FrameBegin
    void endFrame(const SourceLoc& loc);
    bool inFrame() const { return frame_.has_value(); }
    int framesRead() const { return framesRead_; }
    // Make requests (MakeTexture, MakeShadow, ...) are numbered in the order they come, and say
    // whether the world of their frame (or file) has ended: that places them among the frames.
    int nextMakeSerial() { return ++makeSerial_; }
    bool afterWorld() const { return state_.world == RibState::World::After; }

    // ---- For request handlers (rib_requests.h)
    // Where primitives go: the scene, or the object being defined (ObjectBegin).
    Scene& scene() { return state_.defining ? *state_.defining->object : scene_; }
    // The scene's camera, also while an object is defined (the object's own scene has none).
    const CameraDesc& camera() const { return scene_.camera; }
    Log& log() { return log_; }
    RibState& state() { return state_; }
    const RibState& state() const { return state_; }
    // The parameter list that ends a request: ("name" value) pairs, each name declared or an
    // inline declaration, each value of the declared type (rib_params.cpp).
    // `shaderParams`: names without a declaration are taken too (Param::declared false), typed
    // later by the shader that receives them.
    ParamList readParams(RibArgs& args, bool shaderParams = false) const;
    // Runs an attribute request's handler as if it came now (an object's edits replayed at an
    // instance); nothing is recorded for an object being defined.
    void replay(const RibRequest& request);
    // Warns once per owner and name about parameters the owner does not have.
    void warnUnusedParams(const ParamList& params, const std::vector<std::string>& known, const std::string& owner);

  private:
    void parseTokens(RibLexer& lexer);
    RibRequest readRequest(RibLexer& lexer, RibToken nameToken);
    RibValue readArray(RibLexer& lexer, const RibToken& open);
    void dispatch(const RibRequest& request);  // rib_requests.cpp
    // Geometry directly inside a non-primitive solid: warned about (rib_solids.cpp).
    void checkSolidGeometry(const RibRequest& request);
    Param makeParam(RibArgs& args, const RibValue& nameValue, const RibValue& value, bool shaderParam) const;

    struct SavedFrame {
        Scene scene;
        RibState state;
        SourceLoc begin;
    };
    Scene& scene_;
    Log& log_;
    RibState state_;
    FrameHandler frameHandler_;
    ReadDetail detail_;
    std::optional<SavedFrame> frame_;  // inside FrameBegin ... FrameEnd: the state before it
    int framesRead_ = 0;
    int makeSerial_ = 0;
    SourceLoc lastLoc_;  // last line read, for "missing ..." at the end
    int nesting_ = 0;    // parseFile/parseString calls in progress
};

}  // namespace streyes
