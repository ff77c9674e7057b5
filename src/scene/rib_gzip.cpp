#include "scene/rib_gzip.h"

#include <zlib.h>

#include <algorithm>
#include <climits>
#include <new>

#include "streyes/error.h"

namespace streyes {

namespace {

[[noreturn]] void fail(const std::string& sourceName, size_t offset, const std::string& what) {
    throw InputError(SourceLoc{std::make_shared<const std::string>(sourceName), 0, 0, static_cast<long long>(offset)},
                     what);
}

// zlib counts in uInt: large buffers go through in pieces.
uInt piece(size_t n) { return uInt(std::min<size_t>(n, UINT_MAX)); }

}  // namespace

bool isGzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
           static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(std::string_view in, const std::string& sourceName) {
    z_stream zs{};
    if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw std::bad_alloc();  // 16: gzip only
    struct End {
        z_stream& zs;
        ~End() { inflateEnd(&zs); }
    } end{zs};
    std::string out;
    out.resize(std::max<size_t>(in.size() * 4, 1 << 16));
    size_t inPos = 0, outPos = 0, member = 0;  // member: where the current member starts
    while (true) {
        if (outPos == out.size()) out.resize(out.size() * 2);
        zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + inPos));
        zs.avail_in = piece(in.size() - inPos);
        zs.next_out = reinterpret_cast<Bytef*>(&out[outPos]);
        zs.avail_out = piece(out.size() - outPos);
        const uInt inBefore = zs.avail_in, outBefore = zs.avail_out;
        const int rc = inflate(&zs, Z_NO_FLUSH);
        inPos += inBefore - zs.avail_in;
        outPos += outBefore - zs.avail_out;
        if (rc == Z_STREAM_END) {
            if (inPos == in.size()) break;
            if (!isGzip(in.substr(inPos)))
                fail(sourceName, inPos,
                     std::to_string(in.size() - inPos) +
                         " bytes after the end of the gzip stream are not gzip data (is the file damaged?)");
            member = inPos;
            inflateReset(&zs);
            continue;
        }
        if (rc == Z_OK) continue;
        if (rc == Z_BUF_ERROR && inPos == in.size())
            fail(sourceName, in.size(),
                 "truncated gzip stream: the compressed data ends after " + std::to_string(in.size()) +
                     " bytes, before the stream does (was the file cut short?)");
        if (rc == Z_BUF_ERROR) continue;  // the output was full: more room next time round
        if (rc == Z_MEM_ERROR) throw std::bad_alloc();
        fail(sourceName, std::max(member, inPos - (inPos > 0 ? 1 : 0)),
             std::string("corrupt gzip stream: ") + (zs.msg ? zs.msg : "bad data") + " (is the file damaged?)");
    }
    out.resize(outPos);
    return out;
}

std::string gzip(std::string_view in, int level) {
    z_stream zs{};
    if (deflateInit2(&zs, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) throw std::bad_alloc();
    struct End {
        z_stream& zs;
        ~End() { deflateEnd(&zs); }
    } end{zs};
    std::string out;
    out.resize(std::max<size_t>(in.size() / 3, 1 << 12));
    size_t inPos = 0, outPos = 0;
    while (true) {
        if (outPos == out.size()) out.resize(out.size() * 2);
        zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data() + inPos));
        zs.avail_in = piece(in.size() - inPos);
        zs.next_out = reinterpret_cast<Bytef*>(&out[outPos]);
        zs.avail_out = piece(out.size() - outPos);
        const uInt inBefore = zs.avail_in, outBefore = zs.avail_out;
        const bool last = in.size() - inPos == zs.avail_in;
        const int rc = deflate(&zs, last ? Z_FINISH : Z_NO_FLUSH);
        inPos += inBefore - zs.avail_in;
        outPos += outBefore - zs.avail_out;
        if (rc == Z_STREAM_END) break;
        if (rc != Z_OK && rc != Z_BUF_ERROR) throw std::bad_alloc();
    }
    out.resize(outPos);
    return out;
}

}  // namespace streyes
