// The compute-shader GPU path (--backend gpu-compute), pass 1: one step of
// docs/model.md for particle (ku, kv) = this invocation, in single precision: the same step as
// gpu_step.frag (forces from the positions and normals at the start of the step, the springs
// of the mask only, then gpu_cloth_common.glsl's integrator, sphere and ground), on shader
// storage buffers instead of textures, so that no rasterisation is involved. Not in the student
// copy: it holds question 12's and 13's answers.
#include "gpu_cloth_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer position_in { vec4 position[]; };  // w: 1 if pinned
layout(std430, binding = 1) readonly buffer velocity_in { vec4 velocity[]; };
layout(std430, binding = 2) readonly buffer normal_in { vec4 normal[]; };
layout(std430, binding = 3) writeonly buffer position_out { vec4 new_position[]; };
layout(std430, binding = 4) writeonly buffer velocity_out { vec4 new_velocity[]; };
// The divergence check: step_index's count grows by one for each particle whose new state is
// not finite or faster than speed_bound (speed_bound 0: no check).
layout(std430, binding = 5) buffer diverged_count { uint diverged[]; };
// The spring mask (gpu_cloth.hpp): bit i of word k while a spring joins k to neighbours[i].
layout(std430, binding = 6) readonly buffer spring_mask_words { uint spring_mask[]; };
uniform float speed_bound;  // m/s
uniform int step_index;     // the step's place in the batch

uniform int grid_size;     // N
uniform vec3 stiffness;    // K (N/m) of the structural, shear and bending springs
uniform vec3 rest_length;  // L0 (m) of the structural, shear and bending springs
uniform float wind_strength;  // K_w, N
uniform vec3 wind_direction;  // u_w, unit
uniform bool drag_enabled;
uniform ivec2 drag_texel;
uniform vec3 drag_target;
uniform float drag_stiffness;

int index_of(ivec2 k) { return k.x + grid_size * k.y; }

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int i = index_of(k);
  vec4 here = position[i];
  vec3 p = here.xyz;
  vec3 v = velocity[i].xyz;
  if (here.w != 0.0) {  // pinned: never moves, velocity 0
    new_position[i] = here;
    new_velocity[i] = vec4(0.0);
    return;
  }
  vec3 force = vec3(0.0);
  uint joined = spring_mask[i];  // the springs inside the grid and not torn
  for (int s = 0; s < 12; ++s) {
    if ((joined & (1u << s)) == 0u) continue;
    ivec2 j = k + neighbours[s].xy;
    int family = neighbours[s].z;
    force += spring_force(p, position[index_of(j)].xyz, stiffness[family], rest_length[family]);
  }
  if (wind_strength != 0.0) {  // (the normals are computed only for a windy step)
    vec3 n = normal[i].xyz;
    force += wind_strength * dot(n, wind_direction) * n;  // F_w = K_w <n, u_w> n
  }
  if (drag_enabled && k == drag_texel) force += drag_stiffness * (drag_target - p);

  vec3 p_new, v_new;
  integrate(p, v, force, p_new, v_new);
  sphere_contact(p_new, v_new);
  ground_contact(p_new, v_new);
  new_position[i] = vec4(p_new, 0.0);
  new_velocity[i] = vec4(v_new, 0.0);
  if (speed_bound > 0.0) {
    bool finite = !any(isnan(p_new)) && !any(isinf(p_new)) && !any(isnan(v_new)) &&
                  !any(isinf(v_new));
    if (!finite || length(v_new) > speed_bound) atomicAdd(diverged[step_index], 1u);
  }
}
