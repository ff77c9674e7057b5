/* bark: tree bark for the forest scenes. Furrows run along t (up the trunk), wander with a
   low-frequency noise and repeat seamlessly around s; a fine grain varies the colour. */
surface bark(float Ka = 1; float Kd = .8; float Ks = .05; float roughness = .3;
             color lightbark = color(.42, .32, .22); color darkbark = color(.13, .09, .06);
             float furrows = 14;  /* furrows around the trunk */
             float tfreq = 3;)    /* wander along it */
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    float warp = pnoise(point(s * 4, t * tfreq, 0), point(4, 1000, 1000)) - .5;
    /* a ridged noise: 0 in the furrows, 1 on the plates between them */
    float ridge = abs(2 * pnoise(point(s * furrows + 3 * warp, t * tfreq * .5, 1.5),
                                  point(furrows, 1000, 1000)) - 1);
    float plates = smoothstep(.08, .45, ridge);
    float grain = noise(point(s * 90, t * 12, 3.3));
    color Ct = Cs * mix(darkbark, lightbark, plates * (.65 + .7 * grain));
    Oi = Os;
    Ci = Os * (Ct * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, V, roughness));
}
