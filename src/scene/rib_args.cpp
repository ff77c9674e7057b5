#include "scene/rib_args.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace streyes {

std::string formatNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::string plural(size_t n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

std::string describeValue(const RibValue& v) {
    switch (v.kind) {
    case RibValue::Kind::Number: return "the number " + formatNumber(v.nums[0]);
    case RibValue::Kind::String: return "the string \"" + v.strings[0] + "\"";
    case RibValue::Kind::Array:
        if (v.nums.empty() && v.strings.empty()) return "an empty array";
        return "an array of " +
               (v.strings.empty() ? plural(v.nums.size(), "number") : plural(v.strings.size(), "string"));
    }
    return "?";
}

bool isWholeInt(double v) {
    return std::floor(v) == v && v >= double(std::numeric_limits<int>::min()) &&
           v <= double(std::numeric_limits<int>::max());
}

void RibArgs::failAt(const SourceLoc& loc, const std::string& what, bool withUsage) const {
    std::string msg = request_.name + ": " + what;
    if (withUsage && usage_ && *usage_) msg += " (usage: " + std::string(usage_) + ")";
    throw InputError(loc, msg);
}

double RibArgs::number(const char* what) {
    if (done()) fail("missing " + std::string(what));
    const RibValue& v = take();
    if (v.isNumber() || (v.isNumericArray() && v.nums.size() == 1)) return v.nums[0];
    fail(v, std::string(what) + " must be a number, got " + describeValue(v));
}

int RibArgs::integer(const char* what) {
    const RibValue* v = peek();
    double x = number(what);
    if (!isWholeInt(x)) fail(*v, std::string(what) + " must be a whole number, got " + formatNumber(x));
    return int(x);
}

std::string RibArgs::string(const char* what) {
    if (done()) fail("missing " + std::string(what));
    const RibValue& v = take();
    if (v.isString() || (v.isStringArray() && v.strings.size() == 1)) return v.strings[0];
    fail(v, std::string(what) + " must be a string, got " + describeValue(v));
}

std::vector<double> RibArgs::numbers(size_t n, const char* what) {
    std::string expected = "expected " + plural(n, "number") + " (" + what + ")";
    if (done()) fail(expected + ", got none");
    if (peek()->kind == RibValue::Kind::Array) {
        const RibValue& v = take();
        if (!v.isNumericArray() || v.nums.size() != n) fail(v, expected + ", got " + describeValue(v));
        return v.nums;
    }
    std::vector<double> r;
    while (r.size() < n && !done() && peek()->isNumber()) r.push_back(take().nums[0]);
    if (r.size() < n) {
        if (r.empty() && !done()) fail(*peek(), expected + ", got " + describeValue(*peek()));
        fail(expected + ", got " + std::to_string(r.size()));
    }
    return r;
}

std::vector<double> RibArgs::numberList(const char* what) {
    if (!done() && peek()->kind == RibValue::Kind::Array) {
        const RibValue& v = take();
        if (!v.isNumericArray()) fail(v, std::string(what) + " must be numbers, got " + describeValue(v));
        return v.nums;
    }
    std::vector<double> r;
    while (!done() && peek()->isNumber()) r.push_back(take().nums[0]);
    return r;
}

void RibArgs::expectEnd() {
    if (!done()) fail(*peek(), "unexpected extra argument: " + describeValue(*peek()));
}

}  // namespace streyes
