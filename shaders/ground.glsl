#version 330 core
// The ground: one large quad with a procedural, anti-aliased grid (1 m lines, bolder every
// 5 m) that fades out with distance. Shadows go on top (shadow_overlay.glsl), so the ground
// and sky can be kept from frame to frame while the camera stays put.

#if defined VERTEX_SHADER

in vec2 in_corner;        // [-1, 1]^2
#include <frame>
uniform vec3 u_center;    // grid centre [m] (its y is the ground height)
uniform float u_extent;   // half size of the quad [m]
out vec3 v_world;

void main() {
    v_world = u_center + vec3(in_corner.x, 0.0, in_corner.y) * u_extent;
    gl_Position = u_view_proj * vec4(v_world, 1.0);
}

#elif defined FRAGMENT_SHADER

in vec3 v_world;
uniform vec3 u_center;
uniform float u_extent;
uniform float u_spacing;  // minor grid spacing [m]
uniform vec3 u_base;
uniform vec3 u_line;
uniform vec3 u_fog;       // color far away (the horizon)
out vec4 f_color;

float grid(vec2 p, vec2 dp, float spacing, float width) {
    vec2 q = p / spacing;
    vec2 w = dp / spacing;
    vec2 g = abs(fract(q - 0.5) - 0.5) / max(w, 1e-6);
    float line = 1.0 - min(min(g.x, g.y) / width, 1.0);
    // Fade lines out where cells shrink below a few pixels (avoids moiré).
    return line * clamp(1.0 - 2.5 * max(w.x, w.y), 0.0, 1.0);
}

void main() {
    vec2 p = v_world.xz;
    vec2 dp = fwidth(p);
    float minor = grid(p, dp, u_spacing, 1.0);
    float major = grid(p, dp, u_spacing * 5.0, 1.6);
    vec3 rgb = mix(u_base, u_line, max(0.55 * minor, major));
    float d = length(v_world.xz - u_center.xz) / u_extent;
    rgb = mix(rgb, u_fog, smoothstep(0.35, 1.0, d));
    f_color = vec4(rgb, 1.0);
}

#endif
