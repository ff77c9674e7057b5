// Blobby nleaf [code] [floats] [strings] ...: implicit surfaces, kept as the triangles of their
// level surface (scene/blobby_field.h), a polygon mesh like PointsPolygons. Its varying, vertex and
// facevarying variables have a value per leaf; the mesh gets, at each vertex, the leaves' values
// weighted by each leaf's field there (RI Spec 3.2, 5.6), as "vertex" variables.
#include <algorithm>
#include <cmath>
#include <atomic>
#include <filesystem>
#include <optional>

#include "scene/blobby_cut.h"
#include "scene/blobby_field.h"
#include "scene/rib_geometry.h"
#include "streyes/scene_access.h"

namespace streyes {

namespace {

constexpr double kPixelsPerCell = 2;  // without "blobbyresolution": a cell every 2 pixels on screen
constexpr int kMinCells = 8;
constexpr int kMaxCells = 256;  // at most 258^3 grid points: about 140 MB of field values

// A variable with a value per leaf that the mesh can carry per vertex: one float, colour, point,
// vector or normal ("st" two floats), or PRMan's "mpoint" (a matrix: each leaf's reference frame).
bool perLeafVariable(const Param& p) {
    if (p.cls != ParamClass::Varying && p.cls != ParamClass::Vertex && p.cls != ParamClass::FaceVarying) return false;
    if (p.name == "st" && p.type == ParamType::Float && p.arraySize == 2) return true;
    return p.arraySize == 1 && (p.type == ParamType::Float || p.type == ParamType::Color || p.type == ParamType::Point ||
                                p.type == ParamType::Vector || p.type == ParamType::Normal || p.type == ParamType::Matrix);
}

// One key: the code decoded into instructions, every index checked. Nothing (with a warning, as the
// peers give) for a code with an opcode streyes does not know: how many operands follow it is
// unknown, so the rest of the code cannot be read.
std::optional<BlobbyKey> readBlobbyKey(RibParser& reader, RibArgs& args) {
    static std::atomic<int> blobbies{0};
    const int blobbyId = blobbies++;  // the plug-ins' State
    BlobbyKey key;
    const RibValue* nleafValue = args.peek();
    key.nleaf = args.integer("nleaf");
    if (key.nleaf < 1) args.fail(*nleafValue, "nleaf must be at least 1, got " + std::to_string(key.nleaf));
    const RibValue* codeValue = args.peek();
    const std::vector<int> code = intArray(args, "code", 0);
    const RibValue& floatsValue = takeArray(args, "floats", false);
    const std::vector<double>& floats = floatsValue.nums;
    const RibValue& stringsValue = takeArray(args, "strings", true);
    const std::vector<std::string>& strings = stringsValue.strings;
    auto bad = [&](const std::string& what) { args.fail(*codeValue, what); };
    auto floatsAt = [&](size_t at, int index, size_t n, const char* what) {
        if (index < 0 || size_t(index) + n > floats.size())
            bad("instruction " + std::to_string(at) + " (" + what + ") needs " + std::to_string(n) +
                " floats from index " + std::to_string(index) + " but there are " + plural(floats.size(), "float"));
        for (size_t i = size_t(index); i < size_t(index) + n; ++i)
            if (!std::isfinite(floats[i]))
                args.fail(floatsValue, "float " + std::to_string(i) + " (used by instruction " + std::to_string(at) +
                                           ", " + what + ") is " + formatNumber(floats[i]));
        return &floats[size_t(index)];
    };
    auto matrixAt = [&](size_t at, const double* m, BlobbyOp& op, const char* what) {
        op.toObject = Matrix4::fromRowMajor(m);
        if (!invert(op.toObject, &op.toBlob))
            bad("instruction " + std::to_string(at) + " (" + what + ") has a singular matrix");
    };
    if (code.empty()) bad("the code has no instructions");
    std::vector<size_t> pluginLeaves;  // opcode 9000
    size_t pc = 0;
    auto operand = [&](size_t at, const char* what) {
        if (pc >= code.size())
            bad("the code ends inside instruction " + std::to_string(at) + " (" + what + ")");
        return code[pc++];
    };
    auto stringAt = [&](size_t at, int index, const char* what) {
        if (index < 0 || size_t(index) >= strings.size())
            bad("instruction " + std::to_string(at) + " (" + what + ") names string " + std::to_string(index) +
                " but there are " + plural(strings.size(), "string"));
        return index;
    };
    // A field plug-in's arguments: nfloat floats from floatIndex, nstring strings from stringIndex.
    auto pluginFloats = [&](size_t at, int n, int index) {
        if (n < 0) bad("instruction " + std::to_string(at) + " (field plug-in) passes " + std::to_string(n) + " floats");
        const double* f = n > 0 ? floatsAt(at, index, size_t(n), "field plug-in") : nullptr;
        return std::vector<float>(f, f + n);
    };
    auto pluginStrings = [&](size_t at, int n, int index) {
        if (n < 0 || (n > 0 && (index < 0 || size_t(index) + size_t(n) > strings.size())))
            bad("instruction " + std::to_string(at) + " (field plug-in) passes " + std::to_string(n) +
                " strings from index " + std::to_string(index) + " but there are " + plural(strings.size(), "string"));
        return n > 0 ? std::vector<std::string>(strings.begin() + index, strings.begin() + index + n)
                     : std::vector<std::string>();
    };
    // The plug-in's shared object, loaded once; null, with a warning, when there is none.
    auto pluginLibrary = [&](size_t at, const std::string& name) {
        // A plug-in runs code, as a program does: allowed where programs are (not under --safe).
        const SceneAccess access = sceneAccess();
        if (!access.programs)
            throw InputError(args.loc(), "Blobby: instruction " + std::to_string(at) + " names the field plug-in '" +
                                             name + "'" +
                                             (access.safe ? ", refused by --safe: it would load a plug-in, which runs "
                                                            "code. Render without --safe only if you trust the scene"
                                                          : ": plug-ins are not allowed here"));
        const std::string directory =
            args.loc().file ? std::filesystem::path(*args.loc().file).parent_path().string() : std::string();
        std::string where;
        std::shared_ptr<BlobbyPluginLibrary> lib =
            loadBlobbyPlugin(name, reader.state().proceduralPath, directory, args.loc(), &where);
        if (!lib)
            reader.log().lenient("blobby:plugin:" + name, args.loc(),
                                 "Blobby: instruction " + std::to_string(at) + ": no field plug-in '" + name +
                                     "' (looked for '" + name + "' and '" + name + ".so' " + where +
                                     "; add its folder with Option \"searchpath\" \"procedural\" [\"folder:&\"]): "
                                     "its field is taken as 0");
        return lib;
    };
    while (pc < code.size()) {
        const size_t at = key.field.ops.size();
        const int opcode = code[pc++];
        BlobbyOp op;
        using K = BlobbyOp::Kind;
        switch (opcode) {
        case 1000: op.kind = K::Constant; op.value = *floatsAt(at, operand(at, "constant"), 1, "constant"); break;
        case 1001: {
            op.kind = K::Ellipsoid;
            matrixAt(at, floatsAt(at, operand(at, "ellipsoid"), 16, "ellipsoid"), op, "ellipsoid");
            break;
        }
        case 1002: {
            op.kind = K::Segment;
            const double* f = floatsAt(at, operand(at, "segment blob"), 23, "segment blob");
            op.a = {f[0], f[1], f[2]};
            op.b = {f[3], f[4], f[5]};
            op.radius = f[6];
            if (!(op.radius > 0))
                bad("instruction " + std::to_string(at) + " (segment blob) has radius " + formatNumber(op.radius) +
                    ": it must be positive");
            matrixAt(at, f + 7, op, "segment blob");
            break;
        }
        case 1003: {
            // 1003 nameindex floatindex: the depth map's name, then A B C D.
            op.kind = K::Plane;
            const int name = operand(at, "repelling plane");
            if (name < 0 || size_t(name) >= strings.size())
                bad("instruction " + std::to_string(at) + " (repelling plane) names string " + std::to_string(name) +
                    " but there are " + plural(strings.size(), "string"));
            const double* f = floatsAt(at, operand(at, "repelling plane"), 4, "repelling plane");
            std::copy(f, f + 4, op.repel);
            if (op.repel[0] > 0 && !(op.repel[2] != 0))
                bad("instruction " + std::to_string(at) + " (repelling plane) has C = 0: the bump's width must not be 0");
            key.planeMaps.push_back({at, strings[size_t(name)]});
            break;
        }
        case 1004: {
            // PRMan's field plug-in: 1004 name nfloat floatindex nstring stringindex.
            op.kind = K::Plugin;
            const int name = stringAt(at, operand(at, "field plug-in"), "field plug-in");
            const int nfloat = operand(at, "field plug-in"), floatIndex = operand(at, "field plug-in");
            const int nstring = operand(at, "field plug-in"), stringIndex = operand(at, "field plug-in");
            std::vector<float> f = pluginFloats(at, nfloat, floatIndex);
            std::vector<std::string> str = pluginStrings(at, nstring, stringIndex);
            if (auto lib = pluginLibrary(at, strings[size_t(name)]))
                op.plugin = BlobbyPluginLeaf::makePrman(std::move(lib), f, str, args.loc());
            break;
        }
        case 9000: {
            // AIR's field plug-in (Aqsis reads it too): 9000 n, then n operands: name, the matrix
            // placing its space, and optionally nfloat floatindex, nstring stringindex, nint ints.
            op.kind = K::Plugin;
            const int n = operand(at, "field plug-in");
            if (n < 2 || n == 3 || n == 5)
                bad("instruction " + std::to_string(at) + " (field plug-in, 9000) has " + std::to_string(n) +
                    " operands: it takes 2 (name, matrix), 4 (and nfloat, floatindex), 6 (and nstring, "
                    "stringindex) or 7 and more (and nint, then the ints)");
            const int name = stringAt(at, operand(at, "field plug-in"), "field plug-in");
            matrixAt(at, floatsAt(at, operand(at, "field plug-in"), 16, "field plug-in"), op, "field plug-in");
            std::vector<float> f;
            std::vector<std::string> str;
            std::vector<int> ints;
            if (n >= 4) {
                const int nfloat = operand(at, "field plug-in"), floatIndex = operand(at, "field plug-in");
                f = pluginFloats(at, nfloat, floatIndex);
            }
            if (n >= 6) {
                const int nstring = operand(at, "field plug-in"), stringIndex = operand(at, "field plug-in");
                str = pluginStrings(at, nstring, stringIndex);
            }
            if (n >= 7) {
                const int nint = operand(at, "field plug-in");
                if (nint != n - 7)
                    bad("instruction " + std::to_string(at) + " (field plug-in, 9000) has " + std::to_string(n) +
                        " operands but gives nint " + std::to_string(nint) + ": n must be 7 + nint");
                for (int i = 0; i < nint; ++i) ints.push_back(operand(at, "field plug-in"));
            }
            pluginLeaves.push_back(at);
            if (auto lib = pluginLibrary(at, strings[size_t(name)]))
                op.plugin = BlobbyPluginLeaf::makeAir(std::move(lib), op.toObject, op.toBlob, std::move(f),
                                                      std::move(str), std::move(ints), blobbyId, int(at), args.loc());
            break;
        }
        case 0: case 1: case 2: case 3: {
            static const K kinds[] = {K::Add, K::Multiply, K::Max, K::Min};
            static const char* names[] = {"add", "multiply", "maximum", "minimum"};
            op.kind = kinds[opcode];
            const int n = operand(at, names[opcode]);
            if (n < 1) bad("instruction " + std::to_string(at) + " (" + names[opcode] + ") has " +
                           std::to_string(n) + " operands: it needs at least 1");
            for (int i = 0; i < n; ++i) op.operands.push_back(operand(at, names[opcode]));
            break;
        }
        case 4: case 5: case 6: case 7: {
            static const K kinds[] = {K::Subtract, K::Divide, K::Negate, K::Identity};
            static const char* names[] = {"subtract", "divide", "negate", "identity"};
            op.kind = kinds[opcode - 4];
            for (int i = 0; i < (opcode < 6 ? 2 : 1); ++i) op.operands.push_back(operand(at, names[opcode - 4]));
            break;
        }
        default:
            reader.log().lenient("blobby:opcode:" + std::to_string(opcode), args.loc(),
                                 "Blobby: instruction " + std::to_string(at) + " has unknown opcode " +
                                     std::to_string(opcode) +
                                     " (leaves are 1000-1004 and 9000, operators 0-7: add, multiply, maximum, minimum, "
                                     "subtract, divide, negate, identity): the blobby is skipped");
            return std::nullopt;
        }
        for (int o : op.operands)
            if (o < 0 || size_t(o) >= at)
                bad("instruction " + std::to_string(at) + " uses instruction " + std::to_string(o) +
                    ", which is not an earlier one (0 to " + std::to_string(int(at) - 1) + ")");
        if (op.leaf()) key.leaves.push_back(at);
        key.field.ops.push_back(std::move(op));
    }
    // Writers count Aqsis's plug-in leaves in nleaf or not (Aqsis reads both): without them, the
    // per-leaf values are the other leaves'.
    const size_t plugins = size_t(std::count_if(key.leaves.begin(), key.leaves.end(), [&](size_t at) {
        return std::find(pluginLeaves.begin(), pluginLeaves.end(), at) != pluginLeaves.end();
    }));
    if (key.leaves.size() != size_t(key.nleaf) && key.leaves.size() - plugins == size_t(key.nleaf))
        key.leaves.erase(std::remove_if(key.leaves.begin(), key.leaves.end(),
                                        [&](size_t at) {
                                            return std::find(pluginLeaves.begin(), pluginLeaves.end(), at) !=
                                                   pluginLeaves.end();
                                        }),
                         key.leaves.end());
    if (key.leaves.size() != size_t(key.nleaf))
        args.fail(*nleafValue, "nleaf is " + std::to_string(key.nleaf) + " but the code has " +
                                   plural(key.leaves.size(), "leaf") + " (opcodes 1000-1004 and 9000)");
    ParamList params = reader.readParams(args);
    ClassCounts counts{1, size_t(key.nleaf), size_t(key.nleaf), size_t(key.nleaf)};
    key.Cs = readColors(args, params, counts);
    ParamList constant;
    for (Param& p : params.params) {
        if (p.name == "P" || p.name == "Pw" || p.name == "Cs" || !perLeafVariable(p)) {
            constant.params.push_back(std::move(p));
            continue;
        }
        checkCount(args, p, size_t(key.nleaf));
        key.leafVars.push_back(std::move(p));
    }
    key.primvars = otherParams(args, constant, counts, reader.log());
    return key;
}

// Cells along the bound's longest side for a cell every kPixelsPerCell pixels of the bound's
// extent on screen, seen by the camera as set at WorldBegin (the first keys of the camera and of
// the object's transform) at the size the frames are rendered (ReadDetail). A bound that reaches
// behind the eye plane gets the most cells, one wholly behind it the fewest. A procedural's
// output has no camera: its extent in world units times the procedural's pixels per unit. An
// object's blobby is sized as if instanced where it is defined.
int screenCells(RibParser& reader, const PrimitiveDesc& d, const BlobbyField& field) {
    Vec3d lo, hi;
    if (!field.bound(&lo, &hi)) return kMinCells;
    const ReadDetail& detail = reader.readDetail();
    // In an object's definition, as if instanced where it is defined (ObjectBegin's transform).
    const RibState& st = reader.state();
    const Matrix4 toWorld = st.defining ? d.objectToWorld.keys().front() * st.defining->ctm.keys().front()
                                        : d.objectToWorld.keys().front();
    auto cellsFor = [](double pixels) {
        if (!std::isfinite(pixels)) return kMaxCells;
        return int(std::clamp(std::ceil(pixels / kPixelsPerCell), double(kMinCells), double(kMaxCells)));
    };
    if (detail.pixelsPerUnit > 0) {
        const Vec3d size = toWorld.box(Bounds3d(lo, hi)).diagonal();
        return cellsFor(std::max({size.x, size.y, size.z}) * detail.pixelsPerUnit);
    }
    const CameraDesc& cam = reader.camera();
    const double xres = detail.xres > 0 ? detail.xres : cam.xres * detail.formatScale;
    const double yres = detail.yres > 0 ? detail.yres : cam.yres * detail.formatScale;
    const bool perspective = cam.projection == ProjectionKind::Perspective;
    const double aspect = cam.frameAspect > 0 ? cam.frameAspect : cam.pixelAspect * xres / yres;
    double l = -1, r = 1, b = -1, t = 1;
    if (cam.hasScreenWindow) {
        l = cam.screenWindow[0], r = cam.screenWindow[1], b = cam.screenWindow[2], t = cam.screenWindow[3];
    } else if (aspect >= 1) {
        l = -aspect, r = aspect;
    } else {
        b = -1 / aspect, t = 1 / aspect;
    }
    const double s = perspective ? 1 / std::tan(cam.fov * 3.14159265358979323846 / 360) : 1;
    const double ax = s * xres / std::abs(r - l), ay = s * yres / std::abs(t - b);
    const Matrix4 toCamera = toWorld * cam.worldToCamera.keys().front();
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const Vec3d p = toCamera.point({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
        if (perspective && !(p.z > cam.nearClip)) {
            ++behind;
            continue;
        }
        const double x = perspective ? p.x / p.z : p.x, y = perspective ? p.y / p.z : p.y;
        x0 = std::min(x0, x * ax), x1 = std::max(x1, x * ax), y0 = std::min(y0, y * ay), y1 = std::max(y1, y * ay);
    }
    if (behind == 8) return kMinCells;
    if (behind > 0) return kMaxCells;
    return cellsFor(std::max(x1 - x0, y1 - y0));
}

// The polygon mesh of the first key, with the per-leaf values blended by each leaf's field. One
// whose repelling planes read depth maps is cut when its pass renders, where the reader asks for it
// (ReadDetail::deferRepellingMaps): a map an earlier pass of the input writes is there by then.
void addBlobby(RibParser& reader, BlobbyKey& key, const SourceLoc& loc, std::string signature) {
    PolygonMeshDesc d;
    placePrimitive(reader, d, {0.0}, loc);
    const RibState& st = reader.state();  // in an object's definition, as if instanced where it is defined
    const Matrix4 objectToWorld = st.defining ? d.objectToWorld.keys().front() * st.defining->ctm.keys().front()
                                              : d.objectToWorld.keys().front();
    const Param* given = reader.state().attributes->user.find("streyes:blobbyresolution");
    int cells = given ? int(reader.state().attributes->user.getFloat("streyes:blobbyresolution", 0))
                      : screenCells(reader, d, key.field);
    if (cells < 1 || cells > kMaxCells) {
        reader.log().warnOnce("blobby:resolution", loc,
                              "Attribute \"streyes\" \"blobbyresolution\" " + std::to_string(cells) +
                                  " is outside 1 to " + std::to_string(kMaxCells) + ": using " +
                                  std::to_string(cells < 1 ? 1 : kMaxCells));
        cells = cells < 1 ? 1 : kMaxCells;
    }
    Vec3d lo, hi;
    if (!key.field.bound(&lo, &hi)) {
        reader.log().warnOnce("blobby:empty", loc,
                              "Blobby: no ellipsoid, segment blob or field plug-in, so no surface to bound: "
                              "nothing is drawn");
        return;
    }
    d.request = "Blobby";
    d.patchesBefore = reader.scene().patches.size();
    const ReadDetail& detail = reader.readDetail();
    const bool mapped = std::any_of(key.planeMaps.begin(), key.planeMaps.end(),
                                    [&](const auto& m) { return key.field.ops[m.first].repel[0] > 0; });
    if (mapped && detail.deferRepellingMaps && detail.readDepthMap && !st.defining) {
        auto cut = std::make_shared<BlobbyDeferredCut>();
        cut->key = std::move(key);
        cut->cells = cells;
        cut->objectToWorld = objectToWorld;
        cut->loc = loc;
        cut->signature = std::move(signature);
        d.deferred = std::move(cut);
        reader.scene().polygonMeshes.push_back(std::move(d));
        return;
    }
    BlobbyMapLookup lookup;
    if (const BlobbyDepthReader& read = detail.readDepthMap)
        lookup = [&read](const std::string& name, std::string* error) {
            auto map = std::make_shared<BlobbyDepthImage>();
            return read(name, map.get(), error) ? std::shared_ptr<const BlobbyDepthImage>(std::move(map)) : nullptr;
        };
    readBlobbyGrounds(key, objectToWorld, loc, reader.log(), lookup);
    if (cutBlobby(key, cells, loc, reader.log(), d)) reader.scene().polygonMeshes.push_back(std::move(d));
}

// The request's arguments, exactly: two frames' equal requests are one primitive.
std::string requestSignature(const RibRequest& request) {
    std::string s;
    for (const RibValue& a : request.args) {
        s += std::to_string(int(a.kind)) + ":";
        for (double v : a.nums) s.append(reinterpret_cast<const char*>(&v), sizeof v);
        for (const std::string& t : a.strings) s += std::to_string(t.size()) + ":" + t;
        s += ";";
    }
    return s;
}

// A motion block's keys are all read (and checked), but the surface would change its triangles
// from key to key: the first key is drawn, with a warning when the others differ.
void blobbyKeys(RibParser& reader, const RibKeys& keys) {
    std::vector<BlobbyKey> read;
    for (const RibRequest& request : keys.requests) {
        RibArgs args(request, keys.usage);
        std::optional<BlobbyKey> key = readBlobbyKey(reader, args);
        if (!key) return;
        read.push_back(std::move(*key));
    }
    auto same = [](const RibRequest& a, const RibRequest& b) {
        if (a.args.size() != b.args.size()) return false;
        for (size_t i = 0; i < a.args.size(); ++i)
            if (a.args[i].kind != b.args[i].kind || a.args[i].nums != b.args[i].nums ||
                a.args[i].strings != b.args[i].strings)
                return false;
        return true;
    };
    for (size_t i = 1; i < keys.requests.size(); ++i)
        if (!same(keys.requests[i], keys.requests[0])) {
            reader.log().warnOnce("blobby:motion", keys.requests.front().loc,
                                  "Blobby: a motion block's keys differ, but a blobby's triangles cannot move: "
                                  "the first key is drawn at every time");
            break;
        }
    addBlobby(reader, read.front(), keys.requests.front().loc, requestSignature(keys.requests.front()));
}

}  // namespace

void addBlobbyRequests(RibRequestTable& table) {
    table.add("Blobby", {oneKey<blobbyKeys>, "Blobby nleaf [code] [floats] [strings] ...", RibPhase::World,
                         blobbyKeys});
}

}  // namespace streyes
