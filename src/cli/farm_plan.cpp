#include "farm_plan.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "farm_curve_data.h"  // generated at configure time from docs/results/block-curve.json

namespace streyes::farm {

namespace fs = std::filesystem;

std::string Block::str() const {
    return first == last ? std::to_string(first) : std::to_string(first) + "-" + std::to_string(last);
}

std::vector<Block> cutBlocks(int first, int last, int length) {
    std::vector<Block> blocks;
    if (length < 1 || last < first) return blocks;
    for (long f = first; f <= last; f += length) blocks.push_back({int(f), int(std::min<long>(last, f + length - 1))});
    return blocks;
}

namespace {
// "a-b" runs of consecutive numbers, joined by `sep`.
std::string runs(std::vector<int> v, const std::string& sep) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    std::string out;
    for (size_t i = 0; i < v.size();) {
        size_t j = i;
        while (j + 1 < v.size() && v[j + 1] == v[j] + 1) ++j;
        if (!out.empty()) out += sep;
        out += std::to_string(v[i]);
        if (j > i) out += "-" + std::to_string(v[j]);
        i = j + 1;
    }
    return out;
}
}  // namespace

std::string indexList(const std::vector<int>& indices) { return runs(indices, ","); }
std::string frameRanges(const std::vector<int>& frames) { return runs(frames, ", "); }

// ---- The block-length curve ----------------------------------------------------------------------

double BlockCurve::at(double length) const {
    if (blocks.empty()) return 1;
    if (length <= blocks.front()) return cpuPerFrame.front();
    if (length >= blocks.back()) return cpuPerFrame.back();
    size_t k = 1;
    while (blocks[k] < length) ++k;
    const double x0 = 1.0 / blocks[k - 1], x1 = 1.0 / blocks[k], x = 1.0 / length;
    const double t = (x - x0) / (x1 - x0);
    return cpuPerFrame[k - 1] + t * (cpuPerFrame[k] - cpuPerFrame[k - 1]);
}

std::vector<BlockCurve> readCurves(const Json& doc, const std::string& what) {
    const Json& curves = member(doc, "curves");
    if (!curves.is_object()) throw std::runtime_error(what + ": no \"curves\" object (is it tools/block-curve's output?)");
    std::vector<BlockCurve> out;
    for (const auto& [name, c] : curves.items()) {
        BlockCurve bc;
        bc.name = name;
        bc.scene = str(member(c, "scene"));
        const Json& res = member(c, "resolution");
        if (res.is_array() && res.size() == 2) {
            bc.width = int(num(res[0]));
            bc.height = int(num(res[1]));
        }
        std::vector<std::pair<int, double>> pts;
        const Json& points = member(c, "points");
        if (!points.is_array()) throw std::runtime_error(what + ": curve '" + name + "' has no \"points\" array");
        for (const Json& p : points) {
            const double L = num(member(p, "block"), 0), cpu = num(member(p, "cpu_per_frame"), -1);
            if (L < 1 || !(cpu > 0)) throw std::runtime_error(what + ": curve '" + name + "' has a point without a "
                                                              "block of at least 1 and a positive cpu_per_frame");
            pts.emplace_back(int(L), cpu);
        }
        if (pts.empty()) throw std::runtime_error(what + ": curve '" + name + "' has no points");
        std::sort(pts.begin(), pts.end());
        for (const auto& [L, cpu] : pts) {
            if (!bc.blocks.empty() && bc.blocks.back() == L) continue;
            bc.blocks.push_back(L);
            bc.cpuPerFrame.push_back(cpu);
        }
        out.push_back(std::move(bc));
    }
    return out;
}

std::vector<BlockCurve> builtinCurves() {
    return readCurves(parseJson(kBuiltinBlockCurveJson, "the built-in block curve (docs/results/block-curve.json)"),
                      "the built-in block curve (docs/results/block-curve.json)");
}

BlockCurve findCurve(const std::string& spec) {
    auto names = [](const std::vector<BlockCurve>& cs) {
        std::string s;
        for (const BlockCurve& c : cs) s += (s.empty() ? "" : ", ") + c.name;
        return s;
    };
    std::string file = spec, name;
    if (!fs::exists(file)) {
        size_t colon = spec.rfind(':');
        if (colon != std::string::npos && fs::exists(spec.substr(0, colon))) {
            file = spec.substr(0, colon);
            name = spec.substr(colon + 1);
        } else {
            file.clear();
            name = spec;
        }
    }
    const std::vector<BlockCurve> curves = file.empty() ? builtinCurves() : readCurves(loadJson(file), file);
    if (!file.empty() && name.empty()) {
        if (curves.size() == 1) return curves[0];
        throw std::runtime_error("'" + file + "' holds several curves (" + names(curves) + "): give one as " + file +
                                 ":NAME");
    }
    for (const BlockCurve& c : curves)
        if (c.name == name) return c;
    throw std::runtime_error("no block curve '" + name + "'" + (file.empty() ? "" : " in '" + file + "'") +
                             ": the " + (file.empty() ? "built-in curves are " : "file has ") + names(curves) +
                             (file.empty() ? ", or give a file written by tools/block-curve" : ""));
}

