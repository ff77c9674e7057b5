// Tokenizer for RIB (RenderMan Interface Bytestream 3.2): ASCII, binary (RI Spec 3.2, Appendix C)
// and both mixed in one stream.
//
// The lexer turns bytes into request names, numbers, strings and array brackets, each with the
// line it starts on (and, for a binary token, its byte offset). It knows nothing about what
// requests mean: grouping values into requests and arrays is the parser's job. Everything it
// rejects (an unterminated string, a stray character, a NaN or a number that overflows, a
// malformed binary token) is an InputError naming file:line (binary: the file and byte offset).
//
// rib_lexer.cpp reads the ASCII encoding, rib_binary.cpp the binary one: a byte of 0200 or more
// outside a string or comment starts a binary token. Gzip is undone before the lexer (rib_gzip.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "streyes/error.h"

namespace streyes {

enum class RibTokenKind {
    Request,     // a bare identifier: WorldBegin, Translate, ...
    Number,      // -1, .5, 1e-3 (always finite)
    String,      // "...", escapes resolved
    ArrayBegin,  // [
    ArrayEnd,    // ]
    NumberArray, // a binary float array (0310): a whole [...] of numbers in one token
    End,         // end of input
};

struct RibToken {
    RibTokenKind kind = RibTokenKind::End;
    std::string text;   // the identifier, the string's contents, or the number as written (ASCII)
    double number = 0;  // for Number
    std::vector<double> numbers;  // for NumberArray
    int line = 0;       // line the token starts on (1-based)
    long long offset = -1;  // binary tokens: the byte they start at; -1 for ASCII ones
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
    SourceLoc loc(const RibToken& token) const { return {sourceName_, token.line, 0, token.offset}; }
    const std::shared_ptr<const std::string>& sourceName() const { return sourceName_; }
    // The line of the last character read: where "missing ..." at end of input is reported.
    int lastLine() const { return lastLine_; }
    // Where the last token read starts (its line, and its byte offset if it was binary).
    SourceLoc lastLoc() const { return {sourceName_, lastLine_, 0, lastOffset_}; }

  private:
    RibToken scan();
    void skipSpaceAndComments();
    RibToken scanString();
    RibToken scanNumber();
    RibToken scanIdentifier();
    [[noreturn]] void fail(int line, const std::string& what) const;

    // Binary RIB (rib_binary.cpp). Definitions (0314, 0315, 0316) give no token: false.
    bool scanBinary(RibToken& token);
    RibToken scanBinaryString(size_t start, unsigned char code);
    RibToken scanDefinedString(size_t start, unsigned char code);
    RibToken scanStringOperand(size_t definition, const char* what);
    double scanBinaryNumber(size_t start, unsigned char code);
    uint32_t readUnsigned(size_t start, int bytes, const char* what);
    const char* need(size_t start, size_t bytes, const char* what);
    [[noreturn]] void failAt(size_t offset, const std::string& what) const;
    struct BinaryTables {
        std::array<std::string, 256> requests;  // 0314 code -> request name ("" undefined)
        std::vector<std::string> strings;       // 0315/0316 index -> string
        std::vector<bool> stringDefined;
    };

    std::string_view text_;
    size_t pos_ = 0;
    int line_ = 1;
    int lastLine_ = 1;
    long long lastOffset_ = -1;
    std::unique_ptr<BinaryTables> tables_;  // made at the first binary definition
    std::shared_ptr<const std::string> sourceName_;
    bool hasPeeked_ = false;
    RibToken peeked_;
};

}  // namespace streyes
