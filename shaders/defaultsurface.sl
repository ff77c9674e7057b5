/* defaultsurface: what a primitive without a Surface gets. Lit from the eye, needing no
   lights: the renderer's built-in "defaultsurface" (src/shade/shading.cpp). Pixar's standard
   defaultsurface, which Aqsis's built-in follows: brightness Ka + Kd (N.I)^2. */
surface defaultsurface(float Ka = .2; float Kd = .8;)
{
    float d = normalize(N) . normalize(I);
    Oi = Os;
    Ci = Os * Cs * (Ka + Kd * d * d);
}
