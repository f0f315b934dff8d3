#!/usr/bin/env python3
# A stand-in for the radfarm program in job_runner_test.py: each command prints what the real one
# prints to a pipe, and appends its arguments to $FAKE_RADFARM_LOG.
#   FAKE_RADFARM_FAIL=COMMAND   that command fails as radfarm does: a "radfarm: " line, exit 2
#   FAKE_RADFARM_HOLD=1         `status --watch` prints one line, then waits to be stopped
import json
import os
import signal
import sys

args = sys.argv[1:]
if args[:1] == ["--control"]:
    args = args[2:]
with open(os.environ["FAKE_RADFARM_LOG"], "a") as log:
    log.write(" ".join(sys.argv[1:]) + "\n")
command = args[0]
if os.environ.get("FAKE_RADFARM_FAIL") == command:
    print("radfarm: scene.glb: no emitter", file=sys.stderr)
    sys.exit(2)
if command == "render":
    print("round 1: unshot 40.0000% of emitted, 1000 rays, 1.00 Mrays/s, ETA ?", flush=True)
    print("round 2: unshot 10.0000% of emitted, 2000 rays, 1.00 Mrays/s, ETA 3s", flush=True)
    print("final gather 50% of 4000 rays  1.00 Mrays/s  ETA 1s", flush=True)
    print("final gather: 6000 rays in all, 1.00 Mrays/s", flush=True)
    print("converged after 2 rounds: wrote out", flush=True)
elif command == "submit":
    print("7")
elif command == "status":
    job = {"id": 7, "state": "queued", "round": 0, "progress": 0.0, "eta_seconds": None,
           "waiting_for_agents": True}
    print(json.dumps(job), flush=True)
    if os.environ.get("FAKE_RADFARM_HOLD"):
        job.update(state="running", round=1, progress=0.25, eta_seconds=9.6,
                   waiting_for_agents=False)
        print(json.dumps(job), flush=True)
        signal.pause()  # until the runner stops it
    for update in ({"state": "running", "round": 3, "progress": 0.5, "eta_seconds": 4.2,
                    "waiting_for_agents": False},
                   {"state": "running", "round": 4, "progress": 0.4, "eta_seconds": 2.0},
                   {"state": "done", "round": 5, "progress": 1.0, "eta_seconds": None}):
        job.update(update)
        print(json.dumps(job), flush=True)
