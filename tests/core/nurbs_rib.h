// RIB text of NURBS surfaces with exact answers, for the render tests: a disc, a sphere, a torus
// (rational quadratic circles), a square, and a circular trim loop.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace streyes::test {

// The rational quadratic unit circle: 9 points, weights 1 and sqrt(2)/2, knots at the quarters.
struct NurbsCircle {
    static constexpr double kH = 0.70710678118654752440;
    double x[9] = {1, 1, 0, -1, -1, -1, 0, 1, 1};
    double y[9] = {0, 1, 1, 1, 0, -1, -1, -1, 0};
    double w[9] = {1, kH, 1, kH, 1, kH, 1, kH, 1};
    static const char* knots() { return "[0 0 0 0.25 0.25 0.5 0.5 0.75 0.75 1 1 1]"; }
};

// A surface of revolution about z of a rational profile (rho_j, z_j, w_j), u around, v along.
inline std::string nurbsRevolution(const std::vector<double>& rho, const std::vector<double>& z,
                                   const std::vector<double>& w, int vorder, const std::string& vknots) {
    const NurbsCircle c;
    std::ostringstream s;
    s.precision(17);
    s << "NuPatch 9 3 " << NurbsCircle::knots() << " 0 1 " << rho.size() << " " << vorder << " " << vknots
      << " " << "0 1 \"Pw\" [";
    for (size_t j = 0; j < rho.size(); ++j)
        for (int i = 0; i < 9; ++i) {
            const double ww = c.w[i] * w[j];
            s << c.x[i] * rho[j] * ww << " " << c.y[i] * rho[j] * ww << " " << z[j] * ww << " " << ww << "  ";
        }
    s << "]\n";
    return s.str();
}

// A disc of radius r in the plane z (centred on the z axis): the circle and its centre, linear in v.
inline std::string nurbsDisc(double r, double z) {
    return nurbsRevolution({0, r}, {z, z}, {1, 1}, 2, "[0 0 1 1]");
}

// A sphere of radius r: the half circle from the south pole to the north pole, revolved.
inline std::string nurbsSphere(double r) {
    const double h = NurbsCircle::kH;
    return nurbsRevolution({0, r, r, r, 0}, {-r, -r, 0, r, r}, {1, h, 1, h, 1}, 3, "[0 0 0 0.5 0.5 1 1 1]");
}

// A torus: a tube of radius b about the circle of radius a.
inline std::string nurbsTorus(double a, double b) {
    const NurbsCircle c;
    std::vector<double> rho, z, w;
    for (int j = 0; j < 9; ++j) rho.push_back(a + b * c.x[j]), z.push_back(b * c.y[j]), w.push_back(c.w[j]);
    return nurbsRevolution(rho, z, w, 3, NurbsCircle::knots());
}

// The square [x0, x1] x [y0, y1] at depth z, bilinear (order 2), u along x.
inline std::string nurbsSquare(double x0, double x1, double y0, double y1, double z) {
    std::ostringstream s;
    s << "NuPatch 2 2 [0 0 1 1] 0 1 2 2 [0 0 1 1] 0 1 \"P\" [" << x0 << " " << y0 << " " << z << "  " << x1 << " " << y0
      << " " << z << "  " << x0 << " " << y1 << " " << z << "  " << x1 << " " << y1 << " " << z << "]\n";
    return s.str();
}

// TrimCurve with one loop: the circle of radius r about (cu, cv) in (u, v).
inline std::string trimCircle(double cu, double cv, double r) {
    const NurbsCircle c;
    std::ostringstream u, v, w;
    u.precision(17), v.precision(17), w.precision(17);
    for (int i = 0; i < 9; ++i) {
        u << (cu + r * c.x[i]) * c.w[i] << " ";
        v << (cv + r * c.y[i]) * c.w[i] << " ";
        w << c.w[i] << " ";
    }
    return "TrimCurve [1] [3] " + std::string(NurbsCircle::knots()) + " [0] [1] [9] [" + u.str() + "] [" + v.str() +
           "] [" + w.str() + "]\n";
}

}  // namespace streyes::test
