// One triangle that covers the whole screen (no vertex buffer: built from gl_VertexID), on the
// far plane (depth 1), so that it fills only what the scene left empty.
out vec2 screen_position;  // normalised device coordinates, -1..1

void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0) (2,0) (0,2)
  screen_position = corner * 2.0 - 1.0;
  gl_Position = vec4(screen_position, 1.0, 1.0);
}
