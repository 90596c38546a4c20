"""Ctrl-C during a long batch comes back within a second and leaves no worker rolling."""

import select
import signal
import subprocess
import sys
import time

# The child rolls a batch far too long to finish, reports when it has started, and after
# the interrupt measures the CPU time its process spends over half a second: a worker
# still rolling would spend about that much per core.
CHILD = r"""
import sys, time, threading, dicesim
print("rolling", flush=True)
try:
    dicesim.batch(rolls=200_000_000, seed=1)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    cpu = time.process_time()
    time.sleep(0.5)
    print(f"cpu {time.process_time() - cpu:.4f}", flush=True)
"""


def line_within(stream, seconds):
    """The child's next line, or None if it writes none within `seconds` (a batch that
    ignored the interrupt would otherwise keep the test waiting for hours)."""
    ready, _, _ = select.select([stream], [], [], seconds)
    return stream.readline().strip() if ready else None


def test_ctrl_c_stops_a_long_batch_within_a_second_and_every_worker_with_it():
    child = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "rolling"
        time.sleep(1.5)  # well into the batch, every core rolling
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        answer = line_within(child.stdout, 5.0)
        took = time.monotonic() - sent
        assert answer == "interrupted", f"no KeyboardInterrupt within 5 s (got {answer!r})"
        assert took < 1.0, f"the interrupt came back after {took:.2f} s"
        cpu = float(child.stdout.readline().split()[1])
        assert cpu < 0.05, f"{cpu:.3f} s of CPU in the 0.5 s after the interrupt: a worker kept rolling"
        assert child.wait(timeout=10) == 0
    finally:
        child.kill()
