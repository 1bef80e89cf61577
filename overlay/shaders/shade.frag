#version 450

// Head-light shading: full colour where the surface faces the eye, darker toward the
// silhouette, so joints read as round without any light set up in the scene.

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec3 in_to_eye;
layout(location = 2) flat in vec4 in_color;

// Premultiplied alpha: what OpenXR composition layers expect unless flagged otherwise,
// and what an MSAA resolve averages correctly.
layout(location = 0) out vec4 out_color;

const float kAmbient = 0.45;

void main() {
    float facing = max(dot(normalize(in_normal), normalize(in_to_eye)), 0.0);
    vec3 lit = in_color.rgb * mix(kAmbient, 1.0, facing);
    out_color = vec4(lit * in_color.a, in_color.a);
}
