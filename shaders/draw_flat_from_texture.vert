#version 330 core
// The GPU cloth's flat passes (lines; the shadow with draw_ground.frag): each vertex fetches its
// position from the N x N position texture, texel (ku, kv) holding particle k = ku + N kv.
layout(location = 0) in ivec2 texel;  // (ku, kv)
uniform sampler2D position_texture;   // xyz: position, m
uniform mat4 view_projection;
uniform bool project_onto_ground;
uniform float ground_height;   // m
uniform vec3 light_direction;  // unit, towards the light
out vec3 world_position;        // m, where the ground shader draws the cloth's shadow

void main() {
  vec3 p = texelFetch(position_texture, texel, 0).xyz;
  if (project_onto_ground) p -= light_direction * (p.z - ground_height) / light_direction.z;
  world_position = p;
  gl_Position = view_projection * vec4(p, 1.0);
}
