// Binary RIB (RI Spec 3.2, Appendix C) in the lexer: each encoding gives the token its ASCII form
// gives, definitions give none, ASCII mixes in, and every malformed token is an error at its byte.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "scene/rib_lexer.h"
#include "streyes/rib.h"
#include "test_util.h"

namespace streyes {
namespace {

// Bytes written as octal escapes in tests, with NULs kept.
template <size_t N>
std::string bytes(const char (&s)[N]) {
    return std::string(s, N - 1);
}

std::vector<RibToken> lexAll(const std::string& text) {
    RibLexer lexer(text, std::make_shared<const std::string>("b.rib"));
    std::vector<RibToken> tokens;
    while (true) {
        RibToken t = lexer.next();
        if (t.kind == RibTokenKind::End) return tokens;
        tokens.push_back(std::move(t));
    }
}

// The InputError lexing `text` throws: its location and message.
InputError lexError(const std::string& text) {
    try {
        lexAll(text);
    } catch (const InputError& e) {
        return e;
    }
    return InputError("no error");
}

uint64_t bitsOf(double v) {
    uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

TEST(RibBinary, IntegersAreSignedBigEndianOfOneToFourBytes) {
    const auto t = lexAll(bytes("\200\177\200\377\201\001\000\201\377\376\202\001\000\000\203\177\377\377\377"
                                "\203\200\000\000\000"));
    const std::vector<double> expected = {127, -1, 256, -2, 65536, 2147483647, -2147483648.0};
    ASSERT_EQ(t.size(), expected.size());
    for (size_t i = 0; i < t.size(); ++i) {
        EXPECT_EQ(t[i].kind, RibTokenKind::Number);
        EXPECT_EQ(t[i].number, expected[i]) << i;
    }
    EXPECT_EQ(t[0].offset, 0);
    EXPECT_EQ(t[1].offset, 2);
    EXPECT_EQ(t[2].offset, 4);
}

TEST(RibBinary, FixedPointNumbersHaveTheirLastBytesAfterThePoint) {
    // 0204 .b   0205 b.b   0212 b.bb   0213 bb.bb   0214 .__b (Aqsis: bytes before the value are 0)
    const auto t = lexAll(bytes("\204\100\205\003\200\212\001\100\000\213\377\376\200\000\214\001\205\377\000"));
    const std::vector<double> expected = {0.25, 3.5, 1.25, -1.5, 1.0 / 16777216, -1};
    ASSERT_EQ(t.size(), expected.size());
    for (size_t i = 0; i < t.size(); ++i) EXPECT_EQ(t[i].number, expected[i]) << i;
}

TEST(RibBinary, FloatsAreIeeeBigEndian) {
    const auto t = lexAll(bytes("\244\277\200\000\000\245\077\271\231\231\231\231\231\232\244\075\314\314\315"));
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].number, -1.0);
    EXPECT_EQ(bitsOf(t[1].number), bitsOf(0.1));            // 64-bit: exactly the double
    EXPECT_EQ(bitsOf(t[2].number), bitsOf(double(0.1f)));   // 32-bit: exactly the float
}

TEST(RibBinary, StringsAreRawBytesOfAGivenLength) {
    std::string text = bytes("\220\221a\225a\\n\"b\240\020");
    text += std::string(16, 'x');
    text += bytes("\241\000\003\303\251\000");
    const auto t = lexAll(text);
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].text, "");
    EXPECT_EQ(t[1].text, "a");
    EXPECT_EQ(t[2].text, "a\\n\"b");  // no escapes in binary strings
    EXPECT_EQ(t[3].text, std::string(16, 'x'));
    EXPECT_EQ(t[4].text, bytes("\303\251\000"));
    for (const RibToken& x : t) EXPECT_EQ(x.kind, RibTokenKind::String);
}

TEST(RibBinary, RequestsAndStringsAreDefinedOnceAndUsedByCode) {
    // Request code 0 = "Sphere" (an encoded string), code 255 = "Color" (an ASCII string); string
    // 1 = "P", string 0x1234 = "uniform float Kd" (two-byte index, defined by a defined string).
    const std::string text = bytes("\314\000\226Sphere\314\377 \"Color\" \315\001\221P\315\000\240\020uniform float Kd"
                                   "\316\022\064\317\000\246\000\246\377\320\022\064\317\001");
    const auto t = lexAll(text);
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].kind, RibTokenKind::Request);
    EXPECT_EQ(t[0].text, "Sphere");
    EXPECT_EQ(t[1].text, "Color");
    EXPECT_EQ(t[2].kind, RibTokenKind::String);
    EXPECT_EQ(t[2].text, "uniform float Kd");
    EXPECT_EQ(t[3].text, "P");
    EXPECT_EQ(size_t(t[0].offset), text.find(bytes("\246\000")));
}

TEST(RibBinary, FloatArraysAreOneTokenOfNumbers) {
    const auto t = lexAll(bytes("\310\002\077\200\000\000\300\000\000\000\310\000\311\000\001\000\000\000\000"));
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].kind, RibTokenKind::NumberArray);
    EXPECT_EQ(t[0].numbers, (std::vector<double>{1, -2}));
    EXPECT_TRUE(t[1].numbers.empty());
    EXPECT_EQ(t[2].numbers, std::vector<double>{0});
}

