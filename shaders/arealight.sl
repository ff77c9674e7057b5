/* arealight: a light spread over the geometry that follows AreaLightSource (RI Spec 3.2). streyes
   runs it at 16 points of that shape, P each point and N the shape's normal there, and weights
   each by 1/16: each point a Lambertian emitter, intensity * |N . L| / |L|^2 (both sides of the
   shape emit unless twosided is 0; then only the side N points to). shadowname "raytrace": soft
   shadows, each sample's shadow ray going to one of the points. */
light arealight(float intensity = 1; color lightcolor = 1; float twosided = 1; string shadowname = "";)
{
    illuminate(P) {
        float c = (N . L) / length(L);
        if (twosided != 0)
            c = abs(c);
        Cl = intensity * lightcolor * max(c, 0) / (L . L);
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps);
    }
}
