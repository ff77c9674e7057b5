// A layered shader (ShaderLayer / ConnectShaderLayers, streyes/scene.h's ShaderNetwork) bound
// to its shaders, and how a grid runs it: one type for surfaces, displacements and imagers.
//
// The layers run in order over the same grid (the image, for an imager), with the same lights,
// in one interpreter, as Aqsis runs them in one shading environment: each layer starts from what
// the layer before it left (LayerNetwork::carried: Ci and Oi for a surface, P and N for a
// displacement, Ci, Oi and alpha for an imager; the first from the grid's inputs), and after a
// layer runs, each of its connections copies the value one of its parameters or predefined
// variables has then into a later layer's parameter (bound as a primitive variable is,
// overriding the instance's value) or into a predefined variable every later layer reads (Cs,
// say). The last layer's results are the network's (Material::surface, Material::displacement
// is its instance: output variables, message passing and the ray tracer's hits see that layer).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "shade/vm/shader_instance.h"
#include "shade/vm/shading_grid.h"
#include "shade/vm/vm.h"
#include "streyes/error.h"
#include "streyes/scene.h"

namespace streyes {

struct LayerNetwork {
    struct Link {
        int from = 0, to = 0;  // layer indices, from < to
        std::string fromName, toName;
        sl::Global fromGlobal = sl::Global::Count;  // a predefined variable, else a parameter
        sl::Global toGlobal = sl::Global::Count;
        sl::SlType type;  // the target's
        bool string = false;
    };
    std::vector<std::shared_ptr<const sl::ShaderInstance>> layers;  // the last is the material's shader
    std::vector<Link> links;                                        // by `from`, then as declared
    std::vector<sl::Global> carried;  // what a layer leaves the next (by the shaders' type)
};

// Checks `net`'s connections against the layers' shaders (`layers`, one per ShaderDesc, all
// found): a variable that is neither a parameter of its layer nor a predefined variable, types
// that differ (point, vector and normal mix), or a varying value into a uniform parameter are
// warned about (Log::lenient, at the ConnectShaderLayers line) and left out, as the peers leave
// out what they cannot connect. `type`: the layers' kind (surface, displacement or imager).
std::shared_ptr<const LayerNetwork> bindLayerNetwork(const ShaderNetwork& net, sl::ShaderType type,
                                                     std::vector<std::shared_ptr<const sl::ShaderInstance>> layers,
                                                     Log& log);

// Does a connection of `net` copy a predefined variable that may differ when only the camera
// moves (P, N, I, E ...: anything but Cs, Os, Ci, Oi, alpha, s, t, u, v, du, dv, time)? The
// view-use analysis (shade/sl/view_use.h) takes a layer's parameters and inputs as invariant,
// and each layer's own results it checks; such a connection it cannot see, so the material
// then reads the view (Material::viewUse).
bool connectsViewValues(const LayerNetwork& net);

// Runs a network over a grid (one per GridShader: it keeps its scratch arrays from grid to grid).
class LayerNetworkRunner {
  public:
    // Runs every layer of `net` over `grid` with `lights`; `vm`'s results are then the last
    // layer's (valid until its next run, or until this runner's next run). `grid` is left as
    // it was given.
    void run(sl::ShadingVM& vm, const LayerNetwork& net, sl::ShadingGrid& grid,
             const std::vector<sl::LightRef>& lights);
    // After run: the network's value of predefined variable `g`: the last layer's, or for a
    // carried variable the last layer does not name (vm.result would give the grid's input),
    // what the layers before it left.
    sl::ValueRef result(const sl::ShadingVM& vm, sl::Global g) const;

  private:
    std::vector<std::vector<float>> values_;  // per link: comps x n (structure of arrays), or comps
    std::vector<std::vector<std::string>> strings_;
    std::vector<std::vector<sl::Primvar>> primvars_;  // per layer: the grid's and its connected inputs
    std::vector<std::vector<float>> carried_;         // the previous layer's (LayerNetwork::carried)
    std::vector<sl::ValueRef> carriedViews_;          // views of carried_ the last layer started from
    const LayerNetwork* last_ = nullptr;              // the network of the last run
};

}  // namespace streyes
