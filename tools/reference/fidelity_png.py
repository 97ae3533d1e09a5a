"""8-bit PNG reading and writing, box resizing and a 5x7 bitmap font, standard library only.

Used by tools/fidelity for the contact sheets (system python3 has no numpy or imaging library)
and by tools/reference/fidelity_blender.py for its cells (so both sides write the same format).
An image is (width, height, pixels): pixels a bytearray of RGB triples, rows top to bottom.
"""
import struct
import zlib

_SIG = b"\x89PNG\r\n\x1a\n"


def _chunk(tag, data):
    return (struct.pack(">I", len(data)) + tag + data +
            struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def read_png(path):
    """A non-interlaced 8-bit grey, grey+alpha, RGB or RGBA PNG as (w, h, RGB bytearray)
    (alpha dropped: Penumbra's PNGs are opaque)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != _SIG:
        raise ValueError("%s: not a PNG" % path)
    pos, idat, w = 8, [], None
    while pos < len(data):
        n, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if tag == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace or ctype not in (0, 2, 4, 6):
                raise ValueError("%s: only 8-bit non-interlaced grey/RGB(A) PNGs are read" % path)
        elif tag == b"IDAT":
            idat.append(body)
        elif tag == b"IEND":
            break
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    prev = bytearray(stride)
    out = bytearray(w * h * 3)
    for y in range(h):
        ftype = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if ftype == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif ftype == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 255
        elif ftype == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif ftype == 4:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                up_left = prev[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + _paeth(left, prev[i], up_left)) & 255
        prev = line
        o = y * w * 3
        if bpp == 3:
            out[o:o + w * 3] = line
        elif bpp == 4:
            for c in range(3):
                out[o + c:o + w * 3:3] = line[c::4]
        else:  # grey (+ alpha)
            g = line[::bpp]
            for c in range(3):
                out[o + c:o + w * 3:3] = g
    return w, h, out


def write_png(path, w, h, rgb):
    """An 8-bit RGB PNG; each row takes the filter (none, sub or up) with the smallest sum of
    absolute residuals, which keeps rendered images with smooth backgrounds small."""
    stride = w * 3
    parts = []
    prev = bytes(stride)
    for y in range(h):
        line = bytes(rgb[y * stride:(y + 1) * stride])
        sub = line[:3] + bytes(((a - b) & 255) for a, b in zip(line[3:], line))
        up = bytes(((a - b) & 255) for a, b in zip(line, prev))
        best = min(((0, line), (1, sub), (2, up)),
                   key=lambda t: sum(v if v < 128 else 256 - v for v in t[1]))
        parts.append(bytes([best[0]]) + best[1])
        prev = line
    png = (_SIG + _chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
           _chunk(b"IDAT", zlib.compress(b"".join(parts), 9)) + _chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)
    return len(png)


def resize_box(img, cw, ch):
    """Area-average resize (each output pixel averages the source pixels its footprint covers;
    at least one, so enlarging repeats pixels)."""
    w, h, px = img
    out = bytearray(cw * ch * 3)
    xs = [(int(x * w / cw), max(int(x * w / cw) + 1, int((x + 1) * w / cw))) for x in range(cw)]
    for oy in range(ch):
        y0 = int(oy * h / ch)
        y1 = max(y0 + 1, int((oy + 1) * h / ch))
        for ox, (x0, x1) in enumerate(xs):
            s = [0, 0, 0]
            for y in range(y0, y1):
                row = y * w * 3
                for x in range(x0, x1):
                    i = row + 3 * x
                    s[0] += px[i]
                    s[1] += px[i + 1]
                    s[2] += px[i + 2]
            n = (y1 - y0) * (x1 - x0)
            o = (oy * cw + ox) * 3
            out[o:o + 3] = bytes(((s[0] + n // 2) // n, (s[1] + n // 2) // n, (s[2] + n // 2) // n))
    return cw, ch, out


def quantize(img, step):
    """Rounds every channel to the middle of its step (4: 64 levels): PNG's deflate finds
    rendered images' grain far less compressible than the levels it removes are visible."""
    w, h, px = img
    table = bytes(min(255, (v // step) * step + step // 2) for v in range(256))
    return w, h, bytearray(px.translate(table))


def blank(w, h, rgb=(0, 0, 0)):
    return w, h, bytearray(bytes(rgb) * (w * h))


def paste(dst, src, x, y):
    dw, dh, dp = dst
    sw, sh, sp = src
    for r in range(sh):
        if 0 <= y + r < dh:
            n = max(0, min(sw, dw - x))
            o = ((y + r) * dw + x) * 3
            dp[o:o + 3 * n] = sp[r * sw * 3:r * sw * 3 + 3 * n]


# 5x7 glyphs, one int of 5 bits per row (bit 4 = leftmost column): enough for model names
# (drawn upper-case), numbers and the labels.
_FONT = {
    "A": (14, 17, 17, 31, 17, 17, 17), "B": (30, 17, 17, 30, 17, 17, 30),
    "C": (14, 17, 16, 16, 16, 17, 14), "D": (30, 17, 17, 17, 17, 17, 30),
    "E": (31, 16, 16, 30, 16, 16, 31), "F": (31, 16, 16, 30, 16, 16, 16),
    "G": (14, 17, 16, 23, 17, 17, 15), "H": (17, 17, 17, 31, 17, 17, 17),
    "I": (14, 4, 4, 4, 4, 4, 14), "J": (7, 2, 2, 2, 2, 18, 12),
    "K": (17, 18, 20, 24, 20, 18, 17), "L": (16, 16, 16, 16, 16, 16, 31),
    "M": (17, 27, 21, 21, 17, 17, 17), "N": (17, 17, 25, 21, 19, 17, 17),
    "O": (14, 17, 17, 17, 17, 17, 14), "P": (30, 17, 17, 30, 16, 16, 16),
    "Q": (14, 17, 17, 17, 21, 18, 13), "R": (30, 17, 17, 30, 20, 18, 17),
    "S": (15, 16, 16, 14, 1, 1, 30), "T": (31, 4, 4, 4, 4, 4, 4),
    "U": (17, 17, 17, 17, 17, 17, 14), "V": (17, 17, 17, 17, 17, 10, 4),
    "W": (17, 17, 17, 21, 21, 21, 10), "X": (17, 17, 10, 4, 10, 17, 17),
    "Y": (17, 17, 10, 4, 4, 4, 4), "Z": (31, 1, 2, 4, 8, 16, 31),
    "0": (14, 17, 19, 21, 25, 17, 14), "1": (4, 12, 4, 4, 4, 4, 14),
    "2": (14, 17, 1, 2, 4, 8, 31), "3": (31, 2, 4, 2, 1, 17, 14),
    "4": (2, 6, 10, 18, 31, 2, 2), "5": (31, 16, 30, 1, 1, 17, 14),
    "6": (6, 8, 16, 30, 17, 17, 14), "7": (31, 1, 2, 4, 8, 8, 8),
    "8": (14, 17, 17, 14, 17, 17, 14), "9": (14, 17, 17, 15, 1, 2, 12),
    ".": (0, 0, 0, 0, 0, 12, 12), ",": (0, 0, 0, 0, 12, 4, 8),
    "-": (0, 0, 0, 31, 0, 0, 0), "_": (0, 0, 0, 0, 0, 0, 31),
    ":": (0, 12, 12, 0, 12, 12, 0), "/": (1, 1, 2, 4, 8, 16, 16),
    "(": (2, 4, 8, 8, 8, 4, 2), ")": (8, 4, 2, 2, 2, 4, 8),
    "=": (0, 0, 31, 0, 31, 0, 0), "%": (24, 25, 2, 4, 8, 19, 3),
    "|": (4, 4, 4, 4, 4, 4, 4), "+": (0, 4, 4, 31, 4, 4, 0),
    "?": (14, 17, 1, 2, 4, 0, 4), " ": (0,) * 7,
}


def text(img, x, y, s, rgb=(255, 255, 255)):
    """Draws s (upper-cased; unknown characters as '?') at (x, y), 6 px a character."""
    w, h, px = img
    colour = bytes(rgb)
    for ch in s.upper():
        rows = _FONT.get(ch, _FONT["?"])
        for r, bits in enumerate(rows):
            for c in range(5):
                if bits & (16 >> c) and 0 <= x + c < w and 0 <= y + r < h:
                    o = ((y + r) * w + x + c) * 3
                    px[o:o + 3] = colour
        x += 6
    return x
