// The scene as the user describes it before Initialize: materials, templates, clump batches,
// external objects and the domain. Scene assembly turns it into the flat SimState.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <deme/ClumpTemplate.h>
#include <deme/ExternalObject.h>
#include <deme/ForceModel.h>
#include <deme/Materials.h>
#include <deme/Mesh.h>

namespace deme {

class Scene {
  public:
    std::vector<std::shared_ptr<DEMMaterial>> materials;
    // (property, material a, material b) -> value, with a <= b.
    std::map<std::tuple<std::string, unsigned int, unsigned int>, double> pairProperties;
    std::vector<std::shared_ptr<DEMClumpTemplate>> templates;
    std::vector<std::shared_ptr<DEMClumpBatch>> batches;
    // Batches added after Initialize (also in `batches`) that UpdateClumps has not inserted yet.
    std::vector<std::shared_ptr<DEMClumpBatch>> pendingBatches;
    std::vector<std::shared_ptr<DEMExternObj>> externObjs;
    std::vector<std::shared_ptr<DEMMeshConnected>> meshes;
    std::shared_ptr<DEMForceModel> forceModel;  // null: the default (frictional Hertzian)
    // Wildcard values given before Initialize, applied by it: owners of a family get a value, and
    // contacts appearing between two families start with one. Names are checked at Initialize.
    struct FamilyOwnerValue {
        family_t family;
        std::string name;
        float value;
    };
    std::vector<FamilyOwnerValue> familyOwnerWildcards;
    struct ContactInitValue {
        family_t a, b;
        std::string name;
        float value;
    };
    std::vector<ContactInitValue> contactWildcardInits;
    bool hasDomain = false;
    float3 domainSize = make_float3(0.f);
    float3 domainLo = make_float3(0.f);  // lower corner
    unsigned int periodicAxes = 0;       // bit a: axis a is periodic (InstructBoxDomainPeriodicity)
    bool sheared = false;                // SetPeriodicShear: a Lees–Edwards cell
    double shearRate = 0.0;              // its shear rate dvx/dz, 1/s

    size_t numClumps() const {
        size_t n = 0;
        for (const auto& b : batches) n += b->GetNumClumps();
        return n;
    }
};

}  // namespace deme
