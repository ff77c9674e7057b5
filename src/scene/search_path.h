// Search paths: Option "searchpath" "procedural" | "archive" ["dir:dir:..."], RenderMan's way, and
// the environment's after them.
//
// A path is folders separated by ':'. In a new value, '&' stands for the value before and '@'
// for the default: the folder of the RIB file that names the plug-in or archive. The stored path
// keeps '@' (it is resolved where a name is looked up, against that file's folder).
#pragma once

#include <string>
#include <vector>

namespace streyes {

constexpr const char* kDefaultSearchPath = "@";

// The path `spec` gives after `previous`: each '&' is replaced by `previous`.
std::string expandSearchPath(const std::string& spec, const std::string& previous);

// The folders of `path`, '@' replaced by `directory` (the current folder when it is empty), in order.
std::vector<std::string> searchPathFolders(const std::string& path, const std::string& directory);

// The folders an environment variable gives, separated by ':' (empty ones dropped); none when it is
// unset. STREYES_SHADERPATH, STREYES_TEXTUREPATH and STREYES_PROCEDURALPATH (kShaderPathVariable
// ...) are searched after the RIB's own search paths, as RenderMan renderers do with theirs.
std::vector<std::string> environmentSearchPath(const char* variable);
constexpr const char* kShaderPathVariable = "STREYES_SHADERPATH";
constexpr const char* kTexturePathVariable = "STREYES_TEXTUREPATH";
constexpr const char* kProceduralPathVariable = "STREYES_PROCEDURALPATH";

// The first existing regular file named `name`, or `name` + a suffix, in the folders of `path`;
// "" when there is none.
std::string findOnSearchPath(const std::string& name, const std::string& path, const std::string& directory,
                             const std::vector<std::string>& suffixes = {});

// The shared object a plug-in name names (Procedural "DynamicLoad", Blobby field plug-ins), or ""
// when there is none. A name with a '/' is a path (a relative one beside the naming file's folder
// `directory` first, then from the current folder); a bare name is looked up along `path` (Option
// "searchpath" "procedural"), then STREYES_PROCEDURALPATH's folders; each as given and with ".so".
std::string findPluginFile(const std::string& name, const std::string& path, const std::string& directory);
// Where findPluginFile looked for a name, for messages: "in folder, folder, ...".
std::string pluginSearchDescription(const std::string& name, const std::string& path, const std::string& directory);

}  // namespace streyes
