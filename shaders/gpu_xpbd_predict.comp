// The compute-shader GPU path with --integrator xpbd (src/core/xpbd.hpp), pass 1 of a substep h:
// particle (ku, kv) is predicted to move by h v under gravity, the wind and the drag, damped by
// (1 - mu h); and the multipliers of its constraints (those whose lower end it is) go back to 0.
// In single precision the substep's motion is kept apart from the position (displacement[],
// x - x_prev, which the next passes move and divide by h), so that the velocity is not the
// difference of two rounded positions, which loses u |p| / h (xpbd_solve.comp). The forces that
// are not springs are taken once per step, at the first substep (the normals of the step's
// start), and held (external_force[]), as on the CPU.
#include "gpu_cloth_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer position_in { vec4 position[]; };  // w: 1 if pinned
layout(std430, binding = 1) buffer velocity_io { vec4 velocity[]; };
layout(std430, binding = 2) readonly buffer normal_in { vec4 normal[]; };
layout(std430, binding = 7) writeonly buffer displacement_out { vec4 displacement[]; };
layout(std430, binding = 8) writeonly buffer multiplier_out { float multiplier[]; };  // 6 a particle
layout(std430, binding = 9) buffer external_force_io { vec4 external_force[]; };

uniform int grid_size;        // N
uniform float substep;        // h = dt / substeps, s
uniform bool first_substep;   // F_ext is computed now, and read at the next substeps
uniform float wind_strength;  // K_w, N
uniform vec3 wind_direction;  // u_w, unit
uniform bool drag_enabled;
uniform ivec2 drag_texel;
uniform vec3 drag_target;
uniform float drag_stiffness;

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int i = k.x + grid_size * k.y;
  for (int kind = 0; kind < 6; ++kind) multiplier[6 * i + kind] = 0.0;
  vec4 here = position[i];
  if (here.w != 0.0) {  // pinned: never moves, velocity 0
    displacement[i] = vec4(0.0);
    return;
  }
  vec3 force;
  if (first_substep) {
    vec3 n = normal[i].xyz;
    force = wind_strength * dot(n, wind_direction) * n;  // F_w = K_w <n, u_w> n
    if (drag_enabled && k == drag_texel) force += drag_stiffness * (drag_target - here.xyz);
    external_force[i] = vec4(force, 0.0);
  } else {
    force = external_force[i].xyz;
  }
  vec3 v = (1.0 - damping * substep) * velocity[i].xyz +
           substep * (force / mass + vec3(0.0, 0.0, -gravity));
  velocity[i] = vec4(v, 0.0);
  displacement[i] = vec4(substep * v, 0.0);
}
