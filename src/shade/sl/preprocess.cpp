// Boost.Wave drives the preprocessing; the hooks below find #include files along the shader's
// path, stop recursion through includes, note where each macro expansion was called, and turn
// Wave's warnings into ours. Wave is heavy to compile: only this file includes it.
#include "shade/sl/preprocess.h"

#include <algorithm>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <boost/wave.hpp>
#include <boost/wave/cpplexer/cpp_lex_iterator.hpp>
#include <boost/wave/cpplexer/cpp_lex_token.hpp>

namespace streyes::sl {

namespace {

namespace fs = std::filesystem;
namespace wave = boost::wave;

using WaveToken = wave::cpplexer::lex_token<>;
using WaveLexIterator = wave::cpplexer::lex_iterator<WaveToken>;
using WavePosition = WaveToken::position_type;

// An error the hooks name themselves (recursion through includes).
struct HookError {
    SourceLoc loc;
    std::string what;
};

// What one preprocessing run knows besides Wave's own state.
struct State {
    const PreprocessOptions* options = nullptr;
    PreprocessedSource* out = nullptr;
    // The display name of each file by the name Wave gives it (Wave makes paths absolute).
    std::map<std::string, std::shared_ptr<const std::string>> names;
    std::map<std::string, std::shared_ptr<const std::string>> byCanonical;
    // The files being read, outermost first (display names, and canonical ones for recursion).
    std::vector<std::string> stack, canonicalStack;
    SourceLoc directive;   // the last directive's '#'
    bool inDirective = false;  // macros expanded in #if, #elif, #include NAME, #line make no text
    // Macro expansions: nesting, the outermost call, and those whose tokens are still to come.
    int depth = 0;
    SourceLoc callSite;
    struct Pending {
        SourceLoc site;
        size_t tokens = 0;  // non-blank tokens of the expansion still to be written
        std::map<const std::string*, std::shared_ptr<const std::string>> files;  // a name of its own per file
    };
    std::deque<Pending> pending;

    std::string canonical(const std::string& path) const {
        std::error_code ec;
        const fs::path absolute = fs::absolute(fs::path(path), ec);
        fs::path c = fs::weakly_canonical(absolute, ec);
        return ec ? absolute.lexically_normal().string() : c.string();
    }

    void addFile(const std::string& display) {
        auto name = std::make_shared<const std::string>(display);
        byCanonical.emplace(canonical(display), name);
        names.emplace(display, name);
        if (std::find(out->files.begin(), out->files.end(), display) == out->files.end()) out->files.push_back(display);
    }

    // The display name of the file Wave calls `waveName`.
    std::shared_ptr<const std::string> name(const std::string& waveName) {
        auto it = names.find(waveName);
        if (it != names.end()) return it->second;
        auto c = byCanonical.find(canonical(waveName));
        auto name = c != byCanonical.end() ? c->second : std::make_shared<const std::string>(waveName);  // #line "x"
        names.emplace(waveName, name);
        return name;
    }

    SourceLoc loc(const WavePosition& p) {
        return {name(p.get_file().c_str()), int(p.get_line()), int(p.get_column())};
    }
};

// A backslash C has no escape for ("\%" in a format string, which the Shading Language keeps)
// would end a string for Wave's C lexer: it becomes byte 0xff (never in UTF-8; one for one, so
// columns hold), and a backslash again when the text is written.
constexpr char kHiddenBackslash = '\xff';

std::string hideOddEscapes(std::string text) {
    const char* const kEscapes = "abfnrtv?'\"\\01234567xuU\r\n";
    bool inString = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i], next = i + 1 < text.size() ? text[i + 1] : '\0';
        if (!inString) {
            if (c == '"') {
                inString = true;
            } else if (c == '/' && next == '/') {
                while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
            } else if (c == '/' && next == '*') {
                const size_t end = text.find("*/", i + 2);
                i = end == std::string::npos ? text.size() : end + 1;
            }
        } else if (c == '"' || c == '\n') {
            inString = false;  // the end (a newline: an unterminated string, the lexer's to report)
        } else if (c == '\\' && next != '\0') {
            if (!std::strchr(kEscapes, next)) text[i] = kHiddenBackslash;
            ++i;
        }
    }
    return text;
}

