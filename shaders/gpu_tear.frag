#version 330 core
// GPU cloth, pass 3 (tearing, an addition of clothlab; only when --tear-strain E is set), last in
// the step (docs/model.md): the spring from particle (ku, kv) = this texel to its neighbour i is
// removed from the spring mask, for the rest of the run, when the new positions stretch it beyond
// (1 + E) L0. Both ends compute |p_i - p_j| from the same two floats, so they agree bitwise.

uniform sampler2D position_texture;      // xyz: p after the step (m)
uniform usampler2D spring_mask_texture;  // bit i: a spring joins the particle to neighbours[i]
uniform vec3 tear_length;  // (1 + E) L0 (m) of the structural, shear and bending springs

layout(location = 0) out uint spring_mask;  // the mask after the step

// The neighbours of gpu_step.frag, in the same order (the mask's bits): (du, dv, family).
const int neighbour_count = 12;
const ivec3 neighbours[neighbour_count] = ivec3[neighbour_count](
    ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
    ivec3(1, 1, 1), ivec3(-1, -1, 1), ivec3(1, -1, 1), ivec3(-1, 1, 1),
    ivec3(2, 0, 2), ivec3(-2, 0, 2), ivec3(0, 2, 2), ivec3(0, -2, 2));

void main() {
  ivec2 k = ivec2(gl_FragCoord.xy);
  uint mask = texelFetch(spring_mask_texture, k, 0).r;
  vec3 p = texelFetch(position_texture, k, 0).xyz;
  for (int bit = 0; bit < neighbour_count; ++bit) {
    if ((mask & (1u << bit)) == 0u) continue;  // no spring there (border), or torn already
    vec3 p_other = texelFetch(position_texture, k + neighbours[bit].xy, 0).xyz;
    if (length(p - p_other) > tear_length[neighbours[bit].z]) mask &= ~(1u << bit);
  }
  spring_mask = mask;
}
