// Question 5: the coupled springs. coupled_springs::compute_force must give every spring of the
// chain its force (handout equation 2) on BOTH of its ends. Each expected force is worked out
// by hand in the comment above its test. Tolerances: the rounding of a force computed in single
// or double precision, float_rounding K |p| per spring (lab_check.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "lab_check.hpp"
#include "student.hpp"

namespace clothlab {
namespace {

// The student's classes and functions, run by the lab runner (student.hpp).
using student::coupled_springs;

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
// and its reaction on p1: (0, 0, -4), pulled down. Positions of size 1: tolerance 2 springs of
// K |p| = 20.
constexpr double two_masses_tolerance = 2 * 20.0 * lab::float_rounding;

TEST(Q5CoupledSprings, TheSecondSpringPullsTheSecondMassBack) {
  coupled_springs chain = chain_at(2, 20.0, {{0.1, 0, 1}, {0.1, 0, 0.5}, {0.1, 0, -0.2}});
  chain.compute_force();
  LAB_EXPECT_FORCE(chain.particles().get_force(2), glm::dvec3(0, 0, 4), two_masses_tolerance,
                   tr("Q5: mass 2 hangs 0.2 m below the rest length of the second spring, which "
                      "should pull it up with K (L0 - L) = 4 N; is the second spring (p1-p2) in "
                      "compute_force?"),
                   tr("Q5: the stretched second spring pushes mass 2 down instead of pulling it "
                      "up (the force has the wrong sign): spring_force(a, b, K, L0), equation 2, "
                      "is the force on the end at a; which end is mass 2?"));
}

TEST(Q5CoupledSprings, TheSecondSpringPullsTheFirstMassDownToo) {
  coupled_springs chain = chain_at(2, 20.0, {{0.1, 0, 1}, {0.1, 0, 0.5}, {0.1, 0, -0.2}});
  chain.compute_force();
  LAB_EXPECT_FORCE(chain.particles().get_force(1), glm::dvec3(0, 0, -4), two_masses_tolerance,
                   tr("Q5: a spring pulls BOTH of its ends (Newton's third law): the stretched "
                      "second spring pulls mass 2 up by 4 N and mass 1 down by 4 N, while the "
                      "first spring, at its rest length, adds nothing"),
                   tr("Q5: the second spring pushes mass 1 up instead of pulling it down (the "
                      "force has the wrong sign): a stretched spring pulls its two ends towards "
                      "each other, with opposite forces (Newton's third law)"));
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
    LAB_EXPECT_FORCE(chain.particles().get_force(std::size_t(i)), expected,
                     2 * K * lab::float_rounding,
                     i < 4 ? format(tr("Q5: in a chain of 4 masses, mass %d should feel the "
                                       "spring above it and the one below it (equation 2 on "
                                       "each)"),
                                    int(i))
                           : format(tr("Q5: in a chain of 4 masses, mass %d should feel the "
                                       "spring above it (equation 2)"),
                                    int(i)),
                     format(tr("Q5: in a chain of 4 masses, mass %d feels the force of its "
                               "springs with the wrong sign: each spring should pull it towards "
                               "its neighbour when stretched, and push it away when compressed "
                               "(equation 2: spring_force(a, b, K, L0) is the force on a)"),
                            int(i)));
  }
}

// n = 2, gravity 0, damping 0, K = 20, m = 1, dt = 0.01. Step 1: no spring force (rest lengths),
// so v1 = 0, v2 = (1, -1, 0), p1 = (0.1, 0, 0.5), p2 = (0.1 + dt, -dt, 0). Step 2: spring 1 is
// still at its rest length; spring 2 has d = p1 - p2 = (-dt, dt, 0.5) and pulls both ends
// together: F1 = K (0.5 - |d|) d / |d| on mass 1, F2 = -F1 on mass 2; v1 = dt F1 / m,
// v2 = (1, -1, 0) + dt F2 / m (|dt F1| = 4e-5 m/s). Tolerance: the forces' rounding (2 springs of
// K |p| = 20), times dt, and the velocity's own (size 1).
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
  const double tolerance = lab::rounding(2 * 20.0 * dt + 1.0);
  LAB_EXPECT_FORCE(chain.particles().get_velocity(1), dt * F1, tolerance,
                   tr("Q5: after two steps the second spring has stretched and should have "
                      "started to move mass 1 sideways"),
                   tr("Q5: after two steps the second spring has stretched, and it pushes mass 1 "
                      "away from mass 2 instead of pulling it (the force on mass 1 has the wrong "
                      "sign)"));
  LAB_EXPECT_VEC(chain.particles().get_velocity(2), glm::dvec3(1, -1, 0) - dt * F1, tolerance,
                 tr("Q5: after two steps the second spring should have slowed mass 2"));
}

}  // namespace
}  // namespace clothlab
