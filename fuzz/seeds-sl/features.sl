/* A seed for the Shading Language fuzzers: most of the language in one surface shader. */
float helper(float x; output float y) {
    y = x * 2;
    return smoothstep(0, 1, x) + y;
}

surface features(float Ka = 1, Kd = .5, Ks = .3, roughness = .1;
                 color specularcolor = 1;
                 string mapname = "";
                 float values[3] = {1, 2, 3};
                 output varying float glow = 0) {
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    float i, j, acc = 0, y = 0;
    for (i = 0; i < 4; i += 1) {
        if (mod(i, 2) == 1) continue;
        for (j = 0; j < 3; j += 1) {
            acc += values[j] * helper(s + i, y);
            if (acc > 20) break 2;
        }
    }
    while (acc > 1) acc /= 2;
    color C = 0;
    illuminance(P, Nf, PI / 2) {
        C += Cl * (normalize(L) . Nf);
    }
    point Pw = transform("world", P);
    matrix m = matrix "shader" 1;
    point q = transform(m, Pw);
    float n = noise(q * 4) + float cellnoise(q) * 0.1;
    color tex = mapname != "" ? color texture(mapname, s, t, "blur", 0.01) : color(1, 1, 1);
    color sp = spline(t, color(0, 0, 0), color(1, 0, 0), color(0, 1, 0), color(0, 0, 1));
    float d = Du(s) + Dv(t) + area(P) + length(vector(xcomp(q), ycomp(q), zcomp(q)));
    string msg = format("%f %s", acc, "x");
    glow = clamp(n + d * 0, 0, 1);
    Oi = Os;
    Ci = Os * (Cs * tex * (Ka * ambient() + Kd * diffuse(Nf) + C * 0.1) + specularcolor * Ks * specular(Nf, V, roughness)
               + sp * 0.01 + color "hsv" (acc, 0.5, 0.5) * 0.01);
    if (msg == "never") printf("%s\n", msg);
}
