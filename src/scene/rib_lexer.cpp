#include "scene/rib_lexer.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace streyes {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isAlpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isWordChar(char c) { return isAlpha(c) || isDigit(c); }

std::string lower(std::string_view s) {
    std::string r(s);
    for (char& c : r)
        if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
    return r;
}

// "nan", "inf", "-Infinity", ...: words that some writers emit for non-finite values.
bool isNonFiniteWord(std::string_view word) {
    if (!word.empty() && (word[0] == '+' || word[0] == '-')) word.remove_prefix(1);
    std::string w = lower(word);
    return w == "nan" || w == "inf" || w == "infinity" || w.rfind("nan(", 0) == 0;
}

std::string printableChar(unsigned char c) {
    if (c >= 0x20 && c < 0x7f) return std::string("'") + char(c) + "'";
    char buf[16];
    std::snprintf(buf, sizeof buf, "byte 0x%02x", c);
    return buf;
}

}  // namespace

std::string describeToken(const RibToken& token) {
    switch (token.kind) {
    case RibTokenKind::Request: return "the request name '" + token.text + "'";
    case RibTokenKind::Number: {
        if (!token.text.empty()) return "the number " + token.text;
        char buf[32];  // a binary number: no text as written
        std::snprintf(buf, sizeof buf, "%.17g", token.number);
        return std::string("the number ") + buf;
    }
    case RibTokenKind::NumberArray: return "an array of " + std::to_string(token.numbers.size()) + " numbers";
    case RibTokenKind::String: return "the string \"" + token.text + "\"";
    case RibTokenKind::ArrayBegin: return "'['";
    case RibTokenKind::ArrayEnd: return "']'";
    case RibTokenKind::End: return "the end of the input";
    }
    return "?";
}

RibLexer::RibLexer(std::string_view text, std::shared_ptr<const std::string> sourceName)
    : text_(text), sourceName_(std::move(sourceName)) {}

RibToken RibLexer::next() {
    if (hasPeeked_) {
        hasPeeked_ = false;
        return std::move(peeked_);
    }
    return scan();
}

const RibToken& RibLexer::peek() {
    if (!hasPeeked_) {
        peeked_ = scan();
        hasPeeked_ = true;
    }
    return peeked_;
}

void RibLexer::fail(int line, const std::string& what) const { throw InputError(loc(line), what); }

// ---- Whitespace and comments ----------------------------------------------------------------
// `#` starts a comment that runs to the end of the line (`##` structure comments included).
void RibLexer::skipSpaceAndComments() {
    while (pos_ < text_.size()) {
        char c = text_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        } else if (isSpace(c)) {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        } else {
            return;
        }
    }
}

// Each branch returns the token it makes (no token is moved on the way: this is the hot path).
RibToken RibLexer::scan() {
    while (true) {
        skipSpaceAndComments();
        if (pos_ >= text_.size()) {
            RibToken token;
            token.kind = RibTokenKind::End;
            token.line = line_;
            return token;
        }
        const char c = text_[pos_];
        lastLine_ = line_;  // where the token starts
        lastOffset_ = -1;
        if (c == '[' || c == ']') {
            ++pos_;
            RibToken token;
            token.kind = c == '[' ? RibTokenKind::ArrayBegin : RibTokenKind::ArrayEnd;
            token.text.assign(1, c);
            token.line = line_;
            return token;
        }
        if (c == '"') return scanString();
        if (isDigit(c) || c == '-' || c == '+' || c == '.') return scanNumber();
        if (isAlpha(c)) return scanIdentifier();
        const unsigned char u = static_cast<unsigned char>(c);
        if (u >= 0200) {
            lastOffset_ = static_cast<long long>(pos_);
            RibToken token;
            if (scanBinary(token)) return token;
            continue;  // a definition: on to the next token
        }
        const std::string hint = u < 0x20 ? " (a control character: is this a RIB file?)"
                                          : " (RIB has requests, numbers, \"strings\", [arrays] and # comments)";
        fail(line_, "unexpected character " + printableChar(u) + hint);
    }
}

