// Materials: what a body is shaded with. One per attribute state, made when bodies are made from
// the scene (BodyFactory); the shading stage evaluates them (shading.h).
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "geom/body.h"
#include "streyes/scene.h"

namespace streyes {

namespace sl {
class ShaderInstance;  // shade/vm: a compiled Shading Language shader and its parameter values
}
struct LayerNetwork;  // shade/layer_network.h: a layered shader's shaders and connections

enum class SurfaceKind { Constant, Matte, Plastic, Default };

// What a material's shading (surface, displacement, the lights it is lit by, atmosphere) reads of
// the view, i.e. of the camera's position and orientation: whether a point still in world space
// may be shaded once for all the frames of a block under a moving camera (issue 48).
// None: its values at a world-still point do not change when only the camera moves.
// FacingOnly: they change only through which side of the surface faces the eye
//   (faceforward(N, I), or the sign of N.I): shared while that side stays the same.
// Reads: otherwise (I, E or a camera-space value reaches a result; a light moving in world).
// Ordered: the larger is the more conservative (combine with std::max).
enum class ViewUse { None, FacingOnly, Reads };

// The shading rate a surface is diced at when it moves `blur` pixels in one exposure: its
// ShadingRate, raised for fast movers by GeometricApproximation "motionfactor" as RenderMan does,
// times max(1, motionfactor * blur / 16). Blurred detail cannot be seen, so it is not diced.
inline float motionDicingRate(float shadingRate, float motionFactor, double blur) {
    if (!(motionFactor > 0) || !(blur > 0)) return shadingRate;
    return shadingRate * float(std::max(1.0, double(motionFactor) * blur / 16.0));
}

// The shading rate a body is diced at: its lattice's (a curved body), else its ShadingRate (1
// without a material), raised for a fast mover by GeometricApproximation "motionfactor" from the
// pixels it moves in one exposure (`exposure`: the shutter's length in frames; the piece's
// motion `m.motion` is over its whole span). The split loop and the ray tracer's tessellation
// dice by it alike.
float dicingRate(const Body& body, const RasterMeasure& m, double exposure);

// A surface shader bound to its attribute state: what a body points at.
struct Material {
    SurfaceKind kind = SurfaceKind::Default;
    Color Cs{1, 1, 1};
    Color Os{1, 1, 1};
    float Ka = 1, Kd = 1, Ks = 0.5f, roughness = 0.1f;
    // The highlight is (N.H)^(specularExponent / roughness) (RenderSettings::specularExponent).
    float specularExponent = 8;
    Color specularColor{1, 1, 1};
    float shadingRate = 1;
    float motionFactor = 0;  // GeometricApproximation "motionfactor" (motionDicingRate)
    std::vector<int> lights;  // indices into the render's LightSet
    const Attributes* attributes = nullptr;
    // A Shading Language surface (shaders/*.sl or the user's), run over whole grids by the
    // shading stage. Null: the built-in `kind` above, which reproduces the shipped constant,
    // matte, plastic and defaultsurface under the standard lights, three times faster.
    std::shared_ptr<const sl::ShaderInstance> surface;
    // A layered surface (ShaderLayer): its layers, run in order over each grid; `surface` is the
    // last of them. Null: `surface` alone.
    std::shared_ptr<const LayerNetwork> layers;
    bool readsTime = false;  // a shader reads `time`: a still grid is shaded per exposure
    bool readsMaps = false;  // its surface or a light of it calls shadow(): per exposure where maps vary
    // Its surface, displacement, atmosphere or a light of it casts rays (occlusion(), trace(),
    // ...): what they see moves, so a still grid is shaded per exposure, at the exposure's time.
    bool tracesRays = false;
    // What its shading reads of the view (see ViewUse). Set conservatively: makeMaterial for the
    // built-in kinds, SceneShaders::bind for shaders and lights; Reads wherever unknown.
    ViewUse viewUse = ViewUse::Reads;
    // A Shading Language displacement shader, run on each diced grid before the surface, and how
    // far it may move a point in camera space: the split loop grows the body's bounds by it.
    std::shared_ptr<const sl::ShaderInstance> displacement;
    // A layered displacement (ShaderLayer "displacement"): its layers, run in order, each from the
    // P and N the one before left; `displacement` is the last of them. Null: `displacement` alone.
    std::shared_ptr<const LayerNetwork> displacementLayers;
    float displacementBound = 0;
    // A bound given in "object" space: its radius there (else 0). The shared material's
    // displacementBound takes the displacement shader's transform for the primitive's; the
    // factory gives a primitive whose transform stretches otherwise its own copy (withObjectSpace).
    float displacementBoundInObject = 0;
    // A volume shader (Atmosphere) run on the surface's colour after the surface shader.
    std::shared_ptr<const sl::ShaderInstance> atmosphere;
    // Volume shaders (Interior, Exterior) run over the segments of shaders' rays that end on this
    // surface from its inside or its outside (trace/shader_rays.h). Null: none.
    std::shared_ptr<const sl::ShaderInstance> interior, exterior;
    // Sides and Orientation. Bodies compute N = dPdu x dPdv in camera space; flipNormals turns
    // it to the side Orientation calls outside (the primitive's transform may mirror), and
    // oneSided (Sides 1) drops micropolygons whose outside faces away from the eye.
    bool flipNormals = false;
    bool oneSided = false;
    // Attribute "cull" "hidden" 0 / "backfacing" 0 (PRMan's, for baking passes): the surface's
    // grids are shaded even where the occlusion cull would drop them as hidden, or where Sides 1
    // turns every micropolygon away, so that what their shaders bake (bake3d()) covers the whole
    // surface. What is drawn does not change: hidden samples lose to nearer ones, and
    // back-facing micropolygons are still not drawn.
    bool shadeHidden = false;
    bool shadeBackFacing = false;
    // The leaf of a solid this surface bounds (Attributes::solid, geom/solid_tree.h), -1: none.
    // Such a surface is kept two-sided: its far side is where a line of sight leaves the solid.
    int solid = -1;
    // Matte 1 (Attributes::matte): a holdout, drawn as an opaque surface whose hits resolve to
    // colour 0 and alpha 0 (kMatteBit in raster/image_block.h), whatever it is shaded.
    bool matte = false;
    bool smoothShading = true;  // ShadingInterpolation "smooth"; false: "constant"
    // The primitive's own variables (a material of its own): bound to its shaders' parameters of
    // the same name; constant ones, or four corner values interpolated over a bilinear patch (the
    // grid's u, v). "s", "t" and "st" replace the shaders' s and t.
    ParamList primvars;
    // The values of those that are not constant at the four corners of the face (u, v) in
    // {0, 1}^2, RenderMan order: each such variable in turn, four corners of its floats. A
    // polygon mesh's faces carry their own (Body::primvarCorners).
    std::vector<float> primvarCorners;
    // A bicubic patch mesh's: its vertex-class variables follow the patch basis as P does, so a
    // face's block holds their 16 Bezier control values (row by row, u fastest) rather than four
    // corners, evaluated at each vertex's (u, v).
    bool primvarBezier = false;
    // The primitive's object-to-world transform (the CTM where it was given): its shaders'
    // "object" space, and the space its point, vector and normal primitive variables are given
    // in. Set (objectSpaceKnown) on a material of its own: one with primitive variables, or one
    // whose shaders may name "object" space (readsObjectSpace); otherwise the shaders' "object"
    // space cannot be told from their "shader" space and is taken as that.
    MotionTransform objectToWorld;
    bool objectSpaceKnown = false;
    // Its surface (or a layer), displacement or atmosphere names "object" space (a string
    // constant or parameter value "object"): the factory gives each primitive its own copy
    // with objectToWorld. Set by MaterialBinder::bind.
    bool readsObjectSpace = false;
    // A level of detail's dissolve: only the share [dissolveLo, dissolveHi) of a frame's samples
    // sees this surface (bodies/level_of_detail.h). [0, 1): every sample.
    float dissolveLo = 0, dissolveHi = 1;
};

// Binds a material's Shading Language shaders (made by the shading stage, which the bodies
// stage cannot see: BodyFactory calls it for every material it makes).
class MaterialBinder {
  public:
    virtual ~MaterialBinder() = default;
    virtual void bind(Material& material, const Attributes& attributes) const = 0;
};

// How a primitive's transform and kind bear on its sides: whether its object-to-camera transform
// mirrors (so N = dPdu x dPdv computed in camera space points the other way than in object space),
// or whether it always faces the camera (Points, camera-facing Curves: Sides and Orientation do
// not apply).
enum class Facing { Object, Mirrored, Camera };

// Builds a Material from an attribute state; unknown shader names have been handled by the
// parser (they fall back to defaultsurface).
Material makeMaterial(const Attributes& attributes, Facing facing = Facing::Object);
// Matte 1 (kept as the attribute "streyes:matte", rib_attributes.cpp): a holdout.
bool isMatte(const Attributes& attributes);

}  // namespace streyes
