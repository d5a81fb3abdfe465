// Question 5: the coupled springs. coupled_springs::compute_force must give every spring of the
// chain its force (handout equation 2) on BOTH of its ends. Each expected force is worked out
// by hand in the comment above its test.
#include <gtest/gtest.h>

#include <cmath>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::coupled_springs;

using lab::text;

// A chain of n masses with the given positions (particle 0 is the fixed p0).
coupled_springs chain_at(int n, double K, std::initializer_list<glm::dvec3> positions) {
  coupled_springs_parameters p;
  p.mass_count = n;
  p.stiffness = K;
  coupled_springs chain(p);
  std::size_t i = 0;
  for (const glm::dvec3& q : positions)
    chain.particles().set_position(i++, q);
  return chain;
}

// Two masses, K = 20, L0 = 0.5. p0 = (0.1, 0, 1), p1 = (0.1, 0, 0.5): spring 1 is at its rest
// length. p2 = (0.1, 0, -0.2): spring 2 has length 0.7, stretched by 0.2. Equation 2 on p2:
//   F = K (L0 - L) (p2 - p1) / L = 20 (0.5 - 0.7) (0, 0, -0.7) / 0.7 = (0, 0, 4): pulled up;
// and its reaction on p1: (0, 0, -4), pulled down.
TEST(Q5CoupledSprings, TheSecondSpringPullsTheSecondMassBack) {
  coupled_springs chain = chain_at(2, 20.0, {{0.1, 0, 1}, {0.1, 0, 0.5}, {0.1, 0, -0.2}});
  chain.compute_force();
  LAB_EXPECT_VEC(chain.particles().get_force(2), glm::dvec3(0, 0, 4), 1e-9,
                 "Q5: mass 2 hangs 0.2 m below the rest length of the second spring, which "
                 "should pull it up with K (L0 - L) = 4 N; is the second spring (p1-p2) in "
                 "compute_force?");
}

TEST(Q5CoupledSprings, TheSecondSpringPullsTheFirstMassDownToo) {
  coupled_springs chain = chain_at(2, 20.0, {{0.1, 0, 1}, {0.1, 0, 0.5}, {0.1, 0, -0.2}});
  chain.compute_force();
  LAB_EXPECT_VEC(chain.particles().get_force(1), glm::dvec3(0, 0, -4), 1e-9,
                 "Q5: a spring pulls BOTH of its ends (Newton's third law): the stretched "
                 "second spring pulls mass 2 up by 4 N and mass 1 down by 4 N, while the first "
                 "spring, at its rest length, adds nothing");
}

// Four masses in a zigzag, K = 30; every spring acts on both of its ends, so mass i feels
// spring i (to p(i-1)) and spring i+1 (to p(i+1)); the last mass only spring n. Equation 2 is
// evaluated by hand with spring_force (the handout's formula, spring.hpp) for each named pair.
TEST(Q5CoupledSprings, EveryMassFeelsTheSpringsAboveAndBelowIt) {
  const glm::dvec3 p[] = {
      {0.1, 0, 1}, {0.3, 0.1, 0.6}, {0.0, -0.2, 0.1}, {0.4, 0, -0.5}, {0.2, 0.3, -0.8}};
  coupled_springs chain = chain_at(4, 30.0, {p[0], p[1], p[2], p[3], p[4]});
  chain.compute_force();
  const double K = 30.0, L0 = 0.5;
  for (int i = 1; i <= 4; ++i) {
    glm::dvec3 expected = spring_force(p[i], p[i - 1], K, L0);  // spring i, from above
    if (i < 4)
      expected += spring_force(p[i], p[i + 1], K, L0);  // spring i+1, from below
    LAB_EXPECT_VEC(chain.particles().get_force(std::size_t(i)), expected, 1e-9,
                   "Q5: in a chain of 4 masses, mass " + std::to_string(i) +
                       " should feel the spring above it" +
                       (i < 4 ? std::string(" and the one below it") : std::string()) +
                       " (equation 2 on each)");
  }
}

// n = 2, gravity 0, damping 0, K = 20, m = 1, dt = 0.01. Step 1: no spring force (rest lengths),
// so v1 = 0, v2 = (1, -1, 0), p1 = (0.1, 0, 0.5), p2 = (0.1 + dt, -dt, 0). Step 2: spring 1 is
// still at its rest length; spring 2 has d = p1 - p2 = (-dt, dt, 0.5) and pulls both ends
// together: F1 = K (0.5 - |d|) d / |d| on mass 1, F2 = -F1 on mass 2; v1 = dt F1 / m,
// v2 = (1, -1, 0) + dt F2 / m.
TEST(Q5CoupledSprings, SecondStepMovesBothMassesOfTheSecondSpring) {
  coupled_springs_parameters p;
  p.mass_count = 2;
  p.dynamics.gravity = 0.0;
  p.dynamics.damping = 0.0;
  coupled_springs chain(p);
  chain.step();
  chain.step();
  const double dt = 0.01;
  const glm::dvec3 d = {-dt, dt, 0.5};
  const glm::dvec3 F1 = 20.0 * (0.5 - glm::length(d)) * d / glm::length(d);
  LAB_EXPECT_VEC(chain.particles().get_velocity(1), dt * F1, 1e-12,
                 "Q5: after two steps the second spring has stretched and should have started "
                 "to move mass 1 sideways");
  LAB_EXPECT_VEC(chain.particles().get_velocity(2), glm::dvec3(1, -1, 0) - dt * F1, 1e-12,
                 "Q5: after two steps the second spring should have slowed mass 2");
}

}  // namespace
}  // namespace clothlab
