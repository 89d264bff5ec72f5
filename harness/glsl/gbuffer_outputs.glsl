// The outputs of a scene pass: colour always; with RL_GBUFFER the G-buffer of
// harness/core/gbuffer.h (world position, normal + shadow flag, hit uv / layer / fetches, aux).
layout(location = 0) out vec4 o_color;
#ifdef RL_GBUFFER
layout(location = 1) out vec4 o_position;
layout(location = 2) out vec4 o_normal;
layout(location = 3) out vec4 o_hit;
layout(location = 4) out vec4 o_aux;
#endif
