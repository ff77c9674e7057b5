#include "command_line.h"

#include <cstdio>

#include "commands.h"

namespace streyes::cli {

namespace {

// The help in streyes's words: the synopsis first, option groups in lower case, and a column wide
// enough for "--layers N|adaptive".
class Formatter : public CLI::Formatter {
  public:
    explicit Formatter(std::string synopsis) : synopsis_(std::move(synopsis)) {
        column_width(24);
        label("Positionals", "arguments");
        label("REQUIRED", "required");
    }
    std::string make_usage(const CLI::App* app, std::string) const override {
        return synopsis_ + "\n" + app->get_description() + "\n";
    }
    std::string make_description(const CLI::App*) const override { return ""; }

  private:
    std::string synopsis_;
};

bool looksLikeOption(const std::string& a) {
    if (a.size() < 2 || a[0] != '-') return false;
    // A negative number is a value, not an option.
    return !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.');
}

}  // namespace

CommandLine::CommandLine(const std::string& name, const std::string& synopsis, const std::string& description)
    : synopsis_(synopsis), app_(description, "streyes " + name) {
    usageContext() = {name, synopsis};
    app_.formatter(std::make_shared<Formatter>(synopsis));
    // What is not an option of the command is reported by parse() in streyes's words.
    app_.allow_extras();
    // Given twice, the last wins (as scripts that append an option expect).
    app_.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)->group("options");
    app_.set_help_flag("-h,--help", "print this help and exit");
}

CLI::Option* CommandLine::value(const std::string& names, const std::string& typeName, const std::string& help,
                                std::function<void(const std::string&)> convert) {
    return app_.add_option_function<std::string>(names, std::move(convert), help)->type_name(typeName);
}

CLI::Option* CommandLine::value(const std::string& names, const std::string& typeName, const std::string& help,
                                std::string* into) {
    return app_.add_option(names, *into, help)->type_name(typeName);
}

CLI::Option* CommandLine::values(const std::string& names, const std::string& typeName, const std::string& help,
                                 std::vector<std::string>* into) {
    // One value each time it is given: `--option A scene.rib` leaves the scene alone.
    return app_.add_option(names, *into, help)
        ->type_name(typeName)
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

CLI::Option* CommandLine::flag(const std::string& names, const std::string& help, bool* into) {
    return app_.add_flag(names, *into, help);
}

CLI::Option* CommandLine::positionals(const std::string& name, const std::string& help,
                                      std::vector<std::string>* into) {
    return app_.add_option(name, *into, help)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

bool CommandLine::parse(const std::vector<std::string>& args) {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    try {
        app_.parse(reversed);
    } catch (const CLI::CallForHelp&) {
        std::fputs(app_.help().c_str(), stdout);
        return false;
    } catch (const CLI::ArgumentMismatch& e) {
        // "--frames: 1 required A-B missing": the option, and what it takes.
        const std::string what = e.what();
        const std::string name = what.substr(0, what.find(':'));
        const CLI::Option* opt = app_.get_option_no_throw(name);
        if (opt && what.find("missing") != std::string::npos) {
            // Named as it was given ("-o", not "--output"): the last word that is one of its names.
            std::string given = name;
            for (auto a = args.rbegin(); a != args.rend(); ++a)
                if (opt->check_name(*a)) {
                    given = *a;
                    break;
                }
            throw UsageError(given + " needs a value (" + given + " " + opt->get_type_name() + ")");
        }
        throw UsageError(what);
    } catch (const CLI::ParseError& e) {
        throw UsageError(e.what());
    }
    for (const std::string& extra : app_.remaining()) {
        if (looksLikeOption(extra) && extra != "--")
            throw UsageError("unknown option '" + extra.substr(0, extra.find('=')) + "'");
    }
    return true;
}

}  // namespace streyes::cli