// Wave's load_file_to_string, with hideOddEscapes: how #included files are read.
struct LoadShaderFile {
    template <typename IterContextT>
    class inner {
      public:
        template <typename PositionT>
        static void init_iterators(IterContextT& iter_ctx, PositionT const& act_pos, wave::language_support language) {
            using iterator_type = typename IterContextT::iterator_type;
            std::ifstream in(iter_ctx.filename.c_str(), std::ios::binary);
            if (!in) {
                BOOST_WAVE_THROW_CTX(iter_ctx.ctx, wave::preprocess_exception, bad_include_file,
                                     iter_ctx.filename.c_str(), act_pos);
                return;
            }
            std::stringstream ss;
            ss << in.rdbuf();
            iter_ctx.instring = hideOddEscapes(ss.str());
            iter_ctx.first = iterator_type(iter_ctx.instring.begin(), iter_ctx.instring.end(),
                                           PositionT(iter_ctx.filename), language);
            iter_ctx.last = iterator_type();
        }

      private:
        std::string instring;
    };
};

bool isBlank(wave::token_id id) {
    return IS_CATEGORY(id, wave::WhiteSpaceTokenType) || IS_CATEGORY(id, wave::EOLTokenType) ||
           IS_CATEGORY(id, wave::EOFTokenType) || id == wave::T_PLACEHOLDER || id == wave::T_EOI;
}

class Hooks : public wave::context_policies::eat_whitespace<WaveToken> {
  public:
    explicit Hooks(State* s = nullptr) : s_(s) {}

    template <typename ContextT, typename TokenT>
    bool found_directive(ContextT const&, TokenT const& directive) {
        s_->directive = s_->loc(directive.get_position());
        const wave::token_id id = wave::token_id(directive);
        if (id == wave::T_PP_IF || id == wave::T_PP_ELIF || id == wave::T_PP_INCLUDE || id == wave::T_PP_LINE)
            s_->inDirective = true;
        return false;
    }

    // The ends of the directives whose macros were expanded.
    template <typename ContextT>
    bool found_include_directive(ContextT const&, std::string const&, bool) {
        s_->inDirective = false;
        return false;
    }
    template <typename ContextT, typename ContainerT>
    void found_line_directive(ContextT const&, ContainerT const&, unsigned int, std::string const&) {
        s_->inDirective = false;
    }

    template <typename ContextT, typename TokenT, typename ContainerT>
    bool evaluated_conditional_expression(ContextT const&, TokenT const&, ContainerT const&, bool) {
        s_->inDirective = false;
        return false;
    }

    // #include "name": the including file's folder, then the path; #include <name>: the path.
    template <typename ContextT>
    bool locate_include_file(ContextT&, std::string& filePath, bool isSystem, char const*, std::string& dirPath,
                             std::string& nativeName) {
        std::vector<fs::path> candidates;
        const fs::path name(filePath);
        if (name.is_absolute()) {
            candidates.push_back(name);
        } else {
            if (!isSystem) candidates.push_back(fs::path(s_->stack.back()).parent_path() / name);
            for (const std::string& dir : s_->options->includePath) candidates.push_back(fs::path(dir) / name);
        }
        std::error_code ec;
        for (const fs::path& c : candidates) {
            if (!fs::is_regular_file(c, ec)) continue;
            const std::string found = c.lexically_normal().string();
            const std::string canon = s_->canonical(found);
            // A file open twice already is being read again without an include guard to stop it.
            if (std::count(s_->canonicalStack.begin(), s_->canonicalStack.end(), canon) >= 2) {
                std::string chain;
                for (size_t i = 0; i < s_->stack.size(); ++i)
                    if (s_->canonicalStack[i] == canon || !chain.empty()) chain += s_->stack[i] + " includes ";
                throw HookError{s_->directive, "recursion through #include: " + chain + found + " again (an include guard, #ifndef NAME / #define NAME ... #endif, stops it)"};
            }
            filePath = dirPath = nativeName = found;
            return true;
        }
        return false;
    }

