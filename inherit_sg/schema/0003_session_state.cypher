// INHerit-SG map schema, version 3: how each mapping session ended.
// `state` is "finished", "failed" or "interrupted" (a session whose process was killed or
// crashed, marked so by the next writable open); NULL while a session runs, and for
// sessions written before this version (their `finished` time tells).
ALTER TABLE Session ADD IF NOT EXISTS state STRING;
