/* A C program that builds a scene through the RenderMan Interface (include/ri.h) and renders it
 * with streyes, without writing RIB: the square of examples/render_rib's test scene, a quarter of
 * a 64 x 64 image, and a Menger sponge plug-in when one is named.
 *   ri_scene OUT.exr [menger.so]   renders to OUT.exr
 *   ri_scene OUT.rib [menger.so]   writes the scene as RIB instead
 * Returns 0; problems are reported on standard error. */
#include <ri.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: ri_scene OUT.exr|OUT.rib [menger.so]\n");
        return 2;
    }
    const char* out = argv[1];
    size_t n = strlen(out);
    int writesRib = n > 4 && strcmp(out + n - 4, ".rib") == 0;

    RiBegin(writesRib ? out : RI_NULL);
    RiFormat(64, 64, 1);
    RiProjection(RI_ORTHOGRAPHIC, RI_NULL);
    RiScreenWindow(0, 64, 0, 64);
    RiPixelFilter(RiBoxFilter, 1, 1);
    RiPixelSamples(2, 2);
    if (!writesRib) RiDisplay(out, RI_FILE, RI_RGBAZ, RI_NULL);
    RiWorldBegin();
    RiSurface("constant", RI_NULL);
    {
        RtColor orange = {1, 0.5f, 0.25f};
        RtFloat P[12] = {16, 16, 5, 48, 16, 5, 16, 48, 5, 48, 48, 5};
        RiColor(orange);
        RiPatch(RI_BILINEAR, RI_P, (RtPointer)P, RI_NULL);
    }
    if (argc > 2) {
        /* A level-1 sponge over the top-left corner, in front of the square: 8/9 of 9 x 9 pixels. */
        RtString args[2];
        RtBound bound = {2, 11, 2, 11, 1, 10};
        args[0] = argv[2];
        args[1] = "level=1 x=2 y=2 z=1 size=9";
        RiProcedural((RtPointer)args, bound, RiProcDynamicLoad, NULL);
    }
    RiWorldEnd();
    RiEnd();
    return 0;
}