// Binary bytes that happen to be newlines are data, not lines; ASCII around them counts lines.
TEST(RibBinary, MixesWithAsciiAndLinesCountOnlyAsciiNewlines) {
    const std::string text = bytes("Translate \203\000\012\012\012 2\n[ \200\012 ] \"s\"\n\244\000\000\000\000");
    const auto t = lexAll(text);
    ASSERT_EQ(t.size(), 8u);
    EXPECT_EQ(t[0].text, "Translate");
    EXPECT_EQ(t[1].number, 0x0a0a0a);
    EXPECT_EQ(t[1].line, 1);
    EXPECT_EQ(t[1].offset, 10);
    EXPECT_EQ(t[2].number, 2);
    EXPECT_EQ(t[2].offset, -1);  // ASCII
    EXPECT_EQ(t[3].kind, RibTokenKind::ArrayBegin);
    EXPECT_EQ(t[3].line, 2);
    EXPECT_EQ(t[4].number, 10);
    EXPECT_EQ(t[4].line, 2);
    EXPECT_EQ(t[6].line, 2);
    EXPECT_EQ(t[7].line, 3);
    EXPECT_EQ(t[7].offset, long(text.size()) - 5);
}

struct BadBinary {
    const char* name;
    std::string text;
    long long offset;  // where the error is reported
    const char* mentions;
};

std::vector<BadBinary> badBinaryCases() {
    return {
        {"ReservedByte", bytes("Sphere \247"), 7, "0247 is not a binary RIB token"},
        {"RunProgramEnd", bytes("\200\001\377"), 2, "0377 ends a RunProgram answer"},
        {"UndefinedRequest", bytes("\314\001\222Hi\246\002"), 5, "request code 2 is used (0246) but was never defined"},
        {"BadRequestName", bytes("\314\001\223a b"), 0, "defined (0314) as \"a b\", which is not a request name"},
        {"DefinitionWithoutString", bytes("\314\001\200\001"), 0, "must be followed by a string"},
        {"UndefinedString", bytes("\315\003\221x\317\004"), 4, "string index 4 is used (0317) but was never defined"},
        {"UndefinedLongIndex", bytes("\320\001\000"), 0, "string index 256 is used (0320)"},
        {"TruncatedArray", bytes("\200\001\311\000\003\000\000\000\000\000\000\000\000\000\000"), 2,
         "truncated float array: 3 floats need 12 bytes, only 10 left"},
        {"TruncatedArrayLength", bytes("\313\000\001"), 0, "truncated binary RIB: a float array's length needs 4"},
        {"TruncatedString", bytes("\225abc"), 0, "truncated binary RIB: a string needs 5 more bytes, only 3 left"},
        {"TruncatedLongString", bytes("\241\001"), 0, "a string's length needs 2 more bytes, only 1 left"},
        {"TruncatedInteger", bytes("\203\000\000"), 0, "an integer needs 4 more bytes, only 2 left"},
        {"TruncatedDouble", bytes("\245\000\000\000\000\000"), 0, "a 64-bit float needs 4 more bytes"},
        {"NaNFloat", bytes("\200\000\244\177\300\000\000"), 2, "a binary float is NaN"},
        {"InfiniteDouble", bytes("\245\177\360\000\000\000\000\000\000"), 0, "a binary float is infinite"},
        {"NaNInArray", bytes("\310\002\000\000\000\000\377\300\000\000"), 6, "a binary float is NaN"},
    };
}

class MalformedBinaryRib : public testing::TestWithParam<BadBinary> {};

TEST_P(MalformedBinaryRib, IsAnErrorAtItsByte) {
    const BadBinary& c = GetParam();
    const InputError e = lexError(c.text);
    EXPECT_EQ(e.loc.offset, c.offset) << e.what();
    EXPECT_NE(e.message.find(c.mentions), std::string::npos) << e.what();
    EXPECT_EQ(e.loc.str(), "b.rib, byte " + std::to_string(c.offset));
}

INSTANTIATE_TEST_SUITE_P(Lexer, MalformedBinaryRib, testing::ValuesIn(badBinaryCases()),
                         [](const testing::TestParamInfo<BadBinary>& info) { return info.param.name; });

// Through the parser: a binary request's errors name its byte; a float array cannot sit inside [ ].
TEST(RibBinary, RequestErrorsNameTheRequestsByte) {
    Log log;
    const std::string rib = bytes("WorldBegin\n\314\000\231Translate\246\000\200\001\200\002");
    try {
        parseRibString(rib + "\nWorldEnd\n", "t.rib", log);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.str(), "t.rib, byte " + std::to_string(rib.find(bytes("\246\000"))));
        EXPECT_NE(e.message.find("Translate: expected 3 numbers"), std::string::npos) << e.what();
    }
    try {
        parseRibString(bytes("WorldBegin\nColor [ \310\001\000\000\000\000 ]\nWorldEnd\n"), "t.rib", log);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.str(), "t.rib, byte 19");
        EXPECT_NE(e.message.find("arrays cannot be nested: a binary float array inside the array opened at line 2"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace streyes
