// Tokens of the Shading Language (RI Spec 3.2, chapter 11), each at its file, line and column
// (through the preprocessor's #includes and macros).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "shade/sl/preprocess.h"
#include "streyes/error.h"

namespace streyes::sl {

enum class TokenKind { Ident, Number, String, Punct, End };

struct Token {
    TokenKind kind = TokenKind::End;
    std::string text;  // identifier, punctuation, or the string's value (escapes resolved)
    double number = 0;
    SourceLoc loc;               // where it was written
    size_t offset = 0, end = 0;  // where in the preprocessed text: [offset, end)
};

class Lexer {
  public:
    explicit Lexer(const PreprocessedSource& source);
    // The whole source as tokens, ending with one End token. Bad input throws InputError.
    std::vector<Token> tokenize();

  private:
    [[noreturn]] void fail(const std::string& what) const;
    void skipSpaceAndComments();
    char peek(int k = 0) const { return pos_ + size_t(k) < src_.size() ? src_[pos_ + size_t(k)] : '\0'; }
    char advance();

    const PreprocessedSource& pp_;
    const std::string& src_;
    size_t pos_ = 0;
};

}  // namespace streyes::sl
