#include "scene/object_st.h"

#include <string>

namespace streyes {

void addObjectSt(const std::vector<Vec3d>& P, PolygonMeshDesc& d) {
    for (const Param& p : d.primvars.params)
        if (p.name == "s" || p.name == "t" || p.name == "st") return;
    const Attributes* a = d.attributes.get();
    if (!a) return;
    const std::string& surface = a->surface.name;
    const bool builtin = surface == "constant" || surface == "matte" || surface == "plastic" ||
                         surface == "defaultsurface" || surface.empty();
    if (builtin && a->surfaceLayers.layers.empty() && a->displacement.name.empty() &&
        a->displacementLayers.layers.empty())
        return;
    for (int axis = 0; axis < 2; ++axis) {
        Param q;
        q.name = axis == 0 ? "s" : "t";
        q.cls = ParamClass::Vertex;
        q.type = ParamType::Float;
        q.nums.reserve(P.size());
        for (const Vec3d& p : P) q.nums.push_back(axis == 0 ? p.x : p.y);
        d.primvars.params.push_back(std::move(q));
    }
}

}  // namespace streyes
