#version 330 core
// Glowing particles (sparks, fireworks): unlit soft sprites added to what is behind them
// (blend ONE, ONE), so overlapping sparks brighten each other and the order they are drawn in
// does not matter (no sorting). A sprite is a white-hot core the size of the particle, never
// under a few pixels so a far spark still reads, inside a halo of its own color. Reads the
// sphere buffer: rows whose glow flag (in_color.a) is 0 are left to spheres.glsl.

#if defined VERTEX_SHADER

in vec2 in_corner;        // quad corner in [-1, 1]^2
#if defined SPLIT
// SPLIT (the hardware path): the particles' own buffers, positions uploaded every frame, radius
// and color only when they change; with u_palette the color is the default palette's, by index.
in vec3 in_center;        // [m]
in float in_radius;       // [m] (0 hides it)
in vec4 in_rgba;          // rgb in [0, 1] (normalized bytes), a: 1 glows
uniform bool u_palette;
uniform vec3 u_palette_rgb[8];
#else
in vec4 in_sphere;        // xyz centre [m], w radius [m] (0 hides it)
in vec4 in_color;         // rgb in [0, 1], a: 1 to glow
#endif

#include <frame>
uniform float u_min_core; // smallest core radius [px]
uniform float u_halo;     // halo radius / core radius

out vec2 v_offset;        // from the centre [px]
out vec3 v_color;
flat out float v_core;    // core radius [px]
flat out float v_reach;   // halo radius [px]

void main() {
#if defined SPLIT
    vec4 in_sphere = vec4(in_center, in_radius);
    vec4 in_color = vec4(u_palette ? u_palette_rgb[gl_InstanceID % 8] : in_rgba.rgb, in_rgba.a);
#endif
    vec4 eye = u_view * vec4(in_sphere.xyz, 1.0);
    vec4 clip = u_proj * eye;
    v_color = in_color.rgb;
    if (in_sphere.w <= 0.0 || in_color.a < 0.5 || clip.w <= 1e-4) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);   // hidden, lit, or behind the eye
        v_offset = vec2(0.0);
        v_core = v_reach = 1.0;
        return;
    }
    float radius_px = in_sphere.w * u_proj[1][1] * 0.5 * u_viewport.y / clip.w;
    v_core = max(radius_px, u_min_core);
    v_reach = v_core * u_halo;
    v_offset = in_corner * v_reach;
    clip.xy += v_offset / (0.5 * u_viewport) * clip.w;
    gl_Position = clip;
}

#elif defined FRAGMENT_SHADER

in vec2 v_offset;
in vec3 v_color;
flat in float v_core;
flat in float v_reach;
uniform float u_halo_gain; // halo brightness at the centre, times the color
out vec4 f_color;

void main() {
    float r = length(v_offset);
    if (r >= v_reach) discard;
    float d = r / v_reach;                      // 0 at the centre, 1 at the halo's edge
    // A tight bloom round the core plus a wide soft glow, reaching exactly 0 at the edge (no
    // visible square).
    float halo = u_halo_gain * (0.6 * exp(-12.0 * d * d) + 0.4 * exp(-3.0 * d * d))
                 * (1.0 - d * d);
    // The core: a disc with a one-pixel soft edge, hotter (whiter) than the color; its
    // whiteness scales with the color, so a spark that fades dims all over.
    float core = clamp(v_core + 0.5 - r, 0.0, 1.0);
    float peak = max(v_color.r, max(v_color.g, v_color.b));
    vec3 hot = v_color + vec3(0.5 * peak);
    f_color = vec4(v_color * halo + hot * core, 1.0);
}

#endif
