// A small JSON reader and writer for the farm's files: the shot manifest, the tasks' --stats and the
// block-length curve. Reads what those files hold (objects, arrays, strings, numbers, true, false,
// null); numbers are doubles (counters up to 2^53 stay exact).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace streyes::farm {

class Json {
  public:
    enum class Type { Null, Bool, Number, String, Array, Object };

    Json() = default;
    static Json number(double v);
    static Json string(std::string v);
    static Json boolean(bool v);
    static Json array();
    static Json object();

    // Parses `text`; throws std::runtime_error naming `what` (a file name) and the offset.
    static Json parse(const std::string& text, const std::string& what);
    // Reads and parses a file; throws std::runtime_error when it cannot be read or parsed.
    static Json load(const std::string& path);

    Type type() const { return type_; }
    bool isNull() const { return type_ == Type::Null; }
    bool isNumber() const { return type_ == Type::Number; }
    bool isString() const { return type_ == Type::String; }
    bool isArray() const { return type_ == Type::Array; }
    bool isObject() const { return type_ == Type::Object; }

    double num(double fallback = 0) const { return type_ == Type::Number ? number_ : fallback; }
    bool flag(bool fallback = false) const { return type_ == Type::Bool ? bool_ : fallback; }
    const std::string& str() const { return string_; }
    const std::vector<Json>& items() const { return items_; }
    // Object members in the order they were read or added.
    const std::vector<std::pair<std::string, Json>>& members() const { return members_; }

    // A member of an object; a null Json when absent (or when this is not an object).
    const Json& operator[](const std::string& key) const;
    bool has(const std::string& key) const;

    Json& push(Json v);                        // arrays
    Json& set(const std::string& key, Json v);  // objects: replaces or appends

    // Indented text, members in order; ends without a newline.
    std::string dump(int indent = 0) const;

  private:
    Type type_ = Type::Null;
    bool bool_ = false;
    double number_ = 0;
    std::string string_;
    std::vector<Json> items_;
    std::vector<std::pair<std::string, Json>> members_;
};

// A string as a JSON literal, quotes and escapes included.
std::string jsonQuote(const std::string& s);

}  // namespace streyes::farm
