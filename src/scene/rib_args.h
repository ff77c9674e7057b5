// One RIB request as written, and RibArgs, which reads its arguments in order.
//
// Every complaint names the request and the line of the value at fault, and for a positional
// argument shows how the request is written: the reader's messages all go through here, so that
// they read alike in every file.
#pragma once

#include <string>
#include <vector>

#include "streyes/error.h"

namespace streyes {

// One argument of a request: a number, a string, or a bracketed array of either.
struct RibValue {
    enum class Kind { Number, String, Array };
    Kind kind = Kind::Number;
    std::vector<double> nums;          // Number: one; Array: its numbers
    std::vector<std::string> strings;  // String: one; Array: its strings
    int line = 0;
    long long offset = -1;  // binary RIB: the byte the value starts at

    bool isString() const { return kind == Kind::String; }
    bool isNumber() const { return kind == Kind::Number; }
    bool isNumericArray() const { return kind == Kind::Array && strings.empty(); }  // [] counts too
    bool isStringArray() const { return kind == Kind::Array && nums.empty(); }      // [] counts too
};

// A request with its arguments as written, before they are interpreted.
struct RibRequest {
    std::string name;
    std::vector<RibValue> args;
    SourceLoc loc;
};

// For messages: "0.5", "2 numbers", `the string "a"`.
std::string formatNumber(double v);
std::string plural(size_t n, const std::string& word);
std::string describeValue(const RibValue& v);
bool isWholeInt(double v);  // a whole number in int range

// Positional arguments first, in order, then the parameter list (RibParser::readParams).
class RibArgs {
  public:
    RibArgs(const RibRequest& request, const char* usage) : request_(request), usage_(usage) {}

    const std::string& name() const { return request_.name; }
    const SourceLoc& loc() const { return request_.loc; }
    const RibRequest& request() const { return request_; }
    const char* usage() const { return usage_; }
    // A line of this request's input; in binary RIB, which has no lines, the request's byte offset.
    SourceLoc locAt(int line) const { return {request_.loc.file, line, 0, request_.loc.offset}; }
    SourceLoc locOf(const RibValue& v) const {
        return {request_.loc.file, v.line, 0, v.offset >= 0 ? v.offset : request_.loc.offset};
    }

    bool done() const { return next_ >= request_.args.size(); }
    size_t remaining() const { return request_.args.size() - next_; }
    const RibValue* peek() const { return done() ? nullptr : &request_.args[next_]; }
    const RibValue& take() { return request_.args[next_++]; }
    void skipRest() { next_ = request_.args.size(); }

    // Errors at the request's line, or at the line of one value; the usage is shown for
    // positional-argument mistakes, where it is the most useful hint.
    [[noreturn]] void fail(const std::string& what) const { failAt(request_.loc.line, what, true); }
    [[noreturn]] void fail(const RibValue& at, const std::string& what) const { failAt(locOf(at), what, true); }
    [[noreturn]] void failAt(int line, const std::string& what, bool withUsage) const {
        failAt(locAt(line), what, withUsage);
    }
    [[noreturn]] void failAt(const SourceLoc& loc, const std::string& what, bool withUsage) const;

    double number(const char* what);       // one number (or a one-number array)
    int integer(const char* what);         // a number that is a whole number in int range
    std::string string(const char* what);  // one string (or a one-string array)
    // Exactly n numbers, written loose (Translate 1 2 3) or as one array (Translate [1 2 3]).
    std::vector<double> numbers(size_t n, const char* what);
    // Any count of numbers: one array, or loose numbers up to the next string.
    std::vector<double> numberList(const char* what);
    void expectEnd();

  private:
    const RibRequest& request_;
    const char* usage_;
    size_t next_ = 0;
};

}  // namespace streyes
