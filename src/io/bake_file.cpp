// Bake files made pictures (bake_file.h).
#include "io/bake_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace streyes {

namespace {
constexpr const char* kHeader = "Aqsis bake file";
}

bool isBakeFile(const std::string& path) {
    std::ifstream f(path);
    std::string line;
    return f && std::getline(f, line) && line.rfind(kHeader, 0) == 0;
}

bool bakeToPicture(const std::string& path, int* sizeOut, std::vector<float>* rgb, std::string* error) {
    std::ifstream f(path);
    if (!f) {
        *error = "cannot open the bake file";
        return false;
    }
    std::string line;
    int comps = 0;
    if (!std::getline(f, line) || line.rfind(kHeader, 0) != 0) {
        *error = "not a bake file (its first line is not \"Aqsis bake file\")";
        return false;
    }
    if (!std::getline(f, line) || !(std::istringstream(line) >> comps) || comps < 1 || comps > 3) {
        *error = "its second line is not the value count (1, 2 or 3)";
        return false;
    }
    std::vector<float> recs;  // s, t, r, g, b
    int lineNo = 2;
    while (std::getline(f, line)) {
        ++lineNo;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream in(line);
        float v[5] = {0, 0, 0, 0, 0};
        for (int k = 0; k < 2 + comps; ++k)
            if (!(in >> v[k]) || !std::isfinite(v[k])) {
                *error = "line " + std::to_string(lineNo) + " is not " + std::to_string(2 + comps) + " numbers";
                return false;
            }
        if (comps == 1) v[3] = v[4] = v[2];
        if (comps == 2) v[4] = (v[2] + v[3]) / 2;
        recs.insert(recs.end(), v, v + 5);
    }
    const size_t n = recs.size() / 5;
    const int size = std::clamp(1 << int(std::lround(std::log2(std::max(1.0, std::sqrt(double(n)))))), 16, 4096);
    *sizeOut = size;
    float lo[2] = {0, 0}, hi[2] = {1, 1};
    bool rescale = false;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < 2; ++k) rescale = rescale || recs[i * 5 + size_t(k)] < 0 || recs[i * 5 + size_t(k)] > 1;
    if (rescale && n > 0)
        for (int k = 0; k < 2; ++k) {
            lo[k] = hi[k] = recs[size_t(k)];
            for (size_t i = 0; i < n; ++i) {
                lo[k] = std::min(lo[k], recs[i * 5 + size_t(k)]);
                hi[k] = std::max(hi[k], recs[i * 5 + size_t(k)]);
            }
            if (!(hi[k] > lo[k])) hi[k] = lo[k] + 1;
        }
    std::vector<double> sum(size_t(size) * size_t(size) * 4, 0.0);
    const float r = kBakeSplatRadius;
    for (size_t i = 0; i < n; ++i) {
        const float* q = &recs[i * 5];
        const float x = (q[0] - lo[0]) / (hi[0] - lo[0]) * float(size), y = (q[1] - lo[1]) / (hi[1] - lo[1]) * float(size);
        const int x0 = std::max(0, int(std::ceil(x - r - 0.5f))), x1 = std::min(size - 1, int(std::floor(x + r - 0.5f)));
        const int y0 = std::max(0, int(std::ceil(y - r - 0.5f))), y1 = std::min(size - 1, int(std::floor(y + r - 0.5f)));
        for (int py = y0; py <= y1; ++py)
            for (int px = x0; px <= x1; ++px) {
                const float dx = float(px) + 0.5f - x, dy = float(py) + 0.5f - y;
                if (dx * dx + dy * dy >= r * r) continue;
                double* p = &sum[(size_t(py) * size_t(size) + size_t(px)) * 4];
                p[0] += q[2], p[1] += q[3], p[2] += q[4], p[3] += 1;
            }
    }
    rgb->assign(size_t(size) * size_t(size) * 3, 0.0f);
    for (size_t p = 0; p < size_t(size) * size_t(size); ++p)
        if (sum[p * 4 + 3] > 0)
            for (int c = 0; c < 3; ++c) (*rgb)[p * 3 + size_t(c)] = float(sum[p * 4 + size_t(c)] / sum[p * 4 + 3]);
    return true;
}

}  // namespace streyes
