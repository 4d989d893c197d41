"""posekit: example-based processing of triangle-mesh poses.

Vertices are numpy float64 arrays of shape (n, 3), faces integer arrays of shape (m, 3). Options are
those of the command line, as keyword arguments (``key_frames=7`` for ``--key-frames 7``). Bad input
raises ValueError with a one-line message; a compute device that fails raises posekit.DeviceError.

    V, F = posekit.read_mesh("pose.obj")
    V_out, report = posekit.correct(V_ref, V, F)
"""

from ._posekit import (  # noqa: F401
    DeviceError,
    blend_radius,
    check,
    correct,
    correct_sequence,
    deform,
    devices,
    interpolate,
    read_mesh,
    register,
    write_mesh,
)

from . import distributed  # noqa: E402,F401  (imports dask only when called)

__all__ = ["DeviceError", "blend_radius", "check", "correct", "correct_sequence", "deform", "devices", "interpolate", "read_mesh", "register", "write_mesh"]
