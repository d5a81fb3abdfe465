// GPU cloth (handout section 5): one triangle that covers the whole N x N viewport, so that the
// fragment shader runs exactly once per texel, i.e. once per particle. No vertex data: the
// corners (-1,-1), (3,-1), (-1,3) come from the vertex number.
void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) * 2), float((gl_VertexID & 2)));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
