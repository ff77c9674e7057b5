// Gzip-compressed RIB (RFC 1952, through zlib): how large scenes and archives are often stored.
// Reading tells gzip by its magic bytes (1f 8b), never by the file's name, so a compressed file
// reads wherever a RIB file does (the scene, ReadArchive, DelayedReadArchive, frame files).
#pragma once

#include <string>
#include <string_view>

namespace streyes {

// Does `bytes` start with gzip's magic number?
bool isGzip(std::string_view bytes);

// Every member of a gzip stream, inflated and joined (as gzip -d does). A stream that is cut
// short, corrupt (a bad header, bad data or a wrong checksum) or followed by bytes that are not
// another member is an InputError naming `sourceName` and the byte of the compressed input where
// it goes wrong.
std::string gunzip(std::string_view bytes, const std::string& sourceName);

// `bytes` as one gzip member, at zlib's `level` (1 fastest ... 9 smallest).
std::string gzip(std::string_view bytes, int level = 6);

}  // namespace streyes
