// A layered surface (ShaderLayer / ConnectShaderLayers, streyes/scene.h's ShaderNetwork) bound
// to its shaders, and how a grid runs it.
//
// The layers run in order over the same grid, with the same lights, in one interpreter, as
// Aqsis runs them in one shading environment: each layer starts from the Ci and Oi the layer
// before it left (the first from the surface's inputs), and after a layer runs, each of its
// connections copies the value one of its parameters or predefined variables has then into a
// later layer's parameter (bound as a primitive variable is, overriding the instance's value)
// or into a predefined variable every later layer reads (Cs, say). The last layer's results are
// the surface's (Material::surface is its instance: output variables, message passing and the
// ray tracer's hits see that layer).
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

struct SurfaceNetwork {
    struct Link {
        int from = 0, to = 0;  // layer indices, from < to
        std::string fromName, toName;
        sl::Global fromGlobal = sl::Global::Count;  // a predefined variable, else a parameter
        sl::Global toGlobal = sl::Global::Count;
        sl::SlType type;  // the target's
        bool string = false;
    };
    std::vector<std::shared_ptr<const sl::ShaderInstance>> layers;  // the last is Material::surface
    std::vector<Link> links;                                        // by `from`, then as declared
};

// Checks `net`'s connections against the layers' shaders (`layers`, one per ShaderDesc, all
// found): a variable that is neither a parameter of its layer nor a predefined variable, types
// that differ (point, vector and normal mix), or a varying value into a uniform parameter are
// warned about (Log::lenient, at the ConnectShaderLayers line) and left out, as the peers leave
// out what they cannot connect.
std::shared_ptr<const SurfaceNetwork> bindSurfaceNetwork(const ShaderNetwork& net,
                                                         std::vector<std::shared_ptr<const sl::ShaderInstance>> layers,
                                                         Log& log);

// Runs a network over a grid (one per GridShader: it keeps its scratch arrays from grid to grid).
class SurfaceNetworkRunner {
  public:
    // Runs every layer of `net` over `grid` with `lights`; `vm`'s results are then the last
    // layer's (valid until its next run, or until this runner's next run). `grid` is left as
    // it was given.
    void run(sl::ShadingVM& vm, const SurfaceNetwork& net, sl::ShadingGrid& grid,
             const std::vector<sl::LightRef>& lights);

  private:
    std::vector<std::vector<float>> values_;  // per link: comps x n (structure of arrays), or comps
    std::vector<std::vector<std::string>> strings_;
    std::vector<std::vector<sl::Primvar>> primvars_;  // per layer: the grid's and its connected inputs
    std::vector<float> ci_, oi_;                      // the previous layer's Ci and Oi (3 x n)
};

}  // namespace streyes
