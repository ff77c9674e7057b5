// A Blobby field plug-in in PRMan's form (opcode 1004): the built-in ellipsoid's field
// (1 - r^2/R^2)^3 around a centre, from the floats cx cy cz R (object space).
#include <ImplicitField.h>

namespace {

class SphereField : public ImplicitField {
  public:
    SphereField(float cx, float cy, float cz, float R) : c_{cx, cy, cz}, R_(R) {
        for (int i = 0; i < 3; ++i) bbox[2 * i] = c_[i] - R, bbox[2 * i + 1] = c_[i] + R;
    }
    RtFloat Eval(const RtPoint p) override {
        float r2 = 0;
        for (int i = 0; i < 3; ++i) r2 += (p[i] - c_[i]) * (p[i] - c_[i]);
        const float s = 1 - r2 / (R_ * R_);
        return s > 0 ? s * s * s : 0;
    }

  private:
    float c_[3];
    float R_;
};

}  // namespace

extern "C" ImplicitField* ImplicitFieldNew(int nfloat, const RtFloat* float0, const RtFloat* /*float1*/,
                                           int /*nstring*/, const RtString* /*string*/) {
    if (nfloat != 4 || !(float0[3] > 0)) return nullptr;
    return new SphereField(float0[0], float0[1], float0[2], float0[3]);
}
