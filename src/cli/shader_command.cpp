// `streyes shader [-I DIR] FILE.sl ...`: compiles each shader and prints its type, name and
// parameters (what RenderMan's sloinfo prints); a bad shader's errors at file:line:column, exit 2.
#include <iostream>

#include "command_line.h"
#include "commands.h"
#include "shade/scene_shaders.h"
#include "shade/sl/compiler.h"

namespace streyes::cli {

int shaderCommand(const std::vector<std::string>& args) {
    CommandLine cl("shader", "usage: streyes shader [-I DIR ...] FILE.sl [FILE.sl ...]",
                   "\nChecks Shading Language shaders (RenderMan Interface Specification 3.2) and prints each "
                   "one's\ntype, name and parameters with their storage class, type and default. A shader with "
                   "errors\nprints them as file:line:column: what is wrong, and the command exits with 2.");
    sl::PreprocessOptions options;
    std::vector<std::string> files;
    cl.positionals("files", "the shaders (.sl)", &files)->type_name("FILE.sl");
    cl.values("-I", "DIR",
              "look for #include files in DIR (after the including file's own folder; several\n"
              "-I are searched in order, then the standard shaders' folder)",
              &options.includePath);
    cl.app().footer("Shaders are preprocessed as C is (#include, #define, #if ...); STREYES is defined.");
    if (!cl.parse(args)) return 0;
    if (files.empty()) throw UsageError("no shader given");
    // As a render without Option "searchpath" "shader" finds them.
    options.includePath.push_back(standardShaderDir());
    int code = 0;
    for (const std::string& path : files) code = std::max(code, sl::describeShader(path, std::cout, std::cerr, options));
    return code;
}

}  // namespace streyes::cli
