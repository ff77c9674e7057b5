// MakeCubeFaceEnvironment: six perspective pictures taken from the centre of a cube resampled into
// one lat-long picture, which makeOiioTexture makes a lat-long environment map of. OpenImageIO's
// TextureSystem looks environment maps up only in the lat-long layout, so environment() reads the
// map made here as it reads MakeLatLongEnvironment's (one lookup path, one filter).
//
// The faces as RenderMan (RI Spec 3.2, MakeCubeFaceEnvironment) and Aqsis (libs/tex/filtering/
// cubeenvironmentsampler.h) orient them: each is the view from the centre along its axis with the
// up and right below, i.e. a left-handed camera (right = up x forward) as a frame rendered with
// `Projection "perspective" "fov" [fov]` and the camera turned to that axis sees it:
//
//   face  forward  right  up        face  forward  right  up
//   px    +x       -z     +y        nx    -x       +z     +y
//   py    +y       +x     -z        ny    -y       +x     +z
//   pz    +z       +x     +y        nz    -z       -x     +y
//
// A direction takes the face of its largest component (ties: x, then y, then z, as Aqsis), where
// it lands at screen (x, y) = (R.right, R.up) / (R.forward tan(fov / 2)), the face's picture
// spanning the screen window a perspective frame of its size has (the field of view across its
// shorter side). With fov > 90 the faces overlap (PRMan users render them so, to hide seams) and
// the overlap is not read; with fov < 90 directions between faces take the nearest edge.
//
// The lat-long picture is 4N x 2N for faces of N pixels along their longer side (4N across the
// horizon: at fov 90 a face's 90 degrees get N pixels at its centre, 1.27 N here); each texel
// takes its direction's face bilinearly (texel centres at half-integers, clamped at the edges),
// and maketx then filters its MIP levels with the request's filter.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "io/oiio_textures.h"

namespace streyes {

namespace {

struct Face {
    double forward[3], right[3], up[3];
};

// px, nx, py, ny, pz, nz: the order of the request's arguments.
constexpr Face kFaces[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
};

double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

int faceOf(const double R[3]) {
    const double ax = std::fabs(R[0]), ay = std::fabs(R[1]), az = std::fabs(R[2]);
    if (ax >= ay && ax >= az) return R[0] >= 0 ? 0 : 1;
    if (ay >= az) return R[1] >= 0 ? 2 : 3;
    return R[2] >= 0 ? 4 : 5;
}

struct FacePicture {
    std::string path;
    OIIO::ImageSpec spec;
    std::vector<float> pixels;
};

bool readFace(const std::string& path, FacePicture* face, std::string* error) {
    const std::string problem = pictureProblem(path);
    if (!problem.empty()) {
        *error = "the face '" + path + "': " + problem;
        return false;
    }
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        *error = "the face '" + path + "': " + OIIO::geterror();
        return false;
    }
    face->path = path;
    face->spec = in->spec();
    face->pixels.resize(size_t(face->spec.width) * size_t(face->spec.height) * size_t(face->spec.nchannels));
    if (!in->read_image(0, 0, 0, face->spec.nchannels, OIIO::TypeDesc::FLOAT, face->pixels.data())) {
        *error = "the face '" + path + "': " + in->geterror();
        return false;
    }
    return true;
}

// The face's pixels at picture position (px, py) (0 .. width, 0 .. height), bilinearly.
void sampleFace(const FacePicture& f, double px, double py, float* out) {
    const int w = f.spec.width, h = f.spec.height, nc = f.spec.nchannels;
    const double x = std::clamp(px - 0.5, 0.0, double(w - 1)), y = std::clamp(py - 0.5, 0.0, double(h - 1));
    const int x0 = std::min(int(x), w - 1), y0 = std::min(int(y), h - 1);
    const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
    const double fx = x - x0, fy = y - y0;
    const float* p00 = &f.pixels[(size_t(y0) * size_t(w) + size_t(x0)) * size_t(nc)];
    const float* p10 = &f.pixels[(size_t(y0) * size_t(w) + size_t(x1)) * size_t(nc)];
    const float* p01 = &f.pixels[(size_t(y1) * size_t(w) + size_t(x0)) * size_t(nc)];
    const float* p11 = &f.pixels[(size_t(y1) * size_t(w) + size_t(x1)) * size_t(nc)];
    for (int c = 0; c < nc; ++c)
        out[c] = float((1 - fy) * ((1 - fx) * p00[c] + fx * p10[c]) + fy * ((1 - fx) * p01[c] + fx * p11[c]));
}

}  // namespace

bool resampleCubeFaces(const MakeTextureDesc& d, CubeFaceLatLong* out, std::string* error) {
    if (d.cubeFaces.size() != 6) {
        *error = "six faces are needed";
        return false;
    }
    FacePicture faces[6];
    for (int i = 0; i < 6; ++i)
        if (!readFace(d.cubeFaces[size_t(i)], &faces[i], error)) return false;
    const OIIO::ImageSpec& first = faces[0].spec;
    bool sameFormat = true;
    for (const FacePicture& f : faces) {
        if (f.spec.width != first.width || f.spec.height != first.height) {
            *error = "the faces differ in size: '" + faces[0].path + "' is " + std::to_string(first.width) + " x " +
                     std::to_string(first.height) + ", '" + f.path + "' " + std::to_string(f.spec.width) + " x " +
                     std::to_string(f.spec.height) + " (the six must be alike)";
            return false;
        }
        if (f.spec.nchannels != first.nchannels) {
            *error = "the faces differ in channels: '" + faces[0].path + "' has " + std::to_string(first.nchannels) +
                     ", '" + f.path + "' " + std::to_string(f.spec.nchannels) + " (the six must be alike)";
            return false;
        }
        sameFormat = sameFormat && f.spec.format == first.format;
    }
    const int w = first.width, h = first.height, nc = first.nchannels;
    // The screen window of a perspective frame w x h: the field of view across the shorter side.
    const double aspect = double(w) / double(h);
    const double xr = aspect >= 1 ? aspect : 1, yr = aspect >= 1 ? 1 : 1 / aspect;
    const double tanHalf = std::tan(d.cubeFov * M_PI / 360);

    const int n = std::max(w, h);
    out->width = 4 * n;
    out->height = 2 * n;
    out->channels = first.channelnames;
    out->alphaChannel = first.alpha_channel;
    out->format = sameFormat ? first.format.c_str() : "float";
    out->pixels.assign(size_t(out->width) * size_t(out->height) * size_t(nc), 0.0f);
    for (int j = 0; j < out->height; ++j) {
        // OpenImageIO's lat-long layout (+y up): the top row looks along +y, the centre column
        // along +z, s grows towards -x.
        const double theta = M_PI * (0.5 - (j + 0.5) / out->height);
        for (int i = 0; i < out->width; ++i) {
            const double phi = 2 * M_PI * ((i + 0.5) / out->width - 0.5);
            const double R[3] = {-std::sin(phi) * std::cos(theta), std::sin(theta), std::cos(phi) * std::cos(theta)};
            const int f = faceOf(R);
            const Face& face = kFaces[f];
            const double along = dot(R, face.forward) * tanHalf;  // > 0: the largest component
            const double sx = dot(R, face.right) / along, sy = dot(R, face.up) / along;
            const double px = (sx + xr) / (2 * xr) * w, py = (yr - sy) / (2 * yr) * h;
            sampleFace(faces[f], px, py, &out->pixels[(size_t(j) * size_t(out->width) + size_t(i)) * size_t(nc)]);
        }
    }
    return true;
}

}  // namespace streyes
