// Preetham, Shirley and Smits, "A Practical Analytic Model for Daylight" (1999), worked out in
// double from the paper's formulas, for tests of shaders/preethamsky.sl: the sky's zenith
// luminance and chromaticity and the Perez ratio away from the zenith.
#pragma once

#include <cmath>

namespace streyes::preetham_ref {

struct Perez {
    double A, B, C, D, E;
    double operator()(double cosTheta, double gamma) const {
        return (1 + A * std::exp(B / cosTheta)) * (1 + C * std::exp(D * gamma) + E * std::cos(gamma) * std::cos(gamma));
    }
};

// The paper's sky: luminance Y (kcd/m^2) and chromaticity x, y at zenith angle theta and angle gamma
// from a sun at zenith angle thetaS, turbidity T.
struct Sky {
    double x, y, Y;
};
inline Sky preethamSky(double T, double thetaS, double theta, double gamma) {
    const double chi = (4.0 / 9 - T / 120) * (3.14159265358979323846 - 2 * thetaS);
    const double Yz = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
    const double t = thetaS, t2 = t * t, t3 = t2 * t, T2 = T * T;
    const double xz = T2 * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * t) +
                      T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * t + 0.00394) +
                      (0.11693 * t3 - 0.21196 * t2 + 0.06052 * t + 0.25886);
    const double yz = T2 * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * t) +
                      T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * t + 0.00516) +
                      (0.15346 * t3 - 0.26756 * t2 + 0.06670 * t + 0.26688);
    const Perez fY{0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771,
                   -0.0670 * T + 0.3703};
    const Perez fx{-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989,
                   -0.0033 * T + 0.0452};
    const Perez fy{-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537,
                   -0.0109 * T + 0.0529};
    const double c = std::cos(theta);
    return {xz * fx(c, gamma) / fx(1, thetaS), yz * fy(c, gamma) / fy(1, thetaS), Yz * fY(c, gamma) / fY(1, thetaS)};
}

}  // namespace streyes::preetham_ref
