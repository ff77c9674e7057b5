#include "streyes/image_io.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "io/exr_file.h"
#include "io/image_library.h"
#include "util/aov.h"
#include "streyes/error.h"

namespace streyes {

namespace fs = std::filesystem;

bool validChannelMode(const std::string& mode) { return !modeOutputs(mode, nullptr).empty(); }

namespace {

// The modes frames have always been written in (encodeExr); any other goes channel by channel.
bool colourMode(const std::string& mode) { return mode == "rgb" || mode == "rgba" || mode == "rgbaz"; }

// The channels of `mode` from the frame, interleaved. Throws RenderError when the frame does not
// carry an output variable the mode names.
std::vector<float> channelPixels(const std::string& path, const FrameImage& image, const std::vector<std::string>& channels) {
    const size_t n = size_t(image.width) * size_t(image.height), nc = channels.size(), na = image.aovNames.size();
    std::vector<float> data(n * nc);
    for (size_t c = 0; c < nc; ++c) {
        const std::string& name = channels[c];
        const float* src = nullptr;
        size_t stride = 1;
        if (name == "R" || name == "G" || name == "B" || name == "A") {
            src = image.rgba.data() + (name == "R" ? 0 : name == "G" ? 1 : name == "B" ? 2 : 3);
            stride = 4;
        } else if (name == "Z") {
            src = image.z.data();
        } else {
            for (size_t a = 0; a < na; ++a)
                if (image.aovNames[a] == name) src = image.aov.data() + a, stride = na;
        }
        if (!src) throw RenderError("cannot write '" + path + "': the frame has no channel " + name);
        for (size_t i = 0; i < n; ++i) data[i * nc + c] = src[i * stride];
    }
    return data;
}

}  // namespace

bool hasFrameField(const std::string& pattern) { return pattern.find('#') != std::string::npos; }

std::string expandFramePattern(const std::string& pattern, int frame) {
    size_t a = pattern.find('#');
    if (a == std::string::npos) return pattern;
    size_t b = pattern.find_first_not_of('#', a);
    if (b == std::string::npos) b = pattern.size();
    char buf[32];
    std::snprintf(buf, sizeof buf, "%0*d", int(b - a), frame);
    return pattern.substr(0, a) + buf + pattern.substr(b);
}

std::string addFrameField(const std::string& pattern) {
    fs::path p(pattern);
    std::string ext = p.extension().string();
    std::string stem = pattern.substr(0, pattern.size() - ext.size());
    return stem + ".####" + ext;
}

std::vector<int> findFrames(const std::string& pattern) {
    const fs::path p(pattern);
    const std::string name = p.filename().string();
    if (pattern.find('#') < pattern.size() - name.size())
        throw InputError("frame pattern '" + pattern + "': the #### frame field must be in the file name, not a folder");
    const size_t a = name.find('#');
    if (a == std::string::npos) return {};
    const size_t b = std::min(name.find_first_not_of('#', a), name.size());
    const std::string prefix = name.substr(0, a), suffix = name.substr(b);
    std::vector<int> frames;
    std::error_code ec;
    for (fs::directory_iterator it(p.has_parent_path() ? p.parent_path() : fs::path("."), ec), end; !ec && it != end;
         it.increment(ec)) {
        // A candidate is prefix + [-]digits + suffix; expanding the pattern again must give the
        // same name, which rejects "a.7.exr" for "a.####.exr" and out-of-range numbers.
        const std::string n = it->path().filename().string();
        if (n.size() <= prefix.size() + suffix.size() || n.compare(0, prefix.size(), prefix) != 0 ||
            n.compare(n.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string digits = n.substr(prefix.size(), n.size() - prefix.size() - suffix.size());
        if (digits.size() > 9 || digits.find_first_not_of("-0123456789") != std::string::npos) continue;
        char* rest = nullptr;
        const long f = std::strtol(digits.c_str(), &rest, 10);
        if (*rest != '\0' || expandFramePattern(name, int(f)) != n) continue;
        frames.push_back(int(f));
    }
    std::sort(frames.begin(), frames.end());
    return frames;
}

namespace {

fs::path folderOf(const fs::path& target) { return target.has_parent_path() ? target.parent_path() : fs::path("."); }

// Throws, saying what to do, unless `dir` (where `path` goes, chosen by `option`) is a folder.
void requireFolder(const std::string& path, const fs::path& dir, const std::string& option) {
    std::error_code ec;
    const fs::file_status st = fs::status(dir, ec);
    if (fs::is_directory(st)) return;
    const std::string what = "cannot write '" + path + "': ";
    if (fs::exists(st)) throw RenderError(what + "'" + dir.string() + "' is not a folder (choose another " + option + ")");
    if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory)
        throw RenderError(what + "cannot reach the folder '" + dir.string() + "' (" + ec.message() + ")");
    throw RenderError(what + "the folder '" + dir.string() + "' does not exist (create it, or choose another " + option +
                      ")");
}

RenderError notWritable(const std::string& path, const fs::path& dir, int err) {
    return RenderError("cannot write '" + path + "': the folder '" + dir.string() + "' is not writable (" +
                       std::strerror(err) + ")");
}

}  // namespace

void checkWritableFolder(const std::string& path, const std::string& option) {
    const fs::path target(path);
    const fs::path dir = folderOf(target);
    requireFolder(path, dir, option);
    // Permission bits do not say (root ignores them; a read-only mount, a full inode table): a
    // file is created and removed.
    const fs::path probe = dir / ("." + target.stem().string() + ".probe" + std::to_string(getpid()));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw notWritable(path, dir, errno);
    ::close(fd);
    if (::unlink(probe.c_str()) != 0)
        throw RenderError("cannot write '" + path + "': the probe file '" + probe.string() + "' cannot be removed (" +
                          std::strerror(errno) + "; remove it, or choose another " + option + ")");
}

namespace {

// The last frame encoded, and its bytes.
struct EncodedFrame {
    int width = 0, height = 0, x0 = 0, y0 = 0, fullWidth = 0, fullHeight = 0;
    std::string mode, ext;
    std::vector<float> rgba, z, aov;
    std::vector<std::string> aovNames;
    std::vector<unsigned char> bytes;
    // A quantized file's: its quantization and, where it dithers, the frame (the dither follows it).
    Quantize quantize;
    int frame = 0;
};
EncodedFrame& lastEncoded() {
    static EncodedFrame last;
    return last;
}
std::mutex& lastEncodedMutex() {
    static std::mutex m;
    return m;
}
// Bit for bit (NaNs included, and -0 apart from 0).
bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}
std::vector<unsigned char> encodeFrame(const std::string& path, const FrameImage& image, const std::string& mode,
                                       const std::string& ext, bool exr, int nch, bool alpha, bool z, const Quantize& q,
                                       const FrameWindow& window);
void writeBytesInPlace(const std::string& path, const std::vector<unsigned char>& bytes);

// Is channel `channel` one of shader output `name`'s ("name", or "name.X" and the like)?
bool channelOf(const std::string& channel, const std::string& name) {
    return channel == name || (channel.size() > name.size() && channel.compare(0, name.size(), name) == 0 &&
                               channel[name.size()] == '.');
}

// The channels `mode` writes from `image`: a shader output's are the frame's channels of its name.
std::vector<std::string> channelsOf(const std::string& mode, const FrameImage& image) {
    std::vector<std::string> channels;
    for (const std::string& o : modeOutputs(mode, nullptr)) {
        std::vector<std::string> add = modeChannels(o);
        if (add.empty())
            for (const std::string& c : image.aovNames)
                if (channelOf(c, o)) add.push_back(c);
        for (const std::string& c : add)
            if (std::find(channels.begin(), channels.end(), c) == channels.end()) channels.push_back(c);
    }
    return channels;
}

}  // namespace

void writeFrame(const std::string& path, const FrameImage& image, const std::string& mode, const Quantize& quantize,
                const FrameWindow& window) {
    const fs::path target(path);
    const fs::path dir = folderOf(target);
    requireFolder(path, dir, "-o");
    if (access(dir.c_str(), W_OK) != 0) throw notWritable(path, dir, errno);

    const bool alpha = mode != "rgb", z = mode == "rgbaz";
    const int nch = 3 + (alpha ? 1 : 0) + (z ? 1 : 0);
    std::string ext = target.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool exr = ext == ".exr" || ext.empty();
    const Quantize q = exr ? Quantize{} : quantize;  // EXR holds floats
    auto sameQuantize = [&](const Quantize& a) {
        return a.zero == q.zero && a.one == q.one && a.min == q.min && a.max == q.max && a.dither == q.dither;
    };

    // A frame whose pixels equal the last frame encoded (a still shot: every frame of it) reuses
    // its bytes: the encoding is a function of the pixels and the format only (no date, no frame
    // number in the header), so the file is the same, bit for bit, and 64 still frames cost one
    // encoding instead of 64.
    std::vector<unsigned char> bytes;
    {
        std::lock_guard<std::mutex> lock(lastEncodedMutex());
        const EncodedFrame& last = lastEncoded();
        if (last.width == image.width && last.height == image.height && last.x0 == window.x0 && last.y0 == window.y0 &&
            last.fullWidth == window.fullWidth && last.fullHeight == window.fullHeight && last.mode == mode && last.ext == ext &&
            sameBits(last.rgba, image.rgba) && sameBits(last.z, image.z) && sameBits(last.aov, image.aov) &&
            last.aovNames == image.aovNames && sameQuantize(last.quantize) &&
            (q.floats() || q.dither == 0 || last.frame == image.frame))
            bytes = last.bytes;
    }
    if (bytes.empty()) bytes = encodeFrame(path, image, mode, ext, exr, nch, alpha, z, q, window);
    writeBytesInPlace(path, bytes);
}

void writeFileAtomically(const std::string& path, const std::vector<unsigned char>& bytes) {
    const fs::path target(path);
    const fs::path dir = folderOf(target);
    requireFolder(path, dir, "-o");
    if (access(dir.c_str(), W_OK) != 0) throw notWritable(path, dir, errno);
    writeBytesInPlace(path, bytes);
}

namespace {

// Quantizes interleaved pixels of `channels` channels in place (Quantize::apply), then scales them
// to [0, 1] of the storage's integers, which OpenImageIO's float-to-integer conversion turns back
// into exactly those integers (round(v / M * M) = v for every v up to 65535 in float).
void quantizePixels(std::vector<float>& data, int channels, const FrameImage& image, const Quantize& q) {
    if (q.floats()) return;
    const double scale = 1 / q.storageMax();
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float* p = &data[(size_t(y) * size_t(image.width) + size_t(x)) * size_t(channels)];
            for (int c = 0; c < channels; ++c) p[c] = float(q.apply(p[c], x, y, image.frame) * scale);
        }
}

std::vector<unsigned char> encodeFrame(const std::string& path, const FrameImage& image, const std::string& mode,
                                       const std::string& ext, bool exr, int nch, bool alpha, bool z,
                                       const Quantize& q, const FrameWindow& window) {
    // EXR frames through OpenEXR; anything else (a contact sheet's PNG) through the image library.
    std::vector<unsigned char> bytes;
    if (!colourMode(mode)) {
        const std::vector<std::string> channels = channelsOf(mode, image);
        for (const std::string& o : modeOutputs(mode, nullptr))
            if (modeChannels(o).empty() && std::none_of(channels.begin(), channels.end(),
                                                        [&](const std::string& c) { return channelOf(c, o); }))
                throw RenderError("cannot write '" + path + "': the frame has no output variable " + o);
        std::vector<float> data = channelPixels(path, image, channels);
        std::string why;
        try {
            if (exr) bytes = encodeExrChannels(image.width, image.height, channels, data, &window);
        } catch (const std::bad_alloc&) {
            throw;  // out of memory, not a file's fault: the command says so (memory.h)
        } catch (const std::exception& e) {
            throw RenderError("cannot write '" + path + "': " + e.what());
        }
        if (!exr) quantizePixels(data, int(channels.size()), image, q);
        if (!exr && !imageLibrary().encode(path, image.width, image.height, channels, data.data(), q.storage(), &bytes,
                                           &why))
            throw RenderError("cannot write '" + path + "': " + why + " ('" + ext + "')");
    } else if (exr) {
        try {
            bytes = encodeExr(image, alpha, z, &window);
        } catch (const std::bad_alloc&) {
            throw;  // out of memory, not a file's fault: the command says so (memory.h)
        } catch (const std::exception& e) {
            throw RenderError("cannot write '" + path + "': " + e.what());
        }
    } else {
        std::vector<std::string> channels = {"R", "G", "B"};
        if (alpha) channels.push_back("A");
        if (z) channels.push_back("Z");
        std::vector<float> data(size_t(image.width) * size_t(image.height) * size_t(nch));
        for (size_t i = 0, n = size_t(image.width) * size_t(image.height); i < n; ++i) {
            float* d = &data[i * size_t(nch)];
            for (int c = 0; c < 3 + (alpha ? 1 : 0); ++c) d[c] = image.rgba[i * 4 + size_t(c)];
            if (z) d[nch - 1] = image.z[i];
        }
        quantizePixels(data, nch, image, q);
        std::string why;
        if (!imageLibrary().encode(path, image.width, image.height, channels, data.data(), q.storage(), &bytes, &why))
            throw RenderError("cannot write '" + path + "': " + why + " ('" + ext + "')");
    }
    std::lock_guard<std::mutex> lock(lastEncodedMutex());
    EncodedFrame& last = lastEncoded();
    last.width = image.width, last.height = image.height, last.mode = mode, last.ext = ext;
    last.x0 = window.x0, last.y0 = window.y0, last.fullWidth = window.fullWidth, last.fullHeight = window.fullHeight;
    last.rgba = image.rgba, last.z = image.z, last.bytes = bytes;
    last.aov = image.aov, last.aovNames = image.aovNames;
    last.quantize = q, last.frame = image.frame;
    return bytes;
}

void writeBytesInPlace(const std::string& path, const std::vector<unsigned char>& bytes) {
    const fs::path target(path);
    std::error_code ec;
    const fs::path tmp = temporaryFrameName(path, int(getpid()));
    auto fail = [&](const std::string& why) {
        std::error_code ignore;
        fs::remove(tmp, ignore);
        throw RenderError("cannot write '" + path + "': " + why);
    };
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) fail(std::strerror(errno));
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = n < 0 ? errno : EIO;
            ::close(fd);
            fail(std::strerror(err));
        }
        done += size_t(n);
    }
    if (::fsync(fd) != 0) {
        const int err = errno;
        ::close(fd);
        fail(std::strerror(err));
    }
    if (::close(fd) != 0) fail(std::strerror(errno));
    fs::rename(tmp, target, ec);
    if (ec) fail(ec.message());
}

}  // namespace

