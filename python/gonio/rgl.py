"""The RGL ".bsdf" tensor file (Dupuy & Jakob 2018, "An Adaptive Parameterization for Efficient Material
Acquisition and Rendering"), as Mitsuba 3's `measured` plugin reads it (scalar_rgb; mitsuba3 src/bsdfs/measured.cpp)
and pbrt-v4's MeasuredBxDF (which reads spectral files only).

The file holds, per incident elevation theta_i (phi_i = 0: isotropic), the BRDF "reduced" by a microfacet
distribution D: rgb = f cos(theta_o) 4 sigma(wi) / D(m) on a grid of the sample domain of the visible-NDF warp (32
x 32 in the RGL database, 256 x 256 here), and Mitsuba evaluates f cos(theta_o) = rgb(warp^-1(m)) D(m) / (4
sigma(wi)) (jacobian = 1). D is the dominant eigenfunction of the retroreflection kernel (the paper's section 4:
f(w, w) cos = D(w) / (4 sigma(w)) F for a microfacet BRDF, so D = f(w, w) cos 4 sigma(w) up to a scale, found by
power iteration); D decides where the grid's nodes lie. The warp is Mitsuba's own (MarginalContinuous2D2), so the
nodes written here are exactly those the plugin inverts to; exporting therefore needs the `mitsuba` package.
The bins' f enters shaped by D inside each bin (f_bin D(m) / <D>_bin, export_rgl), so that the plugin's f averages
over each bin to the bin's own value.
"""
import struct

import numpy as np

LUMA = np.array([0.2126, 0.7152, 0.0722])
N_NDF = 128       # ndf and sigma: nodes in u = sqrt(2 theta / pi)
N_VNDF = 128      # vndf: u x v per slice
N_SAMPLE = 256    # rgb and luminance: the sample domain per slice (the RGL database has 32). On plastic (1 x 2 degree
                  # bins, 4e6 paths, every 2 degrees) the plugin's f averaged over the bins lit above 5% of the peak
                  # departs from them by a median 2.1%, 1.0%, 1.8% at 10, 40, 70 degrees at 256 (the bins' own
                  # noise 7.4%, 5.6%, 2.0%) against 3.6%, 2.1%, 4.0% at 128; the file is 4x larger (85 MB for 45
                  # angles, half of it gonio's se field)
BIN_SUBSAMPLES = 6  # n x n points per bin for the mean of D over a bin
DTYPES = {np.dtype(np.uint8): 1, np.dtype(np.float32): 10}


def write_tensor_file(path, fields):
    """fields: name -> uint8 / float32 array (or str, written as uint8). Layout: "tensor_file\\0", version 1.0, a
    uint32 field count, then per field: uint16 name length, name, uint16 ndim, uint8 dtype, uint64 offset, uint64
    shape[ndim]; then the C-order data blocks at 8-byte aligned offsets, all little-endian."""
    arrs = {}
    for k, v in fields.items():
        a = np.frombuffer(v.encode(), np.uint8) if isinstance(v, str) else np.ascontiguousarray(v)
        if a.dtype not in DTYPES:
            raise ValueError(f"tensor field {k}: dtype {a.dtype} (uint8 or float32 only)")
        arrs[k] = a
    header = 12 + 2 + 4 + sum(13 + len(k.encode()) + 8 * a.ndim for k, a in arrs.items())
    pos, offsets = (header + 7) // 8 * 8, {}
    for k, a in arrs.items():
        offsets[k] = pos
        pos = (pos + a.nbytes + 7) // 8 * 8
    with open(path, "wb") as fh:
        fh.write(b"tensor_file\0" + struct.pack("<BBI", 1, 0, len(arrs)))
        for k, a in arrs.items():
            name = k.encode()
            fh.write(struct.pack("<H", len(name)) + name + struct.pack("<HBQ", a.ndim, DTYPES[a.dtype], offsets[k]))
            fh.write(struct.pack(f"<{a.ndim}Q", *a.shape))
        for k, a in arrs.items():
            fh.seek(offsets[k])
            fh.write(a.astype(a.dtype.newbyteorder("<"), copy=False).tobytes())


