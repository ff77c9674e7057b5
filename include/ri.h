/* The RenderMan Interface's C binding (RenderMan Interface Specification 3.2), the part streyes
 * implements: enough for a program or a procedural plug-in to build a scene without writing RIB.
 *
 * Every call appends the equivalent RIB request to the current RIB stream, which streyes' RIB
 * reader then reads: a scene built through this API is exactly the scene its RIB would give, with
 * the same checks and messages. Which stream is current:
 *   - inside a plug-in's Subdivide (Procedural "DynamicLoad", or RiProcedural with a function):
 *     that expansion's children, on the thread running it;
 *   - between RiBegin and RiEnd (on the thread that called RiBegin): RiBegin(RI_NULL) renders the
 *     scene at RiEnd to its Display files ("ri.exr" when none; needs streyes::io); any other name,
 *     RiBegin("scene.rib"), writes the RIB to that file instead ("-": standard output), as ASCII
 *     or, with RiOption("rib", "format", &binary, "compression", &gzip, RI_NULL) before RiBegin or
 *     inside the session, as binary RIB (32-bit floats) and gzip-compressed;
 *   - anywhere else a call is reported on standard error and ignored.
 * A bad call (a NaN, an undeclared parameter) is reported at RiEnd, or by the procedural that
 * made it, naming the call by its number and name.
 *
 * Parameter lists end with RI_NULL: RiSphere(1, -1, 1, 360, "Cs", colors, RI_NULL). A name is one
 * RenderMan predeclares, one given to RiDeclare, or an inline declaration ("uniform float Kd").
 *
 * A procedural plug-in (Procedural "DynamicLoad" ["name" "parameters"]) is a shared object
 * exporting, with C linkage:
 *   RtPointer ConvertParameters(RtString paramstr);   once per Procedural request
 *   RtVoid Subdivide(RtPointer data, RtFloat detail);  when a bucket reaches the bound
 *   RtVoid Free(RtPointer data);                       when the render no longer needs it
 * See examples/plugins/menger.c and README.md. */
#ifndef STREYES_RI_H
#define STREYES_RI_H

#ifdef __cplusplus
extern "C" {
#endif

typedef short RtBoolean;
typedef int RtInt;
typedef float RtFloat;
/* const, unlike the 3.2 text: C++ code may pass string literals. */
typedef const char* RtToken;
typedef const char* RtString;
typedef RtFloat RtColor[3];
typedef RtFloat RtPoint[3];
typedef RtFloat RtVector[3];
typedef RtFloat RtNormal[3];
typedef RtFloat RtHpoint[4];
typedef RtFloat RtMatrix[4][4];
typedef RtFloat RtBasis[4][4];
typedef RtFloat RtBound[6];
typedef void* RtPointer;
typedef void RtVoid;
typedef RtPointer RtLightHandle;
typedef RtPointer RtObjectHandle;
typedef RtFloat (*RtFilterFunc)(RtFloat, RtFloat, RtFloat, RtFloat);
typedef RtVoid (*RtProcSubdivFunc)(RtPointer, RtFloat);
typedef RtVoid (*RtProcFreeFunc)(RtPointer);

#define RI_FALSE 0
#define RI_TRUE 1
#define RI_INFINITY 1.0e38f
#define RI_EPSILON 1.0e-10f
#define RI_NULL ((RtToken)0)

/* Standard tokens. */
#define RI_P "P"
#define RI_PW "Pw"
#define RI_N "N"
#define RI_CS "Cs"
#define RI_OS "Os"
#define RI_S "s"
#define RI_T "t"
#define RI_ST "st"
#define RI_FOV "fov"
#define RI_PERSPECTIVE "perspective"
#define RI_ORTHOGRAPHIC "orthographic"
#define RI_BILINEAR "bilinear"
#define RI_BICUBIC "bicubic"
#define RI_PERIODIC "periodic"
#define RI_NONPERIODIC "nonperiodic"
#define RI_RGB "rgb"
#define RI_RGBA "rgba"
#define RI_RGBAZ "rgbaz"
#define RI_FILE "file"
#define RI_INTENSITY "intensity"
#define RI_LIGHTCOLOR "lightcolor"
#define RI_FROM "from"
#define RI_TO "to"
#define RI_KA "Ka"
#define RI_KD "Kd"
#define RI_KS "Ks"
#define RI_ROUGHNESS "roughness"
#define RI_CATMULLCLARK "catmull-clark"

/* The standard bases and their steps, for RiBasis. */
extern RtBasis RiBezierBasis, RiBSplineBasis, RiCatmullRomBasis, RiHermiteBasis, RiPowerBasis;
#define RI_BEZIERSTEP 3
#define RI_BSPLINESTEP 1
#define RI_CATMULLROMSTEP 1
#define RI_HERMITESTEP 2
#define RI_POWERSTEP 4

/* The standard pixel filters, for RiPixelFilter. */
RtFloat RiBoxFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiGaussianFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiTriangleFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiCatmullRomFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);
RtFloat RiSincFilter(RtFloat x, RtFloat y, RtFloat xwidth, RtFloat ywidth);

/* The built-in procedurals, for RiProcedural. */
RtVoid RiProcDelayedReadArchive(RtPointer data, RtFloat detail); /* data: RtString[1], the file */
RtVoid RiProcRunProgram(RtPointer data, RtFloat detail);         /* data: RtString[2], program, datablock */
RtVoid RiProcDynamicLoad(RtPointer data, RtFloat detail);        /* data: RtString[2], plug-in, parameters */
RtVoid RiProcFree(RtPointer data);                               /* free(data), as RISpec says */

