#include "io/SnapshotScene.h"

#include <deme/Error.h>

#include "physics/Quaternion.h"
#include "runtime/Simulation.h"
#include "state/SphereLayout.h"

namespace deme {

SnapshotScene stageSnapshotScene(const Simulation& sim, const SnapshotOptions& o, const std::string& call) {
    const SimState& s = sim.state();  // downloads from the device where it has moved on
    enum class By { NONE, SPEED, HEIGHT, FAMILY, WILDCARD } by = By::NONE;
    int wildcard = -1;
    SnapshotScene scene;
    if (o.colorBy == "speed") {
        by = By::SPEED, scene.label = "speed m/s";
    } else if (o.colorBy == "height") {
        by = By::HEIGHT, scene.label = "height m";
    } else if (o.colorBy == "family") {
        by = By::FAMILY, scene.categorical = true, scene.label = "family";
    } else if (o.colorBy != "none") {
        const std::vector<std::string>& names = sim.forceModel().ownerWildcards;
        for (size_t w = 0; w < names.size(); w++)
            if (names[w] == o.colorBy) wildcard = (int)w;
        if (wildcard < 0) {
            std::string list;
            for (const std::string& n : names) list += ", \"" + n + "\"";
            throwError(call, "cannot colour by \"" + o.colorBy + "\": not \"speed\", \"height\", \"family\", \"none\"" +
                                 (names.empty() ? std::string(" (the force model has no owner wildcards)")
                                                : " or an owner wildcard of the force model" + list));
        }
        by = By::WILDCARD, scene.label = o.colorBy;
    }

    const long n = (long)s.spheres.size();
    scene.spherePos.resize(n);
    scene.sphereRadius.resize(n);
    if (by != By::NONE) scene.value.resize(n);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (long i = 0; i < n; i++) {
        const double3 p = sphereCentre(s, i);
        scene.spherePos[i] = make_float3((float)p.x, (float)p.y, (float)p.z);
        scene.sphereRadius[i] = s.spheres.radius[i];
        const bodyID_t ow = sphereOwner(s, i);
        switch (by) {
        case By::NONE: break;
        case By::SPEED: {
            // As the sphere file's absv: the owner's velocity plus its spin about the owner centre.
            const float4 q = s.owners.oriQ[ow];
            const float3 w = rotateToGlobal(q, s.owners.angVel[ow]);
            scene.value[i] = length(s.owners.vel[ow] + cross(w, rotateToGlobal(q, sphereRelPos(s, i))));
            break;
        }
        case By::HEIGHT: scene.value[i] = (float)p.z; break;
        case By::FAMILY: scene.value[i] = (float)s.owners.family[ow]; break;
        case By::WILDCARD: scene.value[i] = s.wildcards.owner[wildcard][ow]; break;
        }
    }
    scene.triVert.resize(s.cache.triVert.size());
    for (size_t k = 0; k < s.cache.triVert.size(); k++) {
        const double3 p = s.cache.triVert[k];
        scene.triVert[k] = make_float3((float)p.x, (float)p.y, (float)p.z);
    }
    return scene;
}

}  // namespace deme
