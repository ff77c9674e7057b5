// The scene description: what the RIB parser produces and the renderer consumes.
//
// It is a plain description in object/world space, close to the RIB it came from. Turning it
// into camera-space spacetime bodies is the next stage (src/bodies/); nothing here knows about
// buckets, frames blocks or rasters. Times are in frames throughout.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "streyes/error.h"
#include "streyes/quantize.h"
#include "streyes/transform.h"
#include "streyes/vecmath.h"

namespace streyes {

// ---- Parameter lists ------------------------------------------------------------------------
// A RIB parameter with its declared type, e.g. "uniform color Cs" [1 0 0].
enum class ParamType { Float, Integer, String, Point, Vector, Normal, Color, HPoint, Matrix };
enum class ParamClass { Constant, Uniform, Varying, Vertex, FaceVarying };

struct Param {
    std::string name;
    ParamType type = ParamType::Float;
    ParamClass cls = ParamClass::Uniform;
    int arraySize = 1;                  // "float[2]" -> 2
    std::vector<double> nums;           // every numeric value, flattened
    std::vector<std::string> strings;   // for String parameters
    SourceLoc loc;
    // False for a shader parameter given without a declaration: the shader's own declaration
    // gives its type (type is Float or String here, from the value).
    bool declared = true;

    int componentsPerItem() const;      // 3 for point/color..., 4 for hpoint, 16 matrix, times arraySize
};

struct ParamList {
    std::vector<Param> params;
    const Param* find(const std::string& name) const;
    // Convenience readers; return `fallback` when absent. Throw InputError on a type/size mismatch.
    double getFloat(const std::string& name, double fallback) const;
    Color getColor(const std::string& name, Color fallback) const;
    Vec3d getPoint(const std::string& name, Vec3d fallback) const;
    std::string getString(const std::string& name, const std::string& fallback) const;
};

// ---- Graphics state -------------------------------------------------------------------------
struct ShaderDesc {
    std::string name;   // "constant", "matte", "plastic", "defaultsurface", or a shader's file name
    ParamList params;
    SourceLoc loc;
    MotionTransform shaderToWorld;  // the CTM where it was declared: the shader's "shader" space
};

// A RenderMan basis (Basis request): P(u) = [u^3 u^2 u 1] * m * [P0 P1 P2 P3]^T, and `step`, the
// control points from one patch of a PatchMesh to the next. The default is Bezier, step 3.
struct BasisDesc {
    std::array<double, 16> m{-1, 3, -3, 1, 3, -6, 3, 0, -3, 3, 0, 0, 1, 0, 0, 0};  // row-major
    int step = 3;
};
// The named bases: "bezier", "b-spline", "catmull-rom", "hermite", "power". False for other names.
bool basisFromName(const std::string& name, BasisDesc* out);

// TrimCurve: loops of rational B-spline curves in the (u, v) parameter space of the NuPatches that
// follow it (attribute state). Each curve's points are homogeneous (u, v, w), knots as a NuPatch's.
struct TrimCurveDesc {
    int order = 2;
    std::vector<double> knot;  // n + order
    double tmin = 0, tmax = 1;
    std::vector<double> u, v, w;  // n each
};
struct TrimLoops {
    std::vector<std::vector<TrimCurveDesc>> loops;  // each loop's curves, head to tail
    SourceLoc loc;
};

// Detail and DetailRange (RI Spec 3.2, 4.2.4): the primitives declared under a DetailRange are one
// representation of a model. A frame draws it where the raster area of the Detail box (the area of
// the screen rectangle around its corners, times RelativeDetail), seen from that frame's camera,
// lies in [lowertransition, uppertransition], and not outside [minvisible, maxvisible]; in between
// the representations of neighbouring ranges dissolve into each other, sample by sample.
struct LevelOfDetail {
    Bounds3d bound;                // Detail's box, in the space where it was given
    MotionTransform boundToWorld;  // the transform in force at Detail
    bool hasBound = false;         // no Detail before the DetailRange: the area is infinite
    std::array<double, 4> range{0, 0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    SourceLoc loc;                 // the DetailRange
};

// ShaderLayer / ConnectShaderLayers (RI 3.x shader networks, as PRMan 16 and Aqsis read them): a
// surface, displacement or imager made of layers, each a shader instance with its own parameters,
// run in order over the grid (the image, for an imager). After a layer runs, its connections set
// a later layer's parameter (or a predefined variable such as Cs, which every later layer then
// sees) to the value one of its parameters (or a predefined variable) has then. Each layer starts
// from what the one before left: Ci and Oi (surface), P and N (displacement), Ci, Oi and alpha
// (imager); the last layer's are the result.
struct ShaderConnection {
    int from = 0, to = 0;    // indices into ShaderNetwork::layers, from < to
    std::string fromVar, toVar;
    SourceLoc loc;           // the ConnectShaderLayers request
};
struct ShaderNetwork {
    std::vector<ShaderDesc> layers;
    std::vector<std::string> names;  // each layer's name, as ShaderLayer gave it
    std::vector<ShaderConnection> connections;
};

// The attribute state a primitive was declared with. Shared: many primitives point at one.
struct Attributes {
    Color color{1, 1, 1};                        // Color (Cs)
    Color opacity{1, 1, 1};                      // Opacity (Os)
    ShaderDesc surface{"defaultsurface", {}, {}, {}};
    // ShaderLayer "surface": the layers (surface is then the last one's description); empty after
    // a Surface request.
    ShaderNetwork surfaceLayers;
    ShaderDesc displacement;                     // Displacement; no name: none
    // ShaderLayer "displacement": its layers (displacement is then the last one's); empty after a
    // Displacement request.
    ShaderNetwork displacementLayers;
    ShaderDesc atmosphere;                       // Atmosphere (a volume shader); no name: none
    // Interior and Exterior: volume shaders run over the segments of rays (trace(), transmission()
    // and the others) inside and outside the surface. No name: none.
    ShaderDesc interior, exterior;
    // Attribute "displacementbound" "sphere" r: how far displacement may move a point, in the
    // "coordinatesystem" named there: "object" (the primitive's CTM), "shader" / "surface" (the
    // displacement / surface shader's), "world", "camera" or "current" (camera), an image space
    // (scene/bound_spaces.h), or a name CoordinateSystem gave, whose transform the reader keeps in
    // displacementBoundToWorld (also for PRMan's "null": the CTM at the Attribute request).
    double displacementBound = 0;
    std::string displacementBoundSpace = "object";
    MotionTransform displacementBoundToWorld;
    double shadingRate = 1.0;                    // pixels of area per micropolygon
    // GeometricApproximation "motionfactor": a moving surface is diced at a shading rate raised by
    // max(1, motionFactor * blur / 16), blur the pixels it moves in one exposure. 0: off.
    double motionFactor = 0;
    std::vector<int> lights;                     // indices into Scene::lights that are on
    // Every Attribute value given, as "category:name" ("identifier:name", "user:weight",
    // "visibility:camera"): what the features that read them and the Shading Language's
    // attribute() find. Names nobody declared keep the type of their value (Param::declared false).
    ParamList user;
    BasisDesc uBasis, vBasis;                    // Basis, for bicubic patches
    std::shared_ptr<const TrimLoops> trim;       // TrimCurve (none when empty), for NuPatches
    // Sides 1: only the outside is drawn (micropolygons facing away from the eye are not).
    bool twoSided = true;
    // Orientation: which side is the outside, relative to the current coordinate system's
    // handedness ("outside", "inside") or absolute ("lh", "rh"); ReverseOrientation flips it.
    enum class Orientation { Outside, Inside, LeftHanded, RightHanded };
    Orientation orientation = Orientation::Outside;
    // ShadingInterpolation "constant": a micropolygon takes the colour of its first vertex
    // ("smooth", the default here: colours interpolated across it).
    bool smoothShading = true;
    // AreaLightSource in force (an index into Scene::lights): the geometry declared now also
    // makes up that light's shape. -1: none.
    int areaLight = -1;
    // Under a DetailRange: the representation of a model it belongs to. None: always drawn.
    std::shared_ptr<const LevelOfDetail> detail;
    // Inside SolidBegin "primitive": the node of Scene::solids whose boundary this geometry is (a
    // leaf of a solid's tree). -1: not part of a solid.
    int solid = -1;
};
using AttributesPtr = std::shared_ptr<const Attributes>;

// ---- Camera and options -------------------------------------------------------------------------
enum class ProjectionKind { Orthographic, Perspective };

struct CameraDesc {
    ProjectionKind projection = ProjectionKind::Orthographic;  // RenderMan's default
    double fov = 90.0;                    // degrees, across the shorter image dimension
    bool hasScreenWindow = false;
    double screenWindow[4] = {-1, 1, -1, 1};  // left right bottom top
    double frameAspect = 0;               // 0: from the resolution
    int xres = 640, yres = 480;
    double pixelAspect = 1.0;
    double nearClip = 1e-4, farClip = 1e30;  // Clipping; see docs/SCENE-FORMAT.md for the default
    MotionTransform worldToCamera;        // the CTM at WorldBegin
    SourceLoc loc;
    // DepthOfField fstop focallength focaldistance (camera-space units): a thin lens of radius
    // focallength / (2 fstop) focused at z = focaldistance. fstop infinity: a pinhole (the default).
    double fstop = std::numeric_limits<double>::infinity(), focalLength = 0, focalDistance = 0;
    SourceLoc depthOfFieldLoc;
    bool depthOfField() const { return fstop < std::numeric_limits<double>::infinity(); }
};

// Whether two cameras project alike: the same field of view, screen window and frame aspect ratio
// (what a zoom changes; the projection's kind, resolution and clipping are compared elsewhere).
inline bool sameZoom(const CameraDesc& a, const CameraDesc& b) {
    return a.fov == b.fov && a.hasScreenWindow == b.hasScreenWindow && a.frameAspect == b.frameAspect &&
           std::equal(a.screenWindow, a.screenWindow + 4, b.screenWindow);
}

struct FilterDesc {
    std::string type = "gaussian";  // box | triangle | gaussian | catmull-rom | sinc | mitchell | disk
    double xwidth = 2, ywidth = 2;
};

struct DisplayDesc {
    std::string name;   // may hold #### for the frame number
    std::string type;   // "openexr", "file", "tiff", "framebuffer", ...
    std::string mode;   // "rgb", "rgba", "rgbaz"
    SourceLoc loc;
    // The display's own "quantize" [zero one min max] and "dither" [amplitude] parameters, which
    // override the Quantize request's (empty: not given).
    std::vector<double> quantizeParam, ditherParam;
    // A depth display's "append" (Aqsis's "float append" [1]): the frame's map is added to the maps
    // its file holds so far in the input (a multi-map file, read by occlusion() as an occlusion map).
    bool append = false;
    // How an 8- or 16-bit file of this display is quantized: set at WorldBegin from the Quantize
    // request of its mode (or "rgba", or "z" for a depth display) and its own parameters.
    Quantize quantize = kColorQuantize;
};

// MakeTexture "in" "out" swrap twrap filter swidth twidth, MakeLatLongEnvironment "in" "out"
// filter swidth twidth, or MakeCubeFaceEnvironment "px" "nx" "py" "ny" "pz" "nz" "out" fov filter
// swidth twidth: a tiled, MIP-mapped map made from images before the render (streyes/textures.h;
// the scene layer only records it). Relative names are the RIB file's folder's.
struct MakeTextureDesc {
    bool latLongEnvironment = false;
    std::string input, output;
    // MakeCubeFaceEnvironment: the six face pictures, the views along +x, -x, +y, -y, +z, -z (input
    // is the first), and the field of view they were rendered with, in degrees (0 < fov < 180).
    // The map made is a lat-long environment map (docs/SCENE-FORMAT.md, Textures).
    std::vector<std::string> cubeFaces;
    double cubeFov = 90;
    std::string swrap = "black", twrap = "black";  // "black", "clamp" or "periodic"
    std::string filter = "box";                    // resampling filter of the MIP levels
    double swidth = 1, twidth = 1;
    SourceLoc loc;
    // Where it comes among the input's frames: its place among the make requests of its file, and
    // whether it came after the world of the frame it is in (then it runs after that frame's
    // render, else before it). A file of frames hands these over in order (streyes/passes.h).
    int serial = 0;
    bool afterWorld = false;
};

// MakeShadow "picture" "shadow map": a depth map (what a Display "zfile" wrote) made a shadow map,
// a float TIFF holding the depths unfiltered (no MIP levels) with the light camera's matrices
// (docs/SCENE-FORMAT.md). The picture may be written by a frame of the same input: it is made when
// that frame is done. Names are as written (relative to the working folder, as Display names are;
// an input not made by the render is looked for beside the RIB file too).
struct MakeShadowDesc {
    std::string input, output;
    SourceLoc loc;
    int serial = 0;  // as MakeTextureDesc's
    bool afterWorld = false;
};

struct RenderSettings {
    double shutterOpen = 0, shutterClose = 0;  // frame f is exposed during [f+open, f+close]
    int pixelSamplesX = 2, pixelSamplesY = 2;
    FilterDesc filter;
    bool hasFrames = false;                    // Option "streyes" "int frames" [first last]
    int firstFrame = 0, lastFrame = 0;
    // A sequence block (streyes/sequence.h): its still runs live over frames the block does not
    // render (their runs in the input, within their epochs): the shot the renderer builds over.
    bool hasShot = false;
    int shotFirst = 0, shotLast = 0;
    std::vector<DisplayDesc> displays;
    // Option "searchpath" "shader": folders separated by ':' ('&' the path before, '@' the
    // standard shaders); empty: the RIB file's folder, then the standard shaders.
    std::string shaderSearchPath;
    SourceLoc shaderSearchPathLoc;
    // Option "shading" "string builtin" ["off"]: shade constant, matte, plastic and
    // defaultsurface with their Shading Language sources too (the same pixels, slower).
    bool builtinShading = true;
    // Option "shading" "string specular": specular() and specularbrdf() raise N.H to the power
    // specularExponent / roughness: 8 is PRMan's highlight ("prman", the default: what RenderMan
    // users' scenes were lit for), 1 the RI Spec 3.2's formula ("rispec").
    double specularExponent = 8;
    ShaderDesc imager;  // Imager: run over each finished frame's pixels; no name: none
    // ShaderLayer "imager": its layers (imager is then the last one's); empty after an Imager.
    ShaderNetwork imagerLayers;
    // Quantize "type" one min max ditheramplitude, by type ("rgba", "z", or a display mode such as
    // "Cs"); a type not given takes RenderMan's default (kColorQuantize, kDepthQuantize for "z").
    std::map<std::string, Quantize> quantize;
    // The Quantize of display mode `mode`: its own type's, else "z"'s for "z" or "rgba"'s, else
    // RenderMan's default (rib_options.cpp).
    Quantize quantizeOf(const std::string& mode) const;
    double exposureGain = 1, exposureGamma = 1;  // Exposure: rgb = (gain * rgb)^(1 / gamma)
    // Hider "hidden": "jitter" 0 puts samples at the centres of their strata (and times at the
    // centres of theirs); "depthfilter" makes Z the "min" (default), "max" or "average" depth of a
    // pixel's own samples that hit.
    bool jitter = true;
    std::string depthFilter = "min";
    // Option "limits": "bucketsize" [w h] (buckets are square: the larger) and "gridsize"; 0: the
    // command line's or streyes's default.
    int bucketSize = 0, gridSize = 0;
    // DisplayChannel declarations of surface shaders' output parameters (the built-in variables,
    // N, P, ..., need none): a Display mode may name them.
    struct ShaderOutput {
        std::string type, name;
        SourceLoc loc;
    };
    std::vector<ShaderOutput> shaderOutputs;
    // Option "searchpath" "texture": the folders texture() and environment() look in for maps
    // named without one, '&' and '@' (the folder of the RIB file giving the option) resolved;
    // empty: the folder of the scene's file.
    std::vector<std::string> textureSearchPath;
    std::vector<MakeTextureDesc> makeTextures;  // in the order the requests came
    std::vector<MakeShadowDesc> makeShadows;    // likewise (serial orders the two kinds)
    // Option "shadow" "bias": camera-space units a point must lie behind a shadow map's depth to
    // be in shadow, where a shadow() call gives none (beyond what the map's own sampling needs:
    // shade/shadow_map.h).
    double shadowBias = 0;
    // Every Option value given (but "searchpath"), as "category:name" ("user:pass", "limits:eyesplits",
    // "shadow:bias"): what the Shading Language's option() and later passes read. Names nobody
    // declared keep the type of their value (a float or a string, Param::declared false).
    ParamList options;
    // RelativeDetail: scales every Detail's raster area before DetailRange compares it.
    double relativeDetail = 1;
};

// ---- Lights and geometry --------------------------------------------------------------------------
// The time a primitive exists in, frames: a frame sequence (streyes/sequence.h) gives each
// primitive the exposures of the frames it is in; a single scene's primitives exist always. The
// end is open, [t0, t1), where the next frame's exposure begins at t1 (Shutter 0 1): a sample at
// that instant is the next frame's.
struct Lifetime {
    double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
    bool openEnd = false;
    bool always() const { return t0 == -std::numeric_limits<double>::infinity() && t1 == std::numeric_limits<double>::infinity(); }
};

struct LightDesc {
    std::string type;            // "ambientlight" | "distantlight" | "pointlight"
    ParamList params;
    MotionTransform lightToWorld;
    SourceLoc loc;
    bool castsShadows = false;   // Attribute "light" "shadows" "on" where it was declared
    // Attribute "autoshadows" "string shadowmapname" [name] "integer res" [n] (Aqsis): a depth map
    // of this name is rendered from the light before the frame (streyes/passes.h). Empty: none.
    std::string autoShadowMap;
    int autoShadowRes = 300;
    SourceLoc autoShadowLoc;
    // AreaLightSource: the light is spread over the geometry declared after it in its attribute
    // block, kept here as world-space bilinear patches (corners in RenderMan order); its shader
    // runs at points on them (geom/lights.h). areaToWorld takes the patches to the scene's world:
    // the identity, but in a frame sequence, whose world is camera space, the frame's camera.
    bool area = false;
    std::vector<std::array<Vec3d, 4>> areaPatches;
    MotionTransform areaToWorld;
};

// A bilinear patch (Patch "bilinear"; the bodies stage makes one of a Polygon of 3 or 4 vertices
// too), possibly with motion keys. Corners in RenderMan order: P[0]=(u0,v0) P[1]=(u1,v0)
// P[2]=(u0,v1) P[3]=(u1,v1).
struct BilinearPatchDesc {
    std::vector<double> times;                 // motion keys; one entry (any value) when static
    std::vector<std::array<Vec3d, 4>> P;       // object space, one set per key
    bool hasCs = false;                        // varying/uniform Cs given on the primitive
    std::array<Color, 4> Cs{};
    MotionTransform objectToWorld;
    AttributesPtr attributes;
    SourceLoc loc;
    Lifetime life;
    // Primitive variables bound to shader parameters of the same name: constant ones (one value),
    // and varying, vertex or facevarying ones (four values, one a corner in corner order,
    // interpolated bilinearly over the patch; "s", "t" and "st" give the shaders' s and t).
    ParamList primvars;
};

// A procedural primitive as declared: Procedural "DelayedReadArchive" | "RunProgram" |
// "DynamicLoad" with its arguments and a bound in object space. The description is data: the
// procedural stage makes the generator behind it when bodies are made from the scene.
struct Scene;
struct ProceduralDesc {
    std::string kind;               // "DelayedReadArchive", "RunProgram", "DynamicLoad" or "ObjectInstance"
    std::vector<std::string> args;  // the request's string arguments
    std::string directory;          // folder of the declaring file: relative names are looked up there first
    // Option "searchpath" "procedural" and "archive" where it was declared: ':'-separated folders,
    // "@" standing for `directory` (DynamicLoad plug-ins and archives named without a folder).
    std::string proceduralPath = "@", archivePath = "@";
    Bounds3d bound;                 // object space, as declared
    MotionTransform objectToWorld;
    AttributesPtr attributes;
    SourceLoc loc;
    Lifetime life;                  // its children's too
    // ObjectInstance: the object's primitives in its own space, shared by all its instances
    // (args holds the handle; the bound is the object's).
    std::shared_ptr<const Scene> object;
    // ... and where attributes were set inside the object's definition, each attribute state its
    // primitives hold with what they take in this instance: those in force at ObjectInstance with
    // the object's own settings over them. A state not listed takes `attributes`.
    std::vector<std::pair<AttributesPtr, AttributesPtr>> objectAttributes;
};

// ---- Curved and polygonal primitives ----------------------------------------------------------
// What every primitive below has: motion keys (one entry, any value, when static), its
// object-to-world transform, attributes and the place it was declared. Positions are given per key.
struct PrimitiveDesc {
    std::vector<double> times;
    MotionTransform objectToWorld;
    AttributesPtr attributes;
    SourceLoc loc;
    Lifetime life;
    // The primitive's own variables a shader binds by name (float, color or string; one value for
    // the whole primitive: constant, or uniform where it has one face). Cs is apart, above.
    ParamList primvars;
};

// A colour primitive variable ("Cs") as given: its storage class and values. Empty when the
// primitive gives none (the attribute Color applies). Uniform values are one per face; varying
// ones one per corner of the primitive's varying grid (see each primitive); vertex ones one per
// control point.
struct ColorPrimvar {
    ParamClass cls = ParamClass::Constant;
    std::vector<Color> values;
    bool given() const { return !values.empty(); }
};

// Patch "bicubic" (a 4x4 mesh) and PatchMesh "bicubic" | "bilinear". Control points row by row,
// u fastest: P[key][j * nu + i]. Bicubic patches use the Basis in force at the request.
struct PatchMeshDesc : PrimitiveDesc {
    bool bicubic = true;
    int nu = 4, nv = 4;                       // control points along u and v
    bool uPeriodic = false, vPeriodic = false;
    BasisDesc uBasis, vBasis;
    std::vector<std::vector<Vec3d>> P;        // object space, one set per key
    ColorPrimvar Cs;                          // varying: one per corner of the patch grid

