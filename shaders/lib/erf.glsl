// erf.glsl: the error function, its complement and its inverse in single precision, for the Beckmann microsurface
// (beckmann.glsl): its Smith Lambda is written with erfc, its visible normals are sampled by inverting a CDF in erf's
// domain. GLSL has none of the three.
#ifndef GONIO_ERF_GLSL
#define GONIO_ERF_GLSL
#include "compat.glsl"

const float INV_SQRT_PI = 0.564189583547756f;

// erfc(x) for x >= 0, relative error below 1.2e-7 everywhere (Press et al., Numerical Recipes, 2nd ed., Sec. 6.2,
// erfcc: a Chebyshev fit of t exp(-x^2 + P(t)), t = 1 / (1 + x / 2)). Relative, so erfc(x) of large x keeps its
// digits, which the Beckmann Lambda needs. erfc(inf) = 0.
GONIO_INLINE float erfc_nonnegative(float x) {
    float t = 1.0f / (1.0f + 0.5f * x);
    float p = -0.82215223f + t * 0.17087277f;
    p = 1.48851587f + t * p;
    p = -1.13520398f + t * p;
    p = 0.27886807f + t * p;
    p = -0.18628806f + t * p;
    p = 0.09678418f + t * p;
    p = 0.37409196f + t * p;
    p = 1.00002368f + t * p;
    return t * exp(-x * x - 1.26551223f + t * p);
}

// erf(x) for every x.
GONIO_INLINE float erf_any(float x) {
    float c = erfc_nonnegative(abs(x));
    return x < 0.0f ? c - 1.0f : 1.0f - c;
}

// Giles 2011, "Approximating the erfinv function" (GPU Computing Gems, Jade ed., ch. 10), the single-precision
// approximation, relative error below 4e-7: erf^-1(y) from y and w = -log((1 - y)(1 + y)), which the callers compute
// each as its arguments keep it accurate.
GONIO_INLINE float erfinv_giles(float y, float w) {
    float p;
    if (w < 5.0f) {
        w = w - 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = sqrt(w) - 3.0f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * y;
}

// erf^-1(y), y in (-1, 1) (clamped to the floats inside it).
GONIO_INLINE float erfinv_any(float y) {
    y = clamp(y, -0.99999994f, 0.99999994f);
    return erfinv_giles(y, -log((1.0f - y) * (1.0f + y)));
}

// erf^-1(1 - e) from e in (0, 2): erfc^-1(e), accurate where e is small (where 1 - e has lost e's digits), as deep in
// the tail as e's floats go (1e-37). Giles's approximation holds to e = 1e-7 (its w to 16); below, x from the tail's
// asymptote erfc(x) ~ exp(-x^2) / (x sqrt(pi)), then Newton's method on log erfc(x) = log e (3 steps).
GONIO_INLINE float erfcinv_any(float e) {
    e = clamp(e, 1e-37f, 1.99999988f);
    float x = erfinv_giles(1.0f - e, -log(e * (2.0f - e)));
    if (e < 1e-6f) {
        float l = -log(e * 1.7724539f);   // x^2 + log x = l
        x = sqrt(l - 0.5f * log(l));
        for (int it = 0; it < 3; ++it) {
            float c = erfc_nonnegative(x);
            x += (log(c) - log(e)) * c * exp(x * x) * 0.88622693f;   // sqrt(pi) / 2
        }
    }
    return x;
}
#endif
