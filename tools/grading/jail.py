"""The sandbox every piece of a submission runs in: Debian's bubblewrap (``bwrap``).

Each run gets, from ``bwrap``:

- its own PID, mount, IPC, network, UTS (and, where possible, cgroup) namespaces: it sees
  only its own processes, no network but a loopback of its own, no other System V IPC;
- a root filesystem of read-only binds: the system (``/usr`` and its links), this Python and
  its virtual environment, the grader's sandbox scripts, the job's input files, and the
  library parts the job may use; a minimal ``/etc`` (the loader's cache, a ``passwd`` naming
  the sandbox's user); fresh ``/proc`` and ``/dev``; no ``/work``, no ``/root``, no
  ``/home``, no other submission, no output folder;
- a private home and ``/tmp`` (tmpfs, size-capped), the only writable places, gone when it
  ends;
- a clean environment (only the variables set here);
- ``--die-with-parent`` and ``--new-session``: when the grader (or bwrap) ends, everything in
  the sandbox is killed; the PID namespace ends with its first process, so nothing outlives
  the run, whatever it forked or daemonised.

Inside, the command runs as an unprivileged user: as root, ``setpriv`` switches to a uid of
its own (``uid_base + slot``: one per concurrent worker, no capabilities, ``no_new_privs``;
each grading run claims a block of uids of its own with :func:`claim_uids`, so that two runs
on one machine never share one) after bwrap has made the mounts, so the sandbox's processes
are not root in any namespace; as an ordinary user, bwrap's user namespace maps the
sandbox's ``nobody`` to the grader's own uid. ``prlimit`` caps memory (address space), CPU
seconds, the size of any file written, open files, core dumps, and (as root, where the uid
is the sandbox's own) processes.

Root never writes into a directory the sandbox can write: the sandbox's writable places are
its own tmpfs, and the inputs are written by the grader into a folder that the sandbox sees
read-only.
"""

from __future__ import annotations

import fcntl
import os
import pwd
import random
import selectors
import shutil
import signal
import stat
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

#: First uid of the sandboxes' users when the grader runs as root: a run claims one of
#: ``UID_BLOCKS`` blocks of ``BLOCK`` uids from here (``uid_base + slot``).
UID_BASE = 1_900_000_000
BLOCK, UID_BLOCKS = 64, 4096
#: Where runs (as root) lock the uid block they use: root's own, never a shared /tmp.
UID_LOCKS = Path("/run/wheelkin-grade")
#: The home directory inside the sandbox.
HOME = "/home/student"
#: Where the grader's sandbox scripts, the job and the library parts are mounted.
SCRIPTS, JOB, LIBRARY = "/opt/grader", "/opt/job", "/opt/wheelkin"
#: In a command's arguments, stands for the fd on which the sandboxed program reports.
REPORT_FD = "{report_fd}"


class SandboxUnavailable(RuntimeError):
    """bubblewrap is missing or cannot make its namespaces here (said with the reason)."""


@dataclass
class Limits:
    seconds: float = 120.0
    memory: int = 4 * 2**30          # address space, bytes
    output: int = 2_000_000          # bytes the run may print (stdout and stderr)
    file_size: int = 100 * 2**20     # largest file it may write
    tmp_size: int = 256 * 2**20      # each tmpfs (home, /tmp)
    processes: int = 64              # as root: processes and threads of the sandbox's uid
    open_files: int = 512
    report: int = 8 * 2**20          # bytes it may report on REPORT_FD


@dataclass
class Outcome:
    """What a sandboxed run did."""

    returncode: int | None
    seconds: float
    timed_out: bool = False
    over_output: bool = False
    printed: int = 0
    report: list[str] = field(default_factory=list)   # the report's lines
    tail: str = ""                                     # the last of its output (for logs)
    left_behind: int = 0                               # processes of its uid found after it


def bwrap_path() -> str:
    found = shutil.which("bwrap")
    if not found:
        raise SandboxUnavailable("bubblewrap (bwrap) is not installed: apt-get install "
                                 "bubblewrap")
    return found


