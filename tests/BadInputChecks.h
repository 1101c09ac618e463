// Checks shared by the bad-input tests (test_bad_input*.cpp): a call must throw deme::Error whose
// message names the call, and the minimal valid scene the tests spoil one input of.
#pragma once

#include <deme/deme.h>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace deme_test {

// Runs f; it must throw deme::Error whose what() contains every fragment.
inline void expectDemeError(const std::function<void()>& f, const std::vector<std::string>& fragments) {
    std::string msg;
    bool threw = false;
    EXPECT_THROW(
        {
            try {
                f();
            } catch (const deme::Error& e) {
                msg = e.what();
                threw = true;
                throw;
            }
        },
        deme::Error);
    if (!threw) return;  // EXPECT_THROW has already reported it
    for (const auto& frag : fragments)
        EXPECT_NE(msg.find(frag), std::string::npos) << "message \"" << msg << "\" lacks \"" << frag << "\"";
}

// SCOPED_TRACE so that a failure reports the line of the check, not of the helper.
#define EXPECT_DEME_ERROR(...)                     \
    do {                                           \
        SCOPED_TRACE("EXPECT_DEME_ERROR");         \
        ::deme_test::expectDemeError(__VA_ARGS__); \
    } while (0)

inline std::map<std::string, double> goodMaterial() { return {{"E", 1e8}, {"nu", 0.3}, {"CoR", 0.5}, {"mu", 0.5}}; }

// The minimal valid scene of the brief, up to (not including) Initialize: one sphere of mass 1 kg and
// radius 0.01 m at the origin of a 1 m box, dt = 1e-5 s.
struct Scene1 {
    deme::DEMSolver sim;
    std::shared_ptr<deme::DEMMaterial> mat;
    std::shared_ptr<deme::DEMClumpTemplate> type;
    std::shared_ptr<deme::DEMClumpBatch> batch;
    Scene1() {
        sim.SetVerbosity("QUIET");
        mat = sim.LoadMaterial(goodMaterial());
        sim.InstructBoxDomainDimension(1, 1, 1);
        type = sim.LoadSphereType(1.0f, 0.01f, mat);
        batch = sim.AddClumps(type, {deme::make_float3(0, 0, 0)});
        sim.SetInitTimeStep(1e-5);
    }
};

}  // namespace deme_test
