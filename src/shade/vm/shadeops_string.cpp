// Strings: printf, format, concat, match, comparisons and string arrays. Strings are uniform:
// format() of varying values formats the first point that runs.
#include <regex.h>

#include <algorithm>
#include <cstdio>

#include "shade/vm/ops.h"
#include "shade/vm/vm.h"

namespace streyes::sl::ops {

namespace {

// RenderMan's format: %f %g %e %d for floats, %s strings, %c %p %v %n triples ("x y z"),
// %m matrices, %% a percent sign; flags, width and precision as in C.
std::string formatAt(Exec& x, const int32_t* regs, int count, int lane) {
    const std::string& fmt = x.str(regs[0]);
    std::string out;
    int next = 1;
    char buf[128];
    for (size_t k = 0; k < fmt.size(); ++k) {
        char c = fmt[k];
        if (c == '\\' && k + 1 < fmt.size() && fmt[k + 1] == '%') {
            out += '%';
            ++k;
            continue;
        }
        if (c != '%') {
            out += c;
            continue;
        }
        size_t start = k++;
        while (k < fmt.size() && std::string("-+ #0123456789.").find(fmt[k]) != std::string::npos) ++k;
        if (k >= fmt.size()) {
            out += fmt.substr(start);
            break;
        }
        const char conv = fmt[k];
        if (conv == '%') {
            out += '%';
            continue;
        }
        std::string spec = fmt.substr(start, k - start);  // "%" + flags, width, precision
        if (next >= count) {
            out += "<missing>";
            continue;
        }
        const int r = regs[next++];
        const Register& reg = x.reg(r);
        if (reg.type.isString()) {
            std::snprintf(buf, sizeof buf, (spec + "s").c_str(), x.str(r).c_str());
            out += buf;
            continue;
        }
        RegView v = x.view(r);
        const int i = v.varying ? lane : 0;
        const std::string fspec = spec + (conv == 'e' || conv == 'g' || conv == 'f' ? std::string(1, conv) : std::string("g"));
        const int nc = v.comps * v.elems;
        if (conv == 'd' || conv == 'i') {
            std::snprintf(buf, sizeof buf, (spec + ".0f").c_str(), double(v.comp(0)[i]));
            out += buf;
            continue;
        }
        for (int cc = 0; cc < nc; ++cc) {
            std::snprintf(buf, sizeof buf, fspec.c_str(), double(v.comp(cc)[i]));
            if (cc) out += ' ';
            out += buf;
        }
    }
    return out;
}

bool anyVarying(Exec& x, const int32_t* regs, int count) {
    for (int k = 0; k < count; ++k)
        if (regs[k] >= 0 && x.varying(regs[k])) return true;
    return false;
}

int firstActive(const Exec& x) {
    for (int i = 0; i < x.n; ++i)
        if (x.mask[i]) return i;
    return 0;
}

}  // namespace

void printf_(Exec& x, const Instr& in) {
    const int32_t* regs = x.extra(in.a[1]);
    const int count = in.a[2];
    if (x.active == 0) return;
    if (!anyVarying(x, regs, count)) {
        x.vm.print(formatAt(x, regs, count, 0));
        return;
    }
    for (int i = 0; i < x.n; ++i)
        if (x.mask[i]) x.vm.print(formatAt(x, regs, count, i));
}

void format(Exec& x, const Instr& in) {
    x.str(in.a[0]) = formatAt(x, x.extra(in.a[1]), in.a[2], firstActive(x));
}

void concat(Exec& x, const Instr& in) {
    const int32_t* regs = x.extra(in.a[1]);
    std::string s;
    for (int k = 0; k < in.a[2]; ++k) s += x.str(regs[k]);
    x.str(in.a[0]) = s;
}

// match(pattern, subject): 1 when the (POSIX extended) regular expression is found in the
// subject; a bad pattern matches nothing.
void match(Exec& x, const Instr& in) {
    float r = 0;
    regex_t re;
    if (regcomp(&re, x.str(in.a[1]).c_str(), REG_EXTENDED | REG_NOSUB) == 0) {
        r = regexec(&re, x.str(in.a[2]).c_str(), 0, nullptr, 0) == 0 ? 1.0f : 0.0f;
        regfree(&re);
    }
    x.ptr(in.a[0])[0] = r;
}

void smov(Exec& x, const Instr& in) {
    // A resizable destination was given the source's length first (alike).
    const int elems = x.elements(in.a[0]);
    const int selems = x.elements(in.a[1]);
    for (int e = 0; e < elems; ++e) {
        if (selems == 0) x.str(in.a[0], e).clear();
        else x.str(in.a[0], e) = x.str(in.a[1], std::min(e, selems - 1));
    }
}

void streq(Exec& x, const Instr& in) { x.ptr(in.a[0])[0] = x.str(in.a[1]) == x.str(in.a[2]) ? 1.0f : 0.0f; }
void strne(Exec& x, const Instr& in) { x.ptr(in.a[0])[0] = x.str(in.a[1]) != x.str(in.a[2]) ? 1.0f : 0.0f; }

namespace {
// String arrays take uniform indices; one outside the array is clamped into it and reported.
// -1: the array is empty (a resizable one): read as "", written nowhere.
int stringIndex(Exec& x, const Instr& in, int arrayReg, int indexReg) {
    const int len = x.elements(arrayReg);
    float f = x.ptr(indexReg)[0];
    if (!(f >= 0 && f < float(len)) && x.active > 0) x.indexOutOfRange(in, arrayReg, f);
    if (len == 0) return -1;
    if (!(f >= 0)) return 0;
    return f >= float(len - 1) ? len - 1 : int(f);
}
}  // namespace

void saref(Exec& x, const Instr& in) {
    const int e = stringIndex(x, in, in.a[1], in.a[2]);
    if (e < 0) x.str(in.a[0]).clear();
    else x.str(in.a[0]) = x.str(in.a[1], e);
}
void saset(Exec& x, const Instr& in) {
    const int e = stringIndex(x, in, in.a[0], in.a[1]);
    if (e >= 0) x.str(in.a[0], e) = x.str(in.a[2]);
}

}  // namespace streyes::sl::ops
