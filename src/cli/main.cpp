// The streyes command. Exit codes: 0 done, 1 the command failed, 2 bad input or usage.
// Each command parses its own options with CLI11 (command_line.h) and prints its own --help.
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "streyes/error.h"

using namespace streyes;
using namespace streyes::cli;

namespace {
// A usage error: the message, the command's synopsis and where the options are, so that the
// message is not scrolled away by the whole help.
void printUsageError(const UsageError& e) {
    const UsageContext& c = usageContext();
    const std::string usage(kUsage);
    const std::string synopsis = c.synopsis.empty() ? usage.substr(0, usage.find("\n\n")) : c.synopsis;
    std::fprintf(stderr, "streyes: %s\n\n%s\n\nstreyes %s--help lists the options.\n", e.what(), synopsis.c_str(),
                 c.command.empty() ? "" : (c.command + " ").c_str());
}
}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    try {
        if (args.empty()) throw UsageError("no command given");
        if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (args[0] == "--version") {
            std::printf("streyes %s\n", STREYES_VERSION);
            return 0;
        }
        const std::vector<std::string> rest(args.begin() + 1, args.end());
        const std::string& command = args[0];
        if (command == "render") return renderCommand(rest);
        if (command == "farm") return farmCommand(rest);
        if (command == "compare") return compareCommand(rest);
        if (command == "sheet") return sheetCommand(rest);
        if (command == "shader") return shaderCommand(rest);
        if (command == "catrib") return catribCommand(rest);
        throw UsageError("unknown command '" + args[0] + "' (render, compare, sheet, shader, catrib or farm)");
    } catch (const UsageError& e) {
        printUsageError(e);
        return 2;
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.report().c_str());
        return 2;
    } catch (const RenderError& e) {
        std::fprintf(stderr, "\nstreyes: render failed: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {  // where no command said more (render does: memory.h)
        std::fprintf(stderr, "\nstreyes: failed: out of memory (an allocation failed): give it a smaller task, "
                             "or run it where more memory is free\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nstreyes: render failed: %s\n", e.what());
        return 1;
    }
}
