#version 450

// Places the shared meshes (see hand_geometry.h) on one instance: a joint, bone or capsule
// on the capsule mesh, a box on the box mesh.

layout(location = 0) in vec4 in_local;   // capsule: unit direction, w which end; box: corner
layout(location = 1) in vec4 in_normal;  // in the same frame
layout(location = 2) in vec4 in_start;   // capsule: centre xyz, radius w; box: centre
layout(location = 3) in vec4 in_end;     // capsule: centre xyz, radius w; box: half extents
layout(location = 4) in vec4 in_orientation;  // box: unit quaternion xyzw
layout(location = 5) in vec4 in_color;        // linear rgb, alpha

layout(push_constant) uniform View {
    mat4 view_projection;
    vec4 eye_position;
} view;

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec3 out_to_eye;
layout(location = 2) flat out vec4 out_color;

// The ghost is drawn twice (depth, then colour with an EQUAL test): both passes must
// compute bit-identical depths.
invariant gl_Position;

const float kBoxVertex = 2.0;  // hand_geometry.h

vec3 rotate(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

void main() {
    vec3 normal;
    vec3 position;
    if (in_local.w > kBoxVertex - 0.5) {
        vec4 q = normalize(in_orientation);
        normal = rotate(q, in_normal.xyz);
        position = in_start.xyz + rotate(q, in_local.xyz * in_end.xyz);
    } else {
        vec3 axis = in_end.xyz - in_start.xyz;
        float len = length(axis);
        vec3 w = len > 1e-7 ? axis / len : vec3(0.0, 0.0, 1.0);
        // Right-handed frame (u x v = w) so the mesh keeps its outward winding.
        vec3 helper = abs(w.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
        vec3 u = normalize(cross(helper, w));
        vec3 v = cross(w, u);
        normal = in_local.x * u + in_local.y * v + in_local.z * w;
        vec4 end = in_local.w < 0.5 ? in_start : in_end;
        position = end.xyz + end.w * normal;
    }

    out_normal = normal;
    out_to_eye = view.eye_position.xyz - position;
    out_color = in_color;
    gl_Position = view.view_projection * vec4(position, 1.0);
}