BlockChoice chooseBlock(int frames, int slots, const BlockCurve& curve, int renderBlock, int maxBlock) {
    BlockChoice choice;
    slots = std::max(1, slots);
    renderBlock = std::max(1, renderBlock);
    const int longest = std::max(1, std::min(frames, maxBlock));
    for (int L = 1; L <= longest; ++L) {
        BlockOption o;
        o.block = L;
        o.tasks = (frames + L - 1) / L;
        o.waves = (o.tasks + slots - 1) / slots;
        // Tasks start in order as slots free up; all blocks but the last are equally long, so the
        // waves of `slots` tasks model the schedule: each wave takes as long as its longest task.
        const std::vector<Block> blocks = cutBlocks(1, frames, L);
        double waveTime = 0;
        for (size_t k = 0; k < blocks.size(); ++k) {
            // The renderer cuts a task into its own frame blocks of renderBlock frames, the last
            // shorter: each costs what a block of its length costs (counting the process's start
            // once a block: conservative).
            double t = 0;
            for (int left = blocks[k].length(); left > 0; left -= renderBlock) {
                const int m = std::min(left, renderBlock);
                t += m * curve.at(m);
            }
            o.cpu += t;
            waveTime = std::max(waveTime, t);
            if ((k + 1) % size_t(slots) == 0 || k + 1 == blocks.size()) {
                o.wall += waveTime;
                waveTime = 0;
            }
        }
        choice.options.push_back(o);
    }
    double minWall = choice.options[0].wall;
    for (const BlockOption& o : choice.options) minWall = std::min(minWall, o.wall);
    // Within 5% of the shortest wall time, the least CPU; of those as cheap (within 0.5%), the
    // shortest wall time; of those as quick (within 0.5%), the shortest block.
    double minCpu = -1;
    for (const BlockOption& o : choice.options)
        if (o.wall <= minWall * 1.05 && (minCpu < 0 || o.cpu < minCpu)) minCpu = o.cpu;
    auto cheap = [&](const BlockOption& o) { return o.wall <= minWall * 1.05 && o.cpu <= minCpu * 1.005; };
    double quickest = -1;
    for (const BlockOption& o : choice.options)
        if (cheap(o) && (quickest < 0 || o.wall < quickest)) quickest = o.wall;
    for (const BlockOption& o : choice.options)
        if (cheap(o) && o.wall <= quickest * 1.005) {
            choice.chosen = o;
            break;
        }
    const BlockOption& c = choice.chosen;
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "block %d: %d task%s on %d slot%s (%d wave%s); from curve '%s', the shortest modelled wall time "
                  "(within 5%%) at the least CPU; %.2f CPU s per frame against %.2f at block 1%s",
                  c.block, c.tasks, c.tasks == 1 ? "" : "s", slots, slots == 1 ? "" : "s", c.waves,
                  c.waves == 1 ? "" : "s", curve.name.c_str(), curve.at(std::min(c.block, renderBlock)), curve.at(1),
                  renderBlock < longest ? (", the renderer keeping at most " + std::to_string(renderBlock) +
                                           " frames together at this size").c_str()
                                        : "");
    choice.why = buf;
    return choice;
}

// ---- The manifest ------------------------------------------------------------------------------------

std::string manifestPathFor(const std::string& outputPattern) {
    const fs::path p(outputPattern);
    std::string name = p.filename().string();
    size_t hash = name.find('#');
    std::string stem = hash == std::string::npos ? fs::path(name).stem().string() : name.substr(0, hash);
    while (!stem.empty() && (stem.back() == '.' || stem.back() == '_' || stem.back() == '-')) stem.pop_back();
    if (stem.empty()) stem = "frames";
    return (p.parent_path() / (stem + ".farm.json")).string();
}

std::string shellQuote(const std::string& s) {
    if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                          "@%+=:,./_-") == std::string::npos)
        return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string Manifest::farmDir() const {
    std::string p = path;
    if (p.size() > 5 && p.compare(p.size() - 5, 5, ".json") == 0) p.resize(p.size() - 5);
    return p;
}

std::string Manifest::logPath(long job, int task) const {
    return farmDir() + "/logs/" + std::to_string(job) + "_" + std::to_string(task) + ".log";
}

