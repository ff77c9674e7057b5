// The grid interpreter. A ShadingVM belongs to one thread; compiled programs are shared.
//
//   ShadingVM vm;                       // per thread; keeps its registers between grids
//   vm.setTextureSource(&textures);
//   vm.run(surface, grid, lights);      // every instruction over all the grid's points
//   ValueRef ci = vm.result(Global::Ci);
//
// Each instruction runs once per grid over all points (structure of arrays); uniform values
// are computed once; varying control flow runs under a mask stack. Light shaders run over the
// surface's points when an illuminance loop (or ambient, diffuse, specular, phong) first needs
// them, once per grid and light; a light whose run read nothing varying (an ambient light, a
// distant light without shadows) is run once and its results given again to the grids after,
// while everything uniform it could read is the same. Nothing is allocated per grid once the VM
// has seen grids of that size and programs of that shape.
//
// Never NaN or infinity: division by zero, sqrt, log and pow outside their domains give 0,
// and so does any non-finite value reaching an output; each such point is counted in
// stats().sanitised, which the caller can read to warn once.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "shade/vm/exec.h"
#include "shade/vm/grid_kernels.h"
#include "shade/vm/peers.h"
#include "shade/vm/point_cloud_source.h"
#include "shade/vm/program.h"
#include "shade/vm/ray_source.h"
#include "shade/vm/shader_instance.h"
#include "shade/vm/shading_grid.h"
#include "shade/vm/solar_seen.h"
#include "shade/vm/texture_source.h"

namespace streyes::sl {

struct Frame;

// One of the shaders message passing reads (peers.h): its instance and its "shader" space.
struct PeerShader {
    const ShaderInstance* shader = nullptr;
    Matrix4 toCurrent;
};
using PeerShaders = std::array<PeerShader, kPeerCount>;

// A light's results over the surface's points (L from the surface towards the light).
struct LightResult {
    bool valid = false;
    bool ambient = false;   // no illuminate or solar: only ambient() sees it
    bool nonDiffuse = false, nonSpecular = false;
    // The same at every point (a point-free light given again, runLight): L, Cl and Ln hold one
    // value each (3 floats) and lit one byte, read at [0] for every point, and the results hold
    // for any positions of this run (Ps is not kept).
    bool uniform = false;
    std::string category;   // __category
    std::vector<float> Ps;  // the positions it ran for (3 x n)
    std::vector<float> L, Cl;  // 3 x n each (3 when uniform)
    std::vector<float> Ln;     // L normalised (3 x n): what diffuse, specular and phong use
    std::vector<uint8_t> lit;  // 1 where an illuminate or solar statement reached the point
    // Point i's index into L, Cl, Ln (component c at c * stride(n) + at(i)) and lit.
    size_t at(int i) const { return uniform ? 0 : size_t(i); }
    size_t stride(size_t n) const { return uniform ? 1 : n; }
    const ShaderInstance* shader = nullptr;
    // Output parameters after the run, for lightsource(): floats (all points when varying)
    // and strings; offset of each parameter's values, -1 if not an output.
    std::vector<float> outFloats;
    std::vector<std::string> outStrings;
    std::vector<int> outOffset;
    std::vector<uint8_t> outVarying;
};

class ShadingVM {
  public:
    ShadingVM();
    ~ShadingVM();
    ShadingVM(const ShadingVM&) = delete;
    ShadingVM& operator=(const ShadingVM&) = delete;

