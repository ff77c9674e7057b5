/* ground: a forest floor. Fractal noise (octaves of noise) over the position in shader space
   mixes bare earth and moss; patches of fallen leaves; a fine grain. */
surface ground(float Ka = 1; float Kd = .9; float scale = .5; float octaves = 4;
               color earth = color(.28, .20, .13); color moss = color(.16, .26, .07);
               color litter = color(.42, .27, .11);)
{
    normal Nf = faceforward(normalize(N), I);
    point Pp = transform("shader", P) * scale;
    float f = 0, amp = .5, o;
    point q = Pp;
    for (o = 0; o < octaves; o += 1) {
        f += amp * (noise(q) - .5);
        q *= 2.03;
        amp *= .5;
    }
    float m = smoothstep(-.08, .12, f);
    float patches = smoothstep(.58, .72, noise(Pp * 1.7 + point(7.1, 3.2, 1.3)));
    color Ct = mix(earth, moss, m);
    Ct = mix(Ct, litter, .7 * patches);
    Ct *= .8 + .4 * noise(Pp * 37);
    Oi = Os;
    Ci = Os * Cs * Ct * (Ka * ambient() + Kd * diffuse(Nf));
}
