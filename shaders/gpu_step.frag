#version 330 core
// GPU cloth, pass 1 (questions 12 and 13): one step of docs/model.md for particle (ku, kv) =
// this texel, in single precision. Forces from the positions and normals at the start of the
// step, then the integrator, then the ground contact. Writes the new position and velocity.

uniform sampler2D position_texture;  // xyz: p (m), w: 1 if pinned
uniform sampler2D velocity_texture;  // xyz: v (m/s)
uniform sampler2D normal_texture;    // xyz: n of the current positions (unit)
uniform usampler2D spring_mask_texture;  // bit i: a spring joins the particle to neighbours[i]
uniform int grid_size;               // N

uniform vec3 stiffness;    // K (N/m) of the structural, shear and bending springs
uniform vec3 rest_length;  // L0 (m) of the structural, shear and bending springs: h, h√2, 2h

uniform float time_step;  // dt, s
uniform float damping;    // mu, 1/s
uniform float mass;       // m, kg
uniform float gravity;    // g0, m/s^2: g = (0, 0, -g0)
uniform bool explicit_euler;  // false: semi-implicit (the handout's code order)

uniform float wind_strength;   // K_w, N
uniform vec3 wind_direction;   // u_w, unit

// Additions (docs/model.md, "Interaction and contacts").
uniform bool drag_enabled;       // the mouse drag: F_d = K_d (q - p) on one particle
uniform ivec2 drag_texel;        // (ku, kv) of the dragged particle
uniform vec3 drag_target;        // q, m
uniform float drag_stiffness;    // K_d, N/m
uniform bool sphere_enabled;     // a sphere the cloth collides with
uniform vec3 sphere_centre;      // c, m
uniform float sphere_radius;     // r, m
uniform float sphere_friction;   // mu_s, 1/s

uniform bool ground_enabled;
uniform float ground_height;    // z_g, m
uniform float ground_friction;  // mu_g, 1/s

layout(location = 0) out vec4 new_position;
layout(location = 1) out vec4 new_velocity;

// The 12 particles a particle can be joined to (handout figure 6): (du, dv) and the spring family
// (0 structural, 1 shear, 2 bending). Each texel gathers the forces of its own springs.
const int neighbour_count = 12;
const ivec3 neighbours[neighbour_count] = ivec3[neighbour_count](
    ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),       // structural, h
    ivec3(1, 1, 1), ivec3(-1, -1, 1), ivec3(1, -1, 1), ivec3(-1, 1, 1),     // shear, h√2
    ivec3(2, 0, 2), ivec3(-2, 0, 2), ivec3(0, 2, 2), ivec3(0, -2, 2));      // bending, 2h

// Whether a spring joins particle k to its neighbour k + neighbours[i].xy: the neighbour is inside
// the grid (springs stop at its border) and the spring has not torn (tearing is an addition of
// clothlab, off by default: shaders/gpu_tear.frag clears the spring's bit in the mask).
bool joined(ivec2 k, int i) {
  ivec2 neighbour = k + neighbours[i].xy;
  bool inside = neighbour.x >= 0 && neighbour.y >= 0 && neighbour.x < grid_size &&
                neighbour.y < grid_size;
  return inside && (texelFetch(spring_mask_texture, k, 0).r & (1u << i)) != 0u;
}

// Handout equation 2: the force that a spring (K, L0) between i and j exerts on i,
// F = K (L0 - |p_i - p_j|) (p_i - p_j) / |p_i - p_j|.
vec3 spring_force(vec3 p_i, vec3 p_j, float K, float L0) {
  vec3 d = p_i - p_j;
  float L = length(d);
  return K * (L0 - L) / L * d;
}

