"""Image errors, defined as renderer/image_metrics.h defines them (so that the numbers agree with
`glint render --log`), FLIP (PyPI flip-evaluator), and EXR reading."""
import numpy as np

EPS = 0.01
TRIM = 0.001


def read_exr(path):
    import mitsuba_export as mx
    mi = mx._mitsuba()
    img = np.array(mi.Bitmap(path), dtype=np.float32)
    return img[..., :3]


def _lum(img):
    return 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]


def relmse(img, ref):
    x, r = img.astype(np.float64), ref.astype(np.float64)
    return float(np.mean((x - r) ** 2 / (r * r + EPS)))


def relmse_trimmed(img, ref):
    x, r = img.astype(np.float64), ref.astype(np.float64)
    per_pixel = np.mean((x - r) ** 2 / (r * r + EPS), axis=-1).ravel()
    per_pixel = np.where(np.isnan(per_pixel), np.inf, per_pixel)
    drop = int(np.floor(TRIM * per_pixel.size))
    keep = np.sort(per_pixel)[: per_pixel.size - drop]
    return float(np.mean(keep))


def mape(img, ref):
    x, r = img.astype(np.float64), ref.astype(np.float64)
    return float(np.mean(np.abs(x - r) / (np.abs(r) + EPS)))


def mean_lum(img):
    return float(np.mean(_lum(img.astype(np.float64))))


def mean_bias(img, ref):
    m = mean_lum(ref)
    return (mean_lum(img) - m) / m if m != 0 else float("nan")


def flip(img, ref):
    """Mean HDR-FLIP of a linear image against a linear reference."""
    import flip_evaluator as fl
    r = np.ascontiguousarray(np.maximum(np.nan_to_num(ref, posinf=0), 0), dtype=np.float32)
    x = np.ascontiguousarray(np.maximum(np.nan_to_num(img, posinf=0), 0), dtype=np.float32)
    if float(r.max()) <= 0 and float(x.max()) <= 0:
        return 0.0
    _, mean, _ = fl.evaluate(r, x, "HDR", applyMagma=False)
    return float(mean)
