// Environments that are shaders: a surface shader (shaders/preethamsky.sl, say) looked at along
// a direction stands for an environment map of a name, with no map file made:
//
//   Option "environment:sky" "string shader" ["preethamsky"] "float turbidity" [3] ...
//
// makes environment("sky", R), and indirectdiffuse()'s and occlusion()'s "environmentmap" "sky",
// run the shader with I = R (the map's space: "shader", "world" and "current" spaces are all that
// space, so the shader's points and vectors are given in it), and give its Ci. Exact in every
// direction (no map's resolution), unfiltered (the footprint is not read: for skies, smooth at the
// scale of a lookup's cone), at the cost of a shader run per direction.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "shade/vm/shader_instance.h"
#include "shade/vm/texture_source.h"

namespace streyes {

class ShaderEnvironments {
  public:
    void add(const std::string& name, std::shared_ptr<const sl::ShaderInstance> shader);
    bool empty() const { return named_.empty(); }
    // The shader's Ci along each direction of q into out (channels 0..2, as many as `channels`;
    // a fourth is 1). False when `name` is not one of these environments.
    bool lookup(const std::string& name, int channels, const sl::DirectionQuery& q, float* const* out) const;

  private:
    struct Named {
        std::string name;
        std::shared_ptr<const sl::ShaderInstance> shader;
    };
    std::vector<Named> named_;
};

}  // namespace streyes