    void setTextureSource(TextureSource* t) { textures_ = t; }
    TextureSource* textureSource() const { return textures_; }
    // What occlusion(), indirectdiffuse(), trace() and transmission() ask (none: they give
    // their no-hit values, counted in stats().raysMissing).
    void setRaySource(RaySource* r) { rays_ = r; }
    RaySource* raySource() const { return rays_; }
    // Where bake3d(), texture3d() and bake() write and read (none: they write nothing and find
    // nothing).
    void setPointClouds(PointCloudSource* p) { clouds_ = p; }
    PointCloudSource* pointClouds() const { return clouds_; }
    // Where run-time warnings go (an array index out of range, a loop past the budget), once a
    // place in a shader; without a log they are only counted in stats().
    void setLog(Log* log) { log_ = log; }
    // Loop iterations one run of a program over one grid may make (the surface's, and each
    // light's, displacement's, ... on their own): a shader whose loops go past it has each loop
    // end at its next turn, warned once. Runaway loops cannot hang a render.
    static constexpr uint64_t kDefaultLoopBudget = uint64_t(1) << 18;
    void setLoopBudget(uint64_t iterations) { loopBudget_ = iterations; }
    // specular() and specularbrdf() raise N.H to the power k / roughness: 8, PRMan's highlight
    // (the default), or 1, the RI Spec's formula (Option "shading" "specular" "rispec").
    void setSpecularExponent(float k) { specularExponent_ = k; }
    float specularExponent() const { return specularExponent_; }
    // Where printf writes (default: stderr).
    void setPrintSink(std::function<void(const std::string&)> sink) { print_ = std::move(sink); }
    // At most this many instructions a run (the shader and the lights it calls), else InputError;
    // 0 (the default): no limit, a shader that loops forever hangs, as in any renderer. The
    // Shading Language fuzzer sets one (fuzz/fuzz_sl.h).
    void setInstructionBudget(uint64_t instructions) { instructionBudget_ = instructions; }
    // The loops the hot operations run over a grid's points: the SIMD kernels of this CPU (the
    // default), or another set with the same results bit for bit (gridKernelsScalar(): the plain
    // path tests compare against).
    void setKernels(const GridKernels& k) { kernels_ = &k; }
    const GridKernels& kernels() const { return *kernels_; }

    // Message passing: the shaders of the primitive whose grid is shaded next (null: none). Each
    // call starts a new grid: surface() and the others read a peer's parameters as its last run
    // over this grid left them (a displacement's after it ran; the surface's as they are when a
    // light it calls runs), or, for a peer not run yet over it, as bound from the instance, the
    // primitive variables and the defaults.
    void setPeers(const PeerShaders& peers) {
        peers_ = peers;
        ++peerGrid_;
    }
    // The name of the grid's shader `which` (shadername(type)); "" when it has none.
    const std::string& peerShaderName(Peer which) const;

    // Runs `shader` over `grid`. `lights` are the lights on for the surface (for surface and
    // volume shaders). Bad bindings (a primitive variable whose type differs from the
    // parameter's) throw InputError at the primitive variable's location.
    void run(const ShaderInstance& shader, const ShadingGrid& grid, const std::vector<LightRef>& lights = {});

    // After run: a predefined variable's final value (Ci, Oi, P, N ...), valid until the next
    // run. A variable the shader never touched is the grid's input (valid while the caller's
    // arrays are), or an invalid ValueRef when there was none.
    ValueRef result(Global g) const;
    // After run: an output parameter's value (invalid if there is none by that name).
    ValueRef output(const std::string& name) const;
    // Binds a shader's parameters for `grid` (primitive variables, the instance's values, the
    // defaults) without running its body; then param() reads them. describe uses this.
    void bindParams(const ShaderInstance& shader, const ShadingGrid& grid);
    // After run or bindParams: parameter `name` (element `element` of an array), output or not.
    ValueRef param(const std::string& name, int element = 0) const;
    std::vector<std::string> paramStrings(const std::string& name) const;

    const ShadeStats& stats() const { return stats_; }
    void resetStats() { stats_ = {}; }

    // ---- Used by the operations (shade/vm) ----
    void print(const std::string& s) const;
    // A run-time warning at instruction `in` of the running program, once per `kind` and place.
    void warnOnce(const Exec& x, const Instr& in, const char* kind, const std::string& what);
    // The matrix from space `name` to current space of the program running (its own "shader"
    // and "object" spaces). False (identity given, counted) when nobody defined the space.
    bool spaceToCurrent(const std::string& name, float m[16]);
    bool currentToSpace(const std::string& name, float m[16]);
    // Lights for the running surface at positions P (3 x n, current space): runs each light
    // once per grid and positions.
    const std::vector<LightResult>& lightsAt(Exec& x, const RegView& P);
    // surface(name, var) and the others: peer `which`'s parameter `name` into register `dst` of
    // the running program when its type fits (then true).
    bool readPeer(Exec& x, Peer which, const std::string& name, int dst);
    const LightResult* currentLight() const { return currentLight_; }
    void setCurrentLight(const LightResult* l) { currentLight_ = l; }
    int nextRandom() { return randomCalls_++; }
    // Inside a light's illuminate(from ...): the light position register, for shadow().
    int illuminateFrom = -1;
    int solarAxis = -1;
    SolarSeen solarSeen;  // the last solar(axis, angle) a light of this VM ran
    // The running light: the points its illuminate or solar statements reached.
    uint8_t* lit(int n) {
        if (lit_.size() < size_t(n)) lit_.resize(size_t(n), 0);
        return lit_.data();
    }
    size_t lightCount() const { return lights_ ? lights_->size() : 0; }

