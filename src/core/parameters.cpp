#include "core/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/i18n.hpp"

namespace clothlab {

std::string_view stage_name(stage_kind stage) {
  switch (stage) {
    case stage_kind::spring:
      return "spring";
    case stage_kind::coupled:
      return "coupled";
    case stage_kind::cloth:
      return "cloth";
  }
  return "?";
}

std::string_view integrator_name(integrator_kind kind) {
  switch (kind) {
    case integrator_kind::semi_implicit:
      return N_("semi-implicit");
    case integrator_kind::explicit_euler:
      return N_("explicit");
    case integrator_kind::velocity_verlet:
      return N_("verlet");
    case integrator_kind::runge_kutta_4:
      return N_("rk4");
    case integrator_kind::implicit_euler:
      return N_("implicit");
    case integrator_kind::xpbd:
      return N_("xpbd");
  }
  return "?";
}

std::optional<integrator_kind> parse_integrator(std::string_view name) {
  for (integrator_kind kind : all_integrators) {
    if (integrator_name(kind) == name)
      return kind;
  }
  return std::nullopt;
}

std::string_view resolution_scaling_name(resolution_scaling scaling) {
  switch (scaling) {
    case resolution_scaling::per_particle:
      return "per-particle";
    case resolution_scaling::resolution_independent:
      return "resolution-independent";
  }
  return "?";
}

std::optional<resolution_scaling> parse_resolution_scaling(std::string_view name) {
  for (resolution_scaling scaling :
       {resolution_scaling::per_particle, resolution_scaling::resolution_independent}) {
    if (resolution_scaling_name(scaling) == name)
      return scaling;
  }
  return std::nullopt;
}

// Question 10: how the grid size N changes the cloth, and how to make it not change it.
//
// The cloth of side S is resolved by N x N particles at spacing h = S / (N - 1). In the
// handout's convention every particle has mass m and every spring stiffness K whatever N.
//
// Stretching. Stretch the grid uniformly by a strain e along x. A structural spring along x
// (rest length h) gets longer by h e and pulls with K_struct h e; there is one per row and the
// rows are h apart, so the tension per unit width of cloth is K_struct h e / h = K_struct e.
// A shear spring (rest h sqrt 2, at 45 degrees, strain e/2 along it) pulls with K_shear h e/sqrt 2,
// of which h e K_shear / 2 along x; two per cell: K_shear e per unit width. A bending spring (rest
// 2h, one per row) adds 2 K_bend e. The in-plane stiffness of the sheet, tension per unit width
// per unit strain, is K_struct + K_shear + 2 K_bend (N/m): h has cancelled. In two dimensions a
// spring's stiffness IS the sheet's stretching stiffness, at any resolution.
// What N changes in the handout's convention is the load: the mass per unit area is m / h^2,
// N^2 times larger on a grid twice as fine (up to the border), so the finer cloth is heavier for
// the same springs and sags more: it looks softer. Keeping the total mass M fixed,
// m_N = M / N^2, keeps the load per unit area M / S^2 and with it the sag.
//
// Bending. Bend the cloth along x to a curvature kappa (a cylinder of radius 1/kappa) without
// stretching it. A bending spring spans an arc of length 2h whose chord is
// 2 sin(h kappa) / kappa = 2h (1 - (h kappa)^2 / 6 + ...): it is compressed by h^3 kappa^2 / 3 and
// stores K_bend h^6 kappa^4 / 18. There is one per particle and direction, 1 / h^2 per unit area,
// so the bending energy per unit area is K_bend h^4 kappa^4 / 18. A flat spring grid has no
// first-order resistance to bending; its resistance is this fourth-order one, and it is the same
// at every N when K_bend h^4 is: K_bend,N = K_bend (h_ref / h)^4. (The catch of bending springs:
// they also stiffen the sheet in the plane by 2 K_bend,N per unit width, which now grows with N.)
//
// Stability. The highest frequency of the grid is omega_max ~ sqrt(sum of K / m) (stability.hpp).
// Per particle: it does not change with N; the limit dt < 2 / omega_max stays put while the cloth
// looks softer. Resolution independent: m_N ~ 1 / N^2, so omega_max grows like N from the
// stretching springs (like N^3 from the bending ones): the finer the grid, the smaller dt must be.
cloth_parameters effective_cloth_parameters(const cloth_parameters& parameters) {
  cloth_parameters effective = parameters;
  effective.scaling = resolution_scaling::per_particle;
  if (parameters.scaling == resolution_scaling::per_particle)
    return effective;
  const double n = std::max(parameters.grid_size, 2);
  const double n_ref = std::max(parameters.reference_grid_size, 2);
  const double total_mass = parameters.dynamics.mass * n_ref * n_ref;  // M = m N_ref^2
  effective.dynamics.mass = total_mass / (n * n);                      // m_N = M / N^2
  effective.bending_stiffness = effective_bending_stiffness(parameters, parameters.grid_size);
  return effective;
}

void check_effective(const cloth_parameters& parameters, const char* who) {
  if (parameters.scaling != resolution_scaling::per_particle)
    // (not translated: a programming error)
    throw std::invalid_argument(std::string(who) +
                                ": takes the parameters at the loaded N "
                                "(effective_cloth_parameters), not resolution-independent ones");
}

double effective_bending_stiffness(const cloth_parameters& parameters, int grid_size) {
  if (parameters.scaling == resolution_scaling::per_particle)
    return parameters.bending_stiffness;
  const double n = std::max(grid_size, 2);
  const double n_ref = std::max(parameters.reference_grid_size, 2);
  const double spacing_ratio = (n - 1) / (n_ref - 1);  // h_ref / h
  return parameters.bending_stiffness * std::pow(spacing_ratio, 4);
}

}  // namespace clothlab
