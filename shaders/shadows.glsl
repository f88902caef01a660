#version 330 core
// Blob shadows: one soft dark disc on the ground under each sphere, fading with height.
// Reads the same per-sphere buffer as spheres.glsl.

#if defined VERTEX_SHADER

in vec2 in_corner;        // quad corner in [-1, 1]^2
in vec4 in_sphere;        // xyz centre [m], w radius [m]

uniform mat4 u_view_proj;
uniform float u_ground;   // ground height [m]
uniform float u_strength; // darkness of a shadow right under a sphere resting on the ground

out vec2 v_uv;
out float v_alpha;

void main() {
    float r = in_sphere.w;
    float h = in_sphere.y - r - u_ground;          // gap between sphere and ground [m]
    // Higher spheres cast wider, fainter shadows; none for spheres below the ground.
    float fade = clamp(1.0 - h / (5.0 * r + 1.5), 0.0, 1.0);
    if (r <= 0.0 || in_sphere.y < u_ground || fade <= 0.0) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_uv = vec2(0.0);
        v_alpha = 0.0;
        return;
    }
    float s = r * (1.3 + 0.7 * (1.0 - fade));
    vec3 p = vec3(in_sphere.x + s * in_corner.x, u_ground, in_sphere.z + s * in_corner.y);
    gl_Position = u_view_proj * vec4(p, 1.0);
    gl_Position.z -= 2e-4 * gl_Position.w;            // just above the ground, no z-fighting
    v_uv = in_corner;
    v_alpha = u_strength * fade;
}

#elif defined FRAGMENT_SHADER

in vec2 v_uv;
in float v_alpha;
out vec4 f_color;

void main() {
    float q = dot(v_uv, v_uv);
    if (q >= 1.0) discard;
    float a = v_alpha * (1.0 - q) * (1.0 - 0.5 * q);
    f_color = vec4(0.0, 0.0, 0.0, a);
}

#endif
