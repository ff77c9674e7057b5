// Writing RIB in each of its encodings: ASCII, binary (RI Spec 3.2, Appendix C), and either one
// gzip-compressed. `streyes catrib` converts files with it, and RiBegin("file.rib") writes its
// file through it (Option "rib" "format" and "compression", as PRMan reads them).
//
// What is written reads back as the same requests with the same values: ASCII numbers are the
// shortest text that reads back as the same double, binary reals are 64-bit floats. The one
// exception is asked for: `float32` writes reals as 32-bit floats (binary RIB's usual, half the
// size), and then ASCII output writes the values those floats have, so that a binary file and an
// ASCII one made with float32 hold the same values.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace streyes {

struct RibEncoding {
    bool binary = false;   // binary RIB; false: ASCII
    bool float32 = false;  // reals as 32-bit floats (binary), or rounded to their values (ASCII)
    bool gzip = false;     // the whole stream gzip-compressed
};

// The value a number is written with under float32: a whole number in int range stays (it is
// written as an integer), a number beyond a float's range stays (it is written as a 64-bit float),
// any other becomes the nearest 32-bit float.
double ribFloat32(double v);

class RibWriter {
  public:
    explicit RibWriter(const RibEncoding& encoding) : encoding_(encoding) {}

    void request(const std::string& name);  // starts a request (a new line in ASCII)
    void number(double v);
    void string(std::string_view s);
    void numbers(const std::vector<double>& v);       // an array of numbers
    void strings(const std::vector<std::string>& v);  // an array of strings

    // The bytes written so far, gzip-compressed when the encoding says so.
    std::string finish() const;

  private:
    void separate();  // ASCII: a space between values
    void binaryNumber(double v);
    void binaryString(std::string_view s);  // a string inline (0220, 0240)
    void bytes(unsigned char lead, uint32_t value, int count);

    RibEncoding encoding_;
    std::string out_;
    bool lineStarted_ = false;
    std::unordered_map<std::string, int> requestCodes_;  // binary: request name -> 0314 code
    std::unordered_map<std::string, int> stringIndices_;  // binary: string -> 0315 index
};

// Every request of `input` (ASCII, binary or both, gzip-compressed or not) written again in
// `encoding`, token by token: comments are dropped, requests and values kept (but for float32).
// Malformed input is an InputError naming `sourceName`, as the reader would report it.
void encodeRib(RibWriter& writer, std::string_view input, const std::string& sourceName);
std::string encodeRib(std::string_view input, const std::string& sourceName, const RibEncoding& encoding);

}  // namespace streyes