    int uPatches() const;                     // patches along u (RenderMan's nupatches)
    int vPatches() const;
    int uVarying() const { return uPatches() + (uPeriodic ? 0 : 1); }
    int vVarying() const { return vPatches() + (vPeriodic ? 0 : 1); }
};

// SubdivisionMesh "catmull-clark": faces as vertex-index loops, RenderMan's tags.
struct SubdivisionMeshDesc : PrimitiveDesc {
    std::vector<int> faceSizes, faceVertices;
    int vertexCount = 0;                      // largest index + 1
    std::vector<int> creaseEdges;             // vertex pairs of sharp edges ("crease" chains, split)
    std::vector<float> creaseSharpness;       // one per pair
    std::vector<int> corners;                 // "corner" vertices
    std::vector<float> cornerSharpness;
    std::vector<int> holes;                   // "hole" faces
    int interpolateBoundary = 0;              // 0 none, 1 edges and corners, 2 edges only
    std::vector<std::vector<Vec3d>> P;        // vertexCount points per key
    ColorPrimvar Cs;                          // varying/vertex: per vertex; uniform: per face
};

// Sphere, Cylinder, Cone, Disk, Paraboloid, Hyperboloid, Torus: the request's arguments per key,
// in the order RenderMan gives them (angles in degrees).
enum class QuadricKind { Sphere, Cylinder, Cone, Disk, Paraboloid, Hyperboloid, Torus };
struct QuadricDesc : PrimitiveDesc {
    QuadricKind kind = QuadricKind::Sphere;
    std::vector<std::array<double, 7>> params;  // per key
    ColorPrimvar Cs;                            // varying: the 4 corners of the (u, v) domain
};

// NuPatch: a non-uniform rational B-spline surface of any order. Control points row by row, u
// fastest: P[key][j * nu + i], the points divided by their weights ("Pw"); the weights (1 for "P")
// are the same at every key. Knots hold nu + uorder (nv + vorder) values; the surface is the part
// over [umin, umax] x [vmin, vmax]. `trim` is the TrimCurve in force when it was declared.
struct NuPatchDesc : PrimitiveDesc {
    int nu = 0, uorder = 0, nv = 0, vorder = 0;
    std::vector<double> uknot, vknot;
    double umin = 0, umax = 1, vmin = 0, vmax = 1;
    std::vector<std::vector<Vec3d>> P;        // object space, one set per key
    std::vector<double> w;                    // nu * nv weights, all positive
    ColorPrimvar Cs;                          // uniform/constant: one; varying: the corners of the spans
    std::shared_ptr<const TrimLoops> trim;

