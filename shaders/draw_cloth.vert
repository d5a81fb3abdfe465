// The CPU cloth: positions and normals come from the simulation's arrays every frame.
layout(location = 0) in vec3 position;  // m
layout(location = 1) in vec3 vertex_normal;
layout(location = 2) in vec2 grid_coordinates;  // (u, v) = (ku, kv) / (N - 1)
uniform mat4 view_projection;
out vec3 world_position;
out vec3 normal;
out vec2 texture_coordinates;
out vec3 surface_colour;

void main() {
  world_position = position;
  normal = vertex_normal;
  texture_coordinates = grid_coordinates;
  surface_colour = vec3(1.0);
  gl_Position = view_projection * vec4(position, 1.0);
}
