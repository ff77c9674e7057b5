// The streyes command. Exit codes: 0 done, 1 the command failed, 2 bad input or usage.
#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"
#include "streyes/error.h"

using namespace streyes;
using namespace streyes::cli;

namespace {
bool asksForHelp(const std::vector<std::string>& args) {
    for (const std::string& a : args)
        if (a == "--help" || a == "-h") return true;
    return false;
}

// A usage error: the message, the command's synopsis (its usage up to the first blank line) and
// where the options are, so that the message is not scrolled away by the whole help.
void printUsageError(const char* message, const char* usage, const std::string& command) {
    const std::string text = usage;
    const size_t end = text.find("\n\n");
    std::fprintf(stderr, "streyes: %s\n\n%s\n\nstreyes %s--help lists the options.\n", message,
                 text.substr(0, end).c_str(), command.empty() ? "" : (command + " ").c_str());
}
}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    const char* usage = kUsage;  // printed with a usage error: the command's own, once it is known
    std::string command;         // "render", "farm" ...: whose --help the error points to
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
        if (args[0] == "render") {
            command = "render";
            std::vector<std::string> rest(args.begin() + 1, args.end());
            for (const std::string& a : rest)
                if (a == "--help" || a == "-h") {
                    std::fputs(kUsage, stdout);
                    return 0;
                }
            return renderCommand(rest);
        }
        if (args[0] == "farm") {
            usage = kFarmUsage;
            command = "farm";
            std::vector<std::string> rest(args.begin() + 1, args.end());
            // Help for farm itself; `--` ends farm's options (what follows goes to sbatch).
            for (const std::string& a : rest) {
                if (a == "--") break;
                if (a == "--help" || a == "-h") {
                    std::fputs(kFarmUsage, stdout);
                    return 0;
                }
            }
            return farmCommand(rest);
        }
        if (args[0] == "compare" || args[0] == "sheet" || args[0] == "shader" || args[0] == "catrib") {
            usage = args[0] == "compare" ? kCompareUsage
                    : args[0] == "sheet" ? kSheetUsage
                    : args[0] == "shader" ? kShaderUsage
                                          : kCatribUsage;
            command = args[0];
            std::vector<std::string> rest(args.begin() + 1, args.end());
            if (asksForHelp(rest)) {
                std::fputs(usage, stdout);
                return 0;
            }
            if (args[0] == "shader") return shaderCommand(rest);
            if (args[0] == "catrib") return catribCommand(rest);
            return args[0] == "compare" ? compareCommand(rest) : sheetCommand(rest);
        }
        throw UsageError("unknown command '" + args[0] + "'");
    } catch (const UsageError& e) {
        printUsageError(e.what(), usage, command);
        return 2;
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.report().c_str());
        return 2;
    } catch (const RenderError& e) {
        std::fprintf(stderr, "\nstreyes: render failed: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "\nstreyes: render failed: %s\n", e.what());
        return 1;
    }
}
