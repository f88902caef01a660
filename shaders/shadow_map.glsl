#version 330 core
// Blob shadows, drawn from above into a small texture covering the ground under the scene:
// one soft disc per sphere (a point sprite, exact in this orthographic view), fading and
// widening with height. Overlaps multiply the light (blend: dst *= 1 - darkness). The ground
// shader then darkens itself with this texture, so a frame costs one cheap pass however many
// shadows overlap on screen.

#if defined VERTEX_SHADER

in vec4 in_sphere;        // xyz centre [m], w radius [m]
in float in_glow;         // 1: a glowing particle, which is a light and casts no shadow

uniform vec3 u_region;    // x0, z0 [m] of the texture's corner, and its side [m]
uniform float u_texels;   // texture side [texels]
uniform float u_ground;   // ground height [m]
uniform float u_strength; // darkness right under a sphere resting on the ground, in [0, 1]

flat out float v_alpha;

void main() {
    float r = in_sphere.w;
    float h = in_sphere.y - r - u_ground;           // gap between sphere and ground [m]
    float fade = clamp(1.0 - h / (5.0 * r + 1.5), 0.0, 1.0);
    float s = r * (1.3 + 0.7 * (1.0 - fade));      // higher: wider and fainter
    v_alpha = u_strength * fade;
    if (r <= 0.0 || in_glow >= 0.5 || in_sphere.y < u_ground || fade <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        gl_PointSize = 1.0;
        return;
    }
    vec2 uv = (in_sphere.xz - u_region.xy) / u_region.z;
    gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
    gl_PointSize = max(2.0 * s / u_region.z * u_texels, 1.0);
}

#elif defined FRAGMENT_SHADER

flat in float v_alpha;
out vec4 f_dark;

void main() {
    vec2 d = gl_PointCoord * 2.0 - 1.0;
    float q = dot(d, d);
    if (q >= 1.0) discard;
    f_dark = vec4(vec3(v_alpha * (1.0 - q) * (1.0 - 0.5 * q)), 1.0);
}

#endif