    int uSpans() const { return nu - uorder + 1; }  // RenderMan's segments: varying counts are spans + 1
    int vSpans() const { return nv - vorder + 1; }
};

// Polygon, GeneralPolygon, PointsPolygons and PointsGeneralPolygons as written: each polygon its
// loops of indices into the points, the outline first, then any holes. The bodies stage makes
// them bilinear patches: a Polygon of 3 or 4 vertices as one (unless it is concave), any other
// cut into triangles and convex quads.
struct BlobbyDeferredCut;  // scene/blobby_cut.h

struct PolygonMeshDesc : PrimitiveDesc {
    std::string request;                                  // "Polygon", "GeneralPolygon", ...
    std::vector<std::vector<Vec3d>> P;                    // object space, one set per key
    std::vector<std::vector<std::vector<int>>> polygons;  // per polygon, its loops
    ColorPrimvar Cs;  // uniform: per polygon; varying, vertex: per point; facevarying: per loop vertex
    // How many bilinear patches (Scene::patches) were read before it: a Polygon made one patch
    // takes its primitive id among them there, as ids decide exact depth ties.
    size_t patchesBefore = 0;
    // A Blobby cut when its pass renders (its repelling planes' depth maps are read then): no
    // polygons until cutDeferredBlobbies (scene/blobby_cut.h) replaces it with its meshes.
    std::shared_ptr<const BlobbyDeferredCut> deferred;
};

// Curves "linear" | "cubic" [nvertices] "nonperiodic" | "periodic": flat ribbons along each curve
// (the v Basis and its step for cubic curves). Varying values are one per segment end of each
// curve (periodic curves: one per segment); vertex values one per control point.
struct CurvesDesc : PrimitiveDesc {
    bool cubic = false;
    bool periodic = false;
    BasisDesc basis;                          // the v basis in force at the request
    std::vector<int> nvertices;               // control points per curve
    std::vector<std::vector<Vec3d>> P;        // object space, one set per key
    ParamClass widthClass = ParamClass::Constant;
    std::vector<double> width{1.0};           // "constantwidth" (one), or "width" by its class
    ParamClass normalClass = ParamClass::Varying;
    std::vector<Vec3d> N;                     // empty: camera-facing ribbons; else their normals
    ColorPrimvar Cs;                          // uniform: per curve; varying, vertex as above

