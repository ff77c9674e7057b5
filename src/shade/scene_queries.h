// option() and attribute() of the Shading Language, answered from the scene: RenderMan's
// standard names from the camera, the options and the primitive's attributes, and
// "category:name" from the Option and Attribute values the scene keeps
// (RenderSettings::options, Attributes::user). Whatever the scene comes to keep there, shaders
// can read by its "category:name".
#pragma once

#include <map>
#include <string>

#include "shade/vm/state_queries.h"
#include "streyes/scene.h"

namespace streyes {

// The options' values by the names option() knows them by: made once per render.
class OptionValues {
  public:
    explicit OptionValues(const Scene& scene);
    const sl::QueryValue* find(const std::string& name) const;

  private:
    std::map<std::string, sl::QueryValue> values_;
};

// A value the scene keeps (an Option or Attribute parameter) as a shader receives it; false for
// what the Shading Language has no type for (hpoint).
bool queryValueOf(const Param& p, sl::QueryValue& out);

// One grid's answers: the render's options, the attributes of the primitive being shaded.
class SceneQueries final : public sl::StateQueries {
  public:
    SceneQueries() = default;
    SceneQueries(const OptionValues* options, const Attributes* attributes)
        : options_(options), attributes_(attributes) {}
    bool option(const std::string& name, sl::QueryValue& out) const override;
    bool attribute(const std::string& name, sl::QueryValue& out) const override;

  private:
    const OptionValues* options_ = nullptr;
    const Attributes* attributes_ = nullptr;
};

}  // namespace streyes
