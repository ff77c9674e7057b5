#include "scene/rib_writer.h"

#include <charconv>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <limits>

#include "scene/rib_gzip.h"
#include "scene/rib_lexer.h"

namespace streyes {

namespace {

// Whole numbers in int range are written as integers, exactly. -0 is not one: it stays a real,
// so that its sign survives.
bool writtenAsInteger(double v) {
    return std::floor(v) == v && v >= double(std::numeric_limits<int32_t>::min()) &&
           v <= double(std::numeric_limits<int32_t>::max()) && !(v == 0 && std::signbit(v));
}

bool floatRange(double v) { return std::fabs(v) <= double(std::numeric_limits<float>::max()); }

// Bytes of an integer's binary encoding: its lead byte and the 1-4 bytes its value needs. A
// negative integer takes four: readers that take shorter ones as unsigned (Aqsis) then read the
// same values as those that take them as signed (the RI Spec, Affine).
int integerBytes(int32_t i) { return 1 + (i < 0 ? 4 : i < 0x80 ? 1 : i < 0x8000 ? 2 : i < 0x800000 ? 3 : 4); }

// Short strings that recur (parameter names, shader names) are defined once and referred to by
// index; longer ones are written where they are used.
constexpr size_t kMaxDefinedString = 64;
constexpr int kMaxStringIndices = 1 << 16;  // 0316 and 0320 take two-byte indices

}  // namespace

double ribFloat32(double v) {
    if (writtenAsInteger(v) || !floatRange(v)) return v;
    return double(float(v));
}

void RibWriter::bytes(unsigned char lead, uint32_t value, int count) {
    out_ += char(lead);
    for (int i = count - 1; i >= 0; --i) out_ += char((value >> (8 * i)) & 0xff);
}

void RibWriter::separate() {
    if (lineStarted_) out_ += ' ';
    lineStarted_ = true;
}

void RibWriter::request(const std::string& name) {
    if (!encoding_.binary) {
        if (!out_.empty()) out_ += '\n';
        out_ += name;
        lineStarted_ = true;
        return;
    }
    auto it = requestCodes_.find(name);
    if (it == requestCodes_.end()) {
        if (requestCodes_.size() == 256) {  // every code taken: the name as ASCII
            out_ += name;
            out_ += ' ';
            return;
        }
        const int code = int(requestCodes_.size());
        it = requestCodes_.emplace(name, code).first;
        out_ += char(0314);
        out_ += char(code);
        binaryString(name);
    }
    out_ += char(0246);
    out_ += char(it->second);
}

void RibWriter::number(double v) {
    if (encoding_.binary) {
        binaryNumber(v);
        return;
    }
    separate();
    if (encoding_.float32) v = ribFloat32(v);
    char buf[32];
    // The shortest text that reads back as this double.
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    (void)ec;
    out_.append(buf, end);
}

void RibWriter::binaryNumber(double v) {
    if (writtenAsInteger(v)) {
        const int32_t i = int32_t(v);
        const int count = integerBytes(i) - 1;
        bytes(0200 + (count - 1), uint32_t(i), count);
    } else if (encoding_.float32 && floatRange(v)) {
        const float f = float(v);
        uint32_t bits;
        std::memcpy(&bits, &f, sizeof bits);
        bytes(0244, bits, 4);
    } else {
        uint64_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        bytes(0245, uint32_t(bits >> 32), 4);
        for (int i = 3; i >= 0; --i) out_ += char((bits >> (8 * i)) & 0xff);
    }
}

void RibWriter::binaryString(std::string_view s) {
    if (s.size() < 16) {
        out_ += char(0220 + s.size());
    } else {
        const size_t n = s.size();
        const int count = n < (1u << 8) ? 1 : n < (1u << 16) ? 2 : n < (1u << 24) ? 3 : 4;
        bytes(0240 + (count - 1), uint32_t(n), count);
    }
    out_.append(s.data(), s.size());
}

void RibWriter::string(std::string_view s) {
    if (encoding_.binary) {
        if (s.size() < 2 || s.size() > kMaxDefinedString) {
            binaryString(s);
            return;
        }
        auto it = stringIndices_.find(std::string(s));
        if (it == stringIndices_.end()) {
            if (int(stringIndices_.size()) == kMaxStringIndices) {
                binaryString(s);
                return;
            }
            const int index = int(stringIndices_.size());
            it = stringIndices_.emplace(std::string(s), index).first;
            bytes(index < 256 ? 0315 : 0316, uint32_t(index), index < 256 ? 1 : 2);
            binaryString(s);
        }
        const int index = it->second;
        bytes(index < 256 ? 0317 : 0320, uint32_t(index), index < 256 ? 1 : 2);
        return;
    }
    separate();
    out_ += '"';
    for (char c : s) {
        const unsigned char u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out_ += '\\';
            out_ += c;
        } else if (c == '\n') {
            out_ += "\\n";
        } else if (u < 0x20 || u == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\%03o", u);  // three digits: a digit after it stays its own
            out_ += buf;
        } else {
            out_ += c;
        }
    }
    out_ += '"';
}

