#version 450

// The ghost: see-through where it faces the eye and brighter, more opaque toward its
// silhouette (a rim), so it reads as an outline of the tracked hand rather than as a
// second solid hand, even where it overlaps the physical one.

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec3 in_to_eye;
layout(location = 2) flat in vec4 in_color;

layout(location = 0) out vec4 out_color;  // premultiplied, as shade.frag

const float kCentreOpacity = 0.25;  // of the configured ghost alpha, where it faces the eye
const float kRimWhite = 0.5;        // how far the rim's colour goes toward white

void main() {
    float facing = max(dot(normalize(in_normal), normalize(in_to_eye)), 0.0);
    float rim = 1.0 - facing;
    float alpha = in_color.a * mix(kCentreOpacity, 1.0, rim);
    vec3 color = mix(in_color.rgb, vec3(1.0), kRimWhite * rim);
    out_color = vec4(color * alpha, alpha);
}
