/* sunlight: the sun as a distant light whose colour follows the clear sky model of Preetham,
   Shirley and Smits, "A Practical Analytic Model for Daylight" (SIGGRAPH 1999), Appendix A.1:
   the sun's light after Rayleigh scattering, tau_R = exp(-0.008735 lambda^-4.08 m), and
   scattering by aerosols (Angstrom's formula), tau_a = exp(-beta lambda^-alpha m) with
   alpha = 1.3 and beta = 0.04608 T - 0.04586, over the relative optical mass
   m = 1 / (cos thetaS + 0.15 (93.885 - thetaS in degrees)^-1.253). A documented simplification of
   the paper's spectral sum: the two transmittances are taken at one wavelength per channel
   (lambda = 0.65, 0.57, 0.475 micrometres for red, green, blue) on a white sun; the paper's
   ozone, mixed-gas and water-vapour terms (a few per cent in the visible) are left out.
   Cl = intensity * (tau_R tau_a) at those wavelengths: 0 with the sun below the horizon.

   The sun lies in the direction from - to (as distantlight's from and to, in the light's
   "shader" space: the CTM at LightSource); up is the zenith (world +y unless given). With shadows
   on (Attribute "light" "shadows" "on", or shadowname "raytrace") its shadow rays are parallel to
   from - to; angle is the sun's angular radius in degrees (0.27; 0: hard shadows), over which
   the renderer spreads them: it reads solar()'s axis and angle, whatever the shader's name
   (docs/SCENE-FORMAT.md, "Sun and sky"). Another shadowname is a
   shadow map's, read as shadowdistant reads it. */

/* The paper's transmittance of the sun's light at wavelength lambda (micrometres) through
   optical mass m, turbidity T. */
float preethamSunTransmittance(float lambda; float m; float T)
{
    float beta = 0.04608 * T - 0.04586;
    return exp(-0.008735 * pow(lambda, -4.08) * m) * exp(-beta * pow(lambda, -1.3) * m);
}

light sunlight(float intensity = 1; float turbidity = 3; float angle = 0.27;
               point from = point "shader" (0, 1, 1); point to = point "shader" (0, 0, 0);
               vector up = vector "world" (0, 1, 0);
               string shadowname = ""; float samples = 16; float blur = 0; float bias = 0;)
{
    vector S = normalize(from - to);
    float cosS = S . normalize(up);
    color sun = 0;
    if (cosS > 0) {
        float thetaDeg = degrees(acos(min(cosS, 1)));
        float m = 1 / (cosS + 0.15 * pow(93.885 - thetaDeg, -1.253));
        sun = color(preethamSunTransmittance(0.65, m, turbidity), preethamSunTransmittance(0.57, m, turbidity),
                    preethamSunTransmittance(0.475, m, turbidity));
    }
    solar(to - from, radians(angle)) {
        Cl = intensity * sun;
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur, "bias", bias);
    }
}
