#!/usr/bin/env python3
"""ww-corrected in NumPy: Bati, Pacanowski & Barla 2019, Equation 4, as gonio's built-in computes it
(shaders/lib/models/builtin/02-ww-corrected.glsl, models/common.glsl), for a dielectric coat over a Lambertian base:

    f = f_r0(l, v) + T01 T10 / eta^2  albedo / pi  exp(-tau (1 / cos l1 + 1 / cos v1))

f_r0 the coat's GGX reflection (exact dielectric Fresnel at the half vector, height-correlated Smith G2), T01 and T10
one minus Fresnel at the geometric normal, (l1, v1) l and v refracted into the coat (Snell), 1 / eta^2 the solid-angle
factor. A model for gonio's Python API, f(l, v, params) -> (N, 3): params are eta (the coat's IOR over the
exterior's), alpha (its roughness), tau (its optical depth, RGB) and albedo (the base's, RGB).

    import gonio
    from numpy_ww_corrected import ww_corrected, params_of
    run = gonio.simulate(stack, theta_i=[0, 45], paths=1e6)
    cmp = gonio.compare(stack, run, models=["ww-corrected", gonio.Model(ww_corrected, "ww-numpy", params_of(stack))])
"""
import numpy as np


def fresnel_dielectric(c, eta):
    """Unpolarised Fresnel reflectance from outside into index eta (fresnel.glsl); 1 under total reflection."""
    c = np.clip(c, 0.0, 1.0)
    s2 = (1 - c * c) / (eta * eta)
    ct = np.sqrt(np.maximum(1 - s2, 0.0))
    rs, rp = (c - eta * ct) / (c + eta * ct), (eta * c - ct) / (eta * c + ct)
    return np.where(s2 >= 1, 1.0, 0.5 * (rs * rs + rp * rp))


def ggx_D(m, alpha):
    a2 = alpha * alpha
    s = (m[:, 0] ** 2 + m[:, 1] ** 2) / a2 + m[:, 2] ** 2
    return np.where(m[:, 2] > 0, 1 / (np.pi * a2 * s * s), 0.0)


def ggx_lambda(w, alpha):
    t2 = (w[:, 0] ** 2 + w[:, 1] ** 2) / (w[:, 2] ** 2)
    return 0.5 * (np.sqrt(1 + alpha * alpha * t2) - 1)


def ww_corrected(l, v, p):
    eta, alpha = p["eta"], p["alpha"]
    tau, albedo = np.asarray(p["tau"], float), np.asarray(p["albedo"], float)
    up = (l[:, 2] > 0) & (v[:, 2] > 0)   # a BRDF: nothing on the transmission side
    lz, vz = np.where(up, l[:, 2], 1.0), np.where(up, v[:, 2], 1.0)
    h = l + v
    h = h / np.linalg.norm(h, axis=1)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        g2 = 1 / (1 + ggx_lambda(l, alpha) + ggx_lambda(v, alpha))
        top = fresnel_dielectric(np.sum(l * h, axis=1), eta) * ggx_D(h, alpha) * g2 / (4 * lz * vz)
    t01, t10 = 1 - fresnel_dielectric(lz, eta), 1 - fresnel_dielectric(vz, eta)
    cos1 = lambda z: np.sqrt(np.maximum(0.0, 1 - (1 - z * z) / (eta * eta)))   # the refracted cosine (Snell)
    a = np.exp(-tau[None, :] * (1 / np.maximum(cos1(lz), 1e-6) + 1 / np.maximum(cos1(vz), 1e-6))[:, None])
    base = (t01 * t10 / (eta * eta))[:, None] * albedo[None, :] / np.pi * a
    return np.where(up[:, None], np.nan_to_num(top)[:, None] + base, 0.0)


def params_of(stack):
    """The parameters of a gonio.Stack of one dielectric coat over a Lambertian base."""
    coat, base = stack.layers
    rgb = lambda x: np.broadcast_to(np.asarray(x, float), (3,))
    return {"eta": float(coat["ior"]) / float(stack.keys.get("exterior_ior", 1.0)), "alpha": float(coat["roughness"]),
            "tau": rgb(coat.get("optical_depth", 0.0)), "albedo": rgb(base["albedo"])}
