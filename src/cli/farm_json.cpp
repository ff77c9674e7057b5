#include "farm_json.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace streyes::farm {

Json parseJson(const std::string& text, const std::string& what) {
    try {
        return Json::parse(text);
    } catch (const Json::parse_error& e) {
        // "[json.exception.parse_error.101] parse error at line 3, column 5: ..." without its tag.
        std::string why = e.what();
        const size_t tag = why.find("] ");
        if (why.rfind("[json.exception", 0) == 0 && tag != std::string::npos) why = why.substr(tag + 2);
        throw std::runtime_error(what + ": not valid JSON: " + why);
    }
}

Json loadJson(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read '" + path + "'");
    std::ostringstream ss;
    ss << f.rdbuf();
    return parseJson(ss.str(), path);
}

const Json& member(const Json& j, const std::string& key) {
    static const Json kNull;
    if (!j.is_object()) return kNull;
    const auto it = j.find(key);
    return it == j.end() ? kNull : *it;
}

double num(const Json& j, double fallback) { return j.is_number() ? j.get<double>() : fallback; }

std::string str(const Json& j) { return j.is_string() ? j.get<std::string>() : std::string(); }

std::string dumpJson(const Json& j) { return j.dump(2, ' ', false, Json::error_handler_t::replace); }

}  // namespace streyes::farm
