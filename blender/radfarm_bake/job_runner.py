"""Runs radfarm commands one after another without blocking Blender.

A bake is a short pipeline of `radfarm` commands: `render` on this machine, or `submit`, `status
--watch --json` and `fetch` on a farm. Each command is a child process; a thread per output stream
turns its lines into events on a queue, and `JobRunner.poll` (called from Blender's main thread, by
a modal operator's timer or in a loop in background mode) folds them into the state the panel and
the status bar show. Nothing here imports bpy, so it runs and is tested outside Blender.
"""

import json
import queue
import re
import subprocess
import threading
import time

RUNNING, DONE, FAILED, CANCELLED = "running", "done", "failed", "cancelled"

# `render`'s log lines (stdout is a pipe, so one line per change, never a redrawn bar).
_ROUND = re.compile(r"^round (\d+)[: ]")
_ETA = re.compile(r"ETA (\d+)s")
_GATHER = re.compile(r"^final gather")


class JobRunner:
    """One bake's commands. `poll` and `cancel` belong to the thread that made the runner."""

    def __init__(self, radfarm, job_file, out_dir, control=None, clock=time.monotonic,
                 on_line=None):
        """`on_line(runner)`, if given, is called after each line a command prints has been
        taken in (poll takes in all that came since the last call at once)."""
        self.radfarm = radfarm
        self.job_file = job_file
        self.out_dir = out_dir
        self.control = control  # the farm's control socket; None: render on this machine
        self.clock = clock
        self._listener = on_line
        self.state = RUNNING
        self.stage = ""  # what the bake is doing, in words
        self.progress = 0.0  # 0..1, never falls
        self.eta_seconds = None
        self.job_id = None
        self.message = ""  # why it failed
        self._events = queue.Queue()
        self._process = None
        self._open_streams = 0
        self._stdout = []
        self._stderr = []
        self._on_exit = None
        self._started = clock()
        if control is None:
            self._run(["render", job_file, "--out", out_dir], "rendering on this machine",
                      self._rendered)
        else:
            self._run(["submit", job_file], "submitting to the farm", self._submitted)

    # --- the pipeline -------------------------------------------------------------------------

    def _command(self, args):
        if self.control is None:
            return [self.radfarm] + args
        return [self.radfarm, "--control", self.control] + args

    def _run(self, args, stage, on_exit):
        self.stage = stage
        self._stdout, self._stderr = [], []
        self._on_exit = on_exit
        try:
            self._process = subprocess.Popen(self._command(args), stdin=subprocess.DEVNULL,
                                             stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                             encoding="utf-8", errors="replace", bufsize=1)
        except OSError as error:
            self._fail("cannot run %s: %s" % (self.radfarm, error.strerror))
            return
        self._open_streams = 2
        for name, stream in (("out", self._process.stdout), ("err", self._process.stderr)):
            threading.Thread(target=self._read, args=(name, stream), daemon=True).start()

    def _read(self, name, stream):
        for line in stream:
            self._events.put((name, line.rstrip("\n")))
        stream.close()
        self._events.put((name, None))

    def _rendered(self, code):
        if code == 0:
            self._finish()
        else:
            self._fail(self._error_text("render"))

    def _submitted(self, code):
        if code != 0:
            self._fail(self._error_text("submit"))
            return
        self.job_id = self._stdout[-1].strip() if self._stdout else None
        if not self.job_id or not self.job_id.isdigit():
            self._fail("submit printed no job id")
            return
        self._run(["status", self.job_id, "--watch", "--json"], "job %s queued" % self.job_id,
                  self._watched)

    def _watched(self, code):
        if self.state == CANCELLED:
            return
        if code != 0:
            self._fail(self._error_text("the farm's job %s" % self.job_id))
            return
        self._run(["fetch", self.job_id, "--out", self.out_dir],
                  "fetching job %s" % self.job_id, self._fetched)

    def _fetched(self, code):
        if code == 0:
            self._finish()
        else:
            self._fail(self._error_text("fetch"))

    # --- progress -----------------------------------------------------------------------------

    def _on_line(self, line):
        self._stdout.append(line)
        if self._on_exit == self._watched:
            self._on_job(line)
        elif self._on_exit == self._rendered:
            self._on_render_line(line)

    def _on_render_line(self, line):
        round_match = _ROUND.match(line)
        if round_match:
            self.stage = "round %s" % round_match.group(1)
        elif _GATHER.match(line):
            self.stage = "final gather"
        eta = _ETA.search(line)
        if eta:
            self.eta_seconds = int(eta.group(1))
            # render's log lines carry no share of the work; the time spent and the time still
            # to come give one.
            spent = self.clock() - self._started
            self._advance(spent / (spent + self.eta_seconds) if spent > 0 else 0.0)

    def _on_job(self, line):
        try:
            job = json.loads(line)
        except ValueError:
            return
        if not isinstance(job, dict):
            return
        state = job.get("state")
        if state == "running" and job.get("round"):
            self.stage = "job %s round %s" % (self.job_id, job["round"])
        elif state:
            self.stage = "job %s %s" % (self.job_id, state)
        if job.get("waiting_for_agents"):
            self.stage += ", no agent connected"
        if isinstance(job.get("progress"), (int, float)):
            self._advance(float(job["progress"]))
        eta = job.get("eta_seconds")
        self.eta_seconds = int(round(eta)) if isinstance(eta, (int, float)) else None

    def _advance(self, fraction):
        self.progress = max(self.progress, min(max(fraction, 0.0), 1.0))

    def _error_text(self, what):
        # radfarm's last line on stderr says why, after its "radfarm: " prefix.
        lines = [line for line in self._stderr if line.strip()]
        if not lines:
            return "%s failed" % what
        return lines[-1][len("radfarm: "):] if lines[-1].startswith("radfarm: ") else lines[-1]

    def _finish(self):
        self.state = DONE
        self.stage = "done"
        self.progress = 1.0
        self.eta_seconds = 0

    def _fail(self, message):
        if self.state == RUNNING:
            self.state = FAILED
            self.message = message

    # --- the caller's side --------------------------------------------------------------------

    def poll(self, wait_seconds=0.0):
        """Takes in what the commands printed; returns True while the bake runs. With
        `wait_seconds`, waits up to that long for the first event (background mode)."""
        if self.state != RUNNING:
            return False
        try:
            event = self._events.get(timeout=wait_seconds) if wait_seconds > 0 else None
        except queue.Empty:
            event = None
        while True:
            if event is not None:
                self._take(event)
            if self.state != RUNNING or self._process is None:
                break
            try:
                event = self._events.get_nowait()
            except queue.Empty:
                break
        return self.state == RUNNING

    def _take(self, event):
        name, line = event
        if line is None:
            self._open_streams -= 1
            if self._open_streams == 0:
                code = self._process.wait()
                self._process = None
                self._on_exit(code)
        elif name == "out":
            self._on_line(line)
            if self._listener is not None:
                self._listener(self)
        else:
            self._stderr.append(line)

    def cancel(self):
        """Stops the running command; a farm job is cancelled on the master too."""
        if self.state != RUNNING:
            return
        self.state = CANCELLED
        self.stage = "cancelled"
        if self._process is not None:
            self._process.terminate()
            self._process.wait()
            self._process = None
        if self.control is not None and self.job_id:
            subprocess.run(self._command(["cancel", self.job_id]), stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=30,
                           check=False)
