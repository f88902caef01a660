#version 330 core
// Spheres as instanced impostors: one camera-facing quad per sphere, ray-cast per pixel, with
// the exact depth written so spheres intersect each other and the scene correctly.

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
in vec4 in_color;         // rgb in [0, 1], a: 1 glows (glow.glsl draws it instead)
#endif

#include <frame>

out vec3 v_center;        // sphere centre, eye space
out vec3 v_point;         // this corner, eye space
out vec3 v_color;
flat out float v_radius;

void main() {
#if defined SPLIT
    vec4 in_sphere = vec4(in_center, in_radius);
    vec4 in_color = vec4(u_palette ? u_palette_rgb[gl_InstanceID % 8] : in_rgba.rgb, in_rgba.a);
#endif
    vec3 c = (u_view * vec4(in_sphere.xyz, 1.0)).xyz;
    float r = in_sphere.w;
    float d = length(c);
    v_center = c;
    v_radius = r;
    v_color = in_color.rgb;
    if (r <= 0.0 || d <= r * 1.001 || in_color.a >= 0.5) {   // hidden, eye inside, or glows
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        v_point = c;
        return;
    }
    // The quad faces the eye through the centre and is just wide enough to cover the sphere's
    // silhouette cone (half-width r·d/sqrt(d²-r²)), so perspective never clips the disc.
    vec3 dir = c / d;
    vec3 side = normalize(cross(dir, abs(dir.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 up = cross(side, dir);
#if defined SPLIT
    // The hardware path puts the quad in the plane touching the sphere's nearest point, not
    // through its centre (the cone is narrower there by (d - r) / d): every ray's hit lies
    // behind it, so the fragment shader can promise depth_greater and the GPU rejects hidden
    // fragments before shading them (with gl_FragDepth written and no promise it shades every
    // one: a million spheres at 1080p was 45 ms a frame on an H100).
    float half_width = 1.02 * r * (d - r) / sqrt(d * d - r * r);   // 2%: no edge cut off
    vec3 p = c - r * dir + half_width * (in_corner.x * side + in_corner.y * up);
#else
    float half_width = r * d / sqrt(d * d - r * r);
    vec3 p = c + half_width * (in_corner.x * side + in_corner.y * up);
#endif
    v_point = p;
    gl_Position = u_proj * vec4(p, 1.0);
}

#elif defined FRAGMENT_SHADER

#if defined SPLIT && defined GL_ARB_conservative_depth   // (a driver without it: no promise)
#extension GL_ARB_conservative_depth : enable
layout(depth_greater) out float gl_FragDepth;
#endif

in vec3 v_center;
in vec3 v_point;
in vec3 v_color;
flat in float v_radius;

#include <frame>

out vec4 f_color;

void main() {
    // Ray from the eye (origin of eye space) through this pixel against the sphere.
    vec3 ray = normalize(v_point);
    float b = dot(ray, v_center);
    float disc = b * b - dot(v_center, v_center) + v_radius * v_radius;
    if (disc < 0.0) discard;
    vec3 hit = ray * (b - sqrt(disc));
    vec3 n = (hit - v_center) / v_radius;

    // Only z and w of the projected hit are needed for its depth.
    float clip_z = u_proj[2][2] * hit.z + u_proj[3][2];
    float clip_w = u_proj[2][3] * hit.z + u_proj[3][3];
    gl_FragDepth = 0.5 * clip_z / clip_w + 0.5;

    // Blinn-Phong with a hemispherical ambient term (sky above, ground bounce below).
    float diffuse = max(dot(n, u_light_eye), 0.0);
    float s = max(dot(n, normalize(u_light_eye - ray)), 0.0);
    s *= s; s *= s; s *= s; s *= s; s *= s;    // s^32 without pow(): cheaper on llvmpipe
    float spec = s;
    float hemi = 0.5 + 0.5 * dot(n, u_sky);
    vec3 ambient = v_color * mix(0.18, 0.42, hemi);
    vec3 rgb = ambient + v_color * 0.75 * diffuse + vec3(0.28) * spec;
    f_color = vec4(rgb, 1.0);
}

#endif