def read_tensor_file(path):
    """name -> array, the inverse of write_tensor_file (and the reader of any RGL file)."""
    codes = {v: k for k, v in DTYPES.items()}
    with open(path, "rb") as fh:
        data = fh.read()
    if data[:12] != b"tensor_file\0" or data[12:14] != b"\x01\x00":
        raise ValueError(f"{path}: not a tensor file of version 1.0")
    (n,) = struct.unpack_from("<I", data, 14)
    pos, out = 18, {}
    for _ in range(n):
        (ln,) = struct.unpack_from("<H", data, pos)
        name = data[pos + 2:pos + 2 + ln].decode()
        pos += 2 + ln
        ndim, dtype, offset = struct.unpack_from("<HBQ", data, pos)
        pos += 11
        shape = struct.unpack_from(f"<{ndim}Q", data, pos)
        pos += 8 * ndim
        dt = codes[dtype].newbyteorder("<")
        count = int(np.prod(shape)) if ndim else 1
        out[name] = np.frombuffer(data, dt, count, offset).reshape(shape)
    return out


def u_to_theta(u):
    return np.asarray(u) ** 2 * (np.pi / 2)


def theta_to_u(theta):
    return np.sqrt(np.asarray(theta) * (2 / np.pi))


def azimuthal_overlap(ta, tb):
    """int_0^2pi max(0, cos ta cos tb + sin ta sin tb cos phi) dphi."""
    a = np.cos(ta) * np.cos(tb)
    b = np.sin(ta) * np.sin(tb)
    with np.errstate(invalid="ignore", divide="ignore"):
        phi0 = np.arccos(np.clip(-a / np.where(b > 0, b, 1), -1, 1))
    mid = 2 * (a * phi0 + b * np.sin(phi0))
    return np.where(a >= b, 2 * np.pi * a, np.where(a <= -b, 0.0, mid))


def ndf_and_sigma(retro_cos, iterations=8):
    """D and sigma on the u grid from the retroreflection Y(f(w, w)) cos(theta) at its nodes (power iteration on
    D <- r sigma[D]), normalised so that int D cos = 1, floored at 1e-4 of its peak."""
    u = np.linspace(0, 1, N_NDF)
    t = u_to_theta(u)
    du = np.full(N_NDF, 1.0 / (N_NDF - 1))
    du[0] = du[-1] = 0.5 / (N_NDF - 1)
    w = np.pi * u * np.sin(t) * du                      # d(solid angle) / dphi: sin theta dtheta = pi u sin du
    A = azimuthal_overlap(t[:, None], t[None, :])       # (N, N)
    r = np.maximum(retro_cos, 1e-12 * max(retro_cos.max(), 1e-30))
    D = np.ones(N_NDF)
    for _ in range(iterations):
        D = r * (A @ (w * D))
        D /= D.max()
    D /= 2 * np.pi * np.sum(w * D * np.cos(t))           # int D cos dm = 1
    D = np.maximum(D, 1e-4 * D.max())
    sigma = A @ (w * D)
    return D, sigma


def lerp_grid(values, u):
    """Mitsuba's bilinear interpolant of a table on nodes k / (n - 1), along u."""
    n = values.shape[-1]
    x = np.clip(np.asarray(u) * (n - 1), 0, n - 1)
    i = np.minimum(x.astype(int), n - 2)
    a = x - i
    return (1 - a) * values[i] + a * values[i + 1]


