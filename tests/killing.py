"""Start an MPI run in a session of its own and SIGKILL all of it once a condition holds.

Open MPI's mpirun puts each rank in a process group of its own, so killing mpirun's group
leaves the ranks running until they notice: they can finish a step after the test has read
the outputs (seen in CI as a steps.csv one row ahead of fields.xdmf). The ranks stay in
mpirun's session, so every process of that session is killed, and the call returns only when
none of them can write any more."""
import os
import pathlib
import signal
import subprocess
import time


def _session_members(session):
    """The live (not zombie) processes whose session id is `session`."""
    members = []
    for stat in pathlib.Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue  # the process ended while the table was read
        state, sid = fields[0], int(fields[3])
        if sid == session and state != "Z":
            members.append(int(stat.parent.name))
    return members


def run_until(command, ready, hang_guard=900.0):
    """Run `command` until `ready()` holds (polled every 0.05 s), then SIGKILL every process it
    started. Returns whether it was still running when killed (False: it ended by itself, or
    the hang guard, far above the seconds these runs take, ran out)."""
    run = subprocess.Popen(command, start_new_session=True, stdout=subprocess.DEVNULL)
    deadline = time.monotonic() + hang_guard
    while not ready() and run.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    still_running = run.poll() is None
    while True:
        members = _session_members(run.pid)
        if not members:
            break
        for pid in members:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        time.sleep(0.05)
    run.wait()
    return still_running
