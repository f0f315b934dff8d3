# blender/radfarm_bake/job_runner.py outside Blender (ctest JobRunner), against fake_radfarm.py:
# the commands of a bake in order, its progress and ETA as they come, failures in radfarm's own
# words, and a cancelled farm job cancelled on the master.
#   python3 job_runner_test.py SOURCE_DIR
import os
import sys
import tempfile
import time
import unittest

source_dir = sys.argv.pop(1)
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(source_dir, "blender", "radfarm_bake"))
import job_runner  # noqa: E402

FAKE = os.path.join(source_dir, "tests", "blender", "fake_radfarm.py")


class FakeClock:
    """Seconds since the runner started: one more at each call, so progress is exact."""

    def __init__(self):
        self.now = 0.0

    def __call__(self):
        self.now += 1.0
        return self.now


class JobRunnerTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.log = os.path.join(self.dir.name, "commands")
        os.environ["FAKE_RADFARM_LOG"] = self.log
        os.environ.pop("FAKE_RADFARM_FAIL", None)
        os.environ.pop("FAKE_RADFARM_HOLD", None)

    def tearDown(self):
        self.dir.cleanup()

    def commands(self):
        with open(self.log) as f:
            return f.read().splitlines()

    def start(self, control=None, clock=time.monotonic, program=FAKE):
        """A runner that records what the panel would show after each line of output."""
        self.seen = []
        return job_runner.JobRunner(
            program, "job.toml", "out", control=control, clock=clock,
            on_line=lambda r: self.seen.append((r.stage, r.progress, r.eta_seconds)))

    def run_to_end(self, runner):
        # As background mode does: waiting on the commands' output, never a sleep.
        while runner.poll(wait_seconds=10):
            pass
        return self.seen

    def test_render_on_this_machine(self):
        runner = self.start(clock=FakeClock())
        seen = self.run_to_end(runner)
        self.assertEqual(runner.state, job_runner.DONE, runner.message)
        self.assertEqual(self.commands(), ["render job.toml --out out"])
        stages = [stage for stage, _, _ in seen]
        self.assertIn("round 2", stages)
        self.assertIn("final gather", stages)
        etas = [eta for _, _, eta in seen if eta is not None]
        self.assertIn(3, etas)
        progress = [p for _, p, _ in seen]
        self.assertEqual(progress, sorted(progress), "progress fell")
        self.assertGreater(max(progress), 0.0)
        self.assertEqual((runner.progress, runner.eta_seconds), (1.0, 0))

    def test_farm_submit_watch_fetch(self):
        runner = self.start(control="/farm/control.sock")
        seen = self.run_to_end(runner)
        self.assertEqual(runner.state, job_runner.DONE, runner.message)
        self.assertEqual(runner.job_id, "7")
        self.assertEqual(self.commands(), [
            "--control /farm/control.sock submit job.toml",
            "--control /farm/control.sock status 7 --watch --json",
            "--control /farm/control.sock fetch 7 --out out",
        ])
        stages = [stage for stage, _, _ in seen]
        self.assertIn("job 7 queued, no agent connected", stages)
        self.assertIn("job 7 round 3", stages)
        # The master's 0.4 after 0.5 does not take the bar back.
        self.assertIn(("job 7 round 4", 0.5, 2), seen)
        self.assertIn(("job 7 round 3", 0.5, 4), seen)

    def test_a_failed_command_says_why(self):
        os.environ["FAKE_RADFARM_FAIL"] = "submit"
        runner = self.start(control="c.sock")
        self.run_to_end(runner)
        self.assertEqual(runner.state, job_runner.FAILED)
        self.assertEqual(runner.message, "scene.glb: no emitter")
        self.assertEqual(len(self.commands()), 1, "went on after a failed submit")

    def test_a_failed_farm_job_is_not_fetched(self):
        os.environ["FAKE_RADFARM_FAIL"] = "status"
        runner = self.start(control="c.sock")
        self.run_to_end(runner)
        self.assertEqual(runner.state, job_runner.FAILED)
        self.assertNotIn("fetch", " ".join(self.commands()))

    def test_no_program(self):
        runner = self.start(program=os.path.join(self.dir.name, "none"))
        self.assertFalse(runner.poll())
        self.assertEqual(runner.state, job_runner.FAILED)
        self.assertIn("cannot run", runner.message)

    def test_cancel_stops_the_watch_and_the_farm_job(self):
        os.environ["FAKE_RADFARM_HOLD"] = "1"
        runner = self.start(control="c.sock")
        while runner.progress < 0.25:
            self.assertTrue(runner.poll(wait_seconds=10), runner.message)
        self.assertEqual((runner.stage, runner.eta_seconds), ("job 7 round 1", 10))
        runner.cancel()
        self.assertEqual(runner.state, job_runner.CANCELLED)
        self.assertFalse(runner.poll())
        self.assertEqual(self.commands()[-1], "--control c.sock cancel 7")


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
