/* distantlight: parallel light travelling from "from" towards "to" (RI Spec 3.2).
   shadowname "raytrace": ray-traced shadows, as for pointlight. */
light distantlight(float intensity = 1; color lightcolor = 1;
                   point from = point "shader" (0, 0, 0); point to = point "shader" (0, 0, 1);
                   string shadowname = "";)
{
    solar(to - from, 0) {
        Cl = intensity * lightcolor;
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps);
    }
}
