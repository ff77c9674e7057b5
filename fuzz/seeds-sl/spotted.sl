/* A seed for the Shading Language fuzzers: a spot light with a shadow() lookup. */
light spotted(float intensity = 1; color lightcolor = 1;
              point from = point "shader" (0, 0, 0), to = point "shader" (0, 0, 1);
              float coneangle = radians(30), conedeltaangle = radians(5), beamdistribution = 2;
              string shadowname = "") {
    uniform vector A = (to - from) / length(to - from);
    illuminate(from, A, coneangle) {
        float cosangle = L . A / length(L);
        float atten = pow(cosangle, beamdistribution) / (L . L);
        atten *= smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle);
        if (shadowname != "") atten *= 1 - shadow(shadowname, Ps);
        Cl = atten * intensity * lightcolor;
    }
}
