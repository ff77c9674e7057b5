/* defaultsurface: what a primitive without a Surface gets. Lit from the eye, needing no
   lights: the renderer's built-in "defaultsurface" (src/shade/shading.cpp). */
surface defaultsurface(float Ka = .2; float Kd = .8;)
{
    float d = abs(normalize(N) . normalize(I));
    Oi = Os;
    Ci = Os * Cs * (Ka + Kd * d);
}
