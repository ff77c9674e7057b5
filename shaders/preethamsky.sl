/* preethamsky: a clear sky after Preetham, Shirley and Smits, "A Practical Analytic Model for
   Daylight" (SIGGRAPH 1999). The sky's luminance Y (kcd/m^2) and chromaticity x, y in a
   direction at zenith angle theta and angle gamma from the sun are the zenith's values times the
   Perez distribution's ratio F(theta, gamma) / F(0, thetaS), with the paper's zenith formulas and
   coefficient tables (its Appendix A.2) for turbidity T; xyY goes to linear RGB (Rec. 709, D65)
   by the shading language's "xyY" colour space. For a dome or backdrop around the scene: the
   direction is the one looked along (I). Unlit: Ci = Os * intensity * sky.

   The sun lies in the direction from - to (as distantlight's from and to, given in the shader's
   space: the CTM where Surface is declared; put the block under CoordSysTransform "name" for a
   named space); up is the zenith (world +y unless given). Directions below the horizon see the
   horizon's sky; a sun below the horizon is taken at the horizon (the model's range is
   0 <= thetaS <= 90 degrees; turbidity 2 to 10 is what the paper fits). intensity scales
   kcd/m^2 to the picture's units (0.05: a midday zenith of about 0.3-0.5). */

/* The Perez et al. sky distribution, as the paper writes it. */
float preethamPerez(float A; float B; float C; float D; float E; float costheta; float gamma)
{
    float cg = cos(gamma);
    return (1 + A * exp(B / costheta)) * (1 + C * exp(D * gamma) + E * cg * cg);
}

surface preethamsky(float turbidity = 3; float intensity = 0.05;
                    point from = point "shader" (0, 1, 1); point to = point "shader" (0, 0, 0);
                    vector up = vector "world" (0, 1, 0);)
{
    float T = turbidity;
    vector Z = normalize(up);
    vector S = normalize(from - to);
    vector V = normalize(I);
    float thetaS = acos(clamp(S . Z, 0, 1));
    float costheta = max(V . Z, 0.001);
    float gamma = acos(clamp(V . S, -1, 1));

    /* Zenith luminance (kcd/m^2) and chromaticity. */
    float chi = (4.0 / 9 - T / 120) * (PI - 2 * thetaS);
    float Yz = (4.0453 * T - 4.9710) * tan(chi) - 0.2155 * T + 2.4192;
    float t1 = thetaS, t2 = thetaS * thetaS, t3 = thetaS * thetaS * thetaS, TT = T * T;
    float xz = TT * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * t1)
             + T * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * t1 + 0.00394)
             + (0.11693 * t3 - 0.21196 * t2 + 0.06052 * t1 + 0.25886);
    float yz = TT * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * t1)
             + T * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * t1 + 0.00516)
             + (0.15346 * t3 - 0.26756 * t2 + 0.06670 * t1 + 0.26688);

    /* The distribution coefficients for Y, x and y. */
    float AY = 0.1787 * T - 1.4630, BY = -0.3554 * T + 0.4275, CY = -0.0227 * T + 5.3251,
          DY = 0.1206 * T - 2.5771, EY = -0.0670 * T + 0.3703;
    float Ax = -0.0193 * T - 0.2592, Bx = -0.0665 * T + 0.0008, Cx = -0.0004 * T + 0.2125,
          Dx = -0.0641 * T - 0.8989, Ex = -0.0033 * T + 0.0452;
    float Ay = -0.0167 * T - 0.2608, By = -0.0950 * T + 0.0092, Cy = -0.0079 * T + 0.2102,
          Dy = -0.0441 * T - 1.6537, Ey = -0.0109 * T + 0.0529;

    float Y = Yz * preethamPerez(AY, BY, CY, DY, EY, costheta, gamma) / preethamPerez(AY, BY, CY, DY, EY, 1, thetaS);
    float x = xz * preethamPerez(Ax, Bx, Cx, Dx, Ex, costheta, gamma) / preethamPerez(Ax, Bx, Cx, Dx, Ex, 1, thetaS);
    float y = yz * preethamPerez(Ay, By, Cy, Dy, Ey, costheta, gamma) / preethamPerez(Ay, By, Cy, Dy, Ey, 1, thetaS);

    Oi = Os;
    Ci = Os * intensity * color "xyY" (x, y, max(Y, 0));
}