    int segments(size_t curve) const;         // segments of one curve
    int varying(size_t curve) const { return segments(curve) + (periodic ? 0 : 1); }
};

// Points: camera-facing discs of diameter "width" (one per point) or "constantwidth".
struct PointsDesc : PrimitiveDesc {
    std::vector<std::vector<Vec3d>> P;        // object space, one set per key
    std::vector<double> width{1.0};           // one per point, or one for all
    ColorPrimvar Cs;                          // varying, vertex: per point
};

// ---- Solids (SolidBegin ... SolidEnd) ---------------------------------------------------------------
// A node of a solid's tree: a "primitive" solid is a leaf (the geometry declared in it bounds it);
// the others combine their children, in order ("difference" subtracts the second and later ones
// from the first).
enum class SolidOp { Primitive, Union, Intersection, Difference };
struct SolidNode {
    SolidOp op = SolidOp::Primitive;
    int parent = -1;            // index in Scene::solids; -1: the root of a tree
    std::vector<int> children;  // indices in Scene::solids, in the order declared
    SourceLoc loc;              // the SolidBegin
};

struct Scene {
    CameraDesc camera;
    RenderSettings settings;
    std::vector<LightDesc> lights;
    std::vector<BilinearPatchDesc> patches;
    std::vector<ProceduralDesc> procedurals;
    std::vector<PatchMeshDesc> patchMeshes;
    std::vector<SubdivisionMeshDesc> subdivisionMeshes;
    std::vector<QuadricDesc> quadrics;
    std::vector<PolygonMeshDesc> polygonMeshes;
    std::vector<CurvesDesc> curves;
    std::vector<PointsDesc> points;
    std::vector<NuPatchDesc> nuPatches;
    std::vector<SolidNode> solids;  // every solid's tree; Attributes::solid points at its leaves
    std::string sourceName;  // the scene file, for messages and default output names
    int frameNumber = 0;     // FrameBegin n, when the scene was one frame of a sequence
    SourceLoc frameLoc;      // where that FrameBegin (or the frame's file) is
    // A merged frame sequence (streyes/sequence.h): each frame's own world-to-camera transform
    // (camera space is each frame's own; the merged camera is the identity). Shaders' "world"
    // space and shadow maps' lookups take the frame's. Empty: camera.worldToCamera for every frame.
    std::map<int, MotionTransform> frameWorldToCamera;
    // A merged frame sequence under a zoom: the camera (its projection) of each frame whose
    // field of view, screen window or frame aspect ratio differs from `camera`'s. Empty: none.
    std::map<int, CameraDesc> frameCamera;
};

// Every primitive of the scene (a procedural's output) exists only during `life`.
void setLifetime(Scene& scene, const Lifetime& life);

}  // namespace streyes
