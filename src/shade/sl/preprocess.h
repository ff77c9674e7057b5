// The C preprocessor in front of the Shading Language compiler, as RenderMan's shader compilers
// have it: #include, #define with and without arguments, #undef, #if / #ifdef / #ifndef / #elif /
// #else / #endif with defined(), #line, #error. Boost.Wave does the work (the library Aqsis's aqsl
// uses); this keeps where every token came from, so that errors name the original file, line and
// column through includes and macros.
//
//   PreprocessedSource pp = preprocess(text, "glass.sl", {{"include", "shaders"}});
//   Lexer lexer(pp);  // tokens located through pp.marks
//
// Predefined: STREYES (1), and Boost.Wave's own standard macros (__FILE__, __LINE__, __STDC__,
// ...); nothing that claims to be another renderer.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "streyes/error.h"

namespace streyes::sl {

struct PreprocessOptions {
    // Folders searched for `#include "name"` after the including file's own folder, and for
    // `#include <name>`, in order: `streyes shader -I DIR`, then the shader search path.
    std::vector<std::string> includePath;
};

struct PreprocessedSource {
    std::string text;  // the tokens: directives and comments gone, macros expanded

    // Where the text came from: the text from `offset` on (to the next mark) is at `loc`, the
    // column counting on within it. A token a macro's body made is at its place in the #define.
    struct Mark {
        size_t offset = 0;
        SourceLoc loc;
    };
    std::vector<Mark> marks;  // sorted by offset

    // Every file read: the shader's own first (as named), then what it included, once each.
    std::vector<std::string> files;
    // #warning, and a macro defined twice differently: where, and what.
    std::vector<std::pair<SourceLoc, std::string>> warnings;

    // Where each macro expansion was called from. The tokens one expansion made share a file
    // name string of their own (its pointer tells them apart), so an error at one of them can say
    // which call it is about.
    std::vector<std::pair<const std::string*, SourceLoc>> expansions;

    // Where text[offset] came from.
    SourceLoc locate(size_t offset) const;
    // "in the expansion of the macro at a.sl:3:20" when `loc` is at a token a macro made, else "".
    std::string expansionOf(const SourceLoc& loc) const;
};

// Preprocesses `source`, named `file` (its folder is where its own #includes are looked for
// first). Errors (an #include not found, a macro given the wrong number of arguments, an #if
// without its #endif, files that include each other without end, #error) throw InputError at the
// original file:line:column.
PreprocessedSource preprocess(const std::string& source, const std::string& file,
                              const PreprocessOptions& options = {});

}  // namespace streyes::sl
