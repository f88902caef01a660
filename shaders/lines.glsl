#version 330 core
// Thick lines as instanced screen-space quads (core profile has no wide GL lines):
// width in pixels, optional dashes measured in metres along the segment (the DASHED variant,
// for rows with a dash period > 0; the plain one draws every row solid).

#if defined VERTEX_SHADER

in vec2 in_corner;        // x: 0 at start, 1 at end; y: -1 / +1 across
in vec3 in_start;         // [m]
in vec3 in_end;           // [m]
in vec4 in_color;         // rgba
in vec2 in_style;         // x: width [px], y: dash period [m] (0 = solid)

#include <frame>
uniform float u_caps;     // 1: extend past each end by half a width (joints without gaps);
                          // 0: not (additive trails, where overlaps would double the light)

out vec4 v_color;
out float v_along;        // distance from the start [m]
out float v_across;       // distance from the centre line [px]
flat out float v_dash;
flat out float v_half;    // half width [px]

void main() {
    vec4 a = u_view_proj * vec4(in_start, 1.0);
    vec4 b = u_view_proj * vec4(in_end, 1.0);
    float eps = 1e-3;
    // Clip the segment against the eye plane so endpoints behind the camera do not flip.
    v_color = in_color;
    v_dash = in_style.y;
    v_half = 0.5 * in_style.x;
    if (a.w < eps && b.w < eps) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_along = 0.0;
        v_across = 0.0;
        return;
    }
    float len = distance(in_start, in_end);
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
    float half_w = 0.5 * in_style.x + 0.5;         // half a pixel more for the soft edge
    vec4 p = in_corner.x < 0.5 ? ca : cb;
    // Extend by half a width past each end so joints between segments have no gaps.
    float cap = u_caps * half_w;
    vec2 offset = normal * in_corner.y * half_w + dir * (in_corner.x < 0.5 ? -cap : cap);
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
#if defined DASHED
    // Only this variant can discard: on llvmpipe a shader that may discard while writing depth
    // costs about twice as much per pixel, so solid lines (nearly all) are drawn without it.
    if (fract(v_along / v_dash) > 0.55) discard;
#endif
    // Soft one-pixel edge: coverage falls from 1 to 0 across the last pixel (the quad ends
    // where it reaches 0).
    float coverage = clamp(v_half + 0.5 - abs(v_across), 0.0, 1.0);
    f_color = vec4(v_color.rgb, v_color.a * coverage);
}

#endif