    template <typename ContextT>
    void opened_include_file(ContextT const&, std::string const&, std::string const& absname, bool) {
        s_->addFile(absname);
        s_->stack.push_back(absname);
        s_->canonicalStack.push_back(s_->canonical(absname));
    }

    template <typename ContextT>
    void returning_from_include_file(ContextT const&) {
        if (s_->stack.size() > 1) {
            s_->stack.pop_back();
            s_->canonicalStack.pop_back();
        }
    }

    template <typename ContextT, typename TokenT, typename ContainerT, typename IteratorT>
    bool expanding_function_like_macro(ContextT const&, TokenT const&, std::vector<TokenT> const&, ContainerT const&,
                                       TokenT const& call, std::vector<ContainerT> const&, IteratorT const&,
                                       IteratorT const&) {
        entered(call.get_position());
        return false;
    }

    template <typename ContextT, typename TokenT, typename ContainerT>
    bool expanding_object_like_macro(ContextT const&, TokenT const&, ContainerT const&, TokenT const& call) {
        entered(call.get_position());
        return false;
    }

    template <typename ContextT, typename ContainerT>
    void rescanned_macro(ContextT const&, ContainerT const& result) {
        if (s_->inDirective) return;
        if (--s_->depth > 0) return;
        State::Pending p;
        p.site = s_->callSite;
        for (const auto& t : result)
            if (!isBlank(wave::token_id(t))) ++p.tokens;
        if (p.tokens) s_->pending.push_back(std::move(p));
    }

    template <typename ContextT, typename ContainerT>
    bool found_warning_directive(ContextT const&, ContainerT const& message) {
        std::string text;
        for (const auto& t : message) text += t.get_value().c_str();
        warn(s_->directive, "#warning " + text);
        return true;  // said; go on
    }

  private:
    void entered(const WavePosition& call) {
        if (s_->inDirective) return;
        if (s_->depth++ == 0) s_->callSite = s_->loc(call);
    }
    void warn(const SourceLoc& at, const std::string& what) {
        s_->out->warnings.emplace_back(at, what);
    }

    State* s_;
};

using Context = wave::context<std::string::const_iterator, WaveLexIterator, LoadShaderFile, Hooks>;

// C99 (no C++ keywords or alternative tokens), pp-numbers as C has them (1.5x stays one token,
// for the lexer to refuse), whitespace kept between tokens a macro puts side by side.
const wave::language_support kLanguage = wave::language_support(
    wave::support_c99 | wave::support_option_variadics | wave::support_option_insert_whitespace |
    wave::support_option_prefer_pp_numbers | wave::support_option_no_newline_at_end_of_file);

// Wave's descriptions start with the severity ("error: ...").
std::string describe(const char* description) {
    std::string d = description;
    for (const char* prefix : {"fatal error: ", "error: ", "warning: ", "remark: "})
        if (d.rfind(prefix, 0) == 0) return d.substr(std::string(prefix).size());
    return d;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Wave notices a missing #endif only at the end of everything: find the #if that has none, in
// the first file read whose conditionals do not balance.
bool findUnclosedIf(const std::string& mainSource, State& s, SourceLoc* at) {
    for (size_t f = 0; f < s.out->files.size(); ++f) {
        const std::string& file = s.out->files[f];
        const std::string text = f == 0 ? mainSource : readFile(file);
        std::vector<WavePosition> open;
        try {
            WaveLexIterator it(text.begin(), text.end(), WavePosition(file.c_str()), kLanguage), end;
            for (; it != end; ++it) {
                const wave::token_id id = wave::token_id(*it);
                if (id == wave::T_PP_IF || id == wave::T_PP_IFDEF || id == wave::T_PP_IFNDEF) open.push_back(it->get_position());
                else if (id == wave::T_PP_ENDIF && !open.empty()) open.pop_back();
            }
        } catch (const wave::cpplexer::cpplexer_exception&) {
            continue;
        }
        if (!open.empty()) {
            *at = s.loc(open.back());
            return true;
        }
    }
    return false;
}

// The "/*" of the comment that runs to the end of `text` (strings and // comments skipped).
void findCommentStart(const std::string& text, SourceLoc* at) {
    int line = 1, column = 1;
    for (size_t i = 0; i < text.size(); ++i, ++column) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            column = 0;
        } else if (c == '"') {
            for (++i, ++column; i < text.size() && text[i] != '"' && text[i] != '\n'; ++i, ++column)
                if (text[i] == '\\') ++i, ++column;
            if (i < text.size() && text[i] == '\n') --i, --column;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i + 1 < text.size() && text[i + 1] != '\n') ++i, ++column;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            const size_t end = text.find("*/", i + 2);
            if (end == std::string::npos) {
                at->line = line;
                at->column = column;
                return;
            }
            for (; i < end + 1; ++i, ++column)
                if (text[i] == '\n') ++line, column = 0;
        }
    }
}

