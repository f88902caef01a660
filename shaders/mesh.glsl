#version 330 core
// Lit flat-shaded meshes: boxes (the cookbook's cube, walls) and planes. Double-sided.
// The INSTANCED variant draws many boxes in one call, each instance's model and color read
// from its row (``geometry.box_instances``) instead of the uniforms.

#if defined VERTEX_SHADER

in vec3 in_position;
in vec3 in_normal;
#include <frame>
out vec3 v_normal;
#if defined INSTANCED
in vec4 in_model_x;       // the model's rows: scaled axes' x components, then the centre's x
in vec4 in_model_y;
in vec4 in_model_z;
in vec4 in_color;
flat out vec4 v_color;
#else
uniform mat4 u_model;     // columns: the box's scaled axes, then its centre
#endif

void main() {
#if defined INSTANCED
    mat4 model = transpose(mat4(in_model_x, in_model_y, in_model_z, vec4(0.0, 0.0, 0.0, 1.0)));
    v_color = in_color;
#else
    mat4 model = u_model;
#endif
    v_normal = mat3(model) * in_normal;
    gl_Position = u_view_proj * (model * vec4(in_position, 1.0));
}

#elif defined FRAGMENT_SHADER

in vec3 v_normal;
#if defined INSTANCED
flat in vec4 v_color;
#else
uniform vec4 u_color;
#endif
#include <frame>
out vec4 f_color;

void main() {
#if defined INSTANCED
    vec4 color = v_color;
#else
    vec4 color = u_color;
#endif
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    float diffuse = abs(dot(n, u_light_world));
    float hemi = 0.5 + 0.5 * n.y;
    vec3 rgb = color.rgb * (mix(0.25, 0.45, hemi) + 0.7 * diffuse);
    f_color = vec4(rgb, color.a);
}

#endif
