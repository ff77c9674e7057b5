// Reading a RIB stream: files and strings, tokens grouped into requests, the checks at the end of
// the input, and the public entry points (streyes/rib.h).
#include "scene/rib_parser.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/rib_gzip.h"
#include "streyes/rib.h"

namespace streyes {

// ---- Files and strings ----------------------------------------------------------------------------
void RibParser::parseFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw InputError("cannot open scene '" + path + "': " + std::strerror(EISDIR));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open scene '" + path + "': " + std::strerror(errno));
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw InputError("cannot read scene '" + path + "': " + std::strerror(errno));
    if (scene_.sourceName.empty()) scene_.sourceName = path;
    parseString(text.str(), path);
}

void RibParser::parseString(const std::string& text, const std::string& sourceName) {
    // Archives that read themselves would recurse without end.
    constexpr int kMaxNesting = 64;
    if (nesting_ >= kMaxNesting)
        throw InputError(lastLoc_, "scene files nested more than " + std::to_string(kMaxNesting) +
                                       " deep (does an archive read itself?)");
    ++nesting_;
    struct Unnest {
        int& n;
        ~Unnest() { --n; }
    } unnest{nesting_};
    // Compressed input, told by its first bytes: lines and byte offsets count the inflated stream.
    const std::string inflated = isGzip(text) ? gunzip(text, sourceName) : std::string();
    RibLexer lexer(isGzip(text) ? std::string_view(inflated) : std::string_view(text),
                   std::make_shared<const std::string>(sourceName));
    parseTokens(lexer);
    lastLoc_ = lexer.lastLoc();
}

void RibParser::parseTokens(RibLexer& lexer) {
    while (true) {
        RibToken token = lexer.next();
        if (token.kind == RibTokenKind::End) return;
        if (token.kind != RibTokenKind::Request)
            throw InputError(lexer.loc(token), "expected a request name, got " + describeToken(token) +
                                                   " with no request before it");
        RibRequest request = readRequest(lexer, std::move(token));
        lastLoc_ = request.loc;
        dispatch(request);
    }
}

// ---- Grouping tokens into requests ----------------------------------------------------------------
namespace {
// Another place in the same input, for messages: "line 12", or "byte 1234" in binary RIB.
std::string where(const SourceLoc& loc) {
    return loc.offset >= 0 ? "byte " + std::to_string(loc.offset) : "line " + std::to_string(loc.line);
}
}  // namespace

// A request's arguments are every value up to the next request name.
RibRequest RibParser::readRequest(RibLexer& lexer, RibToken nameToken) {
    RibRequest request;
    request.name = std::move(nameToken.text);
    request.loc = lexer.loc(nameToken);
    while (true) {
        const RibToken& t = lexer.peek();
        if (t.kind == RibTokenKind::Request || t.kind == RibTokenKind::End) break;
        RibToken token = lexer.next();
        RibValue value;
        value.line = token.line;
        value.offset = token.offset;
        switch (token.kind) {
        case RibTokenKind::Number:
            value.kind = RibValue::Kind::Number;
            value.nums.push_back(token.number);
            break;
        case RibTokenKind::String:
            value.kind = RibValue::Kind::String;
            value.strings.push_back(std::move(token.text));
            break;
        case RibTokenKind::NumberArray:
            value.kind = RibValue::Kind::Array;
            value.nums = std::move(token.numbers);
            break;
        case RibTokenKind::ArrayBegin: value = readArray(lexer, token); break;
        default:
            throw InputError(lexer.loc(token), "unexpected ']' with no '[' before it (in " + request.name + " at " +
                                                   where(request.loc) + ")");
        }
        request.args.push_back(std::move(value));
    }
    return request;
}

