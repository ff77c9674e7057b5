/* sky: for a dome or backdrop around the scene. A gradient from the horizon to the zenith
   along the direction looked at (in world space), and clouds: fractal noise on a plane above,
   thinning towards the horizon. Unlit. */
surface sky(color horizon = color(.78, .86, .95); color zenith = color(.22, .42, .82);
            color cloudcolor = color(1, 1, 1); float cloudcover = .5; float cloudscale = 1.2;
            vector up = (0, 1, 0);)  /* world space */
{
    vector D = normalize(vtransform("world", I));
    vector Z = normalize(up);
    float h = D . Z;
    float above = clamp(h, 0, 1);
    color Ct = mix(horizon, zenith, pow(above, .6));
    /* where the ray meets a cloud plane one unit up */
    point q = point(0, 0, 0) + (D - h * Z) / max(above, .04) * cloudscale;
    float f = 0, amp = .5, o;
    for (o = 0; o < 5; o += 1) {
        f += amp * noise(q);
        q *= 2.1;
        amp *= .5;
    }
    float cloud = smoothstep(cloudcover, cloudcover + .2, f) * smoothstep(0, .12, above);
    Ct = mix(Ct, cloudcolor, cloud);
    Oi = Os;
    Ci = Os * Ct;
}
