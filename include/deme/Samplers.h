// Lattice samplers that fill simple regions with grain centres (e.g. to seed clumps before settling).
// All points lie inside the region (boundary included, within a tiny tolerance) and come in a
// deterministic order: z-major layers, then rows along y, then x. The lattice is laid out from the
// region's lower corner and centred so a box is filled as symmetrically as the lattice allows.
#pragma once

#include <vector>

#include "VectorTypes.h"

namespace deme {

// Hexagonal close packing: every interior point has 12 neighbours at exactly `spacing`.
// In-layer triangular lattice (row pitch spacing*sqrt(3)/2, odd rows shifted by spacing/2),
// layers stacked A/B/A/B with pitch spacing*sqrt(2/3) along z.
class HCPSampler {
  public:
    explicit HCPSampler(float spacing);  // spacing <= 0 or non-finite -> Error
    float GetSpacing() const { return m_spacing; }

    std::vector<float3> SampleBox(const float3& center, const float3& half_dims) const;
    std::vector<float3> SampleCylinderZ(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleCylinderX(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleCylinderY(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleSphere(const float3& center, float radius) const;

  private:
    float m_spacing;
};

// Simple cubic grid with pitch `spacing` along every axis.
class GridSampler {
  public:
    explicit GridSampler(float spacing);  // spacing <= 0 or non-finite -> Error
    float GetSpacing() const { return m_spacing; }

    std::vector<float3> SampleBox(const float3& center, const float3& half_dims) const;
    std::vector<float3> SampleCylinderZ(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleCylinderX(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleCylinderY(const float3& center, float radius, float half_height) const;
    std::vector<float3> SampleSphere(const float3& center, float radius) const;

  private:
    float m_spacing;
};

}  // namespace deme
