// The ground: a large horizontal square at z = ground_height.
layout(location = 0) in vec2 corner;  // m, x and y
uniform mat4 view_projection;
uniform float ground_height;  // m
out vec3 world_position;

void main() {
  world_position = vec3(corner, ground_height);
  gl_Position = view_projection * vec4(world_position, 1.0);
}
