// Binary RIB (RI Spec 3.2, Appendix C): the tokens that a byte of 0200 or more starts. Numbers
// are big-endian; strings are raw bytes (no escapes); binary and ASCII tokens mix freely.
//
//   0200 + 4d + w   an integer (d = 0) or fixed-point number: w + 1 bytes, two's complement, the
//                   last d of them after the radix point (the value over 256^d)
//   0220 + n        a string of n bytes (0-15)
//   0240 + l        a string whose length takes l + 1 bytes
//   0244, 0245      a 32-bit, a 64-bit IEEE float
//   0246 c          the request that code c was defined as
//   0310 + l        an array of 32-bit floats, its length in l + 1 bytes
//   0314 c s        defines request code c as the request named by the string s
//   0315 + w i s    defines string index i (w + 1 bytes) as s
//   0317 + w i      the string defined as index i
//   0247-0307, 0321-0377 are reserved.
//
// Integers are signed as Affine's reader (and RiCPP) read them; Aqsis reads those of 1-3 bytes as
// unsigned. The two agree on what rib_writer.cpp writes (a negative integer always takes 4 bytes).
// A definition gives no token: it is read with the string it needs, and scanning goes on.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "scene/rib_lexer.h"

namespace streyes {

namespace {

std::string octal(unsigned char code) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0%03o", code);
    return buf;
}

bool isRequestName(const std::string& s) {
    if (s.empty()) return false;
    auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
    if (!alpha(s[0])) return false;
    for (char c : s)
        if (!alpha(c) && !(c >= '0' && c <= '9')) return false;
    return true;
}

std::string printable(const std::string& s) {
    std::string r;
    for (unsigned char c : s) {
        if (c >= 0x20 && c < 0x7f) {
            r += char(c);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\%03o", c);
            r += buf;
        }
    }
    return r;
}

}  // namespace

void RibLexer::failAt(size_t offset, const std::string& what) const {
    throw InputError(SourceLoc{sourceName_, line_, 0, static_cast<long long>(offset)}, what);
}

// The next `bytes` bytes of a token that began at `start`; the input must hold them.
const char* RibLexer::need(size_t start, size_t bytes, const char* what) {
    const size_t left = text_.size() - pos_;
    if (left < bytes)
        failAt(start, std::string("truncated binary RIB: ") + what + " needs " + std::to_string(bytes) +
                          " more byte" + (bytes == 1 ? "" : "s") + ", only " + std::to_string(left) + " left");
    const char* p = text_.data() + pos_;
    pos_ += bytes;
    return p;
}

uint32_t RibLexer::readUnsigned(size_t start, int bytes, const char* what) {
    const unsigned char* p = reinterpret_cast<const unsigned char*>(need(start, size_t(bytes), what));
    uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
    return v;
}

double RibLexer::scanBinaryNumber(size_t start, unsigned char code) {
    const int bytes = (code & 3) + 1, fraction = (code >> 2) & 3;
    const uint32_t u = readUnsigned(start, bytes, fraction ? "a fixed-point number" : "an integer");
    int64_t v = u;
    if (u >> (8 * bytes - 1)) v -= int64_t(1) << (8 * bytes);  // two's complement over its bytes
    // Exact: at most 32 significant bits over a power of two.
    return fraction ? double(v) / double(int64_t(1) << (8 * fraction)) : double(v);
}

// 0220 + n: n bytes; 0240 + l: a length of l + 1 bytes, then that many.
RibToken RibLexer::scanBinaryString(size_t start, unsigned char code) {
    RibToken token;
    token.kind = RibTokenKind::String;
    token.line = line_;
    token.offset = static_cast<long long>(start);
    const size_t length = code < 0240 ? size_t(code - 0220) : readUnsigned(start, code - 0240 + 1, "a string's length");
    token.text.assign(need(start, length, "a string"), length);
    return token;
}

// 0317 + w: the string defined under an index of w + 1 bytes.
RibToken RibLexer::scanDefinedString(size_t start, unsigned char code) {
    const uint32_t index = readUnsigned(start, code - 0317 + 1, "a string reference's index");
    if (!tables_ || index >= tables_->strings.size() || !tables_->stringDefined[index])
        failAt(start, "string index " + std::to_string(index) + " is used (" + octal(code) +
                          ") but was never defined (0315 and 0316 define strings)");
    RibToken token;
    token.kind = RibTokenKind::String;
    token.line = line_;
    token.offset = static_cast<long long>(start);
    token.text = tables_->strings[index];
    return token;
}

