"""Output folders that are safe to share: path checks and OS file locks.

* :func:`prepare_dir` turns every way a user-given folder can be unusable
  (empty, a file, below a file, a device, not writable) into one
  :class:`~tribolmp.errors.SetupError` line naming the option, instead of a
  ``FileExistsError`` traceback after minutes of work.
* :class:`DirLock` is an exclusive ``fcntl.flock`` on ``<folder>/.lock``.
  The lock belongs to the open file description, so the kernel releases it
  when the holder dies, however it dies (SIGKILL included): a lock left by a
  killed run is simply taken over, and no marker file ever needs deleting by
  hand.  The holder writes its PID into the file so that a second run can
  name it.

Foundation module: standard library and :mod:`tribolmp.errors` only.
"""

from __future__ import annotations

import errno
import fcntl
import os
import sys
import time
from pathlib import Path

from .errors import SetupError

__all__ = ["DirLock", "FolderBusyError", "prepare_dir", "prepare_file"]


class FolderBusyError(SetupError):
    """Another live process holds the lock of a folder (exit code 2)."""


def prepare_dir(path: str | os.PathLike | None, field: str = "--out") -> Path:
    """Create ``path`` as a writable folder or raise one line naming ``field``.

    Parameters
    ----------
    path : str or path-like
        Folder to create (parents included) or reuse.
    field : str
        The option or scene key the path came from, used in the message.

    Returns
    -------
    Path
        The folder.

    Raises
    ------
    SetupError
        Empty path, an existing non-folder (file, device), a path below a file,
        or a folder this process cannot write.
    """
    if path is None or not str(path).strip():
        raise SetupError(f"{field}: expected a folder path, got an empty string")
    p = Path(path).expanduser()
    if p.exists() and not p.is_dir():
        kind = "a file" if p.is_file() else "not a folder (a device or special file)"
        raise SetupError(f"{field}: expected a folder, got {str(p)!r}, which is {kind}")
    try:
        p.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise SetupError(
            f"{field}: expected a folder, got {str(p)!r}: a part of that path is a file"
        ) from None
    except NotADirectoryError:
        raise SetupError(
            f"{field}: expected a folder, got {str(p)!r}: a part of that path is a file"
        ) from None
    except PermissionError:
        raise SetupError(f"{field}: cannot create folder {str(p)!r}: permission denied") from None
    except OSError as exc:
        raise SetupError(
            f"{field}: cannot create folder {str(p)!r}: {exc.strerror or exc}"
        ) from None
    if not os.access(p, os.W_OK | os.X_OK):
        raise SetupError(f"{field}: expected a writable folder, got {str(p)!r} (permission denied)")
    return p


def prepare_file(path: str | os.PathLike | None, field: str) -> Path:
    """Check that a file can be written at ``path`` (its folder is created) or raise one line.

    Parameters
    ----------
    path : str or path-like
        The file to be written later (a figure, a table).
    field : str
        The option it came from, used in the message.

    Returns
    -------
    Path

    Raises
    ------
    SetupError
        Empty path, an existing folder, or a folder that cannot be created or written.
    """
    if path is None or not str(path).strip():
        raise SetupError(f"{field}: expected a file path, got an empty string")
    p = Path(path).expanduser()
    if p.is_dir():
        raise SetupError(f"{field}: expected a file path, got {str(p)!r}, which is a folder")
    prepare_dir(p.parent, f"{field} (its folder)")
    return p


class DirLock:
    """Exclusive lock of a folder for one process, released when it exits.

    Parameters
    ----------
    folder : str or path-like
        The folder to lock (it must exist); the lock file is ``folder/.lock``
        unless ``name`` says otherwise.
    wait : bool
        Wait for the holder to finish instead of raising :class:`FolderBusyError`.
    timeout : float, optional
        Longest wait in seconds (``None``: no limit).
    what : str
        How the folder is named in messages (e.g. ``"output folder"``).
    name : str
        File name of the lock inside ``folder``.
    stream : file, optional
        Where the "waiting for PID" line goes (default stderr; ``None`` with
        ``quiet`` prints nothing).
    quiet : bool
        Print no waiting line.

    Examples
    --------
    >>> with DirLock(out):            # doctest: +SKIP
    ...     run_everything(out)
    """

    def __init__(
        self,
        folder,
        *,
        wait: bool = False,
        timeout: float | None = None,
        what: str = "output folder",
        name: str = ".lock",
        stream=None,
        quiet: bool = False,
    ):
        self.folder = Path(folder)
        self.path = self.folder / name
        self.wait = wait
        self.timeout = timeout
        self.what = what
        self.stream = stream
        self.quiet = quiet
        self._fd: int | None = None

    def holder(self) -> str:
        """PID recorded by the current holder (``"?"`` when unreadable)."""
        try:
            return self.path.read_text().split()[0]
        except (OSError, IndexError):
            return "?"

    def acquire(self) -> DirLock:
        """Take the lock (see the class parameters for waiting); return ``self``."""
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o666)
        except OSError as exc:
            raise SetupError(
                f"{self.what} {str(self.folder)!r}: cannot "
                f"create its lock file: {exc.strerror or exc}"
            ) from None
        t0 = time.monotonic()
        told = False
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except OSError as exc:
                if exc.errno not in (errno.EAGAIN, errno.EACCES, errno.EWOULDBLOCK):
                    os.close(fd)
                    raise SetupError(
                        f"{self.what} {str(self.folder)!r}: cannot lock it: {exc.strerror or exc}"
                    ) from None
            pid = self.holder()
            if not self.wait or (self.timeout is not None and time.monotonic() - t0 > self.timeout):
                os.close(fd)
                raise FolderBusyError(
                    f"{self.what} {str(self.folder)!r} is in use "
                    f"by another tribolmp process (PID {pid}); "
                    "wait for it to finish or choose another folder"
                )
            if not told and not self.quiet:
                print(
                    f"waiting for PID {pid}, which holds {self.what} {str(self.folder)!r}",
                    file=self.stream or sys.stderr,
                    flush=True,
                )
                told = True
            time.sleep(0.2)
        # Record the holder for the next process's message; truncate after locking so a
        # waiting process never reads a half-written PID of ours over the old one.
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n".encode())
        self._fd = fd
        return self

    def release(self) -> None:
        """Give the lock back (closing the file releases the flock)."""
        if self._fd is not None:
            fd, self._fd = self._fd, None
            try:
                os.ftruncate(fd, 0)
            except OSError:
                pass
            os.close(fd)

    def __enter__(self) -> DirLock:
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()
