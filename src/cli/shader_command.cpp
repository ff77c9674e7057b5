// `streyes shader FILE.sl ...`: compiles each shader and prints its type, name and parameters
// (what RenderMan's sloinfo prints); a bad shader's errors at file:line:column, exit 2.
#include <iostream>

#include "commands.h"
#include "shade/sl/compiler.h"

namespace streyes::cli {

const char* kShaderUsage =
    "usage: streyes shader FILE.sl [FILE.sl ...]\n"
    "\n"
    "Checks Shading Language shaders (RenderMan Interface Specification 3.2) and prints each one's\n"
    "type, name and parameters with their storage class, type and default. A shader with errors\n"
    "prints them as file:line:column: what is wrong, and the command exits with 2.\n";

int shaderCommand(const std::vector<std::string>& args) {
    if (args.empty()) throw UsageError("no shader given");
    int code = 0;
    for (const std::string& path : args) {
        if (!path.empty() && path[0] == '-') throw UsageError("unknown option '" + path + "'");
        code = std::max(code, sl::describeShader(path, std::cout, std::cerr));
    }
    return code;
}

}  // namespace streyes::cli
