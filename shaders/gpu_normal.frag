// GPU cloth, pass 2: the vertex normal of particle (ku, kv) = this texel (docs/model.md):
//   n = normalize(d_u x d_v),
//   d_u = p(min(ku+1, N-1), kv) - p(max(ku-1, 0), kv),
//   d_v = p(ku, min(kv+1, N-1)) - p(ku, max(kv-1, 0)).

uniform sampler2D position_texture;  // xyz: p (m), w: 1 if pinned
uniform int grid_size;               // N

layout(location = 0) out vec4 normal;  // xyz: n, unit

vec3 position_at(int ku, int kv) { return texelFetch(position_texture, ivec2(ku, kv), 0).xyz; }

void main() {
  ivec2 k = ivec2(gl_FragCoord.xy);  // (ku, kv)
  int last = grid_size - 1;
  vec3 d_u = position_at(min(k.x + 1, last), k.y) - position_at(max(k.x - 1, 0), k.y);
  vec3 d_v = position_at(k.x, min(k.y + 1, last)) - position_at(k.x, max(k.y - 1, 0));
  normal = vec4(normalize(cross(d_u, d_v)), 0.0);
}
