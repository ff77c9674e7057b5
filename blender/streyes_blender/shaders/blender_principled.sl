/* blender_principled: Blender's Principled BSDF as the streyes add-on exports it. Burley's
   diffuse (with its roughness-dependent retro-reflection, as Cycles' Principled BSDF) weighted
   by 1 - metallic, a GGX highlight (Smith shadowing, Schlick Fresnel from 0.08 specular for
   dielectrics, the base colour for metals), emission, the base colour from Cs or from an image
   (basemap, sRGB-decoded when basemap_srgb is 1) looked up at the mesh's UVs (s, t).
   Light units: a light's Cl is irradiance / pi (the add-on's convention, so that "matte" gives
   Cycles' Lambertian brightness); BRDFs are therefore multiplied by pi. Not rendered:
   subsurface, transmission, clearcoat, sheen, anisotropy, normal maps. */

float srgb_decode(float c)
{
    float v = c / 12.92;
    if (c > 0.04045)
        v = pow((c + 0.055) / 1.055, 2.4);
    return v;
}

float schlick_weight(float c)
{
    float m = clamp(1 - c, 0, 1);
    return m * m * m * m * m;
}

float smith_g1(float c; float a2)
{
    return 2 * c / (c + sqrt(a2 + (1 - a2) * c * c));
}

surface blender_principled(float metallic = 0; float specular = 0.5; float roughness = 0.5;
                           color emission = 0; string basemap = ""; float basemap_srgb = 1;
                           float Ka = 1;)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color base = Cs;
    if (basemap != "") {
        color tex = color texture(basemap, s, t);
        if (basemap_srgb != 0)
            tex = color(srgb_decode(comp(tex, 0)), srgb_decode(comp(tex, 1)), srgb_decode(comp(tex, 2)));
        base = tex;
    }
    float r = clamp(roughness, 0, 1);
    float a = max(r * r, 0.001);
    float a2 = a * a;
    color f0 = mix(color(0.08 * specular), base, metallic);
    float nv = max(Nf . V, 1e-4);
    float fv = schlick_weight(nv);
    color diff = 0;
    color spec = 0;
    illuminance(P, Nf, PI / 2) {
        vector Ln = normalize(L);
        float nl = Nf . Ln;
        if (nl > 0) {
            vector H = normalize(Ln + V);
            float nh = max(Nf . H, 0);
            float lh = max(Ln . H, 0);
            float fl = schlick_weight(nl);
            float rr = 2 * r * lh * lh;
            /* Burley: (1 - fl/2)(1 - fv/2) + rr (fl + fv + fl fv (rr - 1)), times 1/pi, times pi */
            float fd = (1 - 0.5 * fl) * (1 - 0.5 * fv) + rr * (fl + fv + fl * fv * (rr - 1));
            diff += Cl * nl * fd;
            float d = nh * nh * (a2 - 1) + 1;
            float D = a2 / (PI * d * d);
            float G = smith_g1(nl, a2) * smith_g1(nv, a2);
            color F = f0 + (color(1) - f0) * schlick_weight(lh);
            spec += Cl * F * (PI * D * G / (4 * nv));
        }
    }
    Oi = Os;
    Ci = Os * ((1 - metallic) * base * (Ka * ambient() + diff) + spec + emission);
}
