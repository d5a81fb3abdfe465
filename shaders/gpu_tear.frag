// GPU cloth, pass 3 (tearing, an addition of clothlab; only when --tear-strain E is set), last in
// the step (docs/model.md): the spring from particle (ku, kv) = this texel to its neighbour i is
// removed from the spring mask, for the rest of the run, when the new positions stretch it beyond
// (1 + E) L0. Both ends compute |p_i - p_j| from the same two floats, so they agree bitwise.
#include "gpu_cloth_common.glsl"  // the neighbours and the tearing rule

uniform sampler2D position_texture;      // xyz: p after the step (m)
uniform usampler2D spring_mask_texture;  // bit i: a spring joins the particle to neighbours[i]

layout(location = 0) out uint spring_mask;  // the mask after the step


void main() {
  ivec2 k = ivec2(gl_FragCoord.xy);
  uint mask = texelFetch(spring_mask_texture, k, 0).r;
  vec3 p = texelFetch(position_texture, k, 0).xyz;
  for (int bit = 0; bit < neighbour_count; ++bit) {
    if ((mask & (1u << bit)) == 0u) continue;  // no spring there (border), or torn already
    vec3 p_other = texelFetch(position_texture, k + neighbours[bit].xy, 0).xyz;
    if (overstretched(p, p_other, neighbours[bit].z)) mask &= ~(1u << bit);
  }
  spring_mask = mask;
}