[[noreturn]] void fail(const Context& ctx, State& s, const std::string& source, SourceLoc at, int code,
                       const std::string& description, const std::string& related) {
    using E = wave::preprocess_exception;
    // Directive errors carry the directive's line: give the column of its '#'.
    if (s.directive.file && at.file == s.directive.file && at.line == s.directive.line && at.column <= 1)
        at.column = s.directive.column;
    std::string what = description;
    switch (code) {
        case E::bad_include_file: {
            // Wave names the file in its description ("could not find include file: x.h").
            const size_t colon = description.rfind(": ");
            const std::string name = colon == std::string::npos ? related : description.substr(colon + 2);
            std::string path;
            for (const std::string& d : s.options->includePath) path += (path.empty() ? "" : ":") + d;
            what = "#include \"" + name + "\": no such file in the including file's folder" +
                   (path.empty() ? std::string(" (no include path: give one with streyes shader -I DIR, or Option \"searchpath\" \"shader\")")
                                 : " or along " + path);
            break;
        }
        case E::missing_matching_endif:
            if (findUnclosedIf(source, s, &at)) what = "this #if has no #endif";
            else what = "an #if has no #endif";
            break;
        case E::unbalanced_if_endif:  // an included file's #if without #endif
            if (findUnclosedIf(source, s, &at)) what = "this #if has no #endif";
            break;
        case E::too_few_macroarguments:
        case E::too_many_macroarguments:
        case E::empty_macroarguments: {
            // Wave names the macro in its description ("too many macro arguments: SQ").
            const size_t colon = description.rfind(": ");
            const std::string macro = colon == std::string::npos ? related : description.substr(colon + 2);
            bool hasParams = false, predefined = false;
            WavePosition defined;
            std::vector<WaveToken> params;
            Context::token_sequence_type body;
            what = std::string(code == E::too_many_macroarguments ? "too many" : "too few") + " arguments for macro '" + macro + "'";
            if (ctx.get_macro_definition(macro, hasParams, predefined, defined, params, body)) {
                std::string list;
                for (const WaveToken& p : params) list += (list.empty() ? "" : ", ") + std::string(p.get_value().c_str());
                what += ": it takes " + std::to_string(params.size()) + " (" + list + "), defined at " + s.loc(defined).str();
            }
            break;
        }
        default: break;
    }
    throw InputError(at, what);
}

}  // namespace

SourceLoc PreprocessedSource::locate(size_t offset) const {
    auto it = std::upper_bound(marks.begin(), marks.end(), offset,
                               [](size_t o, const Mark& m) { return o < m.offset; });
    if (it == marks.begin()) return marks.empty() ? SourceLoc{} : marks.front().loc;
    --it;
    SourceLoc loc = it->loc;
    if (loc.column > 0) loc.column += int(offset - it->offset);
    return loc;
}

std::string PreprocessedSource::expansionOf(const SourceLoc& loc) const {
    for (const auto& [file, site] : expansions)
        if (file == loc.file.get()) return "in the expansion of the macro at " + site.str();
    return "";
}

