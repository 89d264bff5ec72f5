// After the slices: every pixel's fetches become the sum over all its slice fragments (kept or
// discarded), written into the G-buffer's fetch channel only (the other outputs are masked).
layout(binding = 1, r32ui) uniform readonly uimage2D rl_fetch_count;
layout(location = 3) out vec4 o_hit;

void main() {
  o_hit = vec4(0.0, 0.0, 0.0, float(imageLoad(rl_fetch_count, ivec2(gl_FragCoord.xy)).r));
}
