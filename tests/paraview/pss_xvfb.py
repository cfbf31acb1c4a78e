"""Run a command under xvfb-run, robustly when other xvfb-run instances start at the same time.

`xvfb-run -a` looks for a free display from :99 upwards; two instances started together can both
pick :99, and the one whose Xvfb loses the race then talks to the other's server and aborts with
"bad X server connection". So the search starts at a random display number, and a run that failed
for that reason (and only for that reason) is retried, up to five times with a growing pause: a
fresh-clone run on 2026-12-02 lost three quick attempts in a row under load, where the display
numbers could not have collided. Xvfb's own messages (xvfb-run -e) are added to the output of a
failed attempt, so that the next failure says why the server was unusable.
"""
import os
import random
import subprocess
import tempfile
import time

X_FAILURES = ("bad X server connection", "Xvfb failed to start", "could not connect to display",
              "cannot open display")


def run(xvfb_run, command, env=None, timeout=120, attempts=5):
    """Returns (exit status, combined output) of the last attempt."""
    output = ""
    for attempt in range(attempts):
        display = random.randint(200, 4000)
        with tempfile.NamedTemporaryFile("r", prefix="pss-xvfb-", suffix=".log") as xlog:
            argv = [xvfb_run, "-n", str(display), "-a", "-e", xlog.name, "-s", "-screen 0 1920x1200x24"] + list(command)
            try:
                result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                        env=env, timeout=timeout)
            except subprocess.TimeoutExpired as e:
                out = e.stdout.decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
                return 124, out + "\n[timed out after %d s]" % timeout
            output = result.stdout
            if result.returncode == 0 or not any(s in output for s in X_FAILURES):
                return result.returncode, output
            server = xlog.read() if os.path.exists(xlog.name) else ""
        print("attempt %d: the X server failed (display race?), retrying; Xvfb said:\n%s"
              % (attempt + 1, server.strip() or "(nothing)"), flush=True)
        time.sleep((1 + attempt) * (1 + random.random() * 2))
    return result.returncode, output
