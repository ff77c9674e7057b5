/* shadowdistant: distantlight (RI Spec 3.2) whose light a shadow map blocks: shadowname names a
   depth map made from the light (an orthographic depth pass, as a distant light's is; "raytrace":
   ray-traced shadows). samples, blur, bias and width go to shadow() (docs/SCENE-FORMAT.md,
   "Shadow maps"). */
light shadowdistant(float intensity = 1; color lightcolor = 1;
                    point from = point "shader" (0, 0, 0); point to = point "shader" (0, 0, 1);
                    string shadowname = ""; float samples = 16; float width = 1; float blur = 0;
                    float bias = 0;)
{
    solar(to - from, 0) {
        Cl = intensity * lightcolor;
        if (shadowname != "")
            Cl *= 1 - shadow(shadowname, Ps, "samples", samples, "swidth", width, "twidth", width, "blur", blur,
                             "bias", bias);
    }
}
