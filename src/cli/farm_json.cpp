#include "farm_json.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace streyes::farm {

namespace {

const Json kNull;

class Parser {
  public:
    Parser(const std::string& text, const std::string& what) : s_(text), what_(what) {}

    Json document() {
        Json v = value(0);
        skipSpace();
        if (i_ != s_.size()) fail("text after the JSON value");
        return v;
    }

  private:
    [[noreturn]] void fail(const std::string& why) const {
        throw std::runtime_error(what_ + ": not valid JSON at byte " + std::to_string(i_) + ": " + why);
    }
    void skipSpace() {
        while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
    }
    bool literal(const char* word) {
        size_t n = std::char_traits<char>::length(word);
        if (s_.compare(i_, n, word) != 0) return false;
        i_ += n;
        return true;
    }
    Json value(int depth) {
        if (depth > 64) fail("nested too deeply");
        skipSpace();
        if (i_ >= s_.size()) fail("unexpected end");
        char c = s_[i_];
        if (c == '{') {
            ++i_;
            Json o = Json::object();
            skipSpace();
            if (i_ < s_.size() && s_[i_] == '}') {
                ++i_;
                return o;
            }
            for (;;) {
                skipSpace();
                if (i_ >= s_.size() || s_[i_] != '"') fail("expected a member name");
                std::string key = string();
                skipSpace();
                if (i_ >= s_.size() || s_[i_] != ':') fail("expected ':'");
                ++i_;
                o.set(key, value(depth + 1));
                skipSpace();
                if (i_ < s_.size() && s_[i_] == ',') {
                    ++i_;
                    continue;
                }
                if (i_ < s_.size() && s_[i_] == '}') {
                    ++i_;
                    return o;
                }
                fail("expected ',' or '}'");
            }
        }
        if (c == '[') {
            ++i_;
            Json a = Json::array();
            skipSpace();
            if (i_ < s_.size() && s_[i_] == ']') {
                ++i_;
                return a;
            }
            for (;;) {
                a.push(value(depth + 1));
                skipSpace();
                if (i_ < s_.size() && s_[i_] == ',') {
                    ++i_;
                    continue;
                }
                if (i_ < s_.size() && s_[i_] == ']') {
                    ++i_;
                    return a;
                }
                fail("expected ',' or ']'");
            }
        }
        if (c == '"') return Json::string(string());
        if (literal("true")) return Json::boolean(true);
        if (literal("false")) return Json::boolean(false);
        if (literal("null")) return Json();
        if (c == '-' || (c >= '0' && c <= '9')) {
            size_t start = i_;
            if (s_[i_] == '-') ++i_;
            while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.' ||
                                      s_[i_] == 'e' || s_[i_] == 'E' || s_[i_] == '+' || s_[i_] == '-'))
                ++i_;
            const std::string text = s_.substr(start, i_ - start);
            char* end = nullptr;
            double v = std::strtod(text.c_str(), &end);
            if (end != text.c_str() + text.size()) fail("bad number '" + text + "'");
            return Json::number(v);
        }
        fail(std::string("unexpected '") + c + "'");
    }
    static void appendUtf8(std::string& out, unsigned cp) {
        if (cp < 0x80) {
            out += char(cp);
        } else if (cp < 0x800) {
            out += char(0xC0 | (cp >> 6));
            out += char(0x80 | (cp & 0x3F));
        } else if (cp < 0x10000) {
            out += char(0xE0 | (cp >> 12));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
        } else {
            out += char(0xF0 | (cp >> 18));
            out += char(0x80 | ((cp >> 12) & 0x3F));
            out += char(0x80 | ((cp >> 6) & 0x3F));
            out += char(0x80 | (cp & 0x3F));
        }
    }
    unsigned hex4() {
        if (i_ + 4 > s_.size()) fail("short \\u escape");
        unsigned v = 0;
        for (int k = 0; k < 4; ++k) {
            char h = s_[i_++];
            v <<= 4;
            if (h >= '0' && h <= '9') v |= unsigned(h - '0');
            else if (h >= 'a' && h <= 'f') v |= unsigned(h - 'a' + 10);
            else if (h >= 'A' && h <= 'F') v |= unsigned(h - 'A' + 10);
            else fail("bad \\u escape");
        }
        return v;
    }
    std::string string() {
        ++i_;  // the opening quote
        std::string out;
        while (i_ < s_.size() && s_[i_] != '"') {
            char c = s_[i_++];
            if (c != '\\') {
                out += c;
                continue;
            }
            if (i_ >= s_.size()) break;
            char e = s_[i_++];
            switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case '/': out += '/'; break;
                case 'b': out += '\b'; break;
                case 'f': out += '\f'; break;
                case 'n': out += '\n'; break;
                case 'r': out += '\r'; break;
                case 't': out += '\t'; break;
                case 'u': {
                    unsigned cp = hex4();
                    if (cp >= 0xD800 && cp < 0xDC00 && i_ + 1 < s_.size() && s_[i_] == '\\' && s_[i_ + 1] == 'u') {
                        i_ += 2;
                        unsigned lo = hex4();
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    }
                    appendUtf8(out, cp);
                    break;
                }
                default: fail(std::string("bad escape '\\") + e + "'");
            }
        }
        if (i_ >= s_.size()) fail("unterminated string");
        ++i_;  // the closing quote
        return out;
    }

    const std::string& s_;
    const std::string& what_;
    size_t i_ = 0;
};

