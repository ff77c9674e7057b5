// The RI C API's calls as RIB (ri_stream.h): what each call writes, how parameter lists are
// counted from declarations and the primitive, and bad calls kept rather than thrown.
#include "scene/ri_stream.h"

#include <gtest/gtest.h>

#include <cmath>

#include "streyes/rib.h"

namespace streyes {
namespace {

std::string lines(const RiStream& s) { return s.text() + "\n"; }

TEST(RiStream, CallsWriteTheirRibRequests) {
    RiStream s("test");
    {
        RiStreamScope scope(&s);
        RiFormat(64, 48, 1);
        RiProjection(RI_PERSPECTIVE, RI_FOV, std::vector<RtFloat>{45}.data(), RI_NULL);
        RiDepthOfField(2, 0.5f, 4);
        RiTranslate(0, 0, 5);
        RiWorldBegin();
        RiAttributeBegin();
        RtColor c = {1, 0.5f, 0.25f};
        RiColor(c);
        RiSurface("constant", RI_NULL);
        RiSphere(1, -1, 1, 360, RI_NULL);
        RiAttributeEnd();
        RiWorldEnd();
    }
    EXPECT_EQ(lines(s),
              "Format 64 48 1\n"
              "Projection \"perspective\" \"fov\" [ 45 ]\n"
              "DepthOfField 2 0.5 4\n"
              "Translate 0 0 5\n"
              "WorldBegin\n"
              "AttributeBegin\n"
              "Color [ 1 0.5 0.25 ]\n"
              "Surface \"constant\"\n"
              "Sphere 1 -1 1 360\n"
              "AttributeEnd\n"
              "WorldEnd\n");
    EXPECT_EQ(s.calls(), 11);
    EXPECT_EQ(s.error(), "");
    Log log;
    const Scene scene = parseRibString(lines(s), "stream", log);
    ASSERT_EQ(scene.quadrics.size(), 1u);
    EXPECT_EQ(scene.camera.xres, 64);
}

TEST(RiStream, SidesOrientationExposureAndHiderReachTheScene) {
    RiStream s("test");
    {
        RiStreamScope scope(&s);
        RiExposure(2, 2.2f);
        const RtInt jitter = 0;
        const RtString filter = "max";
        RiHider("hidden", "jitter", &jitter, "depthfilter", &filter, RI_NULL);
        RiWorldBegin();
        RiSides(1);
        RiOrientation("inside");
        RiReverseOrientation();
        RiShadingInterpolation("constant");
        RiSphere(1, -1, 1, 360, RI_NULL);
        RiWorldEnd();
    }
    EXPECT_EQ(s.error(), "");
    Log log;
    const Scene scene = parseRibString(lines(s), "stream", log);
    EXPECT_EQ(scene.settings.exposureGain, 2.0);
    EXPECT_NEAR(scene.settings.exposureGamma, 2.2, 1e-6);
    EXPECT_FALSE(scene.settings.jitter);
    EXPECT_EQ(scene.settings.depthFilter, "max");
    ASSERT_EQ(scene.quadrics.size(), 1u);
    const Attributes& a = *scene.quadrics[0].attributes;
    EXPECT_FALSE(a.twoSided);
    EXPECT_EQ(a.orientation, Attributes::Orientation::Outside);  // inside, reversed
    EXPECT_FALSE(a.smoothShading);
}

TEST(RiStream, ParameterListsAreCountedFromTheDeclarationAndThePrimitive) {
    RiStream s("test");
    {
        RiStreamScope scope(&s);
        // 4 vertex points (12 floats), a varying color per vertex, a uniform float, a constant string.
        const RtFloat P[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        const RtFloat Cs[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
        const RtFloat k = 0.5f;
        const RtString name = "quad";
        RiPolygon(4, RI_P, P, RI_CS, Cs, "uniform float k", &k, "constant string label", &name, RI_NULL);
        // PointsPolygons: uniform per face, vertex per point (the largest index + 1).
        RtInt nverts[2] = {3, 3};
        RtInt verts[6] = {0, 1, 2, 0, 2, 3};
        const RtFloat w[2] = {7, 8};
        RiDeclare("w", "uniform float");
        RiPointsPolygons(2, nverts, verts, RI_P, P, "w", w, RI_NULL);
    }
    EXPECT_EQ(lines(s),
              "Polygon \"P\" [ 0 0 0 1 0 0 1 1 0 0 1 0 ] \"Cs\" [ 1 0 0 0 1 0 0 0 1 1 1 1 ] "
              "\"uniform float k\" [ 0.5 ] \"constant string label\" [ \"quad\" ]\n"
              "Declare \"w\" \"uniform float\"\n"
              "PointsPolygons [ 3 3 ] [ 0 1 2 0 2 3 ] \"P\" [ 0 0 0 1 0 0 1 1 0 0 1 0 ] \"w\" [ 7 8 ]\n");
    EXPECT_EQ(s.error(), "");
}

// The reader checks every count: what the calls write must read back as the primitives meant.
TEST(RiStream, MeshesAndMotionReadBackAsTheCallsMeant) {
    RiStream s("test");
    {
        RiStreamScope scope(&s);
        RiWorldBegin();
        // A bicubic mesh of 7 x 4 points in the Bezier basis (step 3): 2 x 1 patches, 3 x 2 varying colours.
        std::vector<RtFloat> P, Cs(18, 0.5f);
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 7; ++i) P.insert(P.end(), {RtFloat(i), RtFloat(j), 5});
        RiPatchMesh(RI_BICUBIC, 7, RI_NONPERIODIC, 4, RI_NONPERIODIC, RI_P, P.data(), RI_CS, Cs.data(), RI_NULL);
        // The same points, periodic in u in the B-spline basis (step 1): 7 x 1 patches, 7 x 2 colours.
        RiAttributeBegin();
        RiBasis(RiBSplineBasis, RI_BSPLINESTEP, RiBSplineBasis, RI_BSPLINESTEP);
        std::vector<RtFloat> Cs2(42, 0.25f);
        RiPatchMesh(RI_BICUBIC, 7, RI_PERIODIC, 4, RI_NONPERIODIC, RI_P, P.data(), RI_CS, Cs2.data(), RI_NULL);
        RiAttributeEnd();
        // Bezier again after the block: 2 x 1 patches.
        RiPatchMesh(RI_BICUBIC, 7, RI_NONPERIODIC, 4, RI_NONPERIODIC, RI_P, P.data(), RI_CS, Cs.data(), RI_NULL);
        // A cube as a subdivision mesh with a crease, a corner and a hole; uniform colours.
        RtInt nverts[6] = {4, 4, 4, 4, 4, 4};
        RtInt verts[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
        RtFloat cube[24];
        for (int i = 0; i < 8; ++i) {
            cube[3 * i] = RtFloat(i & 1);
            cube[3 * i + 1] = RtFloat((i >> 1) & 1);
            cube[3 * i + 2] = RtFloat((i >> 2) & 1) + 5;
        }
        RtToken tags[3] = {"crease", "corner", "hole"};
        RtInt nargs[6] = {2, 1, 1, 1, 1, 0};
        RtInt intargs[4] = {0, 1, 7, 5};
        RtFloat floatargs[2] = {2, 3};
        std::vector<RtFloat> uniformCs(18, 1);
        RiSubdivisionMesh(RI_CATMULLCLARK, 6, nverts, verts, 3, tags, nargs, intargs, floatargs, RI_P, cube,
                          "uniform color Cs", uniformCs.data(), RI_NULL);
        // A sphere moving from x = 0 to x = 1.
        RiAttributeBegin();
        RiMotionBegin(2, 0.0, 1.0);
        RiTranslate(0, 0, 5);
        RiTranslate(1, 0, 5);
        RiMotionEnd();
        RiSphere(1, -1, 1, 360, RI_NULL);
        RiAttributeEnd();
        RiWorldEnd();
    }
    ASSERT_EQ(s.error(), "");
    Log log;
    log.setQuiet(true);
    const Scene scene = parseRibString(lines(s), "stream", log);
    ASSERT_EQ(scene.patchMeshes.size(), 3u);
    EXPECT_EQ(scene.patchMeshes[2].Cs.values.size(), 6u);
    EXPECT_EQ(scene.patchMeshes[0].Cs.values.size(), 6u);
    EXPECT_EQ(scene.patchMeshes[1].Cs.values.size(), 14u);
    EXPECT_TRUE(scene.patchMeshes[1].uPeriodic);
    ASSERT_EQ(scene.subdivisionMeshes.size(), 1u);
    EXPECT_EQ(scene.subdivisionMeshes[0].creaseEdges, (std::vector<int>{0, 1}));
    EXPECT_EQ(scene.subdivisionMeshes[0].corners, (std::vector<int>{7}));
    EXPECT_EQ(scene.subdivisionMeshes[0].holes, (std::vector<int>{5}));
    EXPECT_EQ(scene.subdivisionMeshes[0].Cs.values.size(), 6u);
    ASSERT_EQ(scene.quadrics.size(), 1u);
    EXPECT_FALSE(scene.quadrics[0].objectToWorld.isStatic());
    EXPECT_TRUE(log.warnings().empty()) << log.warnings()[0];
}

TEST(RiStream, FloatsReadBackExactly) {
    RiStream s("test");
    const float v = 0.1f + 1e-7f;
    {
        RiStreamScope scope(&s);
        RiTranslate(v, 1.0f / 3.0f, -2.5e-9f);
    }
    float x, y, z;
    ASSERT_EQ(std::sscanf(s.text().c_str(), "Translate %g %g %g", &x, &y, &z), 3);
    EXPECT_EQ(x, v);
    EXPECT_EQ(y, 1.0f / 3.0f);
    EXPECT_EQ(z, -2.5e-9f);
}

TEST(RiStream, BadCallsAreKeptNotThrown) {
    RiStream s("test");
    {
        RiStreamScope scope(&s);
        RiWorldBegin();
        RiSphere(std::nanf(""), -1, 1, 360, RI_NULL);
        RiSphere(1, -1, 1, 360, "undeclared", std::vector<RtFloat>{1}.data(), RI_NULL);  // a second: not kept
    }
    EXPECT_EQ(s.error().rfind("call 2 (RiSphere): a value is not a finite number", 0), 0u) << s.error();

    RiStream t("test");
    {
        RiStreamScope scope(&t);
        RiSphere(1, -1, 1, 360, "undeclared", std::vector<RtFloat>{1}.data(), RI_NULL);
    }
    EXPECT_NE(t.error().find("call 1 (RiSphere): parameter \"undeclared\" is not declared"), std::string::npos)
        << t.error();
}

TEST(RiStream, StreamsAreThreadLocalAndScoped) {
    RiStream outer("outer"), inner("inner");
    {
        RiStreamScope a(&outer);
        RiWorldBegin();
        {
            RiStreamScope b(&inner);
            RiIdentity();
        }
        RiWorldEnd();
    }
    EXPECT_EQ(outer.text(), "WorldBegin\nWorldEnd");
    EXPECT_EQ(inner.text(), "Identity");
    EXPECT_EQ(currentRiStream(), nullptr);
}

void countingSubdivide(RtPointer data, RtFloat) { ++*static_cast<int*>(data); }
void countingFree(RtPointer data) { *static_cast<int*>(data) += 100; }

TEST(RiStream, ProceduralsAreWrittenByKindAndFunctionsKeptById) {
    int counter = 0;
    {
        RiStream s("test");
        {
            RiStreamScope scope(&s);
            RtBound bound = {0, 1, 0, 1, 0, 1};
            RtString archive[1] = {"tree.rib"};
            RiProcedural(archive, bound, RiProcDelayedReadArchive, nullptr);
            RtString plugin[2] = {"menger", "level=2"};
            RiProcedural(plugin, bound, RiProcDynamicLoad, nullptr);
            RiProcedural(&counter, bound, countingSubdivide, countingFree);
        }
        EXPECT_EQ(lines(s),
                  "Procedural \"DelayedReadArchive\" [ \"tree.rib\" ] [ 0 1 0 1 0 1 ]\n"
                  "Procedural \"DynamicLoad\" [ \"menger\" \"level=2\" ] [ 0 1 0 1 0 1 ]\n"
                  "Procedural \"RiFunction\" [ \"" + s.functions().begin()->first + "\" ] [ 0 1 0 1 0 1 ]\n");
        ASSERT_EQ(s.functions().size(), 1u);
        const std::string id = s.functions().begin()->first;
        std::shared_ptr<RiFunctionProcedural> f = findRiFunction(id);
        ASSERT_TRUE(f);
        f->subdivide(f->data, 1);
        EXPECT_EQ(counter, 1);
        f.reset();
        EXPECT_EQ(counter, 1);  // the stream still holds it
    }
    EXPECT_EQ(counter, 101);  // freed with the last owner
}

TEST(RiStream, CallsWithoutAStreamAreIgnored) {
    ASSERT_EQ(currentRiStream(), nullptr);
    RiSphere(1, -1, 1, 360, RI_NULL);  // reported on standard error, nothing else
    SUCCEED();
}

}  // namespace
}  // namespace streyes
