// `streyes catrib FILE.rib ... [-o OUT.rib]`: RIB written again in another encoding (ASCII, binary,
// gzip), as PRMan's catrib does: to make binary or compressed scenes, or to read one.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>

#include "commands.h"
#include "scene/rib_writer.h"
#include "streyes/error.h"

namespace streyes::cli {

const char* kCatribUsage = R"(usage: streyes catrib [options] FILE.rib ... [-o OUT.rib]

Writes the requests of RIB files again, one file after the other, in another encoding, as PRMan's
catrib does: comments are dropped, requests and their values kept exactly. The inputs may be ASCII
or binary RIB (or both mixed), gzip-compressed or not, told by their bytes ("-": standard input).

  --ascii       ASCII RIB, one request a line (the default)
  --binary      binary RIB (RenderMan Interface Specification 3.2, Appendix C): requests and
                recurring strings encoded, reals as 64-bit floats (exact)
  --float32     reals as 32-bit floats, as most binary RIB has them (about half the size; arrays
                become float arrays); with --ascii, the values those floats have
  --gzip        gzip-compress the output (what renderers read as .rib.gz)
  -o FILE       the output file (default: standard output, which must not be a terminal for
                binary or compressed output)

Only the syntax is checked (a malformed file stops it with file:line, or file and byte offset in
binary RIB, and exit status 2); what the requests mean is checked by render. Archives are not
expanded.
)";

namespace {

std::string readInput(const std::string& path) {
    if (path == "-") return std::string(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) throw InputError("cannot read '" + path + "': " + std::strerror(errno));
    return bytes.str();
}

}  // namespace

int catribCommand(const std::vector<std::string>& args) {
    RibEncoding encoding;
    std::string output = "-";
    std::vector<std::string> inputs;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--ascii") encoding.binary = false;
        else if (a == "--binary") encoding.binary = true;
        else if (a == "--float32") encoding.float32 = true;
        else if (a == "--gzip") encoding.gzip = true;
        else if (a == "-o" || a == "--output") {
            if (i + 1 == args.size()) throw UsageError(a + " needs a file name");
            output = args[++i];
        } else if (a.size() > 1 && a[0] == '-') throw UsageError("unknown option '" + a + "'");
        else inputs.push_back(a);
    }
    if (inputs.empty()) throw UsageError("no RIB file given");
    if (output == "-" && (encoding.binary || encoding.gzip) && isatty(STDOUT_FILENO))
        throw UsageError("binary or compressed RIB is not for a terminal: give -o FILE");

    RibWriter writer(encoding);
    for (const std::string& path : inputs) encodeRib(writer, readInput(path), path == "-" ? "<stdin>" : path);
    const std::string bytes = writer.finish();

    if (output == "-") {
        if (std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size() || std::fflush(stdout) != 0)
            throw RenderError(std::string("cannot write to standard output: ") + std::strerror(errno));
        return 0;
    }
    std::ofstream out(output, std::ios::binary | std::ios::trunc);
    if (!out) throw RenderError("cannot write '" + output + "': " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out.flush()) throw RenderError("cannot write '" + output + "': " + std::strerror(errno));
    return 0;
}

}  // namespace streyes::cli
