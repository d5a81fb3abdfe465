// The compute-shader GPU path, pass 2: the vertex normal of particle (ku, kv), central
// differences as in gpu_normal.frag (docs/model.md).
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer position_in { vec4 position[]; };
layout(std430, binding = 2) writeonly buffer normal_out { vec4 normal[]; };

uniform int grid_size;  // N

vec3 position_at(int ku, int kv) { return position[ku + grid_size * kv].xyz; }

void main() {
  ivec2 k = ivec2(gl_GlobalInvocationID.xy);
  if (k.x >= grid_size || k.y >= grid_size) return;
  int last = grid_size - 1;
  vec3 d_u = position_at(min(k.x + 1, last), k.y) - position_at(max(k.x - 1, 0), k.y);
  vec3 d_v = position_at(k.x, min(k.y + 1, last)) - position_at(k.x, max(k.y - 1, 0));
  normal[k.x + grid_size * k.y] = vec4(normalize(cross(d_u, d_v)), 0.0);
}
