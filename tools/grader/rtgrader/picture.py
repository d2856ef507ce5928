"""The graded picture (tools/grader/README.md, "Picture").

With the solutions at hand (the instructor's tree), a chapter's picture is
graded from a view the submission cannot know in advance: each grading draws a
fresh secret, and each chapter's view is derived from it, a turn of the
chapter's own camera about the point it looks at (the chapter programs'
`--view YAW,PITCH`, common/program.hpp), small enough that the scene stays in
view. The reference is drawn at grading time by the solutions' chapter program
from the same view, after the student's program has ended, and both are
compared by imgcmp. A picture the student's process writes without computing
it (a copy of the kit's reference.png, the chapter's own view, a picture kept
from an earlier grading) does not match: no two gradings share a view.

In a student kit (no solutions) the preview draws the chapter's own view at
its own size and compares it with the kit's reference.png, whose difference
image is there to teach.
"""

import hashlib
import hmac
import secrets
import struct

# The turn from the chapter's own view, in degrees: the yaw's size and the pitch (the eye only rises,
# so a camera near a ground plane never sinks under it). Both stay small enough that every chapter's
# scene keeps its objects in the picture, and large enough that no pixel of the chapter's own
# picture is where it was.
YAW_DEGREES = (3.0, 10.0)
PITCH_DEGREES = (2.0, 8.0)
# The graded picture is the chapter's own size halved each way (a quarter of the pixels: the
# reference is drawn at every grading, and the render phase must stay short).
GRADED_SCALE = 2


def draw_secret():
    """A fresh secret for one grading (never stored, never shown)."""
    return secrets.token_bytes(32)


def _uniform(secret, label):
    """A number in [0, 1) from the secret and a label (HMAC-SHA256: unpredictable without the secret)."""
    digest = hmac.new(secret, label.encode(), hashlib.sha256).digest()
    return int.from_bytes(digest[:8], "big") / 2.0 ** 64


def view_for(secret, chapter_id):
    """(yaw, pitch) in degrees for one chapter of one grading, to three decimals."""
    size = YAW_DEGREES[0] + (YAW_DEGREES[1] - YAW_DEGREES[0]) * _uniform(secret, chapter_id + ":yaw")
    sign = -1.0 if _uniform(secret, chapter_id + ":side") < 0.5 else 1.0
    pitch = PITCH_DEGREES[0] + (PITCH_DEGREES[1] - PITCH_DEGREES[0]) * _uniform(secret, chapter_id + ":pitch")
    return round(sign * size, 3), round(pitch, 3)


def view_argument(view):
    return f"{view[0]:.3f},{view[1]:.3f}"


def png_size(path):
    """(width, height) from a PNG file's header, or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def graded_size(reference_png):
    """The graded picture's size: the chapter's own (its reference.png's) halved, at least 16 x 16."""
    size = png_size(reference_png)
    if size is None:
        return None
    return tuple(max(16, (s + GRADED_SCALE - 1) // GRADED_SCALE) for s in size)


def program_arguments(view, size):
    """The chapter program's options for a graded picture."""
    return ["--width", str(size[0]), "--height", str(size[1]), "--view", view_argument(view)]
