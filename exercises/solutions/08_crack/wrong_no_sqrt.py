"""Wrong: the closed forms with 1/2 where they have 1/(2√r): a √r missing in the gradient."""
import numpy as np

EXPECT = "did you miss a 1/√r"


def branch_gradients(r, theta):
    t = np.asarray(theta, float)
    s, c, s3, c3 = np.sin(t / 2), np.cos(t / 2), np.sin(3 * t / 2), np.cos(3 * t / 2)
    return 0.5 * np.array([[-s, c], [c, s], [-s3 * np.sin(t), s + s3 * np.cos(t)],
                           [-c3 * np.sin(t), c + c3 * np.cos(t)]])