def _system_binds(python: bool = True) -> list[str]:
    """Read-only binds of the system: /usr, its links (/bin, /lib ...), this Python (unless
    ``python`` is false)."""
    args = ["--ro-bind", "/usr", "/usr"]
    for top in ("bin", "sbin", "lib", "lib32", "lib64", "libx32"):
        path = Path("/") / top
        if path.is_symlink():
            args += ["--symlink", os.readlink(path), str(path)]
        elif path.is_dir():
            args += ["--ro-bind", str(path), str(path)]
    for path in ("/etc/ld.so.cache", "/etc/ld.so.conf", "/etc/ld.so.conf.d",
                 "/etc/alternatives", "/etc/localtime"):
        if os.path.exists(path):
            args += ["--ro-bind", path, path]
    if not python:
        return args
    prefixes = {Path(sys.base_prefix).resolve(), Path(sys.prefix).resolve()}
    # The interpreter's own directory when it is elsewhere (e.g. pyenv's under /root).
    prefixes.add(Path(os.path.realpath(sys.executable)).parent.parent)
    for prefix in sorted(prefixes):
        if not str(prefix).startswith("/usr/") and prefix != Path("/usr"):
            args += ["--ro-bind", str(prefix), str(prefix)]
    if Path(sys.prefix) != Path(sys.prefix).resolve():  # a venv reached through a link
        args += ["--ro-bind", str(Path(sys.prefix).resolve()), str(Path(sys.prefix))]
    return args


def python_in_sandbox() -> str:
    """The interpreter path to run inside (this one: its prefix is bound at the same path)."""
    return os.path.abspath(sys.executable)


def _with_parents(binds: list[str]) -> list[str]:
    """``binds`` preceded by ``--dir`` for every folder above a mount point, mode 0755 (bwrap
    would make them 0700, which the sandbox's user could not cross)."""
    made: set[str] = {"/", "/tmp", "/home", HOME, "/proc", "/dev"}  # there already
    out: list[str] = []
    i = 0
    while i < len(binds):
        op = binds[i]
        arity = 2 if op in ("--ro-bind", "--bind", "--symlink") else 1
        dest = binds[i + arity]
        for parent in reversed(Path(dest).parents):
            if str(parent) not in made:
                made.add(str(parent))
                out += ["--perms", "0755", "--dir", str(parent)]
        made.add(dest)
        out += binds[i: i + arity + 1]
        i += arity + 1
    return out


