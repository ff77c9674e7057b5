/* shinymetal: metal plus an environment map seen in the reflected direction
   (RI Spec 3.2, appendix A). Without a map it is metal. */
surface shinymetal(float Ka = 1; float Ks = 1; float Kr = 1; float roughness = .1;
                   string texturename = "";)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color env = 0;
    if (texturename != "") {
        vector D = reflect(I, normalize(Nf));
        D = vtransform("current", "world", D);
        env = color environment(texturename, D);
    }
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness) + Kr * env);
}
