#!/usr/bin/env python3
"""state_tamper.py IN OUT EDIT [--keep-checksum]: a copy of a state.gonio (version 9, host/io/state.cpp) with one
field changed, its CRC-32C recomputed (so that the field's own check is what refuses it) unless --keep-checksum
(then the stored checksum no longer matches). For tests/untrusted_inputs_test.sh. EDIT is one of:
  flip:OFFSET         flip the lowest bit of the byte at OFFSET from the end of the header (a damaged file)
  grid:T,P            the bin grid n_theta x n_phi (histograms resized to match, so the size check passes)
  dtheta:X            the bin width in theta
  paths:N             the run's paths (options)
  rse_quantile:X      the --rse-quantile recorded
  phi_i:X             the incident azimuth recorded
  energy:X            the first angle's first energy-book entry, X in units of the light (may be negative)
  theta:X             the first angle's incident angle
  duplicate           the first angle written twice
  trailing            one byte after the last angle"""
import struct
import sys


def crc32c(data):
    table = []
    for i in range(256):
        c = i
        for _ in range(8):
            c = (0x82F63B78 ^ (c >> 1)) if c & 1 else c >> 1
        table.append(c)
    crc = 0xFFFFFFFF
    for b in data:
        crc = table[(crc ^ b) & 0xFF] ^ (crc >> 8)
    return crc ^ 0xFFFFFFFF


HEADER = "<IddIBBBBQdddBBBBBBdIII"   # seed ... the incident azimuth, n_classes, after the magic and the stack
ANGLE = "<dQdd12qQ"   # an angle's theta, paths, seconds, device seconds, energy book, histogram size


class State:

    def __init__(self, data):
        assert data[:8] == b"GONIOST9", "not a version-9 state file"
        n = struct.unpack_from("<Q", data, 8)[0]
        self.prefix = data[:16 + n]   # magic and the stored stack
        self.fields = list(struct.unpack_from(HEADER, data, 16 + n))
        o = 16 + n + struct.calcsize(HEADER)
        count = struct.unpack_from("<Q", data, o)[0]
        o += 8
        self.angles = []
        for _ in range(count):
            head = list(struct.unpack_from(ANGLE, data, o))
            o += struct.calcsize(ANGLE)
            m = head[-1]
            self.angles.append((head, data[o:o + 8 * m]))
            o += 8 * m
        assert o + 4 == len(data), "unexpected layout"

    def bytes(self):
        out = bytearray(self.prefix) + struct.pack(HEADER, *self.fields) + struct.pack("<Q", len(self.angles))
        for head, raw in self.angles:
            out += struct.pack(ANGLE, *head) + raw
        return bytes(out)


def main():
    src, dst, edit = sys.argv[1], sys.argv[2], sys.argv[3]
    keep = "--keep-checksum" in sys.argv[4:]
    data = open(src, "rb").read()
    s = State(data)
    name, _, value = edit.partition(":")
    if name == "flip":
        body = bytearray(data[:-4])
        body[len(s.prefix) + int(value)] ^= 1
        open(dst, "wb").write(bytes(body) + data[-4:])
        return
    if name == "grid":
        t, p = (int(v) for v in value.split(","))
        s.fields[19], s.fields[20] = t, p
        cells = s.fields[21] * t * p * 6 * (len(s.angles[0][1]) // 8 // (s.fields[21] * s.fields[19] * s.fields[20] * 6)
                                            if s.fields[19] * s.fields[20] else 1)
        s.angles = [(h[:-1] + [cells], bytes(8 * cells)) for h, _ in s.angles]
    elif name == "dtheta":
        s.fields[1] = float(value)
    elif name == "paths":
        s.fields[8] = int(value)
    elif name == "rse_quantile":
        s.fields[10] = float(value)
    elif name == "phi_i":
        s.fields[18] = float(value)
    elif name == "energy":
        s.angles[0][0][4] = int(round(float(value) * 2 ** 24))
    elif name == "theta":
        s.angles[0][0][0] = float(value)
    elif name == "duplicate":
        s.angles.insert(0, s.angles[0])
    body = s.bytes() + (b"\0" if name == "trailing" else b"")
    crc = data[-4:] if keep else struct.pack("<I", crc32c(body))
    open(dst, "wb").write(body + crc)


if __name__ == "__main__":
    main()
