// Message passing (RI Spec 3.2, section 15.8): the shaders of the primitive being shaded that
// surface(), displacement(), atmosphere(), incident() and opposite() read a parameter of. The
// renderer names them per grid (ShadingVM::setPeers); lightsource() reads the light of the
// illuminance loop instead.
#pragma once

namespace streyes::sl {

enum class Peer : int {
    Surface,
    Displacement,
    Atmosphere,
    Incident,  // the volume the incident ray crossed: for rays from the eye, the atmosphere
    Opposite,  // the volume on the other side of the surface (none until Interior is run)
};
constexpr int kPeerCount = 5;

inline const char* peerName(Peer p) {
    switch (p) {
        case Peer::Surface: return "surface";
        case Peer::Displacement: return "displacement";
        case Peer::Atmosphere: return "atmosphere";
        case Peer::Incident: return "incident";
        case Peer::Opposite: return "opposite";
    }
    return "?";
}

}  // namespace streyes::sl
