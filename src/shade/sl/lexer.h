// Tokens of the Shading Language (RI Spec 3.2, chapter 11), each with its line and column.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "streyes/error.h"

namespace streyes::sl {

enum class TokenKind { Ident, Number, String, Punct, End };

struct Token {
    TokenKind kind = TokenKind::End;
    std::string text;  // identifier, punctuation, or the string's value (escapes resolved)
    double number = 0;
    int line = 0, column = 0;
    size_t offset = 0, end = 0;  // where in the source: [offset, end)
};

class Lexer {
  public:
    // `file` names the source in errors ("file:line:column: ...").
    Lexer(const std::string& source, std::shared_ptr<const std::string> file);
    // The whole source as tokens, ending with one End token. Bad input throws InputError.
    std::vector<Token> tokenize();
    SourceLoc loc(int line, int column) const { return {file_, line, column}; }

  private:
    [[noreturn]] void fail(const std::string& what) const;
    void skipSpaceAndComments();
    char peek(int k = 0) const { return pos_ + size_t(k) < src_.size() ? src_[pos_ + size_t(k)] : '\0'; }
    char advance();

    const std::string& src_;
    std::shared_ptr<const std::string> file_;
    size_t pos_ = 0;
    int line_ = 1, col_ = 1;
};

}  // namespace streyes::sl
