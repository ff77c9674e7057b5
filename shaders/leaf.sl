/* leaf: a leaf cut out of its patch by opacity: (s, t) in [0,1]^2, t from stem to tip, s
   across. A midrib and side veins, a little colour variation per leaf, and light coming
   through from behind (Kt). */
surface leaf(float Ka = 1; float Kd = .7; float Ks = .08; float roughness = .25; float Kt = .35;
             color leafcolor = color(.18, .40, .08); color veincolor = color(.42, .55, .18);
             float width = .45;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    float x = abs(2 * s - 1);  /* 0 on the midrib, 1 at the patch's sides */
    float halfwidth = 2 * width * pow(max(0, sin(PI * t)), .75) * (1 - .3 * t);
    float inside = 1 - filterstep(halfwidth, x);
    /* midrib and side veins running out towards the tip */
    float rib = 1 - smoothstep(.015, .04, x);
    float side = 1 - smoothstep(.02, .07, abs(mod(t * 7 - x * 2.5, 1) - .5));
    float veins = max(rib, .6 * side * (1 - smoothstep(.4, 1, x / max(halfwidth, .01))));
    /* each leaf its own shade: a cell noise of where the leaf is */
    float shade = cellnoise(transform("shader", point(0, 0, 0)) * 7.3);
    color Ct = Cs * mix(leafcolor * (.75 + .5 * shade), veincolor, veins);
    Oi = Os * inside;
    Ci = Oi * (Ct * (Ka * ambient() + Kd * diffuse(Nf) + Kt * diffuse(-Nf)) + Ks * specular(Nf, V, roughness));
}
