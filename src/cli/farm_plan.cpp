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
    const Json& curves = doc["curves"];
    if (!curves.isObject()) throw std::runtime_error(what + ": no \"curves\" object (is it tools/block-curve's output?)");
    std::vector<BlockCurve> out;
    for (const auto& [name, c] : curves.members()) {
        BlockCurve bc;
        bc.name = name;
        bc.scene = c["scene"].str();
        if (c["resolution"].items().size() == 2) {
            bc.width = int(c["resolution"].items()[0].num());
            bc.height = int(c["resolution"].items()[1].num());
        }
        std::vector<std::pair<int, double>> pts;
        for (const Json& p : c["points"].items()) {
            const double L = p["block"].num(0), cpu = p["cpu_per_frame"].num(-1);
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
    return readCurves(Json::parse(kBuiltinBlockCurveJson, "the built-in block curve (docs/results/block-curve.json)"),
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
    const std::vector<BlockCurve> curves = file.empty() ? builtinCurves() : readCurves(Json::load(file), file);
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
Json strings(const std::vector<std::string>& v) {
    Json a = Json::array();
    for (const std::string& s : v) a.push(Json::string(s));
    return a;
}
Json pair(int a, int b) {
    Json j = Json::array();
    j.push(Json::number(a));
    j.push(Json::number(b));
    return j;
}
}  // namespace

Json Manifest::toJson() const {
    Json j = Json::object();
    j.set("streyes_farm_manifest", Json::number(1));
    j.set("scene", Json::string(scene));
    j.set("output", Json::string(output));
    j.set("executable", Json::string(executable));
    j.set("frames", pair(first, last));
    j.set("shot", pair(shotFirst, shotLast));
    j.set("block", Json::number(block));
    Json bl = Json::array();
    for (const Block& b : blocks) bl.push(pair(b.first, b.last));
    j.set("blocks", bl);
    j.set("seed", Json::number(double(seed)));
    j.set("render_options", strings(renderOptions));
    j.set("resolution", pair(width, height));
    j.set("channels", Json::string(channels));
    j.set("partition", Json::string(partition));
    j.set("cpus_per_task", Json::number(cpusPerTask));
    j.set("sbatch_options", strings(sbatchOptions));
    j.set("block_choice", blockChoice);
    Json subs = Json::array();
    for (const Submission& s : submissions) {
        Json o = Json::object();
        o.set("job", Json::number(double(s.job)));
        Json t = Json::array();
        for (int k : s.tasks) t.push(Json::number(k));
        o.set("tasks", t);
        o.set("time", Json::string(s.time));
        o.set("script", Json::string(s.script));
        subs.push(o);
    }
    j.set("submissions", subs);
    return j;
}

Manifest Manifest::fromJson(const Json& j, const std::string& path) {
    auto bad = [&](const std::string& why) {
        return std::runtime_error("'" + path + "' is not a streyes farm manifest: " + why);
    };
    if (!j.isObject() || j["streyes_farm_manifest"].num(0) != 1) throw bad("no \"streyes_farm_manifest\": 1");
    Manifest m;
    m.path = path;
    m.scene = j["scene"].str();
    m.output = j["output"].str();
    m.executable = j["executable"].str();
    if (m.scene.empty() || m.output.empty()) throw bad("no scene or output");
    if (j["frames"].items().size() != 2) throw bad("\"frames\" is not [first, last]");
    m.first = int(j["frames"].items()[0].num());
    m.last = int(j["frames"].items()[1].num());
    // Manifests written before the shot was kept: their tasks passed the frames as the shot.
    m.shotFirst = m.first, m.shotLast = m.last;
    if (j["shot"].items().size() == 2) {
        m.shotFirst = int(j["shot"].items()[0].num());
        m.shotLast = int(j["shot"].items()[1].num());
    }
    if (m.shotFirst > m.first || m.shotLast < m.last) throw bad("\"shot\" does not hold \"frames\"");
    m.block = int(j["block"].num());
    for (const Json& b : j["blocks"].items()) {
        if (b.items().size() != 2) throw bad("a block is not [first, last]");
        m.blocks.push_back({int(b.items()[0].num()), int(b.items()[1].num())});
    }
    if (m.blocks.empty()) throw bad("no blocks");
    m.seed = uint64_t(j["seed"].num());
    for (const Json& s : j["render_options"].items()) m.renderOptions.push_back(s.str());
    if (j["resolution"].items().size() == 2) {
        m.width = int(j["resolution"].items()[0].num());
        m.height = int(j["resolution"].items()[1].num());
    }
    m.channels = j["channels"].isString() ? j["channels"].str() : "rgbaz";
    m.partition = j["partition"].str();
    m.cpusPerTask = int(j["cpus_per_task"].num());
    for (const Json& s : j["sbatch_options"].items()) m.sbatchOptions.push_back(s.str());
    m.blockChoice = j["block_choice"];
    for (const Json& s : j["submissions"].items()) {
        Submission sub;
        sub.job = long(s["job"].num());
        for (const Json& t : s["tasks"].items()) sub.tasks.push_back(int(t.num()));
        sub.time = s["time"].str();
        sub.script = s["script"].str();
        m.submissions.push_back(sub);
    }
    return m;
}

Manifest Manifest::load(const std::string& path) { return fromJson(Json::load(path), fs::absolute(path).string()); }

void Manifest::save() const {
    const std::string tmp = path + ".tmp" + std::to_string(getpid());
    {
        std::ofstream f(tmp, std::ios::binary);
        f << toJson().dump() << "\n";
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