// ---- Strings ------------------------------------------------------------------------------------
// C escapes: \n \t \r \b \f \\ \" \' and up to three octal digits; a backslash before a newline
// continues the string on the next line. Strings may span lines; one still open at the end of
// the input is reported at the line it began.
RibToken RibLexer::scanString() {
    RibToken token;
    token.kind = RibTokenKind::String;
    token.line = line_;
    ++pos_;  // opening quote
    std::string& s = token.text;
    while (true) {
        if (pos_ >= text_.size())
            fail(token.line, "unterminated string: the '\"' opened here has no closing '\"'");
        char c = text_[pos_++];
        if (c == '"') break;
        if (c == '\n') ++line_;
        if (c != '\\') {
            s += c;
            continue;
        }
        if (pos_ >= text_.size())
            fail(token.line, "unterminated string: the '\"' opened here has no closing '\"'");
        char e = text_[pos_++];
        switch (e) {
        case 'n': s += '\n'; break;
        case 't': s += '\t'; break;
        case 'r': s += '\r'; break;
        case 'b': s += '\b'; break;
        case 'f': s += '\f'; break;
        case '\\': s += '\\'; break;
        case '"': s += '"'; break;
        case '\'': s += '\''; break;
        case '\n': ++line_; break;  // line continuation
        default:
            if (e >= '0' && e <= '7') {
                int value = e - '0';
                for (int i = 0; i < 2 && pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '7'; ++i)
                    value = value * 8 + (text_[pos_++] - '0');
                s += char(value & 0xff);
            } else {
                s += e;  // an unknown escape stands for the character itself, as in most RIB readers
            }
        }
    }
    return token;
}

// ---- Numbers ------------------------------------------------------------------------------------
// The token runs over every character that could belong to a number or a word, so that "1x" or
// "1.2.3" is one malformed number rather than a number followed by something else.
RibToken RibLexer::scanNumber() {
    RibToken token;
    token.kind = RibTokenKind::Number;
    token.line = line_;
    size_t start = pos_;
    while (pos_ < text_.size() &&
           (isWordChar(text_[pos_]) || text_[pos_] == '.' || text_[pos_] == '+' || text_[pos_] == '-'))
        ++pos_;
    std::string_view word = text_.substr(start, pos_ - start);
    token.text = std::string(word);
    if (isNonFiniteWord(word))
        fail(token.line, "'" + token.text + "' is not a valid number: NaN and infinity are not allowed in scenes");

    // std::from_chars is locale-independent but takes no leading '+'.
    std::string_view digits = word;
    if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
    double value = 0;
    auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || end != digits.data() + digits.size() ||
        (ec != std::errc() && ec != std::errc::result_out_of_range))
        fail(token.line, "malformed number '" + token.text + "'");
    if (ec == std::errc::result_out_of_range) {
        // Overflow or underflow: strtod tells which. Underflow is harmless (the value is ~0).
        errno = 0;
        value = std::strtod(token.text.c_str(), nullptr);
        if (!std::isfinite(value))
            fail(token.line, "number '" + token.text +
                                 "' is too large: it overflows to infinity (the largest is about 1.8e308)");
    }
    token.number = value;
    return token;
}

// ---- Request names ------------------------------------------------------------------------------
RibToken RibLexer::scanIdentifier() {
    RibToken token;
    token.kind = RibTokenKind::Request;
    token.line = line_;
    size_t start = pos_;
    while (pos_ < text_.size() && isWordChar(text_[pos_])) ++pos_;
    token.text = std::string(text_.substr(start, pos_ - start));
    if (isNonFiniteWord(token.text))
        fail(token.line, "'" + token.text + "' is not a valid number: NaN and infinity are not allowed in scenes");
    return token;
}

}  // namespace streyes
