// The scene's Shading Language shaders: the compiled programs (one ShaderCache per render, along
// the shader search path) and the instances the scene's Surface and LightSource requests make.
//
// A material keeps the built-in shading (shading.h) when its surface is constant, matte, plastic
// or defaultsurface and every light on it is ambientlight, distantlight or pointlight: the
// shipped .sl sources of these give the same numbers (test), and the built-ins are about three
// times faster. Any other surface or light runs its shader over whole grids (grid_shader.h).
// Option "shading" "builtin" "off" runs every material through its shader.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bodies/material.h"
#include "shade/sl/compiler.h"
#include "shade/vm/shader_instance.h"
#include "streyes/error.h"
#include "streyes/scene.h"

namespace streyes {

// The folder of the shipped shaders (shaders/ of the source tree, or share/streyes/shaders of
// an installation): what '@' stands for in the shader search path.
std::string standardShaderDir();

class SceneShaders final : public MaterialBinder {
  public:
    // Compiles the scene's light shaders. A shader that does not compile, or a parameter that
    // does not fit its declaration, is an InputError (file:line:column of the shader, or the
    // RIB line of the parameter); a light whose shader is not found warns once and is dark.
    SceneShaders(const Scene& scene, Log& log);

    // Sets material.surface (and readsTime) unless the built-in shading serves it.
    void bind(Material& material, const Attributes& attributes) const override;

    // Light `i` of the scene as a shader (null when its shader was not found).
    const sl::ShaderInstance* light(size_t i) const { return i < lights_.size() ? lights_[i].get() : nullptr; }

  private:
    std::shared_ptr<sl::ShaderInstance> instance(const std::string& name, const ParamList& params,
                                                 const SourceLoc& loc, sl::ShaderType type) const;

    MotionTransform worldToCamera_;
    std::unique_ptr<sl::ShaderCache> cache_;  // thread-safe: materials are bound on worker threads too
    bool searchPathSet_ = false;
    std::vector<std::shared_ptr<sl::ShaderInstance>> lights_;
    std::vector<bool> builtinLight_;
    bool builtinShading_ = true;
    Log& log_;
};

// Sets `params` on `shader`: RIB's types (inline or Declare'd) are checked against the shader's
// declarations; a parameter named without a declaration takes the shader's type. Errors name
// the parameter's RIB file:line.
void setShaderParams(sl::ShaderInstance& shader, const ParamList& params);

}  // namespace streyes
