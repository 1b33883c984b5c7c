"""The plots' files written as the C++ writers write theirs (core/atomic_file.hpp): never through a
symlink, nor into a FIFO, a device or a folder that stands at an output's name (those are refused,
and the user's file behind them stays as it was); each file goes to a temporary created exclusively
beside it ("<path>.tmp.<pid>", or ".<n>" after it when that name is taken: whatever was planted
there is left alone) and is renamed over the output only when complete."""
import os
import stat


class RefusedOutput(Exception):
    """An output path that must not be written: its message is the one line to print."""


def not_a_regular_file(path):
    """What stands at `path` (not following a symlink) when it is not a regular file: "a symlink",
    "a folder", "a FIFO", "a device", "a socket"; None when nothing or a regular file is there."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return None
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISLNK(mode):
        return "a symlink"
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    return "a socket"


def check_outputs(paths):
    """Raises RefusedOutput for the first of `paths` that is there and is not a regular file."""
    for path in paths:
        kind = not_a_regular_file(path)
        if kind:
            raise RefusedOutput(f"{path} is {kind}, not a regular file; refusing to write it")


def write_atomic(path, write):
    """Calls write(binary file object) on a fresh temporary beside `path`, then renames it over
    `path`. Raises RefusedOutput when `path` is not a regular file."""
    check_outputs([path])
    stem = f"{path}.tmp.{os.getpid()}"
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
    for n in range(101):
        tmp = stem if n == 0 else f"{stem}.{n}"
        try:
            fd = os.open(tmp, flags, 0o644)
            break
        except FileExistsError:
            continue
    else:
        raise RefusedOutput(f"{path}: no free name for a temporary beside it ({stem}…)")
    try:
        with os.fdopen(fd, "wb") as f:
            write(f)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
