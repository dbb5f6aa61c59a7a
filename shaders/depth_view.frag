#version 330 core
// The depth-map debug view (LearnOpenGL's debug quad). An orthographic map stores linear
// depth and is shown as stored, as is a perspective map that stores linear depth (the
// default); one that stores its projection's depth (the chapters') is linearised first, or
// everything but the nearest surfaces would look white. Either is then stretched over the
// casters' depths (shownFrom..shownTo). A cube map (CUBE) is shown as a panorama, a cascade
// array (ARRAY) as its layers side by side. A moment map shows its first moment (the mean
// depth), an EVSM map unwarped back to depth.

in vec2 texCoords;
out vec4 fragColor;

#if CUBE
uniform samplerCube depthMap;  // a point light's distances / far, shown as a panorama
#elif ARRAY
uniform sampler2DArray depthMap;  // cascades, side by side from the nearest
uniform int layers;
#else
uniform sampler2D depthMap;
#endif
uniform int linearize;
uniform float warp;
uniform int warped;
uniform float nearPlane;
uniform float farPlane;
// The greys' range as fractions of near..far: the casters' depths (depth_view.rs), 0..1 for
// a cube map or layers.
uniform float shownFrom;
uniform float shownTo;

// Depth in [0, 1] back to eye distance, then scaled to [0, 1] over [near, far].
float linearDepth(float depth)
{
    float z = depth * 2.0 - 1.0;
    float eye = (2.0 * nearPlane * farPlane) / (farPlane + nearPlane - z * (farPlane - nearPlane));
    return (eye - nearPlane) / (farPlane - nearPlane);
}

void main()
{
#if CUBE
    // Longitude across, latitude down: every direction from the light once.
    float phi = texCoords.x * 6.2831853;
    float theta = (1.0 - texCoords.y) * 3.1415927;
    vec3 dir = vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
    float shown = texture(depthMap, dir).r;
#elif ARRAY
    float x = texCoords.x * float(layers);
    float layer = floor(x);
    float shown = texture(depthMap, vec3(x - layer, texCoords.y, layer)).r;
#else
    float d = texture(depthMap, texCoords).r;
    // An exponential map stores exp(warp w), w = 2 z - 1 when `warped` (EVSM), else z:
    // back to z (warp 0: a plain depth).
    float w = log(max(d, 1e-30)) / max(warp, 1e-30);
    d = warp > 0.0 ? (warped == 1 ? (w + 1.0) * 0.5 : w) : d;
    float shown = linearize == 1 ? linearDepth(d) : d;
#endif
    shown = clamp((shown - shownFrom) / (shownTo - shownFrom), 0.0, 1.0);
    fragColor = vec4(vec3(shown), 1.0);
}
