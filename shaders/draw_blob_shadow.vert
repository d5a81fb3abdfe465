// A soft round shadow on the ground under a mass: one square per instance, around the blob's
// centre, in the ground plane. Drawn over the ground, which it darkens (multiplied in by blending).
layout(location = 0) in vec4 blob;  // per instance: x, y (m), radius (m), darkness (0..1)
uniform mat4 view_projection;
uniform float ground_height;  // m
out vec2 offset;              // from the centre, in radii
flat out float darkness;

void main() {
  // A strip of 4 vertices: (-1, -1) (1, -1) (-1, 1) (1, 1).
  offset = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1)) * 2.0 - 1.0;
  darkness = blob.w;
  gl_Position = view_projection * vec4(blob.xy + offset * blob.z, ground_height, 1.0);
}
