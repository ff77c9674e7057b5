/* spotlight: a point light within a cone about from -> to, its edge smoothed over
   conedeltaangle, brightest on the axis (cos^beamdistribution) (RI Spec 3.2).
   shadowname "raytrace": ray-traced shadows, as for pointlight. */
light spotlight(float intensity = 1; color lightcolor = 1;
                point from = point "shader" (0, 0, 0); point to = point "shader" (0, 0, 1);
                float coneangle = radians(30); float conedeltaangle = radians(5);
                float beamdistribution = 2; string shadowname = "";)
{
    uniform vector A = (to - from) / length(to - from);
    uniform float cosoutside = cos(coneangle);
    uniform float cosinside = cos(coneangle - conedeltaangle);
    float atten, cosangle;
    illuminate(from, A, coneangle) {
        cosangle = L . A / length(L);
        atten = pow(cosangle, beamdistribution) / (L . L);
        atten *= smoothstep(cosoutside, cosinside, cosangle);
        Cl = atten * intensity * lightcolor;
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps);
    }
}
