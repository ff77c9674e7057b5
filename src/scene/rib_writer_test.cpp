// The RIB writer (rib_writer.h): every encoding reads back as the tokens it was given, with the
// same values to the bit (float32: the values ribFloat32 gives), and the encodings are what
// Appendix C says they are.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "scene/rib_gzip.h"
#include "scene/rib_lexer.h"
#include "scene/rib_writer.h"

namespace streyes {
namespace {

uint64_t bitsOf(double v) {
    uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

std::vector<RibToken> lexAll(const std::string& text) {
    const std::string inflated = isGzip(text) ? gunzip(text, "w.rib") : text;
    RibLexer lexer(inflated, std::make_shared<const std::string>("w.rib"));
    std::vector<RibToken> tokens;
    while (true) {
        RibToken t = lexer.next();
        if (t.kind == RibTokenKind::End) return tokens;
        tokens.push_back(std::move(t));
    }
}

// Numbers that test every width and kind: integers at each byte boundary, negative ones, -0,
// reals with more precision than a float, and beyond a float's range.
const std::vector<double> kNumbers = {0,     1,         127,        128,   -1,    -128,       32767,   32768,
                                      -32769, 8388607,  8388608,    2147483647.0, -2147483648.0, 2147483648.0,
                                      -0.0,  0.1,       -2.5,       1e-30, 1e300, -3.4e38,    16777217,
                                      std::numeric_limits<double>::denorm_min()};

const RibEncoding kEncodings[] = {{false, false, false}, {false, false, true}, {true, false, false},
                                  {true, false, true},   {true, true, false},  {false, true, false}};

std::string describe(const RibEncoding& e) {
    return std::string(e.binary ? "binary" : "ascii") + (e.float32 ? " float32" : "") + (e.gzip ? " gzip" : "");
}

TEST(RibWriter, EveryEncodingReadsBackTheSameTokensAndValues) {
    const std::vector<std::string> strings = {"", "P", "uniform float Kd", "a \"quoted\" \\ back\nslash",
                                              std::string("tab\tnul\0 end", 12), "\xc3\xa9t\xc3\xa9",
                                              std::string(300, 'x')};
    for (const RibEncoding& e : kEncodings) {
        SCOPED_TRACE(describe(e));
        RibWriter w(e);
        w.request("Declare");
        for (double v : kNumbers) w.number(v);
        w.numbers(kNumbers);
        w.numbers({});
        w.numbers({1, 2, 3});
        w.request("Surface");
        for (const std::string& s : strings) w.string(s);
        w.strings(strings);
        w.strings({"P", "P"});
        w.request("Surface");  // a request again: its code
        w.string("uniform float Kd");
        const std::vector<RibToken> t = lexAll(w.finish());

        auto expectNumber = [&](const RibToken& tok, double v) {
            const double want = e.float32 ? ribFloat32(v) : v;
            ASSERT_EQ(tok.kind, RibTokenKind::Number);
            EXPECT_EQ(bitsOf(tok.number), bitsOf(want)) << v << " read " << tok.number;
        };
        // Arrays come as [ ... ] or, for binary float32, as one float array.
        size_t i = 0;
        auto expectArray = [&](const std::vector<double>& v) {
            if (t[i].kind == RibTokenKind::NumberArray) {
                ASSERT_EQ(t[i].numbers.size(), v.size());
                for (size_t k = 0; k < v.size(); ++k)
                    EXPECT_EQ(bitsOf(t[i].numbers[k]), bitsOf(ribFloat32(v[k]))) << v[k];
                ++i;
                return;
            }
            ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayBegin);
            for (double x : v) expectNumber(t[i++], x);
            ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayEnd);
        };
        ASSERT_EQ(t[i].kind, RibTokenKind::Request);
        EXPECT_EQ(t[i++].text, "Declare");
        for (double v : kNumbers) expectNumber(t[i++], v);
        expectArray(kNumbers);
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayBegin);  // [] is never a float array
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayEnd);
        expectArray({1, 2, 3});
        EXPECT_EQ(t[i++].text, "Surface");
        for (const std::string& s : strings) {
            ASSERT_EQ(t[i].kind, RibTokenKind::String);
            EXPECT_EQ(t[i++].text, s);
        }
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayBegin);
        for (const std::string& s : strings) EXPECT_EQ(t[i++].text, s);
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayEnd);
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayBegin);
        EXPECT_EQ(t[i++].text, "P");
        EXPECT_EQ(t[i++].text, "P");
        ASSERT_EQ(t[i++].kind, RibTokenKind::ArrayEnd);
        EXPECT_EQ(t[i++].text, "Surface");
        EXPECT_EQ(t[i++].text, "uniform float Kd");
        EXPECT_EQ(i, t.size());
    }
}

