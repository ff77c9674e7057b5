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

#include "command_line.h"
#include "commands.h"
#include "scene/rib_writer.h"
#include "streyes/error.h"

namespace streyes::cli {

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
    CommandLine cl("catrib", "usage: streyes catrib [options] FILE.rib ... [-o OUT.rib]",
                   "\nWrites the requests of RIB files again, one file after the other, in another encoding, as "
                   "PRMan's\ncatrib does: comments are dropped, requests and their values kept exactly. The inputs "
                   "may be ASCII\nor binary RIB (or both mixed), gzip-compressed or not, told by their bytes (\"-\": "
                   "standard input).");
    RibEncoding encoding;
    std::string output = "-";
    std::vector<std::string> inputs;
    bool ascii = false, binary = false;
    cl.positionals("files", "the RIB files, \"-\" for standard input", &inputs)->type_name("FILE.rib");
    cl.flag("--ascii", "ASCII RIB, one request a line (the default)", &ascii);
    cl.flag("--binary",
            "binary RIB (RenderMan Interface Specification 3.2, Appendix C): requests and\n"
            "recurring strings encoded, reals as 64-bit floats (exact)",
            &binary);
    cl.flag("--float32",
            "reals as 32-bit floats, as most binary RIB has them (about half the size; arrays\n"
            "become float arrays); with --ascii, the values those floats have",
            &encoding.float32);
    cl.flag("--gzip", "gzip-compress the output (what renderers read as .rib.gz)", &encoding.gzip);
    cl.value("-o,--output", "FILE",
             "the output file (default: standard output, which must not be a terminal for\n"
             "binary or compressed output)",
             &output);
    cl.app().footer("Only the syntax is checked (a malformed file stops it with file:line, or file and byte offset "
                    "in\nbinary RIB, and exit status 2); what the requests mean is checked by render. Archives are "
                    "not\nexpanded.");
    if (!cl.parse(args)) return 0;
    if (ascii && binary) throw UsageError("--ascii and --binary: give one encoding");
    encoding.binary = binary;
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