/* ---- Sessions, frames and blocks */
RtVoid RiBegin(RtToken name);
RtVoid RiEnd(void);
RtVoid RiFrameBegin(RtInt number);
RtVoid RiFrameEnd(void);
RtVoid RiWorldBegin(void);
RtVoid RiWorldEnd(void);
RtVoid RiAttributeBegin(void);
RtVoid RiAttributeEnd(void);
RtVoid RiTransformBegin(void);
RtVoid RiTransformEnd(void);
RtVoid RiMotionBegin(RtInt n, ...); /* n times, as RtFloat (promoted to double) */
RtVoid RiMotionBeginV(RtInt n, RtFloat times[]);
RtVoid RiMotionEnd(void);
RtVoid RiArchiveRecord(RtToken type, const char* format, ...); /* accepted and ignored */

/* ---- Options */
RtVoid RiFormat(RtInt xres, RtInt yres, RtFloat pixelaspect);
RtVoid RiFrameAspectRatio(RtFloat ratio);
RtVoid RiScreenWindow(RtFloat left, RtFloat right, RtFloat bottom, RtFloat top);
RtVoid RiClipping(RtFloat hither, RtFloat yon);
RtVoid RiDepthOfField(RtFloat fstop, RtFloat focallength, RtFloat focaldistance);  // fstop RI_INFINITY: a pinhole
RtVoid RiShutter(RtFloat open, RtFloat close);
RtVoid RiPixelSamples(RtFloat xsamples, RtFloat ysamples);
RtVoid RiPixelFilter(RtFilterFunc filter, RtFloat xwidth, RtFloat ywidth);
RtVoid RiProjection(RtToken name, ...);
RtVoid RiProjectionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiDisplay(RtToken name, RtToken type, RtToken mode, ...);
RtVoid RiDisplayV(RtToken name, RtToken type, RtToken mode, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiOption(RtToken name, ...);
RtVoid RiOptionV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiExposure(RtFloat gain, RtFloat gamma);
RtVoid RiHider(RtToken type, ...);
RtVoid RiHiderV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]);
RtToken RiDeclare(const char* name, const char* declaration);

/* ---- Transforms */
RtVoid RiIdentity(void);
RtVoid RiTransform(RtMatrix transform);
RtVoid RiConcatTransform(RtMatrix transform);
RtVoid RiTranslate(RtFloat dx, RtFloat dy, RtFloat dz);
RtVoid RiRotate(RtFloat angle, RtFloat dx, RtFloat dy, RtFloat dz);
RtVoid RiScale(RtFloat sx, RtFloat sy, RtFloat sz);

/* ---- Attributes and shading */
RtVoid RiColor(RtColor color);
RtVoid RiOpacity(RtColor color);
RtVoid RiShadingRate(RtFloat size);
RtVoid RiGeometricApproximation(RtToken type, RtFloat value);
RtVoid RiBasis(RtBasis ubasis, RtInt ustep, RtBasis vbasis, RtInt vstep);
RtVoid RiSides(RtInt sides);
RtVoid RiOrientation(RtToken orientation);
RtVoid RiReverseOrientation(void);
RtVoid RiShadingInterpolation(RtToken type);
RtVoid RiAttribute(RtToken name, ...);
RtVoid RiAttributeV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiSurface(RtToken name, ...);
RtVoid RiSurfaceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtLightHandle RiLightSource(RtToken name, ...);
RtLightHandle RiLightSourceV(RtToken name, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiIlluminate(RtLightHandle light, RtBoolean onoff);

/* ---- Geometry */
RtVoid RiSphere(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, ...);
RtVoid RiSphereV(RtFloat radius, RtFloat zmin, RtFloat zmax, RtFloat thetamax, RtInt n, RtToken tokens[],
                 RtPointer values[]);
RtVoid RiPolygon(RtInt nvertices, ...);
RtVoid RiPolygonV(RtInt nvertices, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiPointsPolygons(RtInt npolys, RtInt nvertices[], RtInt vertices[], ...);
RtVoid RiPointsPolygonsV(RtInt npolys, RtInt nvertices[], RtInt vertices[], RtInt n, RtToken tokens[],
                         RtPointer values[]);
RtVoid RiPatch(RtToken type, ...);
RtVoid RiPatchV(RtToken type, RtInt n, RtToken tokens[], RtPointer values[]);
RtVoid RiPatchMesh(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, ...);
RtVoid RiPatchMeshV(RtToken type, RtInt nu, RtToken uwrap, RtInt nv, RtToken vwrap, RtInt n, RtToken tokens[],
                    RtPointer values[]);
/* tags: "crease", "corner", "hole", "interpolateboundary"; see RISpec 3.2. */
RtVoid RiSubdivisionMesh(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[], RtInt ntags,
                         RtToken tags[], RtInt nargs[], RtInt intargs[], RtFloat floatargs[], ...);
RtVoid RiSubdivisionMeshV(RtToken scheme, RtInt nfaces, RtInt nvertices[], RtInt vertices[], RtInt ntags,
                          RtToken tags[], RtInt nargs[], RtInt intargs[], RtFloat floatargs[], RtInt n,
                          RtToken tokens[], RtPointer values[]);
/* subdivfunc: RiProcDelayedReadArchive, RiProcRunProgram, RiProcDynamicLoad, or a function of the
 * program's own (called with `data` when a bucket reaches the bound; freefunc(data) after). */
RtVoid RiProcedural(RtPointer data, RtBound bound, RtProcSubdivFunc subdivfunc, RtProcFreeFunc freefunc);
RtVoid RiReadArchive(RtToken name, RtVoid (*callback)(RtToken, const char*, ...), ...);

#ifdef __cplusplus
}
#endif

#endif /* STREYES_RI_H */
