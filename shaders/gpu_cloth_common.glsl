// What the two GPU paths share, written once (docs/model.md, in single precision): the 12
// neighbours of a particle, the spring force of equation 2, the integrator, the sphere, the
// ground (question 9) and the tearing rule. Both step shaders (gpu_step.frag, the fragment
// path; gpu_compute_step.comp, the compute path) and both tearing shaders include it: a line
// `#include "gpu_cloth_common.glsl"` is replaced by this file when a shader is loaded
// (src/gl/shader.cpp).

// The 12 particles a particle can be joined to (handout figure 6): (du, dv) and the spring family
// (0 structural, 1 shear, 2 bending). Bit i of a particle's spring mask is neighbours[i]. The C++
// code's neighbour_offsets (src/core/grid_neighbours.hpp), in GLSL: a test checks they are equal.
const int neighbour_count = 12;
const ivec3 neighbours[neighbour_count] = ivec3[neighbour_count](
    ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),       // structural
    ivec3(1, 1, 1), ivec3(-1, -1, 1), ivec3(1, -1, 1), ivec3(-1, 1, 1),     // shear
    ivec3(2, 0, 2), ivec3(-2, 0, 2), ivec3(0, 2, 2), ivec3(0, -2, 2));      // bending

uniform float time_step;      // dt, s
uniform float damping;        // mu, 1/s
uniform float mass;           // m, kg
uniform float gravity;        // g0, m/s^2: g = (0, 0, -g0)
uniform bool explicit_euler;  // false: semi-implicit (the handout's code order)

// Additions (docs/model.md, "Interaction and contacts").
uniform bool sphere_enabled;    // a sphere the cloth collides with
uniform vec3 sphere_centre;     // c, m
uniform float sphere_radius;    // r, m
uniform float sphere_friction;  // mu_s, 1/s

uniform bool ground_enabled;
uniform float ground_height;    // z_g, m
uniform float ground_friction;  // mu_g, 1/s

uniform vec3 tear_length;  // (1 + E) L0 (m) of the structural, shear and bending springs

// Handout equation 2: the force that a spring (K, L0) between i and j exerts on i,
// F = K (L0 - |p_i - p_j|) (p_i - p_j) / |p_i - p_j|.
vec3 spring_force(vec3 p_i, vec3 p_j, float K, float L0) {
  vec3 d = p_i - p_j;
  float L = length(d);
  return K * (L0 - L) / L * d;
}

// The integrator: a = F / m + g, the velocity damped by (1 - mu dt); semi-implicit moves the
// position with the new velocity, explicit (equation 6) with the old one.
void integrate(vec3 p, vec3 v, vec3 force, out vec3 p_new, out vec3 v_new) {
  vec3 a = force / mass + vec3(0.0, 0.0, -gravity);
  v_new = (1.0 - damping * time_step) * v + time_step * a;
  p_new = p + time_step * (explicit_euler ? v : v_new);
}

// The sphere: a particle inside is put back on its surface along n = (p - c)/|p - c|, loses its
// inward normal velocity, and its tangential velocity is damped by (1 - mu_s dt).
void sphere_contact(inout vec3 p_new, inout vec3 v_new) {
  if (!sphere_enabled) return;
  vec3 from_centre = p_new - sphere_centre;
  float distance = length(from_centre);
  if (distance < sphere_radius) {
    vec3 n_s = distance > 0.0 ? from_centre / distance : vec3(0.0, 0.0, 1.0);
    v_new -= min(dot(v_new, n_s), 0.0) * n_s;
    vec3 normal_part = dot(v_new, n_s) * n_s;
    v_new = normal_part + (1.0 - sphere_friction * time_step) * (v_new - normal_part);
    p_new = sphere_centre + sphere_radius * n_s;
  }
}

// Question 9 on the GPU: the ground z = ground_height, after the integrator and the sphere.
void ground_contact(inout vec3 p_new, inout vec3 v_new) {
  // BEGIN SOLUTION Q9: the ground on the GPU
  // STUDENT(handout)| // TODO Q9 (GPU ground): the plane z = ground_height of question 9 on the
  // STUDENT(handout)| // GPU, as on the CPU (when ground_enabled): p_new and v_new are the
  // STUDENT(handout)| // particle's position and velocity after the integration, ground_friction
  // STUDENT(handout)| // the friction rate, time_step the step. For now the GPU cloth falls through.
  // STUDENT(guided)| // TODO Q9 (GPU ground): if ground_enabled and p_new.z < ground_height: put it
  // STUDENT(guided)| // back on the plane, v_new.z = max(v_new.z, 0), and damp v_new.xy by
  // STUDENT(guided)| // (1 - ground_friction time_step). For now the GPU cloth falls through.
  if (ground_enabled && p_new.z < ground_height) {
    p_new.z = ground_height;
    v_new.z = max(v_new.z, 0.0);
    v_new.xy *= 1.0 - ground_friction * time_step;
  }
  // END SOLUTION Q9
}

// Tearing (an addition): whether the spring of the given family between p and p_other is
// stretched beyond (1 + E) L0 and tears. Both ends compute |p - p_other| from the same two
// floats, so they agree bitwise.
bool overstretched(vec3 p, vec3 p_other, int family) {
  return length(p - p_other) > tear_length[family];
}
