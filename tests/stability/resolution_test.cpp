// Question 10: the handout's per-particle convention against the resolution-independent one
// (parameters.cpp derives the scalings): total mass, stretching (a curtain's sag), bending (the
// energy of a cylinder) and the stability bound, across N = 10, 20, 40.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/energy.hpp"
#include "core/spring_mesh.hpp"
#include "core/stability.hpp"

namespace clothlab {
namespace {

constexpr std::array<int, 3> grid_sizes = {10, 20, 40};

cloth_parameters cloth_with(int n, resolution_scaling scaling) {
  cloth_parameters p;
  p.grid_size = n;
  p.scaling = scaling;
  return p;
}

TEST(Resolution, PerParticleScalingChangesNothing) {
  const cloth_parameters p = cloth_with(40, resolution_scaling::per_particle);
  const cloth_parameters e = effective_cloth_parameters(p);
  EXPECT_EQ(e.dynamics.mass, p.dynamics.mass);
  EXPECT_EQ(e.structural_stiffness, p.structural_stiffness);
  EXPECT_EQ(e.shear_stiffness, p.shear_stiffness);
  EXPECT_EQ(e.bending_stiffness, p.bending_stiffness);
}

// M = m N_ref^2 = 400 kg with the defaults (m = 1, N_ref = 20), whatever N.
TEST(Resolution, ResolutionIndependentScalingKeepsTheTotalMass) {
  for (int n : grid_sizes) {
    const cloth_parameters e =
        effective_cloth_parameters(cloth_with(n, resolution_scaling::resolution_independent));
    EXPECT_DOUBLE_EQ(e.dynamics.mass * n * n, 400.0) << "N = " << n;
    EXPECT_EQ(e.structural_stiffness, 5000.0);  // 2D stretching: h cancels
    EXPECT_EQ(e.shear_stiffness, 2000.0);
  }
  // K_bend (h_ref / h)^4 with h = S / (N - 1): (9/19)^4 K_bend at N = 10, K_bend at N_ref.
  EXPECT_DOUBLE_EQ(
      effective_cloth_parameters(cloth_with(10, resolution_scaling::resolution_independent))
          .bending_stiffness,
      500.0 * std::pow(9.0 / 19.0, 4));
  EXPECT_DOUBLE_EQ(
      effective_cloth_parameters(cloth_with(20, resolution_scaling::resolution_independent))
          .bending_stiffness,
      500.0);
}

// A curtain: the whole edge kv = 0 fixed, no bending springs (they also stiffen the plane, and
// their scaling is the bending one), heavily damped until it hangs still. Its lowest point
// depends on the load per unit area and the in-plane stiffness only, so it must not change
// with N in the resolution-independent mode, and must in the handout's, where the cloth gets
// N^2 times heavier. (With the two corners pinned instead, the sag grows like log N in both
// modes: a point support in a membrane concentrates the strain, and a finer grid resolves more
// of it.)
double curtain_lowest_point(int n, resolution_scaling scaling) {
  cloth_parameters p = cloth_with(n, scaling);
  p.bending_stiffness = 0.0;
  p.pins = pin_mode::none;
  p.ground_enabled = false;
  p.dynamics.damping = 5.0;
  p.dynamics.time_step = 1e-3;
  spring_mesh curtain(p);
  for (int ku = 0; ku < n; ++ku)
    curtain.particles().is_fixed[spring_mesh::index(ku, 0, n)] = 1;
  for (int s = 0; s < 2500; ++s)
    curtain.step();
  double lowest = 0.0;
  for (std::size_t k = 0; k < curtain.particles().size(); ++k)
    lowest = std::min(lowest, curtain.particles().position[3 * k + 2]);
  return lowest;
}

TEST(SolutionResolution, StretchingSagIsTheSameAtEveryResolution) {
  const double reference = curtain_lowest_point(20, resolution_scaling::resolution_independent);
  EXPECT_LT(reference, -1.1);  // it hangs (S = 1) and stretches
  for (int n : {10, 40}) {
    EXPECT_NEAR(curtain_lowest_point(n, resolution_scaling::resolution_independent), reference,
                0.02 * std::abs(reference))
        << "N = " << n;
  }
  // The handout's convention: the finer curtain is heavier and hangs much lower.
  const double coarse = curtain_lowest_point(10, resolution_scaling::per_particle);
  const double fine = curtain_lowest_point(40, resolution_scaling::per_particle);
  EXPECT_LT(fine, coarse - 0.5);
}

// Bend the cloth into a cylinder of curvature kappa about the y axis (arc length kept along x).
// The bending springs store K_bend,N h^6 kappa^4 / 18 each (parameters.cpp), N (N - 2) of them:
// about S^2 K_bend,N h^4 kappa^4 / 18 in all, = S^2 K_bend h_ref^4 kappa^4 / 18 at every N in
// the resolution-independent mode (up to (h kappa)^2 and border terms, below 3% here).
double bending_energy_of_cylinder(int n, resolution_scaling scaling, double curvature) {
  spring_mesh cloth(cloth_with(n, scaling));
  for (std::size_t k = 0; k < cloth.particles().size(); ++k) {
    const glm::dvec3 flat = cloth.particles().get_position(k);
    const double angle = flat.x * curvature;
    cloth.particles().set_position(
        k, {std::sin(angle) / curvature, flat.y, (1 - std::cos(angle)) / curvature});
  }
  const std::array<spring_set, 3> sets = cloth.spring_sets();
  const spring_set bending[] = {sets[static_cast<int>(spring_family::bending)]};
  return compute_energy(cloth.particles(), bending, 1.0, 0.0).spring;
}

TEST(Resolution, BendingEnergyOfACylinderIsTheSameAtEveryResolution) {
  constexpr double curvature = 1.0;  // 1/m: the 1 m cloth wraps 1 rad
  const double h_ref = 1.0 / 19.0;
  const double continuum = 500.0 * std::pow(h_ref, 4) * std::pow(curvature, 4) / 18.0;
  for (int n : grid_sizes) {
    EXPECT_NEAR(
        bending_energy_of_cylinder(n, resolution_scaling::resolution_independent, curvature),
        continuum, 0.03 * continuum)
        << "N = " << n;
  }
  // Per particle, the same springs on a finer grid resist bending (h_40 / h_10)^4 = (9/39)^4
  // times less.
  const double ratio = bending_energy_of_cylinder(40, resolution_scaling::per_particle, 1.0) /
                       bending_energy_of_cylinder(10, resolution_scaling::per_particle, 1.0);
  EXPECT_NEAR(ratio, std::pow(9.0 / 39.0, 4), 0.05 * std::pow(9.0 / 39.0, 4));
}

// omega_max^2 <= 8 (K_struct + K_shear + K_bend) / m: unchanged with N per particle; with the
// resolution-independent mass M / N^2 (and K_bend = 0) it grows exactly like N.
TEST(Resolution, StabilityBoundMovesOnlyInTheResolutionIndependentMode) {
  auto omega_max = [](int n, resolution_scaling scaling) {
    cloth_parameters p = cloth_with(n, scaling);
    p.bending_stiffness = 0.0;
    return estimate_stability(spring_mesh(p)).omega_max;
  };
  EXPECT_DOUBLE_EQ(omega_max(40, resolution_scaling::per_particle),
                   omega_max(10, resolution_scaling::per_particle));
  EXPECT_NEAR(omega_max(40, resolution_scaling::resolution_independent) /
                  omega_max(10, resolution_scaling::resolution_independent),
              4.0, 1e-12);
}

TEST(Resolution, NamesReadBack) {
  for (resolution_scaling s :
       {resolution_scaling::per_particle, resolution_scaling::resolution_independent})
    EXPECT_EQ(parse_resolution_scaling(resolution_scaling_name(s)), s);
  EXPECT_FALSE(parse_resolution_scaling("per_particle").has_value());
}

}  // namespace
}  // namespace clothlab
