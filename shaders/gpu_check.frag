// GPU cloth, the divergence check (not a pass of the lab's model): a fragment survives only for
// a particle whose position or velocity is not finite, or whose speed exceeds speed_bound. An
// occlusion query says whether any survived, so the CPU learns whether a step diverged without
// reading the state back. Nothing is written (colour writes are off).

uniform sampler2D position_texture;  // xyz: p (m)
uniform sampler2D velocity_texture;  // xyz: v (m/s)
uniform float speed_bound;           // m/s

layout(location = 0) out vec4 colour;

void main() {
  ivec2 k = ivec2(gl_FragCoord.xy);
  vec3 p = texelFetch(position_texture, k, 0).xyz;
  vec3 v = texelFetch(velocity_texture, k, 0).xyz;
  bool finite = !any(isnan(p)) && !any(isinf(p)) && !any(isnan(v)) && !any(isinf(v));
  if (finite && length(v) <= speed_bound) discard;
  colour = vec4(1.0);
}
