#version 450

// One shape: its mesh placed by the model transform, seen through the view's projection.

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

// 128 bytes, the least every Vulkan device offers (shape_renderer.h: PushConstants).
layout(push_constant) uniform Shape {
    mat4 model_view_projection;
    vec4 model[3];  // rows of the model's linear part
    vec4 color;     // linear rgb, alpha
} shape;

layout(location = 0) out vec3 out_normal;

void main() {
    mat3 linear = transpose(mat3(shape.model[0].xyz, shape.model[1].xyz, shape.model[2].xyz));
    // Models are rotations with scales that keep these normals' directions (uniform, or
    // along the axis of a cylinder), so normalising is all the inverse transpose would add.
    out_normal = linear * in_normal;
    gl_Position = shape.model_view_projection * vec4(in_position, 1.0);
}
