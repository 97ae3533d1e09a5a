"""Image measures shared by tools/reference/evaluate.py and fidelity_blender.py (numpy only, so
Blender's own Python can import it): the PBR Neutral tone mapper, luminance, the Gaussian
window, SSIM."""
import numpy as np


def pbr_neutral(c):
    """Khronos PBR Neutral tone mapper (the same as Penumbra's glsl)."""
    start = 0.8 - 0.04
    desat = 0.15
    x = c.min(axis=-1, keepdims=True)
    offset = np.where(x < 0.08, x - 6.25 * x * x, 0.04)
    c = c - offset
    peak = c.max(axis=-1, keepdims=True)
    d = 1.0 - start
    new_peak = 1.0 - d * d / (peak + d - start)
    scaled = c * (new_peak / np.maximum(peak, 1e-12))
    g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0)
    compressed = scaled * (1.0 - g) + new_peak * g
    return np.where(peak < start, c, compressed)


def luma(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def gaussian_filter(img, sigma=1.5, radius=5):
    t = np.arange(-radius, radius + 1)
    k = np.exp(-t * t / (2 * sigma * sigma))
    k /= k.sum()
    p = np.pad(img, radius, mode="reflect")
    tmp = sum(k[i] * p[:, i:i + img.shape[1]] for i in range(len(k)))
    return sum(k[i] * tmp[i:i + img.shape[0], :] for i in range(len(k)))


def ssim(a, b):
    """SSIM (Wang et al. 2004: 11x11 Gaussian window, sigma 1.5, K1 0.01, K2 0.03, range 1)."""
    c1, c2 = 0.01 ** 2, 0.03 ** 2
    mu_a, mu_b = gaussian_filter(a), gaussian_filter(b)
    saa = gaussian_filter(a * a) - mu_a ** 2
    sbb = gaussian_filter(b * b) - mu_b ** 2
    sab = gaussian_filter(a * b) - mu_a * mu_b
    m = ((2 * mu_a * mu_b + c1) * (2 * sab + c2)) / ((mu_a ** 2 + mu_b ** 2 + c1) * (saa + sbb + c2))
    return float(m.mean())