PreprocessedSource preprocess(const std::string& source, const std::string& file, const PreprocessOptions& options) {
    PreprocessedSource out;
    State s;
    s.options = &options;
    s.out = &out;
    s.addFile(file);
    s.stack.push_back(file);
    s.canonicalStack.push_back(s.canonical(file));
    s.directive = {s.name(file), 1, 1};

    const std::string input = hideOddEscapes(source);
    Context ctx(input.begin(), input.end(), file.c_str(), Hooks(&s));
    ctx.set_language(kLanguage);
    ctx.add_macro_definition("STREYES=1", true);

    // Where the source ends (what "found the end of the file" points at).
    const int endLine = 1 + int(std::count(source.begin(), source.end(), '\n'));
    const int endColumn = 1 + int(source.size() - (source.rfind('\n') == std::string::npos ? 0 : source.rfind('\n') + 1));
    bool inPragma = false;
    try {
        Context::iterator_type it = ctx.begin(), end = ctx.end();
        // A macro defined again differently is thrown past the hooks (by whichever step reads
        // the directive): said, and Wave goes on.
        auto guarded = [&](auto step) {
            for (;;) {
                try {
                    return step();
                } catch (const wave::preprocess_exception& e) {
                    if (e.get_errorcode() != wave::preprocess_exception::macro_redefinition) throw;
                    SourceLoc at{s.name(e.file_name()), int(e.line_no()), int(e.column_no())};
                    if (s.directive.file == at.file && s.directive.line == at.line) at.column = s.directive.column;
                    out.warnings.emplace_back(at, std::string("macro '") + e.get_related_name() +
                                                      "' is defined again differently: the first definition is kept");
                }
            }
        };
        for (;; guarded([&] { ++it; })) {
            if (guarded([&] { return it == end; })) break;
            const WaveToken t = guarded([&] { return *it; });
            const wave::token_id id = wave::token_id(t);
            if (IS_CATEGORY(id, wave::EOLTokenType)) {
                inPragma = false;
                out.text += '\n';
                continue;
            }
            if (IS_CATEGORY(id, wave::EOFTokenType)) continue;
            if (id == wave::T_PP_PRAGMA) inPragma = true;  // #pragma: for other tools; nothing here
            if (inPragma || id == wave::T_PLACEHOLDER) continue;
            if (IS_CATEGORY(id, wave::WhiteSpaceTokenType)) {
                out.text += id == wave::T_SPACE || id == wave::T_SPACE2 ? t.get_value().c_str() : " ";
                continue;
            }
            SourceLoc loc = s.loc(t.get_position());
            if (!s.pending.empty()) {
                // A token of a macro's expansion: a file name of this expansion's own.
                State::Pending& p = s.pending.front();
                auto& own = p.files[loc.file.get()];
                if (!own) {
                    own = std::make_shared<const std::string>(*loc.file);
                    out.expansions.emplace_back(own.get(), p.site);
                }
                loc.file = own;
                if (--p.tokens == 0) s.pending.pop_front();
            }
            out.marks.push_back({out.text.size(), std::move(loc)});
            const size_t at = out.text.size();
            out.text += t.get_value().c_str();
            std::replace(out.text.begin() + std::ptrdiff_t(at), out.text.end(), kHiddenBackslash, '\\');
        }
        out.marks.push_back({out.text.size(), {s.name(file), endLine, endColumn}});
    } catch (const HookError& e) {
        throw InputError(e.loc, e.what);
    } catch (const wave::cpp_exception& e) {
        SourceLoc at{s.name(e.file_name()), int(e.line_no()), int(e.column_no())};
        fail(ctx, s, source, at, e.get_errorcode(), describe(e.description()), e.get_related_name());
    } catch (const wave::cpplexer::cpplexer_exception& e) {
        SourceLoc at{s.name(e.file_name()), int(e.line_no()), int(e.column_no())};
        const std::string what = describe(e.description());
        if (what.find("Unterminated 'C' style comment") != std::string::npos) {
            // Wave finds it at the end of the file: say where the comment opens.
            const std::string text = at.file && *at.file == file ? source : readFile(at.file ? *at.file : "");
            findCommentStart(text, &at);
            throw InputError(at, "unterminated comment");
        }
        throw InputError(at, what);
    }
    return out;
}

}  // namespace streyes::sl
