// The shade of a soft round shadow: darkest at the centre, none from one radius on. Blending
// multiplies the ground's colour by it (overlapping shadows multiply).
in vec2 offset;  // from the centre, in radii
flat in float darkness;
out vec4 colour;

void main() {
  float shade = 1.0 - darkness * (1.0 - smoothstep(0.0, 1.0, length(offset)));
  colour = vec4(vec3(shade), 1.0);
}
