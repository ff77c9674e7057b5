// A command's options through CLI11: the same option names as ever, usage errors as UsageError
// (the message names the option and says what is wrong; exit 2), --help generated from the
// options' descriptions.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace streyes::cli {

class CommandLine {
  public:
    // `name`: "render", "farm submit" ...; `synopsis`: the usage line(s) a usage error repeats;
    // `description`: what the command does, printed by --help after the synopsis.
    CommandLine(const std::string& name, const std::string& synopsis, const std::string& description);

    CLI::App& app() { return app_; }
    const std::string& synopsis() const { return synopsis_; }

    // An option whose value the command converts itself (a range, a size, a name); the last given
    // wins. `convert` throws UsageError naming the option when the value is bad.
    CLI::Option* value(const std::string& names, const std::string& typeName, const std::string& help,
                       std::function<void(const std::string&)> convert);
    CLI::Option* value(const std::string& names, const std::string& typeName, const std::string& help,
                       std::string* into);
    // Given any number of times, each value in order.
    CLI::Option* values(const std::string& names, const std::string& typeName, const std::string& help,
                        std::vector<std::string>* into);
    CLI::Option* flag(const std::string& names, const std::string& help, bool* into);
    // Words that are not options (scenes, images, subcommands), in order.
    CLI::Option* positionals(const std::string& name, const std::string& help, std::vector<std::string>* into);

    // Parses `args` (without the command's words). False when --help was asked for: the help is
    // printed on stdout and the command has nothing more to do.
    bool parse(const std::vector<std::string>& args);

  private:
    std::string synopsis_;
    CLI::App app_;
};

}  // namespace streyes::cli
