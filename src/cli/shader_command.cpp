// `streyes shader [-I DIR] FILE.sl ...`: compiles each shader and prints its type, name and
// parameters (what RenderMan's sloinfo prints); a bad shader's errors at file:line:column, exit 2.
#include <iostream>

#include "commands.h"
#include "shade/scene_shaders.h"
#include "shade/sl/compiler.h"

namespace streyes::cli {

const char* kShaderUsage =
    "usage: streyes shader [-I DIR ...] FILE.sl [FILE.sl ...]\n"
    "\n"
    "Checks Shading Language shaders (RenderMan Interface Specification 3.2) and prints each one's\n"
    "type, name and parameters with their storage class, type and default. A shader with errors\n"
    "prints them as file:line:column: what is wrong, and the command exits with 2.\n"
    "\n"
    "  -I DIR   look for #include files in DIR (after the including file's own folder; several\n"
    "           -I are searched in order, then the standard shaders' folder)\n"
    "\n"
    "Shaders are preprocessed as C is (#include, #define, #if ...); STREYES is defined.\n";

int shaderCommand(const std::vector<std::string>& args) {
    sl::PreprocessOptions options;
    std::vector<std::string> files;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-I") {
            if (i + 1 == args.size()) throw UsageError("-I needs a folder");
            options.includePath.push_back(args[++i]);
        } else if (a.rfind("-I", 0) == 0) {
            options.includePath.push_back(a.substr(2));
        } else if (!a.empty() && a[0] == '-') {
            throw UsageError("unknown option '" + a + "'");
        } else {
            files.push_back(a);
        }
    }
    if (files.empty()) throw UsageError("no shader given");
    // As a render without Option "searchpath" "shader" finds them.
    options.includePath.push_back(standardShaderDir());
    int code = 0;
    for (const std::string& path : files) code = std::max(code, sl::describeShader(path, std::cout, std::cerr, options));
    return code;
}

}  // namespace streyes::cli
