#include "shade/sl/builtins.h"

#include <map>
#include <memory>

#include "shade/vm/ops.h"
#include "shade/vm/peers.h"

namespace streyes::sl {

namespace {

SlType typeOf(char c) {
    switch (c) {
        case 'f': return BaseType::Float;
        case 'c': return BaseType::Color;
        case 'p': return BaseType::Point;
        case 'v': return BaseType::Vector;
        case 'n': return BaseType::Normal;
        case 'm': return BaseType::Matrix;
        case 's': return BaseType::String;
        default: return BaseType::Void;
    }
}

class Table {
  public:
    Table() { build(); }
    const std::vector<const Builtin*>& find(const std::string& name) const {
        static const std::vector<const Builtin*> none;
        auto it = byName_.find(name);
        return it == byName_.end() ? none : it->second;
    }

  private:
    // ret and args in type letters (f c p v n m s, x for void); a trailing '*' in args: more may follow.
    Builtin& add(const std::string& name, const char* ret, const std::string& args, OpFn op,
                 Special special = Special::None) {
        auto b = std::make_unique<Builtin>();
        b->name = name;
        b->ret = typeOf(ret[0]);
        for (char c : args) {
            if (c == '*') b->varargs = true;
            else b->args.push_back(typeOf(c));
        }
        b->op = op;
        b->special = special;
        Builtin& ref = *b;
        byName_[name].push_back(&ref);
        all_.push_back(std::move(b));
        return ref;
    }
    // The same signature for float, color, point, vector and normal (letter T in the pattern).
    void addGeneric(const std::string& name, const std::string& pattern, OpFn op, const char* types = "fcpvn") {
        for (const char* t = types; *t; ++t) {
            std::string args = pattern;
            for (char& c : args)
                if (c == 'T') c = *t;
            add(name, std::string(1, *t).c_str(), args, op);
        }
    }
    void addNoise(const std::string& name, OpFn op, bool periodic, bool varying) {
        static const char* const plain[] = {"f", "ff", "p", "pf"};
        static const char* const periodicArgs[] = {"ff", "ffff", "pp", "pfpf"};
        for (const char* r : {"f", "c", "p", "v"})
            for (const char* a : periodic ? periodicArgs : plain) add(name, r, a, op).varying = varying;
    }

