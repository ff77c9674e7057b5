/* pointlight: light from a point, falling off with the square of the distance (RI Spec 3.2).
   shadowname "raytrace": the renderer traces this light's shadows per sample (shadow() reads 0
   here, the rays are cast for each sample at its own time). */
light pointlight(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                 string shadowname = "";)
{
    illuminate(from) {
        Cl = intensity * lightcolor / (L . L);
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps);
    }
}
