// What the Shading Language's option() and attribute() read: the renderer's graphics state,
// through an interface the renderer implements from its scene (shade/scene_queries.h) and tests
// replace with a double. One per grid (ShadingGrid::state): attribute() answers for the
// primitive being shaded. rendererinfo() is the interpreter's own; textureinfo() asks the
// TextureSource.
#pragma once

#include <string>
#include <vector>

#include "shade/vm/types.h"

namespace streyes::sl {

// A value as a query gives it. The shader's variable must be of the same kind (point, vector
// and normal mix freely) and hold at least `count` elements; else the query gives 0 and leaves
// the variable alone, as RenderMan's do.
struct QueryValue {
    BaseType type = BaseType::Float;   // Float, Color, Point (any point-like), Matrix or String
    int count = 1;                     // elements: "Format" is a float[3], count 3
    std::vector<float> floats;         // count x components (16 for a matrix)
    std::vector<std::string> strings;  // count, for strings

    static QueryValue numbers(std::vector<float> v) {
        QueryValue q;
        q.count = int(v.size());
        q.floats = std::move(v);
        return q;
    }
    static QueryValue string(std::string s) {
        QueryValue q;
        q.type = BaseType::String;
        q.strings.push_back(std::move(s));
        return q;
    }
};

class StateQueries {
  public:
    virtual ~StateQueries() = default;
    // option(name): RenderMan's standard names ("Format", "Clipping", ...) or "category:name"
    // for an Option request's value ("user:pass"). False when there is no such option.
    virtual bool option(const std::string& name, QueryValue& out) const = 0;
    // attribute(name) of the primitive being shaded: standard names ("ShadingRate", "Sides",
    // ...) or "category:name" ("identifier:name", "user:group").
    virtual bool attribute(const std::string& name, QueryValue& out) const = 0;
};

}  // namespace streyes::sl
