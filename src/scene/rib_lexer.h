// Tokenizer for ASCII RIB (RenderMan Interface Bytestream 3.2).
//
// The lexer turns text into requests names, numbers, strings and array brackets, each with the
// line it starts on. It knows nothing about what requests mean: grouping values into requests and
// arrays is the parser's job. Everything it rejects (an unterminated string, a stray character,
// a NaN or a number that overflows) is an InputError naming file:line.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "streyes/error.h"

namespace streyes {

enum class RibTokenKind {
    Request,     // a bare identifier: WorldBegin, Translate, ...
    Number,      // -1, .5, 1e-3 (always finite)
    String,      // "...", escapes resolved
    ArrayBegin,  // [
    ArrayEnd,    // ]
    End,         // end of input
};

struct RibToken {
    RibTokenKind kind = RibTokenKind::End;
    std::string text;   // the identifier, the string's contents, or the number as written
    double number = 0;  // for Number
    int line = 0;       // line the token starts on (1-based)
};

// A short description of a token for messages: `the number 3`, `the string "a"`, `'['`.
std::string describeToken(const RibToken& token);

class RibLexer {
  public:
    // `text` must outlive the lexer. `sourceName` names the input in messages.
    RibLexer(std::string_view text, std::shared_ptr<const std::string> sourceName);

    RibToken next();
    const RibToken& peek();

    SourceLoc loc(int line) const { return {sourceName_, line}; }
    const std::shared_ptr<const std::string>& sourceName() const { return sourceName_; }
    // The line of the last character read: where "missing ..." at end of input is reported.
    int lastLine() const { return lastLine_; }

  private:
    RibToken scan();
    void skipSpaceAndComments();
    RibToken scanString();
    RibToken scanNumber();
    RibToken scanIdentifier();
    [[noreturn]] void fail(int line, const std::string& what) const;

    std::string_view text_;
    size_t pos_ = 0;
    int line_ = 1;
    int lastLine_ = 1;
    std::shared_ptr<const std::string> sourceName_;
    bool hasPeeked_ = false;
    RibToken peeked_;
};

}  // namespace streyes