RibValue RibParser::readArray(RibLexer& lexer, const RibToken& open) {
    RibValue array;
    array.kind = RibValue::Kind::Array;
    array.line = open.line;
    array.offset = open.offset;
    const SourceLoc opened = lexer.loc(open);
    while (true) {
        RibToken t = lexer.next();
        switch (t.kind) {
        case RibTokenKind::ArrayEnd: return array;
        case RibTokenKind::Number:
            if (!array.strings.empty())
                throw InputError(lexer.loc(t), "array mixes strings and numbers: " + describeToken(t) +
                                                   " in an array of strings");
            array.nums.push_back(t.number);
            break;
        case RibTokenKind::String:
            if (!array.nums.empty())
                throw InputError(lexer.loc(t), "array mixes numbers and strings: " + describeToken(t) +
                                                   " in an array of numbers");
            array.strings.push_back(std::move(t.text));
            break;
        case RibTokenKind::ArrayBegin:
        case RibTokenKind::NumberArray:
            throw InputError(lexer.loc(t), "arrays cannot be nested: " +
                                               std::string(t.kind == RibTokenKind::ArrayBegin ? "'['" : "a binary float array") +
                                               " inside the array opened at " + where(opened));
        case RibTokenKind::Request:
            throw InputError(opened, "unterminated array: the '[' opened here has no ']' before " + describeToken(t) +
                                         " at " + where(lexer.loc(t)));
        case RibTokenKind::End:
            throw InputError(opened, "unterminated array: the '[' opened here has no ']' before the end of the input");
        }
    }
}

// ---- Frames ----------------------------------------------------------------------------------------
void RibParser::beginFrame(int number, const SourceLoc& loc) {
    if (frame_)
        throw InputError(loc, "FrameBegin inside the frame begun at line " + std::to_string(frame_->begin.line) +
                                  ": close it with FrameEnd first");
    if (state_.world == RibState::World::Inside)
        throw InputError(loc, "FrameBegin inside the world (WorldBegin at line " +
                                  std::to_string(state_.worldBegin.line) + "): frames hold worlds, not the reverse");
    if (state_.world == RibState::World::After)
        throw InputError(loc, "FrameBegin after a world outside any frame (WorldBegin at line " +
                                  std::to_string(state_.worldBegin.line) + "): put every world in a frame");
    if (state_.motion) throw InputError(loc, "FrameBegin inside a MotionBegin block");
    if (!state_.blocks.empty())
        throw InputError(state_.blocks.back().begin, std::string(RibState::beginName(state_.blocks.back().kind)) +
                                                         " is still open at FrameBegin (line " +
                                                         std::to_string(loc.line) + ")");
    frame_ = SavedFrame{scene_, state_, loc};
    scene_.frameNumber = number;
    scene_.frameLoc = loc;
}

void RibParser::endFrame(const SourceLoc& loc) {
    if (!frame_) throw InputError(loc, "FrameEnd without FrameBegin");
    const int begin = frame_->begin.line;
    if (state_.world == RibState::World::Inside)
        throw InputError(loc, "FrameEnd before WorldEnd (the frame began at line " + std::to_string(begin) + ")");
    if (state_.world == RibState::World::Before)
        throw InputError(loc, "the frame begun at line " + std::to_string(begin) +
                                  " has no WorldBegin ... WorldEnd: a frame is a complete scene");
    Scene done = std::move(scene_);
    scene_ = std::move(frame_->scene);
    state_ = std::move(frame_->state);
    frame_.reset();
    ++framesRead_;
    frameHandler_(std::move(done));
}

// ---- End of input -------------------------------------------------------------------------------
void RibParser::finish() {
    if (frame_) throw InputError(frame_->begin, "FrameBegin is never closed: missing FrameEnd");
    if (state_.motion) throw InputError(state_.motion->begin, "MotionBegin is never closed: missing MotionEnd");
    if (state_.defining) throw InputError(state_.defining->begin, "ObjectBegin is never closed: missing ObjectEnd");
    if (state_.skipping)
        throw InputError(state_.skipping->begin,
                         state_.skipping->beginName + " is never closed: missing " + state_.skipping->endName);
    if (!state_.blocks.empty()) {
        const RibState::Block& open = state_.blocks.back();
        if (open.kind == RibState::BlockKind::World)
            throw InputError(lastLoc_, "missing WorldEnd at the end of the file (WorldBegin at line " +
                                           std::to_string(open.begin.line) + ")");
        throw InputError(open.begin, std::string(RibState::beginName(open.kind)) + " is never closed: missing " +
                                         RibState::endName(open.kind) + " before the end of the file");
    }
    if (state_.world == RibState::World::Before && framesRead_ == 0)
        throw InputError(lastLoc_,
                         "no WorldBegin: a scene needs WorldBegin ... WorldEnd around its lights and "
                         "geometry");
}