std::string Manifest::statsPath(long job, int task) const {
    return farmDir() + "/stats/" + std::to_string(job) + "_" + std::to_string(task) + ".json";
}

std::vector<std::string> Manifest::taskCommand(const Block& b, const std::string& stats) const {
    // --shot: every task decides what the whole animation decides (motion segments, procedural
    // detail) over the frames one machine rendering first..last would, so that its frames equal
    // that machine's.
    std::vector<std::string> cmd = {executable, "render", scene, "--frames", b.str(),
                                    "--shot", Block{shotFirst, shotLast}.str(),
                                    "-o", output, "--resume", "--seed", std::to_string(seed)};
    cmd.insert(cmd.end(), renderOptions.begin(), renderOptions.end());
    if (cpusPerTask > 0) {
        cmd.push_back("--threads");
        cmd.push_back(std::to_string(cpusPerTask));
    }
    cmd.push_back("--stats");
    cmd.push_back(stats);
    return cmd;
}

std::string Manifest::batchScript(int submissionNumber) const {
    std::string blockList;
    for (const Block& b : blocks) blockList += (blockList.empty() ? "" : " ") + b.str();
    // The render line with the block and the stats file left to the shell.
    std::vector<std::string> cmd = taskCommand(Block{0, 0}, "");
    std::string line;
    for (size_t i = 0; i < cmd.size(); ++i) {
        std::string w;
        if (i == 4) w = "\"$FRAMES\"";
        else if (i + 1 == cmd.size()) w = shellQuote(farmDir() + "/stats/") + "\"$TAG.json\"";
        else w = shellQuote(cmd[i]);
        line += (i ? " " : "") + w;
    }
    std::string s;
    s += "#!/bin/bash\n";
    s += "# streyes farm: one frame block of the shot " + path + " per array task\n";
    s += "# (submission " + std::to_string(submissionNumber) + ", written by `streyes farm submit`). A task's whole work is\n";
    s += "# the render line below: --resume skips the frames already complete and --seed fixes the samples,\n";
    s += "# so a task that is requeued or run again renders only what is missing, to the same pixels.\n";
    s += "BLOCKS=(" + blockList + ")\n";
    s += "FRAMES=${BLOCKS[$SLURM_ARRAY_TASK_ID]}\n";
    s += "TAG=${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\n";
    s += "echo \"streyes farm: job $SLURM_ARRAY_JOB_ID task $SLURM_ARRAY_TASK_ID, frames $FRAMES, on $(hostname -s), "
         "attempt $((${SLURM_RESTART_COUNT:-0} + 1)), $(date '+%F %T')\"\n";
    s += "set -- " + line + "\n";
    s += "echo \"streyes farm: $*\"\n";
    s += "\"$@\"\n";
    s += "status=$?\n";
    s += "echo \"streyes farm: exit code $status, $(date '+%F %T')\"\n";
    s += "exit $status\n";
    return s;
}

bool Manifest::sameShot(const Manifest& o, std::string* difference) const {
    auto differs = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
        if (difference) *difference = "its " + what + " " + mine + ", not " + theirs;
        return false;
    };
    auto join = [](const std::vector<std::string>& v) {
        std::string s;
        for (const std::string& w : v) s += (s.empty() ? "" : " ") + w;
        return s.empty() ? std::string("(none)") : "'" + s + "'";
    };
    if (scene != o.scene) return differs("scene is", scene, o.scene);
    if (output != o.output) return differs("output is", output, o.output);
    if (first != o.first || last != o.last)
        return differs("frames are", Block{first, last}.str(), Block{o.first, o.last}.str());
    if (shotFirst != o.shotFirst || shotLast != o.shotLast)
        return differs("shot is", Block{shotFirst, shotLast}.str(), Block{o.shotFirst, o.shotLast}.str());
    if (block != o.block) return differs("block length is", std::to_string(block), std::to_string(o.block));
    if (seed != o.seed) return differs("seed is", std::to_string(seed), std::to_string(o.seed));
    if (renderOptions != o.renderOptions) return differs("render options are", join(renderOptions), join(o.renderOptions));
    if (width != o.width || height != o.height || channels != o.channels)
        return differs("frames are", std::to_string(width) + "x" + std::to_string(height) + " " + channels,
                       std::to_string(o.width) + "x" + std::to_string(o.height) + " " + o.channels);
    return true;
}

namespace {
Json pair(int a, int b) { return Json::array({a, b}); }
}  // namespace

