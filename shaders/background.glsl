#version 330 core
// A vertical sky gradient behind everything (one full-screen triangle, no vertex buffer).

#if defined VERTEX_SHADER

out float v_y;

void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    v_y = 0.5 * p.y + 0.5;
    gl_Position = vec4(p, 1.0, 1.0);
}

#elif defined FRAGMENT_SHADER

in float v_y;
uniform vec3 u_top;
uniform vec3 u_bottom;
out vec4 f_color;

void main() {
    f_color = vec4(mix(u_bottom, u_top, clamp(v_y, 0.0, 1.0)), 1.0);
}

#endif
