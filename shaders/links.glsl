#version 330 core
// Links between particle pairs on the hardware path: one instanced draw of screen-space quads
// (as lines.glsl), each instance a link's two particle indices and its rest length; the ends are
// read from the particles' positions (a float texture refilled from the position buffer on the
// GPU), the strain and color computed here (style.link_colors), so the CPU sends nothing per
// link per frame.

#if defined VERTEX_SHADER

in vec2 in_corner;        // x: 0 at a, 1 at b; y: -1 / +1 across
in ivec2 in_ends;         // particle indices a, b
in vec4 in_link;          // rest length [m], kind (0 spring, 1 bungee, 2 cable, 3 rod),
                          // width [px at 720 rows], dash period when slack [m] (0: none)

uniform sampler2D u_positions;  // RGB32F, particle i at (i % width, i / width)
#include <frame>
uniform float u_strain_full;
uniform vec3 u_compressed, u_rest, u_stretched, u_bungee, u_cable, u_rod;

out vec4 v_color;
out float v_along;
out float v_across;
flat out float v_dash;
flat out float v_half;

vec3 fetch(int i) {
    int w = textureSize(u_positions, 0).x;
    return texelFetch(u_positions, ivec2(i % w, i / w), 0).xyz;
}

void main() {
    vec3 start = fetch(in_ends.x);
    vec3 end = fetch(in_ends.y);
    float len = distance(start, end);
    float strain = (len - in_link.x) / max(in_link.x, 1e-9);
    int kind = int(in_link.y + 0.5);
    vec3 rgb;
    if (kind == 0) {
        float t = clamp(strain / u_strain_full, -1.0, 1.0);
        rgb = u_rest + ((t < 0.0 ? u_compressed : u_stretched) - u_rest) * abs(t);
    } else if (kind == 1) {
        rgb = u_bungee + (u_stretched - u_bungee) * clamp(strain / u_strain_full, 0.0, 1.0);
    } else {
        rgb = kind == 2 ? u_cable : u_rod;
    }
    v_color = vec4(rgb, 1.0);
    v_dash = (in_link.w > 0.0 && strain < -1e-3) ? in_link.w : 0.0;
    float width = in_link.z * u_width_scale;
    v_half = 0.5 * width;

    vec4 a = u_view_proj * vec4(start, 1.0);
    vec4 b = u_view_proj * vec4(end, 1.0);
    float eps = 1e-3;
    if (a.w < eps && b.w < eps) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_along = 0.0;
        v_across = 0.0;
        return;
    }
    float t0 = 0.0, t1 = 1.0;
    if (a.w < eps) t0 = (eps - a.w) / (b.w - a.w);
    if (b.w < eps) t1 = (eps - a.w) / (b.w - a.w);
    vec4 ca = mix(a, b, t0);
    vec4 cb = mix(a, b, t1);
    vec2 sa = ca.xy / ca.w * u_viewport * 0.5;
    vec2 sb = cb.xy / cb.w * u_viewport * 0.5;
    vec2 dir = sb - sa;
    float n = length(dir);
    dir = n > 1e-6 ? dir / n : vec2(1.0, 0.0);
    vec2 normal = vec2(-dir.y, dir.x);
    float half_w = 0.5 * width + 0.5;
    vec4 p = in_corner.x < 0.5 ? ca : cb;
    vec2 offset = normal * in_corner.y * half_w + dir * (in_corner.x < 0.5 ? -half_w : half_w);
    p.xy += offset / (u_viewport * 0.5) * p.w;
    gl_Position = p;
    v_along = mix(t0, t1, in_corner.x) * len;
    v_across = in_corner.y * half_w;
}

#elif defined FRAGMENT_SHADER

in vec4 v_color;
in float v_along;
in float v_across;
flat in float v_dash;
flat in float v_half;
out vec4 f_color;

void main() {
    if (v_dash > 0.0 && fract(v_along / v_dash) > 0.55) discard;
    float coverage = clamp(v_half + 0.5 - abs(v_across), 0.0, 1.0);
    f_color = vec4(v_color.rgb, v_color.a * coverage);
}

#endif
