#version 330 core
// Blob shadows on the GPU (the hardware path): one soft disc per caster, a quad lying on the
// ground under it, widening and fading with its height as render/shadow_splat.py draws them
// on the CPU for llvmpipe (the same constants and profile). Blended with (ZERO,
// ONE_MINUS_SRC_ALPHA), each disc multiplies what is under it by (1 - a): overlaps combine as
// 1 - (1 - a)(1 - b) in any order, as the splatted map does.

#if defined VERTEX_SHADER

in vec2 in_corner;        // [-1, 1]^2
#if defined SPLIT
in vec3 in_center;        // [m] (the particles' position buffer)
in float in_radius;       // [m] (0: hidden)
in vec4 in_rgba;          // a: 1 glows (a light: no shadow)
#else
in vec4 in_sphere;        // sphere rows: xyz centre, w radius [m]
in vec4 in_color;         // a: 1 glows
#endif

#include <frame>
uniform float u_ground;       // ground height [m]
uniform float u_strength;     // darkness under a resting sphere
uniform float u_fade_reach;   // shadow_splat.FADE_REACH [m]
uniform vec2 u_spread;        // shadow_splat.SPREAD_NEAR, SPREAD_FAR

out vec2 v_uv;                // [-1, 1]^2 across the disc
flat out float v_alpha;

void main() {
#if defined SPLIT
    vec3 c = in_center;
    float r = in_radius;
    float glows = in_rgba.a;
#else
    vec3 c = in_sphere.xyz;
    float r = in_sphere.w;
    float glows = in_color.a;
#endif
    float fade = r > 0.0 ? 1.0 - (c.y - r - u_ground) / (5.0 * r + u_fade_reach) : 0.0;
    v_uv = in_corner;
    if (r <= 0.0 || c.y < u_ground || fade <= 0.0 || glows >= 0.5) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_alpha = 0.0;
        return;
    }
    fade = min(fade, 1.0);
    v_alpha = u_strength * fade;
    float rad = r * (u_spread.x + (u_spread.y - u_spread.x) * (1.0 - fade));
    vec3 p = vec3(c.x + in_corner.x * rad, u_ground, c.z + in_corner.y * rad);
    gl_Position = u_view_proj * vec4(p, 1.0);
    gl_Position.z -= 2e-4 * gl_Position.w;    // just above the ground, as shadow_overlay
}

#elif defined FRAGMENT_SHADER

in vec2 v_uv;
flat in float v_alpha;
out vec4 f_color;

void main() {
    float q = dot(v_uv, v_uv);
    // Alpha 0 outside the disc rather than a discard (cheaper, and the blend leaves it as it
    // was).
    float a = q < 1.0 ? v_alpha * (1.0 - q) * (1.0 - 0.5 * q) : 0.0;
    f_color = vec4(0.0, 0.0, 0.0, a);
}

#endif
