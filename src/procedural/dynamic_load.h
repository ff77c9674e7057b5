// Procedural plug-ins: Procedural "DynamicLoad" ["name" "parameters"] with a shared object of
// the RenderMan 3.2 procedural interface, and RiProcedural with a function of the program's own.
//
// The plug-in exports ConvertParameters, Subdivide and Free (C linkage, include/ri.h). It is
// loaded (dlopen) once per path while some procedural uses it; ConvertParameters runs when the
// procedural is made into a generator; Subdivide(data, detail) runs for each expansion, with the
// expansion's RI stream current on its thread (scene/ri_stream.h), and its calls become the
// children (read as RIB under the procedural's transform and attributes); Free(data) runs when
// the generator goes, after the render. Expansions run on any thread, several at once: a plug-in's
// Subdivide must not change what it shares.
//
// The Ri functions the plug-in calls are the program's: every program linking streyes_core
// exports them (an interface link option in CMakeLists.txt: --export-dynamic-symbol=Ri*).
#pragma once

#include <memory>
#include <string>

#include "procedural/procedural.h"

namespace streyes {

// The generator of Procedural "DynamicLoad" ["name" "parameters"] for a name that is not built
// in. Throws InputError naming desc.loc when the plug-in is not found, cannot be loaded, or lacks
// one of the three functions.
std::shared_ptr<const ProceduralGenerator> makePluginGenerator(const ProceduralDesc& desc);

// The generator of Procedural "RiFunction" ["id"]: a function procedural an RI session wrote
// (RiProcedural with a function; function procedurals written by a plug-in's Subdivide are made
// into generators directly). Throws InputError when no stream holds the id.
std::shared_ptr<const ProceduralGenerator> makeFunctionGenerator(const ProceduralDesc& desc);

// The file a plug-in name resolves to, or "" when there is none. A name with a '/' is a path
// (relative ones beside the declaring file first); a bare name is looked up along
// desc.proceduralPath, as given and with ".so" added.
std::string findPlugin(const std::string& name, const ProceduralDesc& desc);

}  // namespace streyes
