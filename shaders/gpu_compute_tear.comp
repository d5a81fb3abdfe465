// The compute-shader GPU path, pass 3 (tearing, an addition; only when --tear-strain E is set),
// last in the step (docs/model.md): the spring from particle (ku, kv) to its neighbour i is
// removed from the spring mask, for the rest of the run, when the new positions stretch it beyond
// (1 + E) L0, as in gpu_tear.frag. Each invocation reads and writes its own mask word only.
layout(local_size_x = 8, local_size_y = 8) in;
#include "gpu_cloth_common.glsl"  // the neighbours and the tearing rule

layout(std430, binding = 0) readonly buffer position_in { vec4 position[]; };  // after the step
layout(std430, binding = 6) buffer spring_mask_words { uint spring_mask[]; };  // bit i: joined

uniform int grid_size;  // N

int index_of(ivec2 k) { return k.x + grid_size * k.y; }

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int here = index_of(k);
  uint mask = spring_mask[here];
  vec3 p = position[here].xyz;
  for (int bit = 0; bit < neighbour_count; ++bit) {
    if ((mask & (1u << bit)) == 0u) continue;  // no spring there (border), or torn already
    vec3 p_other = position[index_of(k + neighbours[bit].xy)].xyz;
    if (overstretched(p, p_other, neighbours[bit].z)) mask &= ~(1u << bit);
  }
  spring_mask[here] = mask;
}