void RibWriter::numbers(const std::vector<double>& v) {
    // A binary float array holds 32-bit floats only: with float32, when every value is one, and
    // when it is no larger than the values one by one (an array of small integers is smaller as
    // integers, an array of reals as a float array).
    const size_t n = v.size();
    const int count = n < (1u << 8) ? 1 : n < (1u << 16) ? 2 : n < (1u << 24) ? 3 : 4;
    bool floatArray = encoding_.binary && encoding_.float32 && n > 0;
    size_t oneByOne = 2;  // [ and ]
    for (size_t i = 0; floatArray && i < n; ++i) {
        const double w = ribFloat32(v[i]);
        floatArray = floatRange(w) && double(float(w)) == w;
        oneByOne += writtenAsInteger(v[i]) ? size_t(integerBytes(int32_t(v[i]))) : 5;
    }
    if (floatArray && 1 + size_t(count) + 4 * n <= oneByOne) {
        bytes(0310 + (count - 1), uint32_t(n), count);
        for (double x : v) {
            const float f = float(ribFloat32(x));
            uint32_t bits;
            std::memcpy(&bits, &f, sizeof bits);
            for (int i = 3; i >= 0; --i) out_ += char((bits >> (8 * i)) & 0xff);
        }
        return;
    }
    if (!encoding_.binary) separate();
    out_ += '[';
    if (!encoding_.binary) lineStarted_ = false;
    for (double x : v) number(x);
    out_ += ']';
    lineStarted_ = true;
}

void RibWriter::strings(const std::vector<std::string>& v) {
    if (!encoding_.binary) separate();
    out_ += '[';
    if (!encoding_.binary) lineStarted_ = false;
    for (const std::string& s : v) string(s);
    out_ += ']';
    lineStarted_ = true;
}

std::string RibWriter::finish() const {
    std::string text = out_;
    if (!encoding_.binary) text += '\n';
    return encoding_.gzip ? gzip(text) : text;
}

// ---- Re-encoding -------------------------------------------------------------------------------
void encodeRib(RibWriter& writer, std::string_view input, const std::string& sourceName) {
    const std::string inflated = isGzip(input) ? gunzip(input, sourceName) : std::string();
    RibLexer lexer(isGzip(input) ? std::string_view(inflated) : input, std::make_shared<const std::string>(sourceName));
    while (true) {
        RibToken t = lexer.next();
        switch (t.kind) {
        case RibTokenKind::End: return;
        case RibTokenKind::Request: writer.request(t.text); break;
        case RibTokenKind::Number: writer.number(t.number); break;
        case RibTokenKind::String: writer.string(t.text); break;
        case RibTokenKind::NumberArray: writer.numbers(t.numbers); break;
        case RibTokenKind::ArrayEnd: throw InputError(lexer.loc(t), "unexpected ']' with no '[' before it");
        case RibTokenKind::ArrayBegin: {
            // The parser's rules: numbers or strings, not both, not nested, closed before the
            // next request.
            std::vector<double> nums;
            std::vector<std::string> strs;
            const SourceLoc opened = lexer.loc(t);
            while (true) {
                RibToken e = lexer.next();
                if (e.kind == RibTokenKind::ArrayEnd) break;
                if (e.kind == RibTokenKind::Number && strs.empty()) nums.push_back(e.number);
                else if (e.kind == RibTokenKind::String && nums.empty()) strs.push_back(std::move(e.text));
                else if (e.kind == RibTokenKind::Number || e.kind == RibTokenKind::String)
                    throw InputError(lexer.loc(e), "array mixes numbers and strings: " + describeToken(e));
                else if (e.kind == RibTokenKind::ArrayBegin || e.kind == RibTokenKind::NumberArray)
                    throw InputError(lexer.loc(e), "arrays cannot be nested");
                else
                    throw InputError(opened, "unterminated array: the '[' opened here has no ']' before " +
                                                 describeToken(e));
            }
            if (strs.empty()) writer.numbers(nums);
            else writer.strings(strs);
            break;
        }
        }
    }
}

std::string encodeRib(std::string_view input, const std::string& sourceName, const RibEncoding& encoding) {
    RibWriter writer(encoding);
    encodeRib(writer, input, sourceName);
    return writer.finish();
}

}  // namespace streyes