  private:
    friend struct Frame;
    Frame& frameFor(const ShaderProgram& p);
    void runFrame(Frame& f, const ShaderInstance& shader, const ShadingGrid& grid, const Matrix4* shaderSpace,
                  bool body = true);
    void bindParamValues(Exec& x, const ShaderInstance& shader, const ShadingGrid& grid);
    void bindGlobals(Exec& x, const ShadingGrid& grid);
    void sanitiseOutputs(Exec& x);
    void execute(Exec& x, int begin, int end);
    void runLight(size_t index, const RegView& P);
    // A light's results that do not depend on the point (an ambient light, a distant light
    // without shadows: no instruction of its run read a varying value), kept from grid to grid
    // with everything uniform the run could read, and given again without running while that is
    // the same: the values a run would give, bit for bit (runLight).
    struct PointFreeLight {
        const ShaderInstance* shader = nullptr;
        uint64_t revision = 0;
        Matrix4 toCurrent;
        Vec3f normal{0, 0, 0};
        bool hasNormal = false;
        float weight = 1;
        std::array<Matrix4, kSpaceCount> spaces{};
        std::vector<NamedSpace> named;
        std::vector<float> globals;  // the uniform predefined variables the light has, as bound
        bool ambient = false, nonDiffuse = false, nonSpecular = false;
        uint8_t lit = 0;
        float L[3] = {0, 0, 0}, Cl[3] = {0, 0, 0}, Ln[3] = {0, 0, 0};
        std::string category;
        std::vector<float> outFloats;
        std::vector<std::string> outStrings;
        std::vector<int> outOffset;
    };
    bool pointFreeKey(const ShaderProgram& lp);
    bool samePointFree(const PointFreeLight& e, const LightRef& ref) const;
    void keepPointFree(const LightRef& ref, const ShaderProgram& lp, const LightResult& res, size_t n);
    static bool pointFreeInstr(const Exec& x, const Instr& in);
    ValueRef view(const Frame& f, int reg, int element = 0) const;

    Frame* peerFrame(Peer which);

    std::vector<std::unique_ptr<Frame>> frames_;
    PeerShaders peers_{};
    uint64_t peerGrid_ = 0;
    Frame* top_ = nullptr;  // the surface (or the only) program's frame of the last run
    TextureSource* textures_ = nullptr;
    RaySource* rays_ = nullptr;
    PointCloudSource* clouds_ = nullptr;
    Log* log_ = nullptr;
    uint64_t loopBudget_ = kDefaultLoopBudget;
    float specularExponent_ = 8;
    std::function<void(const std::string&)> print_;
    ShadeStats stats_;
    const GridKernels* kernels_ = &gridKernels();

    // The run in progress.
    const ShadingGrid* grid_ = nullptr;
    const std::vector<LightRef>* lights_ = nullptr;
    std::vector<LightResult> lightResults_;
    const LightResult* currentLight_ = nullptr;
    const Matrix4* shaderSpace_ = nullptr;  // of the program running
    const Matrix4* objectSpace_ = nullptr;  // of the primitive it shades (a light's: its shader space)
    int randomCalls_ = 0;
    uint64_t runCount_ = 0;
    uint64_t instructionBudget_ = 0, runInstructions_ = 0;
    ShadingGrid lightGrid_;  // the grid a light runs over: the surface's shape
    float lightOrigin_[3] = {0, 0, 0};
    float lightNormal_[3] = {0, 0, 0};  // an area light point's N
    std::vector<uint8_t> lit_;
    std::vector<float> ns_;  // Ns for a light run: the surface's N facing the eye (3 x n)
    std::vector<PointFreeLight> pointFree_;
    size_t pointFreeNext_ = 0;
    std::vector<float> pointFreeKey_;    // the light about to run: its uniform globals as bound
    const Frame* pointFreeWatch_ = nullptr;  // the light frame whose instructions are checked
};

}  // namespace streyes::sl