TEST(RibWriter, Float32KeepsIntegersAndWhatAFloatCannotHold) {
    EXPECT_EQ(ribFloat32(16777217), 16777217);  // an integer: written as one
    EXPECT_EQ(ribFloat32(1e300), 1e300);        // beyond a float: written as a double
    EXPECT_EQ(ribFloat32(0.1), double(0.1f));
    EXPECT_TRUE(std::signbit(ribFloat32(-0.0)));
}

// The encodings are Appendix C's: an integer of the width its value needs (negative ones in four
// bytes), each request and short string defined once and then used by code.
TEST(RibWriter, BinaryIsCompactAndDefinesRequestsAndStringsOnce) {
    RibWriter w({true, false, false});
    w.request("Sphere");
    w.number(1);
    w.number(-1);
    w.number(300);
    w.number(0.5);
    w.request("Sphere");
    w.string("Kd");
    w.string("Kd");
    const std::string out = w.finish();
    const std::string expected = std::string("\314\000\226Sphere\246\000", 11) + "\200\001" +
                                 std::string("\203\377\377\377\377", 5) + std::string("\201\001\054", 3) +
                                 std::string("\245\077\340\000\000\000\000\000\000", 9) + std::string("\246\000", 2) +
                                 std::string("\315\000\222Kd\317\000\317\000", 9);
    EXPECT_EQ(out, expected);
    // float32: a float array for reals (every one of which a float holds), integers one by one.
    RibWriter f({true, true, false});
    f.numbers({0.5, 0.25, 2});
    f.numbers({0, 1, 2, 0.5});
    EXPECT_EQ(f.finish(), std::string("\310\003\077\000\000\000\076\200\000\000\100\000\000\000", 14) +
                              std::string("[\200\000\200\001\200\002\244\077\000\000\000]", 13));
}

// Past 256 request names and 65536 strings, the rest are written as ASCII names and inline strings.
TEST(RibWriter, ManyNamesAndStringsStillReadBack) {
    RibWriter w({true, false, true});
    for (int i = 0; i < 300; ++i) {
        w.request("Request" + std::to_string(i));
        w.string("s" + std::to_string(i * 7));
    }
    for (int i = 0; i < 70000; ++i) w.string("t" + std::to_string(i));
    w.request("Request5");
    const std::vector<RibToken> t = lexAll(w.finish());
    ASSERT_EQ(t.size(), 600u + 70000u + 1u);
    for (int i = 0; i < 300; ++i) {
        EXPECT_EQ(t[2 * i].text, "Request" + std::to_string(i));
        EXPECT_EQ(t[2 * i + 1].text, "s" + std::to_string(i * 7));
    }
    for (int i = 0; i < 70000; ++i) ASSERT_EQ(t[600 + i].text, "t" + std::to_string(i));
    EXPECT_EQ(t.back().kind, RibTokenKind::Request);
    EXPECT_EQ(t.back().text, "Request5");
}

// encodeRib reads any encoding (and mixes) and keeps what a reader sees; its errors are the
// reader's.
TEST(RibWriter, EncodeRibConvertsBetweenEncodings) {
    const std::string ascii = "# comment\nFormat 64 48 1 # more\nColor [0.1 0.2 .3]\nSurface \"plastic\" \"Kd\" 0.5\n";
    const std::string binary = encodeRib(ascii, "a.rib", {true, false, true});
    EXPECT_TRUE(isGzip(binary));
    EXPECT_EQ(encodeRib(binary, "b.rib", {}),
              "Format 64 48 1\nColor [0.1 0.2 0.3]\nSurface \"plastic\" \"Kd\" 0.5\n");
    try {
        encodeRib("Color [1 \"a\"]", "bad.rib", {true, false, false});
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.str(), "bad.rib:1");
        EXPECT_NE(e.message.find("array mixes numbers and strings"), std::string::npos);
    }
}

}  // namespace
}  // namespace streyes