void RibParser::beginFragment(const MotionTransform& ctm, const AttributesPtr& attributes) {
    state_.world = RibState::World::Inside;
    state_.ctm = ctm;
    state_.attributes = std::make_shared<Attributes>(attributes ? *attributes : Attributes());
    state_.fragment = true;
}

void RibParser::finishFragment() {
    if (state_.motion) throw InputError(state_.motion->begin, "MotionBegin is never closed: missing MotionEnd");
    if (state_.defining) throw InputError(state_.defining->begin, "ObjectBegin is never closed: missing ObjectEnd");
    if (state_.skipping)
        throw InputError(state_.skipping->begin,
                         state_.skipping->beginName + " is never closed: missing " + state_.skipping->endName);
    if (!state_.blocks.empty()) {
        const RibState::Block& open = state_.blocks.back();
        throw InputError(open.begin, std::string(RibState::beginName(open.kind)) +
                                         " is never closed in the procedural's output");
    }
}

// ---- Public entry points (streyes/rib.h) ------------------------------------------------------------
Scene parseRibFile(const std::string& path, Log& log) {
    Scene scene;
    scene.sourceName = path;
    RibParser parser(scene, log);
    parser.parseFile(path);
    parser.finish();
    return scene;
}

Scene parseRibString(const std::string& text, const std::string& sourceName, Log& log) {
    Scene scene;
    scene.sourceName = sourceName;
    RibParser parser(scene, log);
    parser.parseString(text, sourceName);
    parser.finish();
    return scene;
}

namespace {

// streyes render --option: each request read as if the file began with it.
void readDefaults(RibParser& parser, const RibDefaults& defaults) {
    for (size_t i = 0; i < defaults.size(); ++i) {
        const std::string name = "--option " + std::to_string(i + 1);
        parser.parseString(defaults[i], name);
        const RibState& state = parser.state();
        if (state.world != RibState::World::Before || !state.blocks.empty() || state.motion || state.defining ||
            state.skipping || parser.inFrame() || parser.framesRead() > 0)
            throw InputError(name + " ('" + defaults[i] + "'): give options and other requests of the kind a scene "
                             "gives before WorldBegin (Option, Format, PixelSamples ...), with every block they open "
                             "closed");
    }
}

}  // namespace

void checkRibDefaults(const RibDefaults& defaults) {
    Log log;
    log.setStrict(true);  // what a file's reader would warn about is a mistake on the command line
    Scene scene;
    RibParser parser(scene, log);
    readDefaults(parser, defaults);
}

void parseRibFrames(const std::string& path, Log& log, const std::function<void(Scene&&)>& frame,
                    const ReadDetail& detail, const std::function<void(Scene&&)>& after,
                    const RibDefaults& defaults) {
    Scene scene;
    scene.sourceName = path;
    RibParser parser(scene, log);
    parser.setReadDetail(detail);
    readDefaults(parser, defaults);
    parser.setFrameHandler([&](Scene&& s) {
        s.sourceName = path;
        frame(std::move(s));
    });
    parser.parseFile(path);
    parser.finish();
    if (parser.framesRead() == 0) frame(std::move(scene));
    else if (after) after(std::move(scene));
}

Scene parseRibFragment(const std::string& text, const std::string& sourceName, const MotionTransform& ctm,
                       const AttributesPtr& attributes, Log& log, const ReadDetail& detail) {
    Scene scene;
    RibParser parser(scene, log);
    parser.setReadDetail(detail);
    parser.beginFragment(ctm, attributes);
    parser.parseString(text, sourceName);
    parser.finishFragment();
    return scene;
}

}  // namespace streyes
