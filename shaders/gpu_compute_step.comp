#version 430 core
// The compute-shader GPU path (--backend gpu-compute, issue 9), pass 1: one step of
// docs/model.md for particle (ku, kv) = this invocation, in single precision: the same step as
// gpu_step.frag (forces from the positions and normals at the start of the step, the springs
// of the mask only, the integrator, the sphere, the ground), on shader storage buffers instead of textures, so that
// no rasterisation is involved. Not in the student copy: it holds question 12's answer.
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
uniform float time_step;   // dt, s
uniform float damping;     // mu, 1/s
uniform float mass;        // m, kg
uniform float gravity;     // g0, m/s^2
uniform bool explicit_euler;
uniform float wind_strength;  // K_w, N
uniform vec3 wind_direction;  // u_w, unit
uniform bool drag_enabled;
uniform ivec2 drag_texel;
uniform vec3 drag_target;
uniform float drag_stiffness;
uniform bool sphere_enabled;
uniform vec3 sphere_centre;
uniform float sphere_radius;
uniform float sphere_friction;
uniform bool ground_enabled;
uniform float ground_height;
uniform float ground_friction;

const ivec3 neighbours[12] = ivec3[12](
    ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
    ivec3(1, 1, 1), ivec3(-1, -1, 1), ivec3(1, -1, 1), ivec3(-1, 1, 1),
    ivec3(2, 0, 2), ivec3(-2, 0, 2), ivec3(0, 2, 2), ivec3(0, -2, 2));

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
    vec3 d = p - position[index_of(j)].xyz;
    float L = length(d);
    force += stiffness[family] * (rest_length[family] - L) / L * d;  // equation 2
  }
  vec3 n = normal[i].xyz;
  force += wind_strength * dot(n, wind_direction) * n;  // F_w = K_w <n, u_w> n
  if (drag_enabled && k == drag_texel) force += drag_stiffness * (drag_target - p);

  vec3 a = force / mass + vec3(0.0, 0.0, -gravity);
  vec3 v_new = (1.0 - damping * time_step) * v + time_step * a;
  vec3 p_new = p + time_step * (explicit_euler ? v : v_new);

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
  if (ground_enabled && p_new.z < ground_height) {
    p_new.z = ground_height;
    v_new.z = max(v_new.z, 0.0);
    v_new.xy *= 1.0 - ground_friction * time_step;
  }
  new_position[i] = vec4(p_new, 0.0);
  new_velocity[i] = vec4(v_new, 0.0);
  if (speed_bound > 0.0) {
    bool finite = !any(isnan(p_new)) && !any(isinf(p_new)) && !any(isnan(v_new)) &&
                  !any(isinf(v_new));
    if (!finite || length(v_new) > speed_bound) atomicAdd(diverged[step_index], 1u);
  }
}