void main() {
  ivec2 k = ivec2(gl_FragCoord.xy);  // (ku, kv): particle ku + N kv
  vec4 position = texelFetch(position_texture, k, 0);
  vec3 p = position.xyz;
  vec3 v = texelFetch(velocity_texture, k, 0).xyz;
  bool pinned = position.w != 0.0;

  if (pinned) {  // question 7: pinned particles never move and keep a zero velocity
    new_position = position;
    new_velocity = vec4(0.0);
    return;
  }

  // Forces: the springs to every neighbour inside the grid, then the wind.
  vec3 force = vec3(0.0);
  // BEGIN SOLUTION Q12: the spring forces on the GPU
  // STUDENT(handout)| // TODO Q12 (GPU springs): add the spring forces to this particle's force,
  // STUDENT(handout)| // as compute_force does on the CPU (question 8), in single precision. The
  // STUDENT(handout)| // 12 possible neighbours are in neighbours[] (offset xy, family z);
  // STUDENT(handout)| // joined(k, i) says whether a spring joins this texel to its neighbour i;
  // STUDENT(handout)| // positions come from position_texture (texelFetch), and stiffness[family]
  // STUDENT(handout)| // and rest_length[family] are set by the CPU. For now the GPU cloth falls
  // STUDENT(handout)| // under gravity alone. Done when ./test.sh -L q12 passes.
  // STUDENT(guided)| // TODO Q12 (GPU springs): for each of the neighbour_count entries of
  // STUDENT(guided)| // neighbours[] that is joined(k, i) to this particle (inside the N x N grid),
  // STUDENT(guided)| // the texel j = k + neighbours[i].xy pulls it by a spring of family
  // STUDENT(guided)| // neighbours[i].z: add spring_force(p, p_j, stiffness[family],
  // STUDENT(guided)| // rest_length[family]), p_j read with texelFetch(position_texture, j, 0).xyz.
  // STUDENT(guided)| // For now the GPU cloth falls under gravity alone.
  for (int i = 0; i < neighbour_count; ++i) {
    if (!joined(k, i)) continue;  // outside the grid (or torn)
    ivec2 j = k + neighbours[i].xy;
    int family = neighbours[i].z;
    vec3 p_j = texelFetch(position_texture, j, 0).xyz;
    force += spring_force(p, p_j, stiffness[family], rest_length[family]);
  }
  // END SOLUTION Q12
  // BEGIN SOLUTION Q13: the wind on the GPU
  // STUDENT(handout)| // TODO Q13 (GPU wind): the wind of question 13 on the GPU, as on the CPU:
  // STUDENT(handout)| // F_w = K_w <n, u_w> n, n read from normal_texture at this texel,
  // STUDENT(handout)| // K_w = wind_strength, u_w = wind_direction (unit).
  // STUDENT(guided)| // TODO Q13 (GPU wind): add F_w = K_w <n, u_w> n, with n read from
  // STUDENT(guided)| // normal_texture at this texel, K_w = wind_strength and u_w = wind_direction
  // STUDENT(guided)| // (already unit).
  vec3 n = texelFetch(normal_texture, k, 0).xyz;
  force += wind_strength * dot(n, wind_direction) * n;  // question 13: F_w = K_w <n, u_w> n
  // END SOLUTION Q13
  if (drag_enabled && k == drag_texel) force += drag_stiffness * (drag_target - p);  // F_d

  // Integrator: a = F / m + g; the velocity is damped by (1 - mu dt).
  vec3 a = force / mass + vec3(0.0, 0.0, -gravity);
  vec3 v_new = (1.0 - damping * time_step) * v + time_step * a;
  // semi-implicit: the position moves with the new velocity; explicit (eq. 6): with the old one.
  vec3 p_new = p + time_step * (explicit_euler ? v : v_new);

  // The sphere: a particle inside is put back on its surface along n = (p - c)/|p - c|, loses its
  // inward normal velocity, and its tangential velocity is damped by (1 - mu_s dt).
  if (sphere_enabled) {
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

  new_position = vec4(p_new, 0.0);
  new_velocity = vec4(v_new, 0.0);
}