std::string formatNumber(double v) {
    if (!std::isfinite(v)) return "null";
    if (v == std::floor(v) && std::fabs(v) < 9.007199254740992e15) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.0f", v);
        return buf;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

}  // namespace

Json Json::number(double v) {
    Json j;
    j.type_ = Type::Number;
    j.number_ = v;
    return j;
}
Json Json::string(std::string v) {
    Json j;
    j.type_ = Type::String;
    j.string_ = std::move(v);
    return j;
}
Json Json::boolean(bool v) {
    Json j;
    j.type_ = Type::Bool;
    j.bool_ = v;
    return j;
}
Json Json::array() {
    Json j;
    j.type_ = Type::Array;
    return j;
}
Json Json::object() {
    Json j;
    j.type_ = Type::Object;
    return j;
}

Json Json::parse(const std::string& text, const std::string& what) { return Parser(text, what).document(); }

Json Json::load(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read '" + path + "'");
    std::ostringstream ss;
    ss << f.rdbuf();
    return parse(ss.str(), path);
}

const Json& Json::operator[](const std::string& key) const {
    for (const auto& m : members_)
        if (m.first == key) return m.second;
    return kNull;
}

bool Json::has(const std::string& key) const {
    for (const auto& m : members_)
        if (m.first == key) return true;
    return false;
}

Json& Json::push(Json v) {
    type_ = Type::Array;
    items_.push_back(std::move(v));
    return items_.back();
}

Json& Json::set(const std::string& key, Json v) {
    type_ = Type::Object;
    for (auto& m : members_)
        if (m.first == key) {
            m.second = std::move(v);
            return m.second;
        }
    members_.emplace_back(key, std::move(v));
    return members_.back().second;
}

std::string jsonQuote(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += char(c);
                }
        }
    }
    return out + "\"";
}

std::string Json::dump(int indent) const {
    const std::string pad(size_t(indent + 2), ' '), end(size_t(indent), ' ');
    switch (type_) {
        case Type::Null: return "null";
        case Type::Bool: return bool_ ? "true" : "false";
        case Type::Number: return formatNumber(number_);
        case Type::String: return jsonQuote(string_);
        case Type::Array: {
            if (items_.empty()) return "[]";
            // Arrays of scalars on one line; others one item a line.
            bool flat = true;
            for (const Json& v : items_) flat = flat && v.type_ != Type::Array && v.type_ != Type::Object;
            bool pairs = true;  // [[1, 4], [5, 8]]: short arrays of numbers, also on one line
            for (const Json& v : items_) {
                pairs = pairs && v.type_ == Type::Array && v.items_.size() <= 2;
                if (pairs)
                    for (const Json& w : v.items_) pairs = pairs && w.type_ == Type::Number;
            }
            std::string out = "[";
            if (flat || pairs) {
                for (size_t k = 0; k < items_.size(); ++k) out += (k ? ", " : "") + items_[k].dump(indent);
                return out + "]";
            }
            for (size_t k = 0; k < items_.size(); ++k) out += (k ? ",\n" : "\n") + pad + items_[k].dump(indent + 2);
            return out + "\n" + end + "]";
        }
        case Type::Object: {
            if (members_.empty()) return "{}";
            std::string out = "{";
            for (size_t k = 0; k < members_.size(); ++k)
                out += (k ? ",\n" : "\n") + pad + jsonQuote(members_[k].first) + ": " + members_[k].second.dump(indent + 2);
            return out + "\n" + end + "}";
        }
    }
    return "null";
}

}  // namespace streyes::farm
