/* A Blobby field plug-in in AIR's form (opcode 9000): the distance from the blob space's origin
   over the float R, so the field 1 - r/R is the level 27/64 on the sphere of radius 37/64 R. */
#include <math.h>

typedef struct {
    int BlobbyId;
    int OpId;
} State;

void ImplicitBound(State* s, float* bd, int niarg, int* iarg, int nfarg, float* farg, int nsarg, char** sarg) {
    (void)s, (void)niarg, (void)iarg, (void)nsarg, (void)sarg;
    const float R = nfarg > 0 ? farg[0] : 1;
    for (int i = 0; i < 3; ++i) bd[2 * i] = -R, bd[2 * i + 1] = R;
}

void ImplicitValue(State* s, float* result, float* p, int niarg, int* iarg, int nfarg, float* farg, int nsarg,
                   char** sarg) {
    (void)s, (void)niarg, (void)iarg, (void)nsarg, (void)sarg;
    const float R = nfarg > 0 ? farg[0] : 1;
    const float r = sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    result[0] = r / R;
}

void ImplicitFree(State* s) { (void)s; }
