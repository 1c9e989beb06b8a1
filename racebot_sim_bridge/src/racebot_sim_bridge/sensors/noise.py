"""Sensor noise as Gazebo's sensors apply it (gazebo/sensors/GaussianNoiseModel).

Pure numpy: no rospy, no pybullet. A noise model is built from the (type, mean, stddev) that
urdf_model reads out of a sensor's <noise> block; `make_noise` gives None for "no noise", so
callers skip the work entirely.

- ray ranges: value + N(mean, stddev), drawn independently for every beam;
- IMU rates and accelerations: the same, per axis;
- camera images: Gazebo adds N(mean, stddev) to each colour channel in [0, 1] (in a shader) and
  clamps. Drawing 2 million normal samples per 800 x 800 frame would cost as much as a quarter
  of the render, so `ImageNoise` draws one large pool of samples once and adds a randomly placed
  window of it to each frame: every pixel still gets an N(mean, stddev) value, frame after frame.
"""
import numpy as np

GAUSSIAN_TYPES = ('gaussian', 'gaussian_quantized')


def make_noise(kind, mean, stddev, enabled=True, rng=None):
    """A GaussianNoise for a <noise> block, or None when there is nothing to add.

    `kind` is the <type> text ('none', 'gaussian', 'gaussian_quantized'; quantisation is not
    modelled). `enabled=False` (the simulator's noise switch) always gives None.
    Raises ValueError for an unknown type or a negative stddev.
    """
    kind = (kind or 'none').strip().lower()
    if kind == 'none':
        return None
    if kind not in GAUSSIAN_TYPES:
        raise ValueError("noise type %r is not supported (use gaussian or none)" % kind)
    if not stddev >= 0.0:
        raise ValueError('noise stddev must be >= 0, got %r' % (stddev,))
    if not enabled or (mean == 0.0 and stddev == 0.0):
        return None
    return GaussianNoise(mean, stddev, rng)


class GaussianNoise:
    """Adds independent N(mean, stddev) samples to every value."""

    def __init__(self, mean, stddev, rng=None):
        self.mean = float(mean)
        self.stddev = float(stddev)
        self.rng = rng if rng is not None else np.random.default_rng()

    def apply(self, values):
        values = np.asarray(values, dtype=np.float64)
        return values + self.rng.normal(self.mean, self.stddev, values.shape)


class ImageNoise:
    """Gaussian noise on 8-bit images: N(mean, stddev) in units of full scale (1.0 = 255)."""

    def __init__(self, mean, stddev, size, rng=None):
        self.mean = float(mean)
        self.stddev = float(stddev)
        self.rng = rng if rng is not None else np.random.default_rng()
        self.size = int(size)
        # Twice the frame size, so that any window of `size` samples starting in the first half fits.
        self.pool = np.rint(self.rng.normal(self.mean * 255.0, self.stddev * 255.0, 2 * self.size)) \
            .clip(-255, 255).astype(np.int16)

    @classmethod
    def from_noise(cls, noise, size, rng=None):
        """An ImageNoise with the mean and stddev of a GaussianNoise (None stays None)."""
        if noise is None:
            return None
        return cls(noise.mean, noise.stddev, size, rng or noise.rng)

    def apply(self, image):
        """uint8 image (any shape with `size` elements) -> noisy uint8 image of the same shape."""
        flat = np.asarray(image, dtype=np.uint8).reshape(-1)
        if flat.size != self.size:
            raise ValueError('image has %d values, the noise was made for %d' % (flat.size, self.size))
        start = int(self.rng.integers(0, self.size + 1))
        noisy = flat.astype(np.int16) + self.pool[start:start + self.size]
        return noisy.clip(0, 255).astype(np.uint8).reshape(np.shape(image))


class AxisNoise:
    """Gazebo's GaussianNoiseModel on each axis of a vector (an IMU's rates or accelerations): per axis a
    bias drawn once, N(bias_mean, bias_stddev) with its sign flipped half the time, as Gazebo draws it at
    load, plus N(mean, stddev) on every sample. `axes`: per axis (mean, stddev, bias_mean, bias_stddev)."""

    def __init__(self, axes, rng=None):
        self.rng = rng if rng is not None else np.random.default_rng()
        axes = np.asarray(axes, dtype=np.float64).reshape(-1, 4)
        if (axes[:, 1] < 0).any() or (axes[:, 3] < 0).any():
            raise ValueError('noise stddev and bias_stddev must be >= 0, got %r' % axes.tolist())
        self.mean, self.stddev = axes[:, 0], axes[:, 1]
        bias = self.rng.normal(axes[:, 2], axes[:, 3])
        self.bias = np.where(self.rng.uniform(size=len(bias)) < 0.5, -bias, bias)

    @classmethod
    def make(cls, axes, enabled=True, rng=None):
        """An AxisNoise, or None when noise is off or every value is 0."""
        if not enabled or not np.any(np.asarray(axes, dtype=np.float64)):
            return None
        return cls(axes, rng)

    def apply(self, values):
        return np.asarray(values, dtype=np.float64) + self.bias + self.rng.normal(self.mean, self.stddev)
