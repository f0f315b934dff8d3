-- A job store as radfarm wrote it at schema version 1 (frozen: never regenerate from the current
-- migrations; the test checks that such a file upgrades to the latest version with its data).
PRAGMA application_id = 1380009009;
PRAGMA user_version = 1;
BEGIN;
CREATE TABLE scenes (
  hash TEXT PRIMARY KEY,
  geometry BLOB NOT NULL,
  size INTEGER NOT NULL CHECK (size >= 0),
  stored_at_ms INTEGER NOT NULL
);
CREATE TABLE jobs (
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  scene_hash TEXT NOT NULL REFERENCES scenes(hash),
  settings TEXT NOT NULL,
  seed INTEGER NOT NULL,
  priority INTEGER NOT NULL,
  state TEXT NOT NULL
    CHECK (state IN ('queued', 'running', 'paused', 'done', 'failed', 'cancelled')),
  submitted_at_ms INTEGER NOT NULL,
  started_at_ms INTEGER,
  finished_at_ms INTEGER,
  error TEXT
);
CREATE TABLE rounds (
  job_id INTEGER NOT NULL REFERENCES jobs(id) ON DELETE CASCADE,
  round INTEGER NOT NULL CHECK (round >= 0),
  shooters INTEGER NOT NULL,
  rays INTEGER NOT NULL,
  unshot_fraction REAL NOT NULL,
  unshot_power REAL NOT NULL,
  duration_seconds REAL NOT NULL,
  recorded_at_ms INTEGER NOT NULL,
  PRIMARY KEY (job_id, round)
) WITHOUT ROWID;
CREATE TABLE checkpoints (
  job_id INTEGER NOT NULL,
  round INTEGER NOT NULL,
  rounds_done INTEGER NOT NULL,
  patches INTEGER NOT NULL,
  radiosity BLOB NOT NULL CHECK (length(radiosity) = 24 * patches),
  unshot BLOB NOT NULL CHECK (length(unshot) = 24 * patches),
  energy BLOB NOT NULL CHECK (length(energy) = 32),
  created_at_ms INTEGER NOT NULL,
  PRIMARY KEY (job_id, round),
  FOREIGN KEY (job_id, round) REFERENCES rounds(job_id, round) ON DELETE CASCADE
);
CREATE TABLE agents (
  name TEXT PRIMARY KEY,
  address TEXT NOT NULL,
  threads INTEGER NOT NULL,
  first_seen_ms INTEGER NOT NULL,
  last_seen_ms INTEGER NOT NULL
);
CREATE TABLE events (
  id INTEGER PRIMARY KEY,
  job_id INTEGER REFERENCES jobs(id) ON DELETE CASCADE,
  time_ms INTEGER NOT NULL,
  level TEXT NOT NULL CHECK (level IN ('info', 'warning', 'error')),
  text TEXT NOT NULL
);
INSERT INTO scenes VALUES ('sha256:cornell', X'0102030405', 5, 1699999990000);
INSERT INTO jobs VALUES (1, 'cornell', 'sha256:cornell', 'sampler = "sobol"', 42, 5, 'running',
  1699999991000, 1699999992000, NULL, NULL);
INSERT INTO jobs VALUES (2, 'queued one', 'sha256:cornell', '', 7, 0, 'queued',
  1699999993000, NULL, NULL, NULL);
INSERT INTO rounds VALUES (1, 0, 3, 65536, 0.5, 1.5, 0.25, 1699999994000);
INSERT INTO checkpoints VALUES (1, 0, 1, 1,
  X'000000000000F03F000000000000E03F000000000000D03F', X'00000000000000000000000000000080A0C8EB85F3CCE17F',
  X'0000000000000040000000000000F03F0000000000000000000000000000F03F', 1699999994000);
INSERT INTO agents VALUES ('agent-1', '10.0.0.2:7000', 16, 1699999990000, 1699999995000);
INSERT INTO events VALUES (1, 1, 1699999992000, 'info', 'started');
COMMIT;
