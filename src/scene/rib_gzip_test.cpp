// Gzip input and output (rib_gzip.h): round trips, several members, and every damaged stream an
// error naming the file and the byte, never a crash or a silently short scene.
#include <gtest/gtest.h>

#include <string>

#include "scene/rib_gzip.h"
#include "streyes/error.h"
#include "streyes/rib.h"

namespace streyes {
namespace {

std::string sampleText() {
    std::string s;
    for (int i = 0; i < 2000; ++i) s += "Translate " + std::to_string(i) + " 0.5 -1\n";
    return s;
}

TEST(RibGzip, RoundTripsAndIsToldByItsMagicBytes) {
    const std::string text = sampleText();
    const std::string z = gzip(text);
    EXPECT_TRUE(isGzip(z));
    EXPECT_FALSE(isGzip(text));
    EXPECT_FALSE(isGzip(std::string("\x1f", 1)));
    EXPECT_LT(z.size(), text.size() / 3);
    EXPECT_EQ(gunzip(z, "a.rib"), text);
    EXPECT_EQ(gunzip(gzip(""), "a.rib"), "");
    EXPECT_EQ(gunzip(gzip(text, 1), "a.rib"), text);
}

TEST(RibGzip, ConcatenatedMembersReadAsOneStream) {
    const std::string a = "WorldBegin\n", b = "WorldEnd\n";
    EXPECT_EQ(gunzip(gzip(a) + gzip(b), "m.rib"), a + b);
}

// Cut after every byte: each prefix is a truncated stream, reported at its end.
TEST(RibGzip, EveryTruncationIsAnErrorAtTheEnd) {
    const std::string z = gzip("WorldBegin\nSphere 1 -1 1 360\nWorldEnd\n");
    for (size_t n = 2; n < z.size(); ++n) {
        try {
            gunzip(z.substr(0, n), "cut.rib.gz");
            ADD_FAILURE() << "no error at " << n << " of " << z.size() << " bytes";
        } catch (const InputError& e) {
            EXPECT_EQ(e.loc.str(), "cut.rib.gz, byte " + std::to_string(n));
            EXPECT_NE(e.message.find("truncated gzip stream"), std::string::npos) << e.what();
        }
    }
}

TEST(RibGzip, DamageAndTrailingBytesAreErrors) {
    const std::string text = sampleText();
    std::string z = gzip(text);
    std::string crc = z;
    crc[crc.size() - 6] ^= 0x5a;  // the CRC-32 in the trailer
    try {
        gunzip(crc, "crc.rib.gz");
        ADD_FAILURE() << "a wrong checksum read";
    } catch (const InputError& e) {
        EXPECT_NE(e.message.find("corrupt gzip stream: incorrect data check"), std::string::npos) << e.what();
        EXPECT_EQ(*e.loc.file, "crc.rib.gz");
    }
    std::string method = z;
    method[2] = 9;  // not deflate
    try {
        gunzip(method, "m.rib.gz");
        ADD_FAILURE() << "an unknown method read";
    } catch (const InputError& e) {
        EXPECT_NE(e.message.find("corrupt gzip stream"), std::string::npos) << e.what();
    }
    try {
        gunzip(z + "junk", "t.rib.gz");
        ADD_FAILURE() << "trailing bytes read";
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.str(), "t.rib.gz, byte " + std::to_string(z.size()));
        EXPECT_NE(e.message.find("4 bytes after the end of the gzip stream are not gzip data"), std::string::npos);
    }
}

// The reader takes gzip wherever it takes RIB text: a string of compressed bytes is the scene.
TEST(RibGzip, TheReaderInflatesAndCountsLinesInTheInflatedText) {
    Log log;
    const Scene s = parseRibString(gzip("Format 40 30 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n"), "z.rib", log);
    EXPECT_EQ(s.camera.xres, 40);
    EXPECT_EQ(s.quadrics.size(), 1u);
    try {
        parseRibString(gzip("WorldBegin\n\nTranslate 1 2\nWorldEnd\n"), "z.rib", log);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.loc.str(), "z.rib:3");
    }
}

}  // namespace
}  // namespace streyes