std::string temporaryFrameName(const std::string& path, int pid) {
    const fs::path target(path);
    return (target.parent_path() / ("." + target.stem().string() + ".tmp" + std::to_string(pid) +
                                    target.extension().string()))
        .string();
}

namespace {

// Does `name` read `pattern`, where a run of '#' stands for a frame number (digits, perhaps a
// minus sign, at least as many characters as the run, as expandFramePattern writes them)?
bool matchesFramePattern(const std::string& name, const std::string& pattern) {
    size_t i = 0, p = 0;
    while (p < pattern.size()) {
        if (pattern[p] != '#') {
            if (i >= name.size() || name[i] != pattern[p]) return false;
            ++i, ++p;
            continue;
        }
        size_t run = pattern.find_first_not_of('#', p);
        if (run == std::string::npos) run = pattern.size();
        const size_t start = i;
        if (i < name.size() && name[i] == '-') ++i;
        const size_t digits = i;
        while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
        if (i == digits || i - start < run - p) return false;
        p = run;
    }
    return i == name.size();
}

}  // namespace

// Temporaries are ".STEM.tmpPID.EXT" (temporaryFrameName) for the frames of `pattern`.
int removeStaleTemporaries(const std::string& pattern) {
    const fs::path p(pattern);
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    const std::string prefix = "." + p.stem().string(), ext = p.extension().string();
    int removed = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string file = entry.path().filename().string();
        // Split ".STEM" + ".tmp" + PID + EXT at the last ".tmp".
        const size_t tmp = file.rfind(".tmp");
        if (tmp == std::string::npos || file.size() < ext.size() ||
            file.compare(file.size() - ext.size(), ext.size(), ext) != 0)
            continue;
        const std::string pidText = file.substr(tmp + 4, file.size() - ext.size() - tmp - 4);
        if (pidText.empty() || pidText.find_first_not_of("0123456789") != std::string::npos || pidText.size() > 9)
            continue;
        if (!matchesFramePattern(file.substr(0, tmp), prefix)) continue;
        // The writer is gone when no process has its id (a live one, even someone else's, stays).
        const long pid = std::strtol(pidText.c_str(), nullptr, 10);
        if (pid <= 0 || pid == long(getpid())) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;
        if (fs::remove(entry.path(), ec)) ++removed;
    }
    return removed;
}

