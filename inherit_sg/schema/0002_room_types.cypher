// INHerit-SG map schema, version 2: the inferred type distribution of each room.
// `types` is JSON text, [["tv room", 0.41], ["living room", 0.33], …]: (type, probability)
// pairs, best first; the room's label is the best type. Rooms written before this version
// read as NULL (no inferred types).
// JSON text rather than a typed STRUCT(type STRING, p DOUBLE)[] column: Kuzu 0.11.3 loses
// the values of a STRUCT list column added by ALTER TABLE once the database checkpoints.
ALTER TABLE Room ADD IF NOT EXISTS types STRING;
