#version 450

// A light from above and slightly in front, plus ambient: enough to tell the faces of a
// box apart. The target is sRGB, so the linear result is encoded on write.

layout(location = 0) in vec3 in_normal;

layout(push_constant) uniform Shape {
    mat4 model_view_projection;
    vec4 model[3];
    vec4 color;
} shape;

layout(location = 0) out vec4 out_color;

const vec3 kToLight = vec3(0.3, 0.9, 0.4);
const float kAmbient = 0.35;

void main() {
    float diffuse = max(dot(normalize(in_normal), normalize(kToLight)), 0.0);
    out_color = vec4(shape.color.rgb * (kAmbient + (1.0 - kAmbient) * diffuse), shape.color.a);
}
