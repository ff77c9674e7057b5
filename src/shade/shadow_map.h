// Depth maps and the Shading Language's shadow() on them: percentage-closer filtering (Reeves,
// Salesin and Cook, "Rendering Antialiased Shadows with Depth Maps", 1987).
//
// A depth map is what a depth pass writes (Display "zfile" | "shadow" "z") and MakeShadow turns
// into a shadow map: each pixel the depth, in the light camera's space, of what that camera saw
// there, with the camera (world -> its camera space) and its projection (world -> screen, the
// screen window at [-1, 1] in x and y: RenderMan's "worldtoscreen", as Pixar's and Aqsis's TIFF
// shadow maps carry it). Depths are never averaged between pixels (no MIP levels).
//
// shadow(map, P) is the fraction of the filter's footprint around P (in the map's pixels) whose
// depth lies in front of P: each texel the box reaches counts by the area it covers, and is in
// front when its depth is below the receiver's depth there minus the bias. The receiver's depth
// at each texel is where that texel's ray meets P's tangent plane (from the grid's derivatives
// of P), so that a plane never shadows itself whatever its slope, and the bias only covers what a
// texel's own samples may differ by (half a texel of the receiver's depth slope) and rounding.
// The footprint: the micropolygon's extent along u and v (times "swidth", "twidth"), plus "blur"
// (a fraction of the map's width and height), at least one texel. Up to kExactTexels texels are
// weighed exactly; a larger footprint takes "samples" jittered taps (stratified; the jitter a
// hash of the point, so the same point gives the same answer).
#pragma once

#include <cfloat>
#include <memory>
#include <string>
#include <vector>

#include "streyes/transform.h"

namespace streyes {

namespace sl {
struct DirectionQuery;
}

struct DepthMap {
    static constexpr float kNoDepth = FLT_MAX;  // a pixel that saw nothing: never in front
    int width = 0, height = 0;
    std::vector<float> z;   // width x height, row-major from the top-left pixel
    Matrix4 worldToCamera;  // the light camera (row vectors, p * M, as RenderMan)
    Matrix4 worldToScreen;  // world -> screen: x and y in [-1, 1] across the image, y up (homogeneous)
    // A multi-map file (Display "append", an occlusion map: shade/occlusion_maps.h): the file as it
    // was before this map was added (null: this is its first), so that the file's maps are this
    // chain, the first map at its end. shadow() reads this one, the file's last.
    std::shared_ptr<const DepthMap> previous;
    bool sameAs(const DepthMap& o) const;  // every pixel and matrix the same bits (previous maps too)
};

// The camera of a depth pass frame: world -> camera and camera -> screen (the projection, the
// screen window mapped to [-1, 1]), from the frame's camera description at time t.
Matrix4 screenProjection(bool perspective, double ax, double bx, double ay, double by, int width, int height);

// A shadow() call's options (sl::TextureOptions' shadow part, resolved).
struct ShadowFilter {
    float sblur = 0, tblur = 0;    // fractions of the map's width and height
    float swidth = 1, twidth = 1;  // scale the micropolygon's footprint
    float bias = 0;                // camera-space units the receiver must lie behind the map's depth
    int samples = 16;              // taps of a footprint larger than kExactTexels texels
};
constexpr int kExactTexels = 256;

// How a map is read from a point in some "current" space: the map's matrices composed once.
class ShadowLookup {
  public:
    // False (with *error) when the matrices do not make a projection (singular).
    bool set(const DepthMap& map, const Matrix4& currentToWorld, std::string* error);
    // The fraction of light blocked at point p (current space) with its changes along u and v
    // (zero: a point with no footprint, which then takes one texel and no tangent plane).
    float occlusion(const Vec3d& p, const Vec3d& dpdu, const Vec3d& dpdv, const ShadowFilter& f) const;
    // Every active point of a query (R, dRdu, dRdv) into out[i].
    void lookup(const sl::DirectionQuery& q, const ShadowFilter& f, float* out) const;

  private:
    const DepthMap* map_ = nullptr;
    Matrix4 toCamera_;  // current -> the map's camera
    Matrix4 toScreen_;  // current -> the map's screen (homogeneous)
    Matrix4 cameraToScreen_;
};

}  // namespace streyes
