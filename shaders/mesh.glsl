#version 330 core
// Lit flat-shaded meshes: boxes (the cookbook's cube, walls) and planes. Double-sided.

#if defined VERTEX_SHADER

in vec3 in_position;
in vec3 in_normal;
uniform mat4 u_view_proj;
uniform mat4 u_model;     // columns: the box's scaled axes, then its centre
out vec3 v_normal;

void main() {
    v_normal = mat3(u_model) * in_normal;
    gl_Position = u_view_proj * (u_model * vec4(in_position, 1.0));
}

#elif defined FRAGMENT_SHADER

in vec3 v_normal;
uniform vec4 u_color;
uniform vec3 u_light;     // unit vector toward the light, world space
out vec4 f_color;

void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float diffuse = abs(dot(n, u_light));
    float hemi = 0.5 + 0.5 * n.y;
    vec3 rgb = u_color.rgb * (mix(0.25, 0.45, hemi) + 0.7 * diffuse);
    f_color = vec4(rgb, u_color.a);
}

#endif