Json Manifest::toJson() const {
    Json j = Json::object();
    j["streyes_farm_manifest"] = 1;
    j["scene"] = scene;
    j["output"] = output;
    j["executable"] = executable;
    j["frames"] = pair(first, last);
    j["shot"] = pair(shotFirst, shotLast);
    j["block"] = block;
    Json& bl = j["blocks"] = Json::array();
    for (const Block& b : blocks) bl.push_back(pair(b.first, b.last));
    j["seed"] = seed;
    j["render_options"] = renderOptions;
    j["resolution"] = pair(width, height);
    j["channels"] = channels;
    j["partition"] = partition;
    j["cpus_per_task"] = cpusPerTask;
    j["sbatch_options"] = sbatchOptions;
    j["block_choice"] = blockChoice;
    Json& subs = j["submissions"] = Json::array();
    for (const Submission& s : submissions)
        subs.push_back({{"job", s.job}, {"tasks", s.tasks}, {"time", s.time}, {"script", s.script}});
    return j;
}

Manifest Manifest::fromJson(const Json& j, const std::string& path) {
    auto bad = [&](const std::string& why) {
        return std::runtime_error("'" + path + "' is not a streyes farm manifest: " + why);
    };
    // [first, last] of whole numbers, or false.
    auto readPair = [](const Json& v, int* a, int* b) {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() || !v[1].is_number_integer()) return false;
        *a = v[0].get<int>();
        *b = v[1].get<int>();
        return true;
    };
    // An array of strings (absent: none).
    auto readStrings = [&](const Json& v, const char* key, std::vector<std::string>* out) {
        if (v.is_null()) return;
        if (!v.is_array()) throw bad(std::string("\"") + key + "\" is not an array of strings");
        for (const Json& s : v) {
            if (!s.is_string()) throw bad(std::string("\"") + key + "\" is not an array of strings");
            out->push_back(s.get<std::string>());
        }
    };
    if (!j.is_object() || num(member(j, "streyes_farm_manifest")) != 1) throw bad("no \"streyes_farm_manifest\": 1");
    Manifest m;
    m.path = path;
    m.scene = str(member(j, "scene"));
    m.output = str(member(j, "output"));
    m.executable = str(member(j, "executable"));
    if (m.scene.empty() || m.output.empty()) throw bad("no scene or output");
    if (!readPair(member(j, "frames"), &m.first, &m.last)) throw bad("\"frames\" is not [first, last]");
    // Manifests written before the shot was kept: their tasks passed the frames as the shot.
    m.shotFirst = m.first, m.shotLast = m.last;
    readPair(member(j, "shot"), &m.shotFirst, &m.shotLast);
    if (m.shotFirst > m.first || m.shotLast < m.last) throw bad("\"shot\" does not hold \"frames\"");
    m.block = int(num(member(j, "block")));
    const Json& blocks = member(j, "blocks");
    if (!blocks.is_array() || blocks.empty()) throw bad("no blocks");
    for (const Json& b : blocks) {
        Block block;
        if (!readPair(b, &block.first, &block.last)) throw bad("a block is not [first, last]");
        m.blocks.push_back(block);
    }
    m.seed = uint64_t(num(member(j, "seed")));
    readStrings(member(j, "render_options"), "render_options", &m.renderOptions);
    readPair(member(j, "resolution"), &m.width, &m.height);
    m.channels = member(j, "channels").is_string() ? str(member(j, "channels")) : "rgbaz";
    m.partition = str(member(j, "partition"));
    m.cpusPerTask = int(num(member(j, "cpus_per_task")));
    readStrings(member(j, "sbatch_options"), "sbatch_options", &m.sbatchOptions);
    m.blockChoice = member(j, "block_choice");
    const Json& subs = member(j, "submissions");
    if (!subs.is_null() && !subs.is_array()) throw bad("\"submissions\" is not an array");
    for (const Json& s : subs) {
        if (!s.is_object()) throw bad("a submission is not an object");
        Submission sub;
        sub.job = long(num(member(s, "job")));
        for (const Json& t : member(s, "tasks")) {
            if (!t.is_number_integer()) throw bad("a submission's \"tasks\" are not task numbers");
            sub.tasks.push_back(t.get<int>());
        }
        sub.time = str(member(s, "time"));
        sub.script = str(member(s, "script"));
        m.submissions.push_back(sub);
    }
    return m;
}

Manifest Manifest::load(const std::string& path) { return fromJson(loadJson(path), fs::absolute(path).string()); }

void Manifest::save() const {
    const std::string tmp = path + ".tmp" + std::to_string(getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        f << dumpJson(toJson()) << "\n";
        f.close();
        if (!f) {
            std::remove(tmp.c_str());
            throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        std::remove(tmp.c_str());
        throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
    }
}

}  // namespace streyes::farm