def export_rgl(run, path, source="reference", n_sample=N_SAMPLE):
    """Write a run's reflection table (gonio.table.IsotropicTable) as an RGL .bsdf file for Mitsuba 3's measured
    plugin (scalar_rgb). Needs incident angles from 0 to at least 80 degrees at most 5 degrees apart, and the
    `mitsuba` package (its warp places the nodes)."""
    import mitsuba as mi
    if not mi.variant():
        mi.set_variant("scalar_rgb")
    from .table import IsotropicTable
    table = IsotropicTable(run, source)
    table.check_dense(5, 80, "an RGL export")

    # D and sigma from the retroreflection, at the ndf grid's nodes
    t = u_to_theta(np.linspace(0, 1, N_NDF))
    w = np.stack([np.sin(t), np.zeros_like(t), np.cos(t)], axis=-1)
    retro = np.nan_to_num(table.f(w, w)) @ LUMA   # f(w, w); beyond the last slice: 0
    D, sigma = ndf_and_sigma(retro * np.cos(t))

    theta_i = np.radians(table.theta_i).astype(np.float32)
    n_t = theta_i.size
    # the visible NDF per slice, a density over (u, v) in [0, 1]^2: 2 pi^2 u sin(theta_m) <wi, m> D / sigma(wi)
    u = np.linspace(0, 1, N_VNDF)
    v = np.linspace(0, 1, N_VNDF)
    tm, pm = u_to_theta(u)[None, :], (2 * v[:, None] - 1) * np.pi
    m = np.stack(np.broadcast_arrays(np.sin(tm) * np.cos(pm), np.sin(tm) * np.sin(pm), np.cos(tm)), axis=-1)
    Dm = lerp_grid(D, u)[None, :]
    vndf = np.zeros((1, n_t, N_VNDF, N_VNDF), np.float32)
    for k, ti in enumerate(theta_i):
        wi = np.array([np.sin(ti), 0.0, np.cos(ti)])
        s_wi = lerp_grid(sigma, theta_to_u(ti))
        vndf[0, k] = 2 * np.pi ** 2 * u[None, :] * np.sin(tm) * np.maximum(m @ wi, 0) * Dm / s_wi
    vndf = np.maximum(vndf, 1e-6 * vndf.max(axis=(2, 3), keepdims=True))
    phi_i = np.array([0.0], np.float32)
    warp = mi.MarginalContinuous2D2(vndf, [phi_i.tolist(), theta_i.tolist()], normalize=True)

    # rgb at the images of the sample grid under the warp: f~ cos(theta_o) 4 sigma(wi) / D(m), where f~ is the bins'
    # f shaped inside each bin by D: f~(wo) = f_bin D(m) / <D>_bin, <D>_bin the cos-weighted mean of D(m) over the
    # bin. Mitsuba returns rgb(warp^-1(m)) D(m) / (4 sigma), so f~ with D cancels to f_bin cos / <D>_bin at the nodes,
    # and the plugin's f, averaged over a bin as the bins average f, gives the bin back (a piecewise-constant f
    # would come back times D's variation inside the bin: 9.5% median departure at 70 degrees on plastic).
    bins = run.bins
    sub = bins.subsample(BIN_SUBSAMPLES)                                   # (n_theta, n_phi, s^2, 3)
    se_table = IsotropicTable(run, source, "se")
    rgb = np.zeros((1, n_t, 3, n_sample, n_sample), np.float32)
    se_rgb = np.zeros_like(rgb)
    grid = np.linspace(0, 1, n_sample)
    for k, ti in enumerate(theta_i):
        um = np.array([[list(warp.sample(mi.Point2f(float(x), float(y)), [0.0, float(ti)])[0]) for x in grid]
                       for y in grid])                                     # (j = y, i = x, 2)
        th, ph = u_to_theta(um[..., 0]), (2 * um[..., 1] - 1) * np.pi
        mm = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], axis=-1)
        wi = np.array([np.sin(ti), 0.0, np.cos(ti)])
        wo = 2 * (mm @ wi)[..., None] * mm - wi
        cos_o = np.maximum(wo[..., 2], 0.0)
        m_sub = sub + wi
        m_sub /= np.linalg.norm(m_sub, axis=-1, keepdims=True)
        d_bin = lerp_grid(D, theta_to_u(np.arccos(np.clip(m_sub[..., 2], -1, 1)))).mean(axis=-1)   # <D>_bin
        row, col = bins.index(wo)
        scale = cos_o * 4 * lerp_grid(sigma, theta_to_u(ti)) / d_bin[row, col]
        rgb[0, k] = np.moveaxis(np.maximum(np.nan_to_num(table.slices[k][row, col]), 0) * scale[..., None], -1, 0)
        se_rgb[0, k] = np.moveaxis(np.nan_to_num(se_table.slices[k][row, col]) * scale[..., None], -1, 0)
    lum = np.einsum("ptcji,c->ptji", rgb, LUMA).astype(np.float32)
    lum = np.maximum(lum, 1e-4 * lum.max(axis=(2, 3), keepdims=True) + 1e-12)
    write_tensor_file(path, {
        "theta_i": theta_i, "phi_i": phi_i,
        "ndf": np.stack([D, D]).astype(np.float32), "sigma": np.stack([sigma, sigma]).astype(np.float32),
        "vndf": vndf, "luminance": lum, "rgb": rgb,
        "description": f"gonio {source} of {run.summary.get('stack', '?')}: {run.summary.get('paths_per_angle', '?')} "
                       f"paths per incident angle, seed {run.summary.get('seed', '?')}",
        "jacobian": np.array([1], np.uint8),
        # gonio's own: the standard errors of rgb at the same nodes, in rgb's units (Mitsuba ignores the field)
        "gonio_se_rgb": se_rgb,
    })
    return path
