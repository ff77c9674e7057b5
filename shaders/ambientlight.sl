/* ambientlight: light from nowhere in particular, seen only by ambient() (RI Spec 3.2). */
light ambientlight(float intensity = 1; color lightcolor = 1;)
{
    Cl = intensity * lightcolor;
}
