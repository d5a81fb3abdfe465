// GPU cloth, pass 1 (questions 12 and 13): one step of docs/model.md for particle (ku, kv) =
// this texel, in single precision. Forces from the positions and normals at the start of the
// step, then the integrator and the constraints. Writes the new position and velocity. The
// neighbours, spring_force, integrate and the contacts (the ground of question 9 among them)
// are in gpu_cloth_common.glsl, which the compute path shares.
#include "gpu_cloth_common.glsl"

uniform sampler2D position_texture;  // xyz: p (m), w: 1 if pinned
uniform sampler2D velocity_texture;  // xyz: v (m/s)
uniform sampler2D normal_texture;    // xyz: n of the current positions (unit)
uniform usampler2D spring_mask_texture;  // bit i: a spring joins the particle to neighbours[i]
uniform int grid_size;               // N

uniform vec3 stiffness;    // K (N/m) of the structural, shear and bending springs
uniform vec3 rest_length;  // L0 (m) of the structural, shear and bending springs

uniform float wind_strength;   // K_w, N
uniform vec3 wind_direction;   // u_w, unit, also when K_w = 0 (no wind)

// The mouse drag, an addition (docs/model.md): F_d = K_d (q - p) on one particle.
uniform bool drag_enabled;       // the mouse drag is on
uniform ivec2 drag_texel;        // (ku, kv) of the dragged particle
uniform vec3 drag_target;        // q, m
uniform float drag_stiffness;    // K_d, N/m

layout(location = 0) out vec4 new_position;
layout(location = 1) out vec4 new_velocity;

// Whether a spring joins particle k to its neighbour k + neighbours[i].xy: the neighbour is inside
// the grid (springs stop at its border) and the spring has not torn (tearing is an addition of
// clothlab, off by default: shaders/gpu_tear.frag clears the spring's bit in the mask).
bool joined(ivec2 k, int i) {
  ivec2 neighbour = k + neighbours[i].xy;
  bool inside = neighbour.x >= 0 && neighbour.y >= 0 && neighbour.x < grid_size &&
                neighbour.y < grid_size;
  return inside && (texelFetch(spring_mask_texture, k, 0).r & (1u << i)) != 0u;
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
  // STUDENT(handout)| // joined(k, i) says whether a spring joins this texel to its neighbour i
  // STUDENT(handout)| // (inside the grid, and not torn: clothlab's tearing works through it);
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
  // STUDENT(handout)| // K_w = wind_strength, u_w = wind_direction (a unit vector, also when
  // STUDENT(handout)| // K_w = 0).
  // STUDENT(guided)| // TODO Q13 (GPU wind): add F_w = K_w <n, u_w> n, with n read from
  // STUDENT(guided)| // normal_texture at this texel, K_w = wind_strength and u_w = wind_direction
  // STUDENT(guided)| // (already unit).
  vec3 n = texelFetch(normal_texture, k, 0).xyz;
  force += wind_strength * dot(n, wind_direction) * n;  // question 13: F_w = K_w <n, u_w> n
  // END SOLUTION Q13
  if (drag_enabled && k == drag_texel) force += drag_stiffness * (drag_target - p);  // F_d

  // The integrator, then the constraints (docs/model.md): the sphere, the ground (question 9).
  vec3 p_new, v_new;
  integrate(p, v, force, p_new, v_new);
  sphere_contact(p_new, v_new);
  ground_contact(p_new, v_new);

  new_position = vec4(p_new, 0.0);
  new_velocity = vec4(v_new, 0.0);
}
