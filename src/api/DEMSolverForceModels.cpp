// DEMSolver: choosing the contact force model (docs/force-models.md).
#include <deme/DEMSolver.h>

#include <fstream>
#include <sstream>

#include <deme/Error.h>

#include "api/Scene.h"
#include "runtime/Simulation.h"

namespace deme {

std::shared_ptr<DEMForceModel> DEMSolver::chooseForceModel(const char* call, std::shared_ptr<DEMForceModel> model) {
    requireNotInitialized(call);
    m_scene->forceModel = model;
    return model;
}

std::shared_ptr<DEMForceModel> DEMSolver::UseFrictionalHertzianModel() {
    return chooseForceModel("UseFrictionalHertzianModel",
                            std::make_shared<DEMForceModel>(DEMForceModel::Kind::FRICTIONAL_HERTZIAN));
}

std::shared_ptr<DEMForceModel> DEMSolver::UseFrictionlessHertzianModel() {
    return chooseForceModel("UseFrictionlessHertzianModel",
                            std::make_shared<DEMForceModel>(DEMForceModel::Kind::FRICTIONLESS_HERTZIAN));
}

std::shared_ptr<DEMForceModel> DEMSolver::DefineContactForceModel(const std::string& code) {
    const char* call = "DefineContactForceModel";
    if (code.find_first_not_of(" \t\r\n") == std::string::npos) throwError(call, "the model's code is empty");
    return chooseForceModel(call, std::make_shared<DEMForceModel>(DEMForceModel::Kind::CUSTOM, code, "force_model"));
}

std::shared_ptr<DEMForceModel> DEMSolver::ReadContactForceModel(const std::string& path) {
    const char* call = "ReadContactForceModel";
    requireNotInitialized(call);
    std::ifstream in(path, std::ios::binary);
    if (!in) throwError(call, "cannot open \"" + path + "\"");
    std::ostringstream code;
    code << in.rdbuf();
    if (code.str().find_first_not_of(" \t\r\n") == std::string::npos)
        throwError(call, "\"" + path + "\" holds no code");
    // Compiler messages name the file and its lines.
    return chooseForceModel(call, std::make_shared<DEMForceModel>(DEMForceModel::Kind::CUSTOM, code.str(), path));
}

}  // namespace deme
