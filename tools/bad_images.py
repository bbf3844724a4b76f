#!/usr/bin/env python3
"""Writes tests/bad_images/: one small hostile image per class of bad input, byte for byte the
same on every run. Each file's exact expected message is in <name>.expected beside it (kept by
hand; `{file}` stands for the path as given, `{any}` for machine-dependent text such as how
much memory is available).

usage: tools/bad_images.py [DIR]      (default tests/bad_images)
"""
import os
import struct
import sys
import zlib


def attribute(name, kind, value):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value


def box(x0, y0, x1, y1):
    return struct.pack("<iiii", x0, y0, x1, y1)


def exr_header(channels, data_window, display_window=None):
    """A single-part scanline OpenEXR header; channels are (name, pixel type: 1 half, 2 float)."""
    chlist = b"".join(
        name.encode() + b"\0" + struct.pack("<iBxxxii", kind, 0, 1, 1) for name, kind in channels
    ) + b"\0"
    header = b"\x76\x2f\x31\x01" + struct.pack("<I", 2)
    header += attribute("channels", "chlist", chlist)
    header += attribute("compression", "compression", b"\0")
    header += attribute("dataWindow", "box2i", box(*data_window))
    header += attribute("displayWindow", "box2i", box(*(display_window or data_window)))
    header += attribute("lineOrder", "lineOrder", b"\0")
    header += attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
    header += attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
    header += attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
    return header + b"\0"


def exr_1x1(channels, display_window=None, origin=(0, 0)):
    """A complete uncompressed 1x1 image whose samples are all 0.5."""
    x, y = origin
    header = exr_header(channels, (x, y, x, y), display_window)
    sizes = {1: 2, 2: 4}
    pixels = b"".join(
        struct.pack("<e", 0.5) if kind == 1 else struct.pack("<f", 0.5) for _, kind in channels
    )
    table_end = len(header) + 8
    block = struct.pack("<ii", y, len(pixels)) + pixels
    assert len(pixels) == sum(sizes[k] for _, k in channels)
    return header + struct.pack("<Q", table_end) + block


def png_chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))


def png(width, height, idat=None, colour=2, depth=8):
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour, 0, 0, 0)
    data = zlib.compress(b"\0\0\0\0") if idat is None else idat
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr) + png_chunk(b"IDAT", data)
            + png_chunk(b"IEND", b""))


def files():
    rgb_float = [("B", 2), ("G", 2), ("R", 2)]
    yield "exr_huge_window.exr", exr_header(rgb_float, (0, 0, 99999, 99999))
    yield "exr_many_half_channels.exr", exr_header(
        [("c%05d" % i, 1) for i in range(5000)], (0, 0, 4095, 4095))
    yield "exr_truncated_header.exr", exr_header(rgb_float, (0, 0, 9, 9))[:60]
    yield "exr_truncated_pixels.exr", exr_1x1(rgb_float)[:-6]
    yield "png_huge.png", png(60000, 60000)
    yield "png_bad_crc.png", png(4, 4)[:-20] + b"\0\0\0\0" + png(4, 4)[-16:]
    yield "png_truncated.png", png(4, 4)[:30]
    yield "not_an_image.txt", b"P6\n2 2\n255\n" + bytes(12)
    yield "empty.exr", b""
    # Valid, but merging it needs the whole 100000 x 100000 display window.
    yield "exr_huge_display_window.exr", exr_1x1(rgb_float, (0, 0, 99999, 99999))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "tests", "bad_images")
    os.makedirs(out, exist_ok=True)
    for name, data in files():
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
