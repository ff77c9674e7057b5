// A bake file (what the Shading Language's bake() writes, in Aqsis's text format: a line
// "Aqsis bake file", a line with the value count (1 to 3), then "s t values..." a line) made a
// picture MakeTexture can turn into a texture, as Aqsis's `teqser -bake=N` does.
//
// Each record is spread over the pixels whose centres lie within kBakeSplatRadius pixels of its
// (s, t) (Aqsis's disk filter of width 8), and each pixel is the mean of the records that reach
// it (black where none do). s and t outside [0, 1] are rescaled to it over the records' range, as
// Aqsis does. Row 0 is t = 0 (textures' top). One value: grey; two: (a, b, mean).
#pragma once

#include <string>
#include <vector>

namespace streyes {

constexpr float kBakeSplatRadius = 4.0f;

// Does the file begin as a bake file does?
bool isBakeFile(const std::string& path);

// The N x N RGB picture of the bake file at `path` (3 floats a pixel, row 0 first). N is the power
// of two nearest the square root of the record count (16 to 4096): about a record a pixel, as a
// bake of a whole surface at its shading rate gives (teqser takes it as -bake=N). False with
// `error` when it cannot be read, its header is not a bake file's, or a line is not numbers.
bool bakeToPicture(const std::string& path, int* size, std::vector<float>* rgb, std::string* error);

}  // namespace streyes
