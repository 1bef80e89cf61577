#version 450

// Resolves the multisampled colour into the target: the mean of the samples. Reading an
// sRGB attachment decodes it, so the mean is taken in linear space; the samples hold
// premultiplied colour, so the mean is also the right edge blend.

layout(input_attachment_index = 0, set = 0, binding = 0) uniform subpassInputMS samples;

layout(location = 0) out vec4 out_color;

const int kSamples = 4;  // pipeline.h: kSamples

void main() {
    vec4 sum = vec4(0.0);
    for (int i = 0; i < kSamples; ++i) {
        sum += subpassLoad(samples, i);
    }
    out_color = sum / float(kSamples);
}
