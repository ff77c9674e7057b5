/* A Menger sponge as a procedural plug-in (Procedural "DynamicLoad", include/ri.h).
 *
 *   Procedural "DynamicLoad" ["menger" "level=3 size=2 x=-1 y=-1 z=-1"] [-1 1 -1 1 -1 1]
 *
 * Parameters (key=value, any order): level (recursion depth, default 2), x y z (the sponge's
 * lowest corner, default 0) and size (its edge, default 1); mindetail (default 0): a cube whose
 * bound covers fewer pixels than this is drawn whole instead of being subdivided further;
 * recurse=function|dso: the 20 sub-cubes are procedurals again, either through RiProcedural with
 * this file's own subdivide function (the default) or through RiProcDynamicLoad, loading this
 * plug-in again by name (plugin=NAME, default "menger": found as the parent was, along the search
 * path; give a path when the parent was given one). Either way each sub-cube is expanded only
 * when a bucket reaches its bound.
 *
 * Build: cc -shared -fPIC -I/where/include menger.c -o menger.so (the Ri functions come from the
 * program that loads it). */
#include <ri.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int level;
    RtFloat x, y, z, size, mindetail;
    int useFunction;
    char plugin[256];
} Sponge;

static void subdivideSponge(RtPointer data, RtFloat detail);

/* The cube [x, x+s]^3 as six quads. */
static void cube(RtFloat x, RtFloat y, RtFloat z, RtFloat s) {
    static RtInt nverts[6] = {4, 4, 4, 4, 4, 4};
    static RtInt verts[24] = {0, 2, 3, 1,  4, 5, 7, 6,  0, 1, 5, 4,  2, 6, 7, 3,  0, 4, 6, 2,  1, 3, 7, 5};
    RtFloat P[24];
    int i;
    for (i = 0; i < 8; ++i) {
        P[3 * i + 0] = (i & 1) ? x + s : x;
        P[3 * i + 1] = (i & 2) ? y + s : y;
        P[3 * i + 2] = (i & 4) ? z + s : z;
    }
    RiPointsPolygons(6, nverts, verts, RI_P, (RtPointer)P, RI_NULL);
}

RtPointer ConvertParameters(RtString paramstr) {
    Sponge* s = (Sponge*)calloc(1, sizeof(Sponge));
    char key[64];
    char value[256];
    const char* p = paramstr ? paramstr : "";
    int used = 0;
    s->level = 2;
    s->size = 1;
    s->useFunction = 1;
    strcpy(s->plugin, "menger");
    while (sscanf(p, " %63[^= ]=%255s%n", key, value, &used) == 2) {
        p += used;
        if (!strcmp(key, "level")) s->level = atoi(value);
        else if (!strcmp(key, "x")) s->x = strtof(value, NULL);
        else if (!strcmp(key, "y")) s->y = strtof(value, NULL);
        else if (!strcmp(key, "z")) s->z = strtof(value, NULL);
        else if (!strcmp(key, "size")) s->size = strtof(value, NULL);
        else if (!strcmp(key, "mindetail")) s->mindetail = strtof(value, NULL);
        else if (!strcmp(key, "recurse")) s->useFunction = !strcmp(value, "function");
        else if (!strcmp(key, "plugin")) snprintf(s->plugin, sizeof s->plugin, "%s", value);
        else fprintf(stderr, "menger: unknown parameter '%s' ignored\n", key);
    }
    return s;
}

/* The sub-cube (i, j, k) of the 27, as a procedural of its own. */
static void subCube(const Sponge* s, int i, int j, int k) {
    RtFloat t = s->size / 3.0f;
    Sponge child = *s;
    RtBound bound;
    child.level = s->level - 1;
    child.x = s->x + (RtFloat)i * t;
    child.y = s->y + (RtFloat)j * t;
    child.z = s->z + (RtFloat)k * t;
    child.size = t;
    bound[0] = child.x;
    bound[1] = child.x + t;
    bound[2] = child.y;
    bound[3] = child.y + t;
    bound[4] = child.z;
    bound[5] = child.z + t;
    if (s->useFunction) {
        Sponge* data = (Sponge*)malloc(sizeof(Sponge));
        *data = child;
        RiProcedural(data, bound, subdivideSponge, RiProcFree);
    } else {
        /* The plug-in again, by name: its parameters as text (%.9g keeps every float exact). */
        char params[512];
        RtString args[2];
        snprintf(params, sizeof params, "level=%d x=%.9g y=%.9g z=%.9g size=%.9g mindetail=%.9g plugin=%s",
                 child.level, child.x, child.y, child.z, child.size, child.mindetail, child.plugin);
        args[0] = s->plugin;
        args[1] = params;
        RiProcedural(args, bound, RiProcDynamicLoad, NULL);
    }
}

static void subdivideSponge(RtPointer data, RtFloat detail) {
    const Sponge* s = (const Sponge*)data;
    int i, j, k;
    if (s->level <= 0 || detail < s->mindetail) {
        cube(s->x, s->y, s->z, s->size);
        return;
    }
    for (k = 0; k < 3; ++k)
        for (j = 0; j < 3; ++j)
            for (i = 0; i < 3; ++i)
                if ((i == 1) + (j == 1) + (k == 1) < 2) subCube(s, i, j, k);
}

RtVoid Subdivide(RtPointer data, RtFloat detail) { subdivideSponge(data, detail); }

RtVoid Free(RtPointer data) { free(data); }