// The string a definition (0314, 0315, 0316) names: ASCII, encoded, or a defined one.
RibToken RibLexer::scanStringOperand(size_t definition, const char* what) {
    skipSpaceAndComments();
    if (pos_ >= text_.size())
        failAt(definition, std::string("truncated binary RIB: ") + what + " is missing its string");
    const unsigned char c = static_cast<unsigned char>(text_[pos_]);
    const size_t start = pos_;
    if (c == '"') return scanString();
    if (c >= 0220 && c <= 0243) {
        ++pos_;
        return scanBinaryString(start, c);
    }
    if (c == 0317 || c == 0320) {
        ++pos_;
        return scanDefinedString(start, c);
    }
    failAt(definition, std::string(what) + " must be followed by a string, not byte " + octal(c));
}

bool RibLexer::scanBinary(RibToken& token) {
    const size_t start = pos_;
    const unsigned char code = static_cast<unsigned char>(text_[pos_++]);
    token.line = line_;
    token.offset = static_cast<long long>(start);
    auto finite = [&](double v, size_t at) {
        if (!std::isfinite(v))
            failAt(at, std::string("a binary float is ") + (std::isnan(v) ? "NaN" : "infinite") +
                           ": NaN and infinity are not allowed in scenes");
        return v;
    };
    if (code <= 0217) {
        token.kind = RibTokenKind::Number;
        token.number = scanBinaryNumber(start, code);
        return true;
    }
    if (code <= 0243) {
        token = scanBinaryString(start, code);
        return true;
    }
    switch (code) {
    case 0244: {
        const uint32_t bits = readUnsigned(start, 4, "a 32-bit float");
        float f;
        std::memcpy(&f, &bits, sizeof f);
        token.kind = RibTokenKind::Number;
        token.number = finite(f, start);
        return true;
    }
    case 0245: {
        const uint64_t high = readUnsigned(start, 4, "a 64-bit float");
        const uint64_t bits = (high << 32) | readUnsigned(start, 4, "a 64-bit float");
        double d;
        std::memcpy(&d, &bits, sizeof d);
        token.kind = RibTokenKind::Number;
        token.number = finite(d, start);
        return true;
    }
    case 0246: {
        const unsigned char c = static_cast<unsigned char>(*need(start, 1, "an encoded request"));
        if (!tables_ || tables_->requests[c].empty())
            failAt(start, "request code " + std::to_string(c) +
                              " is used (0246) but was never defined (0314 defines request codes)");
        token.kind = RibTokenKind::Request;
        token.text = tables_->requests[c];
        return true;
    }
    case 0310:
    case 0311:
    case 0312:
    case 0313: {
        const uint32_t n = readUnsigned(start, code - 0310 + 1, "a float array's length");
        const size_t left = text_.size() - pos_;
        if (uint64_t(n) * 4 > left)
            failAt(start, "truncated float array: " + std::to_string(n) + " floats need " +
                              std::to_string(uint64_t(n) * 4) + " bytes, only " + std::to_string(left) + " left");
        token.kind = RibTokenKind::NumberArray;
        token.numbers.resize(n);
        const unsigned char* p = reinterpret_cast<const unsigned char*>(text_.data() + pos_);
        for (uint32_t i = 0; i < n; ++i, p += 4) {
            const uint32_t bits = uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3];
            float f;
            std::memcpy(&f, &bits, sizeof f);
            token.numbers[i] = finite(f, pos_ + 4 * size_t(i));
        }
        pos_ += 4 * size_t(n);
        return true;
    }
    case 0314: {
        const unsigned char c = static_cast<unsigned char>(*need(start, 1, "a request definition"));
        RibToken name = scanStringOperand(start, "a request definition (0314)");
        if (!isRequestName(name.text))
            failAt(start, "request code " + std::to_string(c) + " is defined (0314) as \"" + printable(name.text) +
                              "\", which is not a request name");
        if (!tables_) tables_ = std::make_unique<BinaryTables>();
        tables_->requests[c] = std::move(name.text);
        return false;
    }
    case 0315:
    case 0316: {
        const uint32_t index = readUnsigned(start, code - 0315 + 1, "a string definition's index");
        RibToken value = scanStringOperand(start, "a string definition (0315, 0316)");
        if (!tables_) tables_ = std::make_unique<BinaryTables>();
        if (index >= tables_->strings.size()) {
            tables_->strings.resize(index + 1);
            tables_->stringDefined.resize(index + 1);
        }
        tables_->strings[index] = std::move(value.text);
        tables_->stringDefined[index] = true;
        return false;
    }
    case 0317:
    case 0320: token = scanDefinedString(start, code); return true;
    default:
        failAt(start, "byte " + octal(code) + " is not a binary RIB token (" +
                          (code == 0377 ? std::string("0377 ends a RunProgram answer, never a file")
                                        : std::string("0247-0307 and 0321-0377 are reserved")) +
                          "): is the file damaged?");
    }
}

}  // namespace streyes
