"""Independent evaluation of docs/tonemap.md, for tests/tonemap.rs.

Reads the beauty (or a colour layer) of an EXR with OpenImageIO, applies exposure, one
operator and the sRGB encoding exactly as docs/tonemap.md writes them (numpy, float64), quantises
to 8 bits, and compares with a PNG that whitted wrote. Prints one line:
    max=<max abs difference in LSB> count=<values that differ>
usage: python tonemap_reference.py IN.exr OUT.png OPERATOR EXPOSURE [LAYER]
"""
import sys

import numpy as np
import OpenImageIO as oiio


def read_rgb(path, layer):
    buf = oiio.ImageBuf(path)
    names = list(buf.spec().channelnames)
    prefix = "" if layer in ("", "beauty") else layer + "."
    pixels = buf.get_pixels(oiio.FLOAT)
    return np.stack([pixels[:, :, names.index(prefix + c)] for c in "RGB"], axis=-1).astype(np.float64)


def srgb(t):
    return np.where(t <= 0.0031308, 12.92 * t, 1.055 * np.power(np.maximum(t, 0.0), 1 / 2.4) - 0.055)


def rows(r):
    return np.array(r, dtype=np.float64)


def agx(v):
    m709_2020 = rows([[0.6274, 0.3293, 0.0433], [0.0691, 0.9195, 0.0113], [0.0164, 0.0880, 0.8956]])
    inset = rows([[0.856627153315983, 0.0951212405381588, 0.0482516061458583],
                  [0.137318972929847, 0.761241990602591, 0.101439036467562],
                  [0.11189821299995, 0.0767994186031903, 0.811302368396859]])
    outset = rows([[1.1271005818144368, -0.1106066430966032, -0.0164939387178346],
                   [-0.1413297634984383, 1.157823702216272, -0.0164939387178343],
                   [-0.1413297634984383, -0.1106066430966029, 1.2519364065950405]])
    m2020_709 = rows([[1.6605, -0.5876, -0.0728], [-0.1246, 1.1329, -0.0083], [-0.0182, -0.1006, 1.1187]])
    c = v @ m709_2020.T
    c = c @ inset.T
    c = (np.log2(np.maximum(c, 1e-10)) - (-12.47393)) / (4.026069 - (-12.47393))
    x = np.clip(c, 0.0, 1.0)
    c = 15.5 * x**6 - 40.14 * x**5 + 31.96 * x**4 - 6.868 * x**3 + 0.4298 * x**2 + 0.1191 * x - 0.00232
    c = c @ outset.T
    c = np.power(np.maximum(c, 0.0), 2.2)
    return np.clip(c @ m2020_709.T, 0.0, 1.0)


def neutral(v):
    x = v.min(axis=-1, keepdims=True)
    offset = np.where(x < 0.08, x - 6.25 * x * x, 0.04)
    c = v - offset
    peak = c.max(axis=-1, keepdims=True)
    d = 1.0 - 0.76
    new_peak = 1.0 - d * d / (peak + d - 0.76)
    g = 1.0 - 1.0 / (0.15 * (peak - new_peak) + 1.0)
    compressed = c * (new_peak / peak) * (1.0 - g) + new_peak * g
    return np.where(peak < 0.76, c, compressed)


OPERATORS = {
    "clamp": lambda v: np.clip(v, 0.0, 1.0),
    "reinhard": lambda v: np.maximum(v, 0.0) / (1.0 + np.maximum(v, 0.0)),
    "aces": lambda v: np.clip(v * (2.51 * v + 0.03) / (v * (2.43 * v + 0.59) + 0.14), 0.0, 1.0),
    "agx": agx,
    "neutral": neutral,
}


def main():
    exr, png, op, ev = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
    layer = sys.argv[5] if len(sys.argv) > 5 else "beauty"
    v = read_rgb(exr, layer) * 2.0**ev
    expected = np.floor(255.0 * srgb(OPERATORS[op](v)) + 0.5).astype(np.int64)
    actual = oiio.ImageBuf(png).get_pixels(oiio.UINT8)[:, :, :3].astype(np.int64)
    if actual.shape != expected.shape:
        print(f"shape {actual.shape} vs {expected.shape}")
        sys.exit(1)
    diff = np.abs(actual - expected)
    print(f"max={int(diff.max())} count={int((diff > 0).sum())}")


if __name__ == "__main__":
    main()
