#version 330 core
// The GPU cloth (question 11): the CPU sent a flat grid once; each vertex fetches its position
// and normal from the N x N state textures, texel (ku, kv) holding particle k = ku + N kv.
layout(location = 0) in ivec2 texel;            // (ku, kv)
layout(location = 2) in vec2 grid_coordinates;  // (u, v) = (ku, kv) / (N - 1)
uniform sampler2D position_texture;  // xyz: position, m
uniform sampler2D normal_texture;    // xyz: unit normal
uniform mat4 view_projection;
out vec3 world_position;
out vec3 normal;
out vec2 texture_coordinates;
out vec3 surface_colour;

void main() {
  world_position = texelFetch(position_texture, texel, 0).xyz;
  normal = texelFetch(normal_texture, texel, 0).xyz;
  texture_coordinates = grid_coordinates;
  surface_colour = vec3(1.0);
  gl_Position = view_projection * vec4(world_position, 1.0);
}
