"""CIEDE2000 colour differences between 8-bit sRGB pixels (Sharma, Wu and Dalal, "The
CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
mathematical observations", 2005; D65 white). Plain Python: both VTK's Python and
ParaView's pvbatch import it. A difference below about 1 is invisible side by side; 2 is
what the colour calibration tests allow.
"""
import math


def srgb_to_lab(rgb):
    """(r, g, b) in 0..255, sRGB-encoded, to CIELAB (D65)."""
    def linear(c):
        c /= 255.0
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4

    r, g, b = (linear(float(c)) for c in rgb[:3])
    x = (0.4124564 * r + 0.3575761 * g + 0.1804375 * b) / 0.95047
    y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b
    z = (0.0193339 * r + 0.1191920 * g + 0.9503041 * b) / 1.08883

    def f(t):
        return t ** (1.0 / 3.0) if t > (6.0 / 29.0) ** 3 else t / (3 * (6.0 / 29.0) ** 2) + 4.0 / 29.0

    fx, fy, fz = f(x), f(y), f(z)
    return 116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)


def ciede2000(lab1, lab2):
    """CIEDE2000 difference of two CIELAB colours (kL = kC = kH = 1)."""
    l1, a1, b1 = lab1
    l2, a2, b2 = lab2
    c_mean = (math.hypot(a1, b1) + math.hypot(a2, b2)) / 2.0
    g = 0.5 * (1.0 - math.sqrt(c_mean ** 7 / (c_mean ** 7 + 25.0 ** 7)))
    a1p, a2p = (1.0 + g) * a1, (1.0 + g) * a2
    c1p, c2p = math.hypot(a1p, b1), math.hypot(a2p, b2)
    h1p = math.degrees(math.atan2(b1, a1p)) % 360.0 if c1p > 0 else 0.0
    h2p = math.degrees(math.atan2(b2, a2p)) % 360.0 if c2p > 0 else 0.0

    dl, dc = l2 - l1, c2p - c1p
    dh = 0.0
    if c1p * c2p > 0:
        dh = h2p - h1p
        if dh > 180.0:
            dh -= 360.0
        elif dh < -180.0:
            dh += 360.0
    dhh = 2.0 * math.sqrt(c1p * c2p) * math.sin(math.radians(dh / 2.0))

    l_mean, cp_mean = (l1 + l2) / 2.0, (c1p + c2p) / 2.0
    if c1p * c2p == 0:
        h_mean = h1p + h2p
    elif abs(h1p - h2p) <= 180.0:
        h_mean = (h1p + h2p) / 2.0
    else:
        h_mean = (h1p + h2p + 360.0) / 2.0 if h1p + h2p < 360.0 else (h1p + h2p - 360.0) / 2.0
    t = (1.0 - 0.17 * math.cos(math.radians(h_mean - 30.0))
         + 0.24 * math.cos(math.radians(2.0 * h_mean))
         + 0.32 * math.cos(math.radians(3.0 * h_mean + 6.0))
         - 0.20 * math.cos(math.radians(4.0 * h_mean - 63.0)))
    d_theta = 30.0 * math.exp(-(((h_mean - 275.0) / 25.0) ** 2))
    r_c = 2.0 * math.sqrt(cp_mean ** 7 / (cp_mean ** 7 + 25.0 ** 7))
    s_l = 1.0 + 0.015 * (l_mean - 50.0) ** 2 / math.sqrt(20.0 + (l_mean - 50.0) ** 2)
    s_c = 1.0 + 0.045 * cp_mean
    s_h = 1.0 + 0.015 * cp_mean * t
    r_t = -math.sin(math.radians(2.0 * d_theta)) * r_c
    return math.sqrt((dl / s_l) ** 2 + (dc / s_c) ** 2 + (dhh / s_h) ** 2
                     + r_t * (dc / s_c) * (dhh / s_h))


def pixel_difference(rgb1, rgb2):
    """CIEDE2000 difference of two 8-bit sRGB pixels."""
    return ciede2000(srgb_to_lab(rgb1), srgb_to_lab(rgb2))


def cool_to_warm_and_primaries(samples=9):
    """(name, (r, g, b) in [0, 1]) pairs: ParaView's default colour map, Cool to Warm
    (diverging, Moreland 2009), at `samples` points, then red, green, blue, cyan, magenta,
    yellow and white, and a dark grey."""
    from vtkmodules.vtkRenderingCore import vtkColorTransferFunction

    cool_to_warm = vtkColorTransferFunction()
    cool_to_warm.SetColorSpaceToDiverging()
    cool_to_warm.AddRGBPoint(0.0, 0.231373, 0.298039, 0.752941)
    cool_to_warm.AddRGBPoint(0.5, 0.865003, 0.865003, 0.865003)
    cool_to_warm.AddRGBPoint(1.0, 0.705882, 0.0156863, 0.14902)
    colours = [("Cool to Warm %.3f" % (i / (samples - 1.0)),
                tuple(cool_to_warm.GetColor(i / (samples - 1.0)))) for i in range(samples)]
    colours += [("red", (1, 0, 0)), ("green", (0, 1, 0)), ("blue", (0, 0, 1)),
                ("cyan", (0, 1, 1)), ("magenta", (1, 0, 1)), ("yellow", (1, 1, 0)),
                ("white", (1, 1, 1)), ("dark grey", (0.2, 0.2, 0.2))]
    return colours


def _self_test():
    # Sharma et al.'s Table 1, pairs 1, 7 and 17.
    for lab1, lab2, expected in (((50.0, 2.6772, -79.7751), (50.0, 0.0, -82.7485), 2.0425),
                                 ((50.0, 0.0, 0.0), (50.0, -1.0, 2.0), 2.3669),
                                 ((50.0, 2.5, 0.0), (73.0, 25.0, -18.0), 27.1492)):
        got = ciede2000(lab1, lab2)
        assert abs(got - expected) < 1e-4, (lab1, lab2, got, expected)


_self_test()
