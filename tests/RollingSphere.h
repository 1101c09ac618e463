// A sphere rolling without slip up an incline, the scene of Incline.RollingSphere* (each backend
// against theory) and GpuParity.RollingSphereOnIncline (the two backends against each other).
#pragma once

#include <cmath>
#include <string>

#include <deme/deme.h>

#include "TestHelpers.h"

namespace deme_test {

// r = 0.2 m, m = 5 kg on a 10 degree incline (gravity tilted), starting at 2 m/s up the slope with
// the matching spin, resting on the plane at its static Hertz overlap.
struct RollingSphere {
    static constexpr double r = 0.2, m = 5.0, g = 9.81, alphaDeg = 10.0, v0 = 2.0, duration = 0.5;
    // Its velocity along the slope after `duration` on `backend`.
    static double velocityAfterRun(const std::string& backend) {
        const double a = alphaDeg * deme::PI / 180.0;
        deme::DEMSolver sim;
        sim.SetVerbosity("QUIET");
        sim.SetBackend(backend);
        auto mat = sim.LoadMaterial(material(1e7, 0.3, 0.5, 0.25));
        sim.InstructBoxDomainDimension(80, 4, 4);
        sim.AddBCPlane(make_float3(0, 0, 0), make_float3(0, 0, 1), mat);
        auto tmpl = sim.LoadSphereType((float)m, (float)r, mat);
        const double Estar = effectiveModulus(1e7, 0.3);
        const double overlap = std::pow(m * g * std::cos(a) / (4.0 / 3.0 * Estar * std::sqrt(r)), 2.0 / 3.0);
        auto ball = sim.AddClumps(tmpl, {make_float3(30.f, 0, (float)(r - overlap))});
        ball->SetVel(make_float3((float)v0, 0, 0));
        ball->SetAngVel(make_float3(0, (float)(v0 / r), 0));  // rolling up the slope from the start
        sim.SetInitTimeStep(1e-4);
        sim.SetGravitationalAcceleration(make_float3((float)(-g * std::sin(a)), 0, (float)(-g * std::cos(a))));
        sim.Initialize();
        auto tr = sim.Track(ball);
        sim.DoDynamics(duration);
        return (double)tr->Vel().x;
    }
    // Rolling without slip, a solid sphere (I = 2/5 m r^2) decelerates at (5/7) g sin(alpha).
    static double theory() { return v0 - 5.0 / 7.0 * g * std::sin(alphaDeg * deme::PI / 180.0) * duration; }
};

}  // namespace deme_test