    void build() {
        using namespace ops;
        for (auto [n, op] : std::initializer_list<std::pair<const char*, OpFn>>{
                 {"radians", radians}, {"degrees", degrees}, {"sin", sin_}, {"cos", cos_}, {"tan", tan_},
                 {"asin", asin_}, {"acos", acos_}, {"atan", atan1}, {"exp", exp_}, {"sqrt", sqrt_},
                 {"inversesqrt", inversesqrt}, {"log", log1}, {"abs", abs_}, {"sign", sign}, {"floor", floor_},
                 {"ceil", ceil_}, {"round", round_}})
            add(n, "f", "f", op);
        add("atan", "f", "ff", atan2_);
        add("pow", "f", "ff", pow_);
        addGeneric("pow", "Tf", pow_, "cpvn");  // component by component, as PRMan takes it
        add("log", "f", "ff", log2_);
        add("mod", "f", "ff", mod);
        add("step", "f", "ff", step);
        add("smoothstep", "f", "fff", smoothstep);
        addGeneric("min", "TT*", min_);
        addGeneric("max", "TT*", max_);
        for (auto& v : {"min", "max"})
            for (const Builtin* b : find(v)) const_cast<Builtin*>(b)->special = Special::MinMax;
        addGeneric("clamp", "TTT", clamp);
        addGeneric("mix", "TTf", mix);
        addGeneric("mix", "TTT", mix, "cpvn");
        add("filterstep", "f", "ff*", filterstep, Special::Filterstep).varying = true;
        for (const char* t : {"f", "c", "p", "v"}) add("spline", t, "*", spline, Special::Spline);
        add("random", "f", "", random).varying = true;
        add("random", "c", "", random).varying = true;
        add("random", "p", "", random).varying = true;
        addNoise("noise", noise, false, false);
        addNoise("pnoise", pnoise, true, false);
        addNoise("cellnoise", cellnoise, false, false);

        // Geometry.
        const char* comps[] = {"xcomp", "ycomp", "zcomp"};
        const char* setcomps[] = {"setxcomp", "setycomp", "setzcomp"};
        for (int i = 0; i < 3; ++i) {
            add(comps[i], "f", "p", comp, Special::Comp).index = i;
            Builtin& s = add(setcomps[i], "x", "pf", setcomp, Special::SetComp);
            s.index = i;
            s.outputs = 1;
        }
        add("comp", "f", "cf", comp);
        add("comp", "f", "pf", comp);
        add("comp", "f", "mff", mcomp);
        add("setcomp", "x", "cff", setcomp, Special::SetComp).outputs = 1;
        add("setcomp", "x", "pff", setcomp, Special::SetComp).outputs = 1;
        add("setcomp", "x", "mfff", msetcomp, Special::SetComp).outputs = 1;
        add("length", "f", "v", length);
        add("normalize", "v", "v", normalize);
        add("normalize", "n", "n", normalize);
        add("distance", "f", "pp", distance);
        add("ptlined", "f", "ppp", ptlined);
        add("rotate", "p", "pfpp", rotatePoint);
        add("area", "f", "p", area).varying = true;
        add("faceforward", "v", "vv", faceforward, Special::Faceforward);
        add("faceforward", "v", "vvv", faceforward);
        add("reflect", "v", "vv", reflect);
        add("refract", "v", "vvf", refract);
        add("fresnel", "x", "vvfff", fresnel, Special::Fresnel).outputs = 0x18;
        add("fresnel", "x", "vvfffvv", fresnel, Special::Fresnel).outputs = 0x78;
        add("depth", "f", "p", depth);
        add("calculatenormal", "n", "p", calculatenormal).varying = true;
        // transform() follows its argument's type; vtransform and ntransform force theirs.
        const char* kinds = "pvn";
        for (int k = 0; k < 3; ++k) {
            std::string t(1, kinds[k]);
            for (const char* fn : {"transform", k == 1 ? "vtransform" : k == 2 ? "ntransform" : nullptr}) {
                if (!fn) continue;
                for (std::string args : {"sT", "ssT", "mT", "smT"}) {
                    args.back() = kinds[k];
                    add(fn, t.c_str(), args, xform, Special::Transform).index = k;
                }
            }
        }
        add("determinant", "f", "m", determinant);
        add("translate", "m", "mv", translateM);
        add("rotate", "m", "mfv", rotateM);
        add("scale", "m", "mp", scaleM);

        // Colour.
        add("ctransform", "c", "sc", ctransform, Special::CTransform);
        add("ctransform", "c", "ssc", ctransform, Special::CTransform);

        // Derivatives.
        for (auto [n, op] : std::initializer_list<std::pair<const char*, OpFn>>{{"Du", Du}, {"Dv", Dv}}) {
            add(n, "f", "f", op);
            add(n, "c", "c", op);
            add(n, "v", "p", op);
            add(n, "v", "v", op);
            add(n, "v", "n", op);
        }
        add("Deriv", "f", "ff", Deriv);
        add("Deriv", "c", "cf", Deriv);
        add("Deriv", "v", "pf", Deriv);
        add("Deriv", "v", "vf", Deriv);

        // Lights.
        add("ambient", "c", "", ambient).lights = true;
        add("diffuse", "c", "n", diffuse).lights = true;
        add("specular", "c", "nvf", specular).lights = true;
        add("specularbrdf", "c", "vnvf", specularbrdf);
        add("phong", "c", "nvf", phong).lights = true;
        add("lightsource", "f", "s*", lightsource, Special::Lightsource);
        // Message passing (RI Spec 3.2, section 15.8): the other shaders of the primitive.
        for (int k = 0; k < kPeerCount; ++k) add(peerName(Peer(k)), "f", "s*", message, Special::Message).index = k;
        for (const char* n : {"ambient", "diffuse", "specular", "phong"})
            for (const Builtin* b : find(n)) const_cast<Builtin*>(b)->varying = true;

        // Information (RI Spec 3.2, section 15.8).
        add("option", "f", "s*", option, Special::Query);
        add("attribute", "f", "s*", attribute, Special::Query);
        add("rendererinfo", "f", "s*", rendererinfo, Special::Query);
        add("rayinfo", "f", "s*", rayinfo, Special::Query);
        add("textureinfo", "f", "ss*", textureinfo, Special::Query);
        add("shadername", "s", "", shadername);
        add("shadername", "s", "s", shadername);

        // Strings.
        add("printf", "x", "s*", printf_, Special::Printf);
        add("format", "s", "s*", format, Special::Format);
        add("concat", "s", "s*", concat, Special::Concat);
        add("match", "f", "ss", match);

        // Ray tracing (PRMan's signatures; occlusion also takes Aqsis's map name first, traced
        // all the same). The listed arguments are the positional ones; option pairs follow.
        add("occlusion", "f", "pnf*", occlusion, Special::Ray).varying = true;
        add("indirectdiffuse", "c", "pnf*", indirectdiffuse, Special::Ray).varying = true;
        add("trace", "c", "pv*", trace, Special::Ray).varying = true;
        add("transmission", "c", "pp*", transmission, Special::Ray).varying = true;
        // gather(category, P, dir, angle, samples, ...) stmt: the parser makes it a loop calling
        // this once a sample (the sample count and number added); 1 where the ray hit.
        add("$gather", "f", "spvfff*", gather, Special::Gather).varying = true;

        // Point clouds and bake files (PRMan's signatures; the listed arguments are the
        // positional ones, (name, value) pairs follow).
        add("bake3d", "f", "sspn*", bake3d, Special::PointCloud).varying = true;
        add("texture3d", "f", "spn*", texture3d, Special::PointCloud).varying = true;
        add("bake", "x", "sff*", bake, Special::Bake);

        // Texture maps: the float form first (the default without a cast).
        for (const char* r : {"f", "c"}) {
            add("texture", r, "s*", texture, Special::Texture).varying = true;
            add("environment", r, "s*", environment, Special::Environment).varying = true;
            add("shadow", r, "s*", shadow, Special::Shadow).varying = true;
        }
    }

    std::map<std::string, std::vector<const Builtin*>> byName_;
    std::vector<std::unique_ptr<Builtin>> all_;
};

}  // namespace

const std::vector<const Builtin*>& findBuiltins(const std::string& name) {
    static const Table table;
    return table.find(name);
}

}  // namespace streyes::sl
