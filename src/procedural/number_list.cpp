#include "procedural/number_list.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace streyes {

std::vector<double> parseNumberList(const char* who, const std::string& key, const std::string& value, size_t n,
                                    const SourceLoc& loc) {
    std::vector<double> r;
    std::stringstream in(value);
    std::string part;
    while (std::getline(in, part, ',')) {
        char* end = nullptr;
        const double v = std::strtod(part.c_str(), &end);
        if (part.empty() || *end != '\0' || !std::isfinite(v))
            throw InputError(loc, std::string(who) + ": '" + key + "=" + value + "' is not " + std::to_string(n) +
                                      " number(s)");
        r.push_back(v);
    }
    if (r.size() != n)
        throw InputError(loc, std::string(who) + ": '" + key + "' takes " + std::to_string(n) +
                                  " comma-separated number(s), got '" + value + "'");
    return r;
}

}  // namespace streyes
