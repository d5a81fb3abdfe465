// The compute-shader GPU path with --integrator xpbd (src/core/xpbd.hpp), pass 2 of a substep,
// once per colour and iteration: the constraint of the colour whose lower end is particle
// (ku, kv), if it has one, moves its two ends by the XPBD paper's equation (26). The colours are
// cloth_constraint_colour's: a colour's springs share no particle, so the invocations of a pass
// write disjoint particles, and the passes follow one another in the CPU's order. The ends are
// at x_prev + displacement (xpbd_predict.comp): the corrections move the displacements.
#include "gpu_cloth_common.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer position_in { vec4 position[]; };  // x_prev; w: pinned
layout(std430, binding = 6) readonly buffer spring_mask_words { uint spring_mask[]; };
layout(std430, binding = 7) buffer displacement_io { vec4 displacement[]; };  // x - x_prev
layout(std430, binding = 8) buffer multiplier_io { float multiplier[]; };  // 6 a particle

uniform int grid_size;     // N
uniform vec3 stiffness;    // K (N/m) of the structural, shear and bending springs
uniform vec3 rest_length;  // L0 (m) of the structural, shear and bending springs
uniform vec3 alpha_tilde;  // alpha / h^2 = 1 / (K h^2) of each family, 1/kg
uniform vec3 gamma;        // alpha~ beta~ / h = beta / (K h) of each family
uniform int colour;        // 0 to 11 (xpbd.hpp)

// The six kinds of constraints seen from their lower end: (du, dv) and the bit of the spring mask
// (neighbours[] of gpu_cloth_common.glsl); kind = colour / 2, its family kind / 2.
const ivec3 kinds[6] = ivec3[6](ivec3(1, 0, 0), ivec3(0, 1, 2), ivec3(1, 1, 4), ivec3(-1, 1, 7),
                                ivec3(2, 0, 8), ivec3(0, 2, 10));

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int kind = colour / 2;
  int family = kind / 2;
  // The colour's parity: of ku (of kv for the kinds along kv), by pairs for the bending springs.
  int along = kinds[kind].x == 0 ? k.y : k.x;
  int span = family == 2 ? 2 : 1;
  if ((along / span) % 2 != colour % 2) return;
  int a = k.x + grid_size * k.y;
  if ((spring_mask[a] & (1u << kinds[kind].z)) == 0u) return;  // outside the grid, or torn
  if (!(stiffness[family] > 0.0)) return;                      // K = 0: no spring
  ivec2 kb = k + kinds[kind].xy;
  int b = kb.x + grid_size * kb.y;
  vec4 pa = position[a], pb = position[b];
  vec3 move_a = displacement[a].xyz, move_b = displacement[b].xyz;
  float w_a = pa.w != 0.0 ? 0.0 : 1.0 / mass;
  float w_b = pb.w != 0.0 ? 0.0 : 1.0 / mass;
  float w = w_a + w_b;
  vec3 d = (pa.xyz - pb.xyz) + (move_a - move_b);  // p_a - p_b
  float L = length(d);
  if (w == 0.0 || L == 0.0) return;
  vec3 n = d / L;
  float C = L - rest_length[family];
  float closing = dot(n, move_a - move_b);  // grad C.(x - x_prev)
  int slot = 6 * a + kind;
  float lambda = multiplier[slot];
  float delta_lambda = (-C - alpha_tilde[family] * lambda - gamma[family] * closing) /
                       ((1.0 + gamma[family]) * w + alpha_tilde[family]);
  multiplier[slot] = lambda + delta_lambda;
  displacement[a] = vec4(move_a + (w_a * delta_lambda) * n, 0.0);
  displacement[b] = vec4(move_b - (w_b * delta_lambda) * n, 0.0);
}
