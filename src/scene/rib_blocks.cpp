// Blocks: WorldBegin/End, AttributeBegin/End and TransformBegin/End save and restore the graphics
// state; MotionBegin/End holds its requests (RibParser::dispatch) and hands them to the request's
// own motion handler at MotionEnd; FrameBegin/End and the blocks whose contents are skipped.
#include "scene/rib_requests.h"

namespace streyes {

const char* RibState::beginName(BlockKind kind) {
    static const char* names[] = {"WorldBegin", "AttributeBegin", "TransformBegin", "SolidBegin"};
    return names[int(kind)];
}

const char* RibState::endName(BlockKind kind) {
    static const char* names[] = {"WorldEnd", "AttributeEnd", "TransformEnd", "SolidEnd"};
    return names[int(kind)];
}

namespace {

using BlockKind = RibState::BlockKind;
using World = RibState::World;

// The inverse of a (moving) transform, key by key.
MotionTransform inverseOf(const MotionTransform& m, RibArgs& args) {
    std::vector<Matrix4> keys;
    for (const Matrix4& k : m.keys()) {
        Matrix4 inv;
        if (!invert(k, &inv)) args.fail("the camera transform is singular: lights before WorldBegin cannot be placed");
        keys.push_back(inv);
    }
    return MotionTransform(m.times(), std::move(keys));
}

// WorldBegin fixes the camera: the CTM so far is world-to-camera, and the world starts at identity.
// Each display's quantization, now that the options are final (Quantize may follow Display): the
// Quantize of its mode, else of "z" for a depth display or "rgba", else RenderMan's default; then
// the display's own "quantize" and "dither".
void resolveQuantize(RenderSettings& settings) {
    for (DisplayDesc& d : settings.displays) {
        d.quantize = settings.quantizeOf(d.mode);
        if (d.quantizeParam.size() == 4) {
            d.quantize.zero = d.quantizeParam[0];
            d.quantize.one = d.quantizeParam[1];
            d.quantize.min = d.quantizeParam[2];
            d.quantize.max = d.quantizeParam[3];
        }
        if (d.ditherParam.size() == 1) d.quantize.dither = d.ditherParam[0];
    }
}

void worldBegin(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (s.fragment) args.fail("a procedural's output is inside the world already: it cannot begin one");
    if (s.world != World::Before)
        args.fail("only one WorldBegin ... WorldEnd block per file is supported (the first began at line " +
                  std::to_string(s.worldBegin.line) + ")");
    if (!s.blocks.empty()) {
        const RibState::Block& open = s.blocks.back();
        throw InputError(open.begin, std::string(RibState::beginName(open.kind)) +
                                         " is still open at WorldBegin (line " + std::to_string(args.loc().line) +
                                         "): close it before WorldBegin");
    }
    if (reader.readsFrames() && reader.framesRead() > 0 && !reader.inFrame())
        args.fail("a world outside FrameBegin ... FrameEnd in a file of frames: put it in a frame");
    reader.scene().camera.worldToCamera = s.ctm;
    reader.scene().camera.loc = args.loc();
    resolveQuantize(reader.scene().settings);
    CameraDesc& camera = reader.scene().camera;
    if (camera.depthOfField() && camera.projection == ProjectionKind::Orthographic) {
        reader.log().warnOnce("depthoffield:orthographic", camera.depthOfFieldLoc,
                              "DepthOfField has no effect with an orthographic projection: ignored");
        camera.fstop = std::numeric_limits<double>::infinity();
    }
    // Lights declared before WorldBegin (PRMan and Aqsis accept them) were placed in camera space:
    // their light-to-world transform is that through the camera's inverse.
    for (int i : s.cameraLights) {
        LightDesc& light = reader.scene().lights[size_t(i)];
        light.lightToWorld = light.lightToWorld.then(inverseOf(s.ctm, args));
    }
    s.cameraLights.clear();
    // Coordinate systems named before WorldBegin were camera-relative: now through the camera's inverse.
    for (const std::string& name : s.cameraSpaces) {
        auto it = s.coordinateSystems.find(name);
        if (it == s.coordinateSystems.end()) continue;
        it->second = it->second.then(inverseOf(s.ctm, args));
        keepCoordinateSystem(reader.scene().settings, name, it->second);
    }
    s.cameraSpaces.clear();
    s.blocks.push_back(RibState::Block{BlockKind::World, args.loc(), s.attributes, s.ctm});
    s.ctm = MotionTransform();
    s.world = World::Inside;
    s.worldBegin = args.loc();
}

void worldEnd(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (s.fragment) args.fail("a procedural's output cannot end the world block");
    if (s.world != World::Inside) args.fail("WorldEnd without WorldBegin");
    const RibState::Block& open = s.blocks.back();
    if (open.kind != BlockKind::World)
        throw InputError(open.begin, std::string(RibState::beginName(open.kind)) +
                                         " is never closed: WorldEnd (line " + std::to_string(args.loc().line) +
                                         ") comes before its " + RibState::endName(open.kind));
    s.attributes = open.attributes;
    s.ctm = open.ctm;
    s.endScopedCoordinateSystems(s.blocks.back());
    s.blocks.pop_back();
    s.world = World::After;
}

void attributeBegin(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    s.blocks.push_back(RibState::Block{BlockKind::Attribute, args.loc(), s.attributes, s.ctm});
}

void transformBegin(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    s.blocks.push_back(RibState::Block{BlockKind::Transform, args.loc(), nullptr, s.ctm});
}

void attributeEnd(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (s.blocks.empty() || s.blocks.back().kind == BlockKind::World)
        args.fail("AttributeEnd without a matching AttributeBegin");
    const RibState::Block& open = s.blocks.back();
    if (open.kind != BlockKind::Attribute)
        args.fail(std::string("AttributeEnd does not match the ") + RibState::beginName(open.kind) + " at line " +
                  std::to_string(open.begin.line) + ": close that with " + RibState::endName(open.kind) + " first");
    s.attributes = open.attributes;
    s.ctm = open.ctm;
    s.endScopedCoordinateSystems(s.blocks.back());
    s.blocks.pop_back();
}

void transformEnd(RibParser& reader, RibArgs& args) {
    RibState& s = reader.state();
    args.expectEnd();
    if (s.blocks.empty() || s.blocks.back().kind == BlockKind::World)
        args.fail("TransformEnd without a matching TransformBegin");
    const RibState::Block& open = s.blocks.back();
    if (open.kind != BlockKind::Transform)
        args.fail(std::string("TransformEnd does not match the ") + RibState::beginName(open.kind) + " at line " +
                  std::to_string(open.begin.line) + ": close that with " + RibState::endName(open.kind) + " first");
    s.ctm = open.ctm;
    s.endScopedCoordinateSystems(s.blocks.back());
    s.blocks.pop_back();
}

// MotionBegin opens a block whose requests are held (see dispatch) and read together at MotionEnd.
void motionBegin(RibParser& reader, RibArgs& args) {
    std::vector<double> times = args.numberList("times");
    args.expectEnd();
    if (times.empty()) args.fail("MotionBegin needs at least one time");
    for (size_t i = 1; i < times.size(); ++i)
        if (!(times[i] > times[i - 1]))
            args.fail("motion times must increase strictly, but " + formatNumber(times[i]) + " follows " +
                      formatNumber(times[i - 1]));
    reader.state().motion = RibState::MotionBlock{std::move(times), args.loc(), {}, ""};
}

void motionEnd(RibParser& reader, RibArgs& args) {
    std::optional<RibState::MotionBlock>& motion = reader.state().motion;
    args.expectEnd();
    if (!motion) args.fail("MotionEnd without MotionBegin");
    RibKeys keys{std::move(motion->times), std::move(motion->requests), motion->usage};
    const SourceLoc begin = motion->begin;
    motion.reset();
    if (keys.requests.size() != keys.times.size())
        args.fail("the MotionBegin at line " + std::to_string(begin.line) + " gives " +
                  plural(keys.times.size(), "time") + ", but the block holds " +
                  plural(keys.requests.size(), "request") + ": give one request per time");
    // Dispatch let in only requests that can move, all the same one.
    ribRequests().find(keys.requests.front().name)->motion(reader, keys);
}

void frameBegin(RibParser& reader, RibArgs& args) {
    if (!reader.readsFrames()) {
        reader.log().warnOnce("request:FrameBegin", args.loc(),
                              "FrameBegin/FrameEnd ignored: the frames rendered come from Option \"streyes\" \"int "
                              "frames\" or the command line");
        args.skipRest();
        return;
    }
    const int number = args.integer("frame");
    args.expectEnd();
    reader.beginFrame(number, args.loc());
}

void frameEnd(RibParser& reader, RibArgs& args) {
    if (!reader.readsFrames()) {
        args.skipRest();
        return;
    }
    args.expectEnd();
    reader.endFrame(args.loc());
}

// ArchiveBegin: everything up to the matching end is skipped (see dispatch).
void skippedBlockBegin(RibParser& reader, RibArgs& args) {
    std::string endName = "ArchiveEnd";
    reader.log().warnOnce(
        "request:" + args.name(), args.loc(),
        "unsupported request '" + args.name() + "' ignored, with everything up to its " + endName);
    args.skipRest();
    reader.state().skipping = RibState::SkippedBlock{args.name(), endName, args.loc(), 1};
}

}  // namespace

void addBlockRequests(RibRequestTable& table) {
    table.add("WorldBegin", {worldBegin, "WorldBegin"});
    table.add("WorldEnd", {worldEnd, "WorldEnd"});
    table.add("AttributeBegin", {attributeBegin, "AttributeBegin"});
    table.add("AttributeEnd", {attributeEnd, "AttributeEnd"});
    table.add("TransformBegin", {transformBegin, "TransformBegin"});
    table.add("TransformEnd", {transformEnd, "TransformEnd"});
    table.add("MotionBegin", {motionBegin, "MotionBegin [t0 t1 ...]"});
    table.add("MotionEnd", {motionEnd, "MotionEnd"});
    table.add("FrameBegin", {frameBegin, "FrameBegin number"});
    table.add("FrameEnd", {frameEnd, "FrameEnd"});
    table.add("ArchiveBegin", {skippedBlockBegin, "ArchiveBegin \"name\""});
}

}  // namespace streyes
