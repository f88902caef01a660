#version 330 core
// Lays the blob-shadow texture (render/shadow_splat.py) on the ground: one quad over the square the
// texture covers, blended dark, just above the ground so it never z-fights the grid.

#if defined VERTEX_SHADER

in vec2 in_corner;            // [-1, 1]^2
#include <frame>
uniform vec3 u_shadow_region; // x0, z0 [m] and side [m]
uniform float u_ground;       // ground height [m]
out vec2 v_uv;

void main() {
    v_uv = 0.5 * in_corner + 0.5;
    vec3 p = vec3(u_shadow_region.x + v_uv.x * u_shadow_region.z, u_ground,
                  u_shadow_region.y + v_uv.y * u_shadow_region.z);
    gl_Position = u_view_proj * vec4(p, 1.0);
    gl_Position.z -= 2e-4 * gl_Position.w;
}

#elif defined FRAGMENT_SHADER

in vec2 v_uv;
uniform sampler2D u_shadow;   // darkness (r channel)
uniform float u_uv_scale;     // the part of the texture in use (1, or 0.5 for crowds)
out vec4 f_color;

void main() {
    // No discard where there is no shadow: alpha 0 blends to the same pixel, and on llvmpipe
    // a discard costs more than the blend it saves.
    f_color = vec4(0.0, 0.0, 0.0, texture(u_shadow, v_uv * u_uv_scale).r);
}

#endif
