// XPBD (src/core/xpbd.hpp) against hand computations: where a hanging mass, a rigid chain and a
// sagging chain come to rest, and the colours the cloth's springs are visited in. (The teacher's
// copy's: the student copy has no XPBD.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <vector>

#include "core/coupled_springs.hpp"
#include "core/single_spring.hpp"
#include "core/spring_mesh.hpp"
#include "core/xpbd.hpp"

namespace clothlab {
namespace {

constexpr double g0 = 9.8;

dynamics_parameters xpbd_dynamics(double dt, double damping, int substeps, int iterations,
                                  double beta = 0.0) {
  dynamics_parameters d;
  d.time_step = dt;
  d.damping = damping;
  d.gravity = g0;
  d.integrator = integrator_kind::xpbd;
  d.xpbd = {.substeps = substeps, .iterations = iterations, .constraint_damping = beta};
  return d;
}

// One distance constraint under gravity: the single spring's mass, hanging from p0. At rest at a
// length L0 + e below p0, a substep h predicts it h^2 g0 lower (v = h g from v = 0), so that
// C = e + h^2 g0 and x - x_prev = h^2 g0 along the spring. The sweeps solve the one linear
// constraint exactly: C + alpha~ lambda + gamma grad C.(x - x_prev) = 0, and the mass ends where
// it started (at rest) when its correction w lambda cancels the prediction, lambda = -h^2 g0 / w
// (w = 1/m). Then at the end of the substep x = x_prev, and
//   e = C = -alpha~ lambda = (alpha / h^2) (h^2 g0 m) = m g0 alpha = m g0 / K:
// the spring's own static extension, whatever h, the sweeps and the damping beta (which acts on
// the motion only). Tolerance 1e-9 m: 30 s with mu = 3 /s leave e^(-mu t / 2) = 3e-20 of the
// start's swing (under 1 m), and the rounding of a contracting fixed point is 1e-15.
struct hanging_case {
  int substeps, iterations;
  double beta;
};

class HangingMass : public testing::TestWithParam<hanging_case> {};

TEST_P(HangingMass, SettlesAtRestLengthPlusMgAlpha) {
  const hanging_case c = GetParam();
  single_spring_parameters p;
  p.stiffness = 50.0;  // alpha = 0.02 m/N
  p.dynamics = xpbd_dynamics(0.01, 3.0, c.substeps, c.iterations, c.beta);
  p.dynamics.mass = 2.0;
  single_spring spring(p);
  for (int s = 0; s < 3000; ++s)
    spring.step();
  const double alpha = 1.0 / p.stiffness;
  const double length = 0.5 + p.dynamics.mass * g0 * alpha;  // L0 + m g alpha = 0.892 m
  const glm::dvec3 expected = glm::dvec3(0.1, 0.0, 1.0) - glm::dvec3(0.0, 0.0, length);
  const glm::dvec3 at = spring.particles().get_position(1);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(at[i], expected[i], 1e-9) << "coordinate " << i;
  std::printf("substeps %d, iterations %d, beta %g: |p1 - p0| = %.15f m (L0 + m g alpha = %.15f)\n",
              c.substeps, c.iterations, c.beta, glm::length(at - glm::dvec3(0.1, 0.0, 1.0)),
              length);
}

INSTANTIATE_TEST_SUITE_P(SubstepsIterationsDamping, HangingMass,
                         testing::Values(hanging_case{10, 1, 0.0}, hanging_case{1, 1, 0.0},
                                         hanging_case{1, 5, 0.0}, hanging_case{10, 1, 20.0},
                                         hanging_case{40, 3, 5.0}));

// The largest |L - L0| of the chain's springs, m.
double largest_violation(const coupled_springs& chain) {
  double worst = 0.0;
  for (const spring& s : chain.springs()) {
    const double L =
        glm::length(chain.particles().get_position(s.a) - chain.particles().get_position(s.b));
    worst = std::max(worst, std::abs(L - s.rest_length));
  }
  return worst;
}

double swinging_rigid_chain_violation(int iterations) {
  coupled_springs_parameters p;
  p.mass_count = 3;
  p.stiffness = std::numeric_limits<double>::infinity();  // alpha = 0: inextensible
  p.dynamics = xpbd_dynamics(0.01, 0.2, 10, iterations);
  coupled_springs chain(p);
  double worst = 0.0;
  for (int s = 0; s < 200; ++s) {  // 2 s of swinging (the last mass starts at (1, -1, 0) m/s)
    chain.step();
    worst = std::max(worst, largest_violation(chain));
  }
  return worst;
}

// alpha = 0 (K infinite): every constraint of a swinging chain of 3 masses holds its length to
// 1e-12 m with 100 sweeps. A visit of a hard constraint sets its C to 0 and disturbs its
// neighbours'; on the chain (fixed top, visited from the top) the sweeps are Gauss-Seidel on
// A dlambda = -C, A = J M^-1 J^T = (1/m) [[1, -1, 0], [-1, 2, -1], [0, -1, 2]] (hanging
// straight), whose Jacobi matrix [[0, 1, 0], [1/2, 0, 1/2], [0, 1/2, 0]] has eigenvalues 0 and
// +-sqrt(3/4): Gauss-Seidel shrinks the violation by 3/4 per sweep. A substep's prediction
// violates the constraints by about h^2 (g0 + v^2 / L0) <= 1e-6 (10 + 8) = 2e-5 m, which 100
// sweeps bring to 2e-5 x 0.75^100 = 6e-18 m: what is left is the rounding of the lengths
// (1e-16 m a visit). With one sweep the same chain stretches by about 1e-6 m: the test fails
// without the iterations.
TEST(XpbdHardConstraint, HoldsItsLengthWithEnoughIterations) {
  const double with_100 = swinging_rigid_chain_violation(100);
  const double with_1 = swinging_rigid_chain_violation(1);
  std::printf("largest |L - L0| over 2 s: %.3g m with 100 sweeps, %.3g m with 1\n", with_100,
              with_1);
  EXPECT_LE(with_100, 1e-12);
  EXPECT_GT(with_1, 1e-8);  // one sweep is not enough: the tolerance needs the iterations
}

// A chain of n masses hanging at rest: the spring model's sag is the sum of the static
// extensions, spring j holding the n - j + 1 masses below it: e_j = (n - j + 1) m g0 / K. XPBD
// with one sweep per substep, from the top: after constraint j is visited, C_j = -alpha~ lambda_j
// = (n - j + 1) m g0 / K exactly as for the hanging mass (lambda_j = -h^2 T_j from the balance
// of the corrections, T_j its tension); then the visit of constraint j + 1 moves their shared
// mass j down by w |lambda_{j+1}| = h^2 g0 (n - j), lengthening spring j by as much. At rest:
//   sag_xpbd = sag_springs + h^2 g0 sum_j (n - j) = sag_springs + h^2 g0 n (n - 1) / 2,
// the Gauss-Seidel order's price, which vanishes as h^2: 9.8e-5 m for n = 5 and h = 1 ms
// (10 substeps of 0.01 s), 9.8e-3 m with one substep. The chain hangs straight, so every move
// is along the vertical and the sum is exact to the rounding: tolerance 1e-9 m. (It settles with
// mu = 1 /s: its slowest mode, the swing, has omega >= sqrt(g0 / 8.9 m) = 1.05 rad/s > mu / 2,
// so every mode decays as e^(-mu t / 2), to e^-40 = 4e-18 of its start in 80 s. With mu = 3 /s
// the swing would be overdamped, decaying as e^(-omega^2 t / mu) only.)
struct sag_case {
  int masses, substeps;
};

class ChainSag : public testing::TestWithParam<sag_case> {};

TEST_P(ChainSag, MatchesTheSpringModelPlusTheSubstepsTerm) {
  const sag_case c = GetParam();
  coupled_springs_parameters p;
  p.mass_count = c.masses;
  p.stiffness = 20.0;
  p.dynamics = xpbd_dynamics(0.01, 1.0, c.substeps, 1);
  coupled_springs chain(p);
  for (int s = 0; s < 8000; ++s)
    chain.step();
  const int n = c.masses;
  double springs_sag = 0.0;  // the spring model's static extensions, summed
  for (int j = 1; j <= n; ++j)
    springs_sag += (n - j + 1) * p.dynamics.mass * g0 / p.stiffness;
  const double h = p.dynamics.time_step / c.substeps;
  const double order_term = h * h * g0 * n * (n - 1) / 2.0;
  const double z_springs = 1.0 - 0.5 * n - springs_sag;  // the last mass, spring model
  const double z = chain.particles().get_position(static_cast<std::size_t>(n)).z;
  std::printf(
      "n = %d, %d substeps: XPBD sags %.3g m more than the springs (h^2 g0 n (n-1)/2 = "
      "%.3g m)\n",
      n, c.substeps, z_springs - z, order_term);
  EXPECT_NEAR(z, z_springs - order_term, 1e-9);
  EXPECT_NEAR(chain.particles().get_position(static_cast<std::size_t>(n)).x, 0.1, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(MassesAndSubsteps, ChainSag,
                         testing::Values(sag_case{2, 10}, sag_case{5, 10}, sag_case{2, 1},
                                         sag_case{5, 1}));

// The cloth's 12 colours: every spring has one, no two springs of a colour share a particle, and
// an inner particle meets all 12 (so that no colouring can do with fewer).
TEST(XpbdColours, TwelveColoursOfSpringsThatShareNoParticle) {
  cloth_parameters p;
  p.grid_size = 9;
  const spring_mesh cloth(p);
  std::vector<std::set<std::uint32_t>> ends(cloth_constraint_colours);
  std::set<int> colours_at_centre;
  const auto centre = static_cast<std::uint32_t>(spring_mesh::index(4, 4, 9));
  std::size_t springs = 0;
  for (const spring_family family : all_spring_families) {
    for (const spring& s : cloth.springs(family)) {
      const int colour = cloth_constraint_colour(s, p.grid_size);
      ASSERT_GE(colour, 0);
      ASSERT_LT(colour, cloth_constraint_colours);
      EXPECT_EQ(colour / 4, static_cast<int>(family)) << "4 colours per family, in order";
      for (const std::uint32_t end : {s.a, s.b}) {
        EXPECT_TRUE(ends[static_cast<std::size_t>(colour)].insert(end).second)
            << "colour " << colour << ": particle " << end << " has two of its springs";
        if (end == centre)
          colours_at_centre.insert(colour);
      }
      ++springs;
    }
  }
  EXPECT_EQ(springs, 2u * 9 * 8 + 2u * 8 * 8 + 2u * 9 * 7);
  EXPECT_EQ(colours_at_centre.size(), 12u);
}

// The solver visits the cloth's constraints colour by colour.
TEST(XpbdColours, TheClothIsVisitedColourByColour) {
  cloth_parameters p;
  p.grid_size = 7;
  p.dynamics.integrator = integrator_kind::xpbd;
  spring_mesh cloth(p);
  cloth.step();
  xpbd_solver solver;
  const std::array<spring_set, 3> sets = cloth.spring_sets();
  force_model forces = {sets, [](std::span<const double>, std::span<double>) {}};
  forces.colour = [](const spring& s) { return cloth_constraint_colour(s, 7); };
  particle_system particles = cloth.particles();
  solver.step(p.dynamics, forces, particles);
  int previous = -1;
  for (const xpbd_constraint& c : solver.constraints()) {
    const int colour = cloth_constraint_colour({c.a, c.b, c.rest_length}, 7);
    EXPECT_GE(colour, previous);
    previous = colour;
  }
  EXPECT_EQ(previous, 11);
}

// The contacts are XPBD's own in every substep (xpbd.hpp): a stiff cloth (N = 12, K_struct = 1e5
// N/m, dt = 0.01 s) that falls on the ground from its two corners comes to rest on it. With the
// damping mu = 0.5 /s every mode's energy shrinks as e^(-mu t): after 30 s, 3e-7 of the some
// 700 J that the fall sets moving (m g0 z over 144 particles falling 0.5 m on average), 2e-4 J;
// bound 1e-3 J. A ground made once after the step fails it: the springs' constraints undo its
// push in the next step's first substep, a speed of its depth over h, and the lower rows keep
// trembling with 3.9 J.
TEST(XpbdContacts, AStiffClothOnTheGroundComesToRest) {
  cloth_parameters p;
  p.grid_size = 12;
  p.structural_stiffness = 1e5;
  p.shear_stiffness = 4e4;
  p.bending_stiffness = 1e4;
  p.dynamics.time_step = 0.01;
  p.dynamics.integrator = integrator_kind::xpbd;
  spring_mesh cloth(p);
  double lowest = 0.0;
  for (int s = 0; s < 3000; ++s)
    cloth.step();
  double kinetic = 0.0;  // J
  const particle_system& particles = cloth.particles();
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const glm::dvec3 v = particles.get_velocity(k);
    kinetic += 0.5 * p.dynamics.mass * glm::dot(v, v);
    lowest = std::min(lowest, particles.get_position(k).z);
  }
  EXPECT_NEAR(lowest, p.ground_height, 1e-12) << "the cloth does not reach the ground";
  EXPECT_LT(kinetic, 1e-3) << "the cloth on the ground does not come to rest";
}

}  // namespace
}  // namespace clothlab