bool isCompleteFrame(const std::string& path, int width, int height, const std::string& mode) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    // As readExr orders them: R, G, B, A, then the others by name.
    std::vector<std::string> channels = modeChannels(mode);
    std::stable_sort(channels.begin(), channels.end(), [](const std::string& a, const std::string& b) {
        auto rank = [](const std::string& n) { return n == "R" ? 0 : n == "G" ? 1 : n == "B" ? 2 : n == "A" ? 3 : 4; };
        return rank(a) != rank(b) ? rank(a) < rank(b) : (rank(a) == 4 && a < b);
    });
    // Reading every pixel is what proves the file complete: a truncated EXR has a good header.
    ImageData img;
    std::string why;
    if (!isExrFile(path) || !readExr(path, &img, &why)) return false;
    if (img.width != width || img.height != height) return false;
    // Shader outputs: whatever channels of their names the file has (their types are the scene's).
    std::vector<std::string> shaderOutputs;
    for (const std::string& o : modeOutputs(mode, nullptr))
        if (modeChannels(o).empty()) shaderOutputs.push_back(o);
    if (shaderOutputs.empty()) return img.channels == channels;
    std::vector<std::string> rest;
    for (const std::string& c : img.channels) {
        bool ofOutput = false;
        for (const std::string& o : shaderOutputs) ofOutput = ofOutput || channelOf(c, o);
        if (!ofOutput) rest.push_back(c);
    }
    for (const std::string& o : shaderOutputs)
        if (std::none_of(img.channels.begin(), img.channels.end(), [&](const std::string& c) { return channelOf(c, o); }))
            return false;
    return rest == channels;
}

int ImageData::channelIndex(const std::string& name) const {
    for (size_t i = 0; i < channels.size(); ++i)
        if (channels[i] == name) return int(i);
    return -1;
}

ImageData readImage(const std::string& path) {
    ImageData img;
    std::string why;
    const bool ok = isExrFile(path) ? readExr(path, &img, &why) : imageLibrary().read(path, &img, &why);
    if (!ok) {
        std::error_code ec;
        if (!fs::exists(path, ec)) why = "no such file";
        throw RenderError("cannot read '" + path + "': " + why);
    }
    return img;
}

}  // namespace streyes
