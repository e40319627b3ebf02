"""The viewer test's screenshots read without third-party packages (tests/viewer_test.sh): an RGBA8 PNG's pixels, and
the hemisphere panels the viewer logs ("panel NAME at X Y size S") with a pixel at a point of a panel's disc."""
import re
import struct
import zlib


def read_png(path):
    """(width, height, rows): rows[y] the bytes of pixel row y, RGBA8, after the PNG filters are undone."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype == 6, "expected RGBA8"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, bpp, stride = zlib.decompress(idat), 4, w * 4
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return w, h, rows


class Screenshot:
    """A screenshot and the panels its run's log placed: px(x, y) an RGB pixel, disc(panel, u, v) the pixel at
    (u, v) in [-1, 1]^2 of a panel (+v up, as the panel's uv: phi = atan2(v, u))."""

    def __init__(self, png, log_text):
        self.w, self.h, self.rows = read_png(png)
        self.panels = {m[0]: tuple(map(float, m[1:]))
                       for m in re.findall(r"panel (\S+) at (\S+) (\S+) size (\S+)", log_text)}

    def px(self, x, y):
        return self.rows[y][4 * x:4 * x + 3]

    def disc(self, name, u, v):
        x0, y0, s = self.panels[name]
        return self.px(int(x0 + (u + 1) / 2 * s), int(y0 + (1 - v) / 2 * s))

    def mean_rgb(self, name, u, v, r=0.04):
        """The mean colour of 9 pixels around (u, v)."""
        ps = [self.disc(name, u + du, v + dv) for du in (-r, 0, r) for dv in (-r, 0, r)]
        return tuple(sum(p[i] for p in ps) / len(ps) for i in range(3))
