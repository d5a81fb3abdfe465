// The compute-shader GPU path with --integrator xpbd (src/core/xpbd.hpp), pass 3 of a substep h:
// the velocity of particle (ku, kv) is its motion over the substep, v = (p - x_prev) / h, its
// displacement divided by h, and it moves by it, p = x_prev + displacement; then the contacts
// (gpu_cloth_common.glsl's sphere and ground, over h: time_step is h in this pass), every
// substep as on the CPU (xpbd.hpp). After the last substep, the divergence check.
#include "gpu_cloth_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) buffer position_io { vec4 position[]; };  // w: 1 if pinned
layout(std430, binding = 1) buffer velocity_io { vec4 velocity[]; };
layout(std430, binding = 5) buffer diverged_count { uint diverged[]; };
layout(std430, binding = 7) readonly buffer displacement_in { vec4 displacement[]; };

uniform int grid_size;     // N
uniform float substep;     // h, s
uniform bool last_substep;
uniform float speed_bound;  // m/s; 0: no check
uniform int step_index;     // the step's place in the batch

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int i = k.x + grid_size * k.y;
  vec4 here = position[i];
  if (here.w != 0.0) return;  // pinned
  vec3 move = displacement[i].xyz;
  vec3 p = here.xyz + move;
  vec3 v = move / substep;
  sphere_contact(p, v);
  ground_contact(p, v);
  if (last_substep && speed_bound > 0.0) {
    bool finite = !any(isnan(p)) && !any(isinf(p)) && !any(isnan(v)) && !any(isinf(v));
    if (!finite || length(v) > speed_bound) atomicAdd(diverged[step_index], 1u);
  }
  position[i] = vec4(p, 0.0);
  velocity[i] = vec4(v, 0.0);
}