@dataclass
class Sandbox:
    """One kind of sandbox: its binds and limits. :meth:`run` starts a fresh one each time.

    ``binds``: (host path, path inside) pairs, read-only; ``slot``: which worker (its uid,
    as root); ``etc``: a folder with ``passwd`` and ``group`` for the sandbox's user;
    ``python``: bind this Python and its virtual environment (at their own paths).
    """

    limits: Limits
    etc: Path
    binds: list[tuple[Path, str]] = field(default_factory=list)
    slot: int = 0
    uid_base: int = UID_BASE
    env: dict[str, str] = field(default_factory=dict)
    python: bool = True

    @property
    def as_root(self) -> bool:
        return os.geteuid() == 0

    @property
    def uid(self) -> int:
        return self.uid_base + self.slot if self.as_root else 65534

    def command(self, argv: list[str]) -> list[str]:
        limits = self.limits
        cmd = [bwrap_path(), "--die-with-parent", "--new-session", "--unshare-pid",
               "--unshare-net", "--unshare-ipc", "--unshare-uts", "--unshare-cgroup-try",
               "--hostname", "sandbox"]
        if not self.as_root:  # an ordinary user: bwrap's user namespace
            cmd += ["--unshare-user", "--uid", "65534", "--gid", "65534", "--disable-userns"]
        # The private tmpfs first, then the read-only binds: a venv or a Python that lives
        # under /tmp (a fresh clone in `mktemp -d`) is bound inside the sandbox's own /tmp.
        cmd += ["--proc", "/proc", "--dev", "/dev",
                "--perms", "1777", "--size", str(limits.tmp_size), "--tmpfs", "/tmp",
                "--perms", "1777", "--size", str(limits.tmp_size), "--tmpfs", HOME]
        binds = [*_system_binds(self.python), "--ro-bind", str(self.etc / "passwd"),
                 "/etc/passwd",
                 "--ro-bind", str(self.etc / "group"), "/etc/group"]
        for host, inside in self.binds:
            binds += ["--ro-bind", str(host), inside]
        cmd += _with_parents(binds)
        cmd += ["--chdir", HOME, "--clearenv"]
        env = {"PATH": "/usr/bin:/bin", "HOME": HOME, "USER": "student", "LOGNAME": "student",
               "TMPDIR": "/tmp", "LANG": "C.UTF-8", "LC_ALL": "C.UTF-8", "TZ": "UTC",
               "PYTHONHASHSEED": "0", "PYTHONDONTWRITEBYTECODE": "1", "MPLBACKEND": "Agg",
               "MPLCONFIGDIR": f"{HOME}/.config/matplotlib",
               "IPYTHONDIR": f"{HOME}/.ipython", "OPENBLAS_NUM_THREADS": "1",
               "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
               "PYDEVD_DISABLE_FILE_VALIDATION": "1", **self.env}
        for key, value in env.items():
            cmd += ["--setenv", key, value]
        cmd.append("--")
        if self.as_root:
            cmd += ["setpriv", f"--reuid={self.uid}", f"--regid={self.uid}", "--clear-groups",
                    "--inh-caps=-all", "--bounding-set=-all", "--no-new-privs", "--"]
        cmd += ["prlimit", f"--as={limits.memory}", f"--fsize={limits.file_size}",
                f"--nofile={limits.open_files}", "--core=0",
                f"--cpu={int(limits.seconds) + 5}"]
        if self.as_root:
            cmd.append(f"--nproc={limits.processes}")
        cmd += ["--", *argv]
        return cmd

    def run(self, argv: list[str]) -> Outcome:
        """Run ``argv`` in a fresh sandbox; the sandboxed program reports on the fd that
        replaces ``REPORT_FD`` in ``argv`` (a pipe; bwrap passes inherited fds on). Output
        beyond the limit, or time beyond the limit, ends the run."""
        limits = self.limits
        report_r, report_w = os.pipe()
        out_r, out_w = os.pipe()
        argv = [a.replace(REPORT_FD, str(report_w)) for a in argv]
        start = time.monotonic()
        try:
            proc = subprocess.Popen(
                self.command(argv), stdin=subprocess.DEVNULL, stdout=out_w, stderr=out_w,
                pass_fds=(report_w,), start_new_session=True, close_fds=True)
        except OSError as exc:
            os.close(report_r), os.close(out_r), os.close(report_w), os.close(out_w)
            raise SandboxUnavailable(f"bwrap could not start: {exc}") from exc
        os.close(report_w)
        os.close(out_w)
        outcome = Outcome(None, 0.0)
        report = bytearray()
        tail = bytearray()
        selector = selectors.DefaultSelector()
        selector.register(out_r, selectors.EVENT_READ, "out")
        selector.register(report_r, selectors.EVENT_READ, "report")
        open_fds = 2
        deadline = start + limits.seconds
        try:
            while open_fds:
                left = deadline - time.monotonic()
                if left <= 0:
                    outcome.timed_out = True
                    break
                for key, _ in selector.select(timeout=min(left, 1.0)):
                    chunk = os.read(key.fd, 65536)
                    if not chunk:
                        selector.unregister(key.fd)
                        open_fds -= 1
                        continue
                    if key.data == "out":
                        outcome.printed += len(chunk)
                        tail = (tail + chunk)[-4000:]
                        if outcome.printed > limits.output:
                            outcome.over_output = True
                    elif len(report) + len(chunk) <= limits.report:
                        report += chunk
                if outcome.over_output:
                    break
        finally:
            if outcome.timed_out or outcome.over_output:
                _kill(proc)
            try:
                outcome.returncode = proc.wait(timeout=max(1.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                outcome.timed_out = True
                _kill(proc)
                outcome.returncode = proc.wait()
            selector.close()
            os.close(out_r)
            os.close(report_r)
        outcome.seconds = time.monotonic() - start
        outcome.report = report.decode("utf-8", "replace").splitlines()
        outcome.tail = tail.decode("utf-8", "replace")
        if self.as_root:  # the namespace is torn down as bwrap ends: give it a moment
            for _ in range(20):
                if not processes_of(self.uid):
                    break
                time.sleep(0.05)
            outcome.left_behind = kill_uid(self.uid)
        return outcome


def _kill(proc: subprocess.Popen) -> None:
    """End bwrap; --die-with-parent and the PID namespace take everything inside with it."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def claim_uids() -> tuple[int, int | None]:
    """A block of uids no other grading run on this machine uses: ``(uid_base, lock)``. The
    lock (an open file, ``flock``-ed) is held until it is closed or the process ends. As an
    ordinary user (whose sandboxes run as that user): ``(UID_BASE, None)``."""
    if os.geteuid() != 0:
        return UID_BASE, None
    UID_LOCKS.mkdir(mode=0o700, exist_ok=True)
    info = os.lstat(UID_LOCKS)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != 0 or info.st_mode & 0o022:
        raise SandboxUnavailable(f"{UID_LOCKS} must be a folder of root's that only root may "
                                 "write")
    start = random.randrange(UID_BLOCKS)
    for k in range(UID_BLOCKS):
        block = (start + k) % UID_BLOCKS
        fd = os.open(UID_LOCKS / f"{block}.lock",
                     os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o600)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            continue
        return UID_BASE + BLOCK * block, fd
    raise SandboxUnavailable(f"all {UID_BLOCKS} blocks of sandbox uids are in use")


def processes_of(uid: int) -> list[int]:
    """The pids of every process whose real uid is ``uid``."""
    found = []
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/status", encoding="ascii", errors="replace") as f:
                for line in f:
                    if line.startswith("Uid:"):
                        if int(line.split()[1]) == uid:
                            found.append(int(entry.name))
                        break
        except OSError:
            continue
    return found


def kill_uid(uid: int) -> int:
    """Kill every process of ``uid`` (there should be none once a sandbox ended); return how
    many there were."""
    pids = processes_of(uid)
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass
    return len(pids)


def write_etc(folder: Path, uid: int) -> Path:
    """``passwd`` and ``group`` for the sandbox (its user named ``student``)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "passwd").write_text(
        f"root:x:0:0:root:/root:/usr/sbin/nologin\n"
        f"student:x:{uid}:{uid}:student:{HOME}:/usr/sbin/nologin\n"
        f"nobody:x:65534:65534:nobody:/nonexistent:/usr/sbin/nologin\n", encoding="ascii")
    (folder / "group").write_text(f"root:x:0:\nstudent:x:{uid}:\nnogroup:x:65534:\n",
                                  encoding="ascii")
    return folder


def probe(work: Path, uid_base: int = UID_BASE) -> None:
    """Start one sandbox that runs ``true``; raise :class:`SandboxUnavailable` with bwrap's
    reason if it cannot (no bubblewrap, namespaces refused: a container without the rights,
    unprivileged user namespaces turned off)."""
    etc = write_etc(work / "etc-probe", uid_base if os.geteuid() == 0 else 65534)
    box = Sandbox(Limits(seconds=30), etc, uid_base=uid_base)
    done = box.run(["true"])
    if done.returncode != 0:
        raise SandboxUnavailable("bubblewrap cannot make its sandbox here: "
                                 + (done.tail.strip().splitlines() or ["no reason given"])[-1])


def user_name() -> str:
    try:
        return pwd.getpwuid(os.geteuid()).pw_name
    except KeyError:
        return str(os.geteuid())
