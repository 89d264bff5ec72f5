// Sampling a cell complex's distance maps on the GPU (Apaza & Andujar, Section 3.3.2): "the
// vertex shader leaves the input vertices untransformed, the projection being performed in a
// geometry shader" (cell_sampling_geom.glsl).
layout(location = 0) in vec3 a_position;  // the mesh in the cube's texture space
out vec3 v_position;

void main() {
  v_position = a_position;
}
