/* shadowpoint: pointlight (RI Spec 3.2) whose light six shadow maps block, one a face of the cube
   about the light (sfpx: the +x face, sfnx: -x, ...; each a 90-degree perspective depth pass
   from "from"): a point reads the map of the world axis its direction from the light is longest
   along. A face without a map leaves its points lit. samples, blur, bias and width go to
   shadow() (docs/SCENE-FORMAT.md, "Shadow maps"). falloff as shadowspot's. */
light shadowpoint(float intensity = 1; color lightcolor = 1; point from = point "shader" (0, 0, 0);
                  string sfpx = ""; string sfnx = ""; string sfpy = ""; string sfny = "";
                  string sfpz = ""; string sfnz = "";
                  float samples = 16; float width = 1; float blur = 0; float bias = 0;
                  float falloff = 2;)
{
    float blocked = 0;
    illuminate(from) {
        /* L runs from the light to the point: its longest world axis is the face the point is on. */
        vector Lw = vtransform("world", L);
        float x = xcomp(Lw), y = ycomp(Lw), z = zcomp(Lw);
        float ax = abs(x), ay = abs(y), az = abs(z);
        if (ax >= ay && ax >= az) {
            if (x > 0) {
                if (sfpx != "")
                    blocked = shadow(sfpx, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
            } else if (sfnx != "")
                blocked = shadow(sfnx, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
        } else if (ay >= az) {
            if (y > 0) {
                if (sfpy != "")
                    blocked = shadow(sfpy, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
            } else if (sfny != "")
                blocked = shadow(sfny, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
        } else {
            if (z > 0) {
                if (sfpz != "")
                    blocked = shadow(sfpz, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
            } else if (sfnz != "")
                blocked = shadow(sfnz, Ps, "samples", samples, "blur", blur, "swidth", width, "twidth", width, "bias", bias);
        }
        if (falloff == 2)
            Cl = (1 - blocked) * intensity * lightcolor / (L . L);
        else if (falloff == 1)
            Cl = (1 - blocked) * intensity * lightcolor / (length(L) / 2);
        else
            Cl = (1 - blocked) * intensity * lightcolor;
    }
}
