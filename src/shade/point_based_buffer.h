// Point-based occlusion and colour bleeding at one shading point (Christensen 2008; PRMan's
// and Aqsis's point-based occlusion() and indirectdiffuse()): the cloud's discs are drawn into a
// cube "microbuffer" of six res x res faces around the point, then the buffer is integrated
// cosine-weighted over the cone about N.
//
// Drawing walks the disc hierarchy (point_based_tree.h) front to back: a cluster whose
// solid angle (its area over its distance squared) is under maxsolidangle is drawn as one disc,
// else opened; a leaf's discs are drawn one by one, those of solid angle maxsolidangle or more
// (and not edge on: seen as a sixteenth of a pixel or more) exactly (each pixel whose centre's ray meets the
// disc, at its radius), the rest, and the
// clusters, as rectangles of the disc's projected area (shaped as its projected ellipse's
// extents), box-filtered into the pixels they touch.
// Discs seen from behind are left out (as Aqsis does): a surface hides what lies on the side its
// normal faces. A pixel keeps coverage up to 1 and the colour of what covers it, nearest first:
// what is drawn after the pixel is full adds nothing, and an exactly drawn disc nearer than
// what filled the pixel replaces it (the walk's order is only nearly front to back).
//
// Occlusion is sum(w cover) / sum(w), indirect diffuse sum(w (colour + (1 - cover) env)) / sum(w)
// (env: the environment map in the pixel's direction, black without one), over the pixels
// whose centre direction d makes d.N > cos(coneangle), w = (d.N) x the pixel's solid angle. The
// microbuffer's own error (a disc drawn exactly; pixel-centre sampling): at most the weight of
// the pixels its outline crosses. A face spans pi/2 radians in res pixels, so an outline of
// angular length L crosses about 2 L res / pi pixels of weight at most pi / (4 res^2) each: the
// error is within about L / (2 res) (point_based_test.cpp counts the pixels exactly).
#pragma once

#include <vector>

#include "shade/point_based_tree.h"

namespace streyes {

struct PointBasedSettings {
    int res = 10;                          // "microbufres": pixels along a face's side
    float maxSolidAngle = 0.03f;           // "maxsolidangle" (steradians)
    float coneAngle = 1.57079632679f;      // "coneangle"
};

// One worker's buffer: reused from point to point (allocates only when res changes).
class CubeMicrobuffer {
  public:
    void setResolution(int res);
    int resolution() const { return res_; }
    // The unit direction through pixel (face, iu, iv)'s centre and the pixel's solid angle.
    const float* direction(int face, int iu, int iv) const { return &dir_[size_t(pixel(face, iu, iv)) * 3]; }
    float solidAngle(int face, int iu, int iv) const { return omega_[size_t(pixel(face, iu, iv))]; }
    // The pixel's coverage after integrate() (tests).
    float coverage(int face, int iu, int iv) const { return cover_[size_t(pixel(face, iu, iv))]; }
    int pixel(int face, int iu, int iv) const { return (face * res_ + iv) * res_ + iu; }

    // Every pixel's centre direction (x, y, z interleaved) and solid angle, in pixel() order
    // (setResolution first): where a caller looks an environment map up once for every point.
    int pixels() const { return 6 * res_ * res_; }
    const float* directions() const { return dir_.data(); }
    const float* solidAngles() const { return omega_.data(); }

    // Draws `tree` seen from P (world) and integrates over the cone about unit N: the covered
    // fraction into *occlusion, and, when colour is not null, the colour seen into colour[3].
    // `environment` (null: black): what each pixel sees where no disc covers it (RGB, pixels()
    // of them in pixel() order); its uncovered share, 1 - coverage, adds that to the colour
    // seen, and, when environmentSeen is not null, alone into environmentSeen[3] (occlusion()'s
    // "environmentcolor": the environment the discs let through).
    void integrate(const DiscHierarchy& tree, const float P[3], const float N[3], const PointBasedSettings& s,
                   float* occlusion, float* colour, const float* environment = nullptr,
                   float* environmentSeen = nullptr);

    // Face f's axis is f / 2 (x, y, z), its side + for even f; its (u, v) axes the next two.
    static int axis(int face) { return face >> 1; }
    static float side(int face) { return face & 1 ? -1.0f : 1.0f; }

  private:
    void clear();
    void drawExact(const float p[3], const float n[3], float radius, const float* colour);
    void drawSquare(const float p[3], const float n[3], float area, float distance, const float* colour);
    void rectOnFace(int face, float x, float y, float hu, float hv, float depth, const float* colour);
    void add(int px, float depth, float cover, const float* colour);

    int res_ = 0;
    std::vector<float> dir_, omega_;                 // per pixel: centre direction, solid angle
    std::vector<float> depth_, cover_, colour_;      // per pixel: nearest depth, coverage, colour (3)
};

}  // namespace streyes
